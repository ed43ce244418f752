#pragma once
/// \file
/// Air as an ideal gas for the pneumatic elements, and the polytropic state of a
/// chamber.
///
/// Pneumatic DOFs: the velocity-level unknown v is the GAUGE pressure [Pa], relative
/// to the standard atmosphere p_atm = 101325 Pa, so the ground is the atmosphere and
/// a model starts at ambient pressure; u is its time integral [Pa s], a its time
/// derivative [Pa/s]; the flow is the mass flow [kg/s] leaving the node into the
/// element. The elements work with the absolute pressure P = p_atm + v.

#include <cmath>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements::pneumatic {

/// Standard atmosphere, the zero of the gauge pressure [Pa].
inline constexpr double atmosphere = 101325.0;
/// Specific gas constant of dry air [J/(kg K)].
inline constexpr double air_gas_constant = 287.05;
/// ISO 8778 standard reference atmosphere (ANR) of ISO 6358: density [kg/m^3] and temperature [K].
inline constexpr double anr_density = 1.185;
inline constexpr double anr_temperature = 293.15;

/// Polytropic gas in a chamber: density rho(P) = rho0 (P/P0)^(1/n), with
/// rho0 = P0 / (R T0) at the reference state (P0, T0). n = 1 is isothermal,
/// n = kappa = 1.4 adiabatic (isentropic: the gas entering the chamber has the
/// chamber's own temperature, so its specific entropy stays that of the reference).
struct polytropic_gas {
  double p0 = atmosphere;        ///< reference absolute pressure [Pa]
  double t0 = anr_temperature;   ///< reference temperature [K]
  double n = 1.0;                ///< polytropic exponent
  /// Density rho, d rho/dP and d^2 rho/dP^2 at the absolute pressure P > 0.
  void density(double p, double& rho, double& d1, double& d2) const {
    const double rho0 = p0 / (air_gas_constant * t0);
    rho = rho0 * std::pow(p / p0, 1.0 / n);
    d1 = rho / (n * p);
    d2 = d1 * (1.0 / n - 1.0) / p;
  }
  /// Temperature T = P / (rho R).
  double temperature(double p, double rho) const { return p / (rho * air_gas_constant); }
};

/// Checks the common chamber parameters (code 100 naming the parameter).
inline void check_chamber(element_context& ctx, double n, double p0, double t0) {
  if (!(n >= 1.0 && n <= 2.0)) ctx.invalid_parameter("polytropic exponent n = " + to_text(n) + " must be in [1, 2]");
  if (!(p0 > -atmosphere) || !std::isfinite(p0))
    ctx.invalid_parameter("initial gauge pressure p0 = " + to_text(p0) + " Pa must be finite and above -101325 Pa "
                          "(vacuum)");
  if (!(t0 > 0) || !std::isfinite(t0)) ctx.invalid_parameter("initial temperature T0 = " + to_text(t0) + " K must be finite and > 0");
}

/// Absolute pressure of a gauge pressure; code 75 when it is not positive.
inline double absolute_pressure(element_context& ctx, double gauge) {
  const double p = atmosphere + gauge;
  if (!(p > 0)) ctx.singular("the absolute pressure " + to_text(p) + " Pa is not positive");
  return p;
}

/// Mass flow into a chamber of volume V with the rate dV/dt (= A x'), and its
/// derivatives. With m = rho(P) V: q = V rho'(P) P' + rho(P) V'.
struct chamber_flow {
  double q = 0;           ///< mass flow into the chamber [kg/s]
  double dq_da = 0;       ///< dq/dP' = V rho'
  double dq_dv = 0;       ///< dq/dP = V rho'' P' + rho' V'
  double dq_dvolume = 0;  ///< dq/dV = rho' P'
  double dq_drate = 0;    ///< dq/dV' = rho
  double rho = 0;         ///< density [kg/m^3]
};
/// The chamber's mass balance at absolute pressure P, its rate dp, volume V and rate dV.
inline chamber_flow chamber_balance(const polytropic_gas& g, double p, double dp, double volume, double dvolume) {
  double rho = 0, d1 = 0, d2 = 0;
  g.density(p, rho, d1, d2);
  return {volume * d1 * dp + rho * dvolume, volume * d1, volume * d2 * dp + d1 * dvolume, d1 * dp, rho, rho};
}

}  // namespace pradis::elements::pneumatic
