#pragma once
/// \file
/// HVOL: hydraulic volume (capacitance) with the bulk modulus of the liquid and
/// optionally entrained air.

#include <array>
#include <cmath>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

template <class = void>
struct hydraulic_volume_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using hydraulic_volume = hydraulic_volume_t<>;
/// HVOL: a rigid volume V filled with liquid of bulk modulus B and, optionally, a
/// volume fraction alpha of undissolved air at p = 0 (gauge) that is compressed
/// polytropically. Flow (the volume flow into the volume):
///   q = C(p) dp/dt,  C(p) = V [ (1 - alpha) / B + alpha / (n pa) (pa / (pa + p))^(1 + 1/n) ]
/// (an inertia block C(p) and, for alpha > 0, a viscous block dC/dp dp/dt).
/// With alpha = 0, C = V / B and the pressure of a volume fed by q rises as B q t / V.
template <class>
struct hydraulic_volume_t {
  static constexpr pradis::passport passport{.name = "HVOL", .ext = 1, .par = 5, .wrk = 2, .adr = 2, .ign = 0};
  static constexpr std::array<domain, 1> domains{domain::hydraulic};
  static constexpr element_help help{
      .title = "hydraulic volume (capacitance), optionally with entrained air",
      .name = "Rigid volume of compressible liquid: q = C(p) dp/dt",
      .field = "hydraulics",
      .dofs = "1 - pressure node [Pa]",
      .parameters = "1 - volume V [m^3] (> 0)\n"
                    "2 - bulk modulus of the liquid B [Pa] (> 0)\n"
                    "3 - volume fraction of entrained air at p = 0, alpha [-] (0 <= alpha < 1; 0: none)\n"
                    "4 - ambient (absolute) pressure pa [Pa] (> 0)\n"
                    "5 - polytropic exponent of the air n [-] (> 0; 1 isothermal, 1.4 adiabatic)",
      .work = "1 - capacitance C(p) [m^3/Pa]\n2 - effective bulk modulus V / C(p) [Pa]",
      .special = "code 100 if V, B, pa or n is not positive or alpha is outside [0, 1); code 75 if, with air, the "
                 "absolute pressure pa + p reaches zero (cavitation is not modelled)"};
  struct parameters {
    double volume = 0;         ///< V [m^3]
    double bulk_modulus = 0;   ///< B [Pa]
    double air_fraction = 0;   ///< alpha at p = 0 [-]
    double ambient = 1e5;      ///< pa [Pa]
    double polytropic = 1.4;   ///< n [-]
  };
  parameters p;
  explicit hydraulic_volume_t(parameters q) : p(q) {}
  /// Example parameters in scaled units (pressure unit 1, so that the all-elements
  /// test's pressures of +-10 are 1/3 of the ambient pressure and the air matters).
  static parameters example() { return {2.0, 50.0, 0.1, 30.0, 1.4}; }
  static hydraulic_volume from_parameters(std::span<const double> v) {
    return hydraulic_volume({v[0], v[1], v[2], v[3], v[4]});
  }
  void new_integration(element_context& ctx) const {
    using namespace hydraulic_detail;
    require_positive(ctx, "volume V", p.volume);
    require_positive(ctx, "bulk modulus B", p.bulk_modulus);
    if (!(p.air_fraction >= 0 && p.air_fraction < 1))
      ctx.invalid_parameter("air fraction alpha = " + to_text(p.air_fraction) + " must be in [0, 1)");
    require_positive(ctx, "ambient pressure pa", p.ambient);
    require_positive(ctx, "polytropic exponent n", p.polytropic);
  }
  /// C(p) and dC/dp.
  void capacitance(double pr, double& c, double& dc, element_context& ctx) const {
    c = p.volume * (1 - p.air_fraction) / p.bulk_modulus;
    dc = 0;
    if (p.air_fraction == 0) return;
    const double pabs = p.ambient + pr;
    if (!(pabs > 0)) ctx.singular("the absolute pressure pa + p = " + to_text(pabs) + " Pa is not positive");
    const double e = 1 + 1 / p.polytropic, r = std::pow(p.ambient / pabs, e);
    const double air = p.volume * p.air_fraction / (p.polytropic * p.ambient) * r;
    c += air;
    dc = -e * air / pabs;
  }
  void evaluate(const local_input<hydraulic_volume>& in, local_output<hydraulic_volume>& out,
                element_context& ctx) const {
    double c = 0, dc = 0;
    capacitance(in.v(0), c, dc, ctx);
    out.f(0) = c * in.a(0);
    ctx.work[0] = c;
    ctx.work[1] = p.volume / c;
    if (!out.want_jacobian) return;
    out.M(0, 0) = c;
    out.C(0, 0) = dc * in.a(0);
  }
  /// The all-elements test keeps the absolute pressure above 10 % of the ambient one.
  bool admissible(const local_input<hydraulic_volume>& in) const {
    return p.air_fraction == 0 || p.ambient + in.v(0) > 0.1 * p.ambient;
  }
};

}  // namespace pradis::elements
