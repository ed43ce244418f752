#pragma once
/// \file
/// PNORF: pneumatic orifice (valve, restriction) with the ISO 6358 flow law, and the
/// pneumatic sources PNSRC (pressure of a node) and PNQ (mass flow).

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/electric/source_kinds.hpp"
#include "pradis/elements/pneumatic/gas.hpp"

namespace pradis::elements {

template <class = void>
struct pneumatic_orifice_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using pneumatic_orifice = pneumatic_orifice_t<>;
/// PNORF: orifice between nodes 1 and 2 with the ISO 6358 law (sonic conductance C,
/// critical pressure ratio b). With P_up > P_dn the upstream and downstream absolute
/// pressures, r = P_dn / P_up and y = (1 - r) / (1 - b):
///     q = C rho0 P_up sqrt(T0 / T) psi(y),   psi = 1 (choked, r <= b),
///     psi = sqrt(1 - ((r - b)/(1 - b))^2) = sqrt(y (2 - y))  (subsonic),
/// rho0 = 1.185 kg/m^3, T0 = 293.15 K (ANR). The subsonic ellipse has an infinite
/// slope at r = 1 (q ~ sqrt(dp)). Regularisation: below the laminar ratio threshold,
/// y < y_l = (1 - b_lam)/(1 - b), psi is the odd cubic a y + c y^3 that matches the
/// ellipse's value s and slope d at y_l (a = (3 s/y_l - d)/2, c = (d - s/y_l)/(2 y_l^2)).
/// So q is C1 everywhere, linear in dp = P1 - P2 near dp = 0 with the finite slope
/// C rho0 sqrt(T0/T) a / (1 - b) (the same from both sides, independent of P_up), and
/// monotonic. Reverse flow (P2 > P1) uses the same law with the roles exchanged.
template <class>
struct pneumatic_orifice_t {
  static constexpr pradis::passport passport{.name = "PNORF", .ext = 2, .par = 4, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::pneumatic, domain::pneumatic};
  static constexpr element_help help{
      .title = "pneumatic orifice, ISO 6358 flow law",
      .name = "Orifice with sonic conductance C and critical pressure ratio b (ISO 6358), laminar near dp = 0",
      .field = "pneumatics",
      .dofs = "1 - node 1 (gauge pressure) [Pa]\n2 - node 2 (gauge pressure) [Pa]",
      .parameters = "1 - sonic conductance C [m^3/(s Pa)] (> 0)\n2 - critical pressure ratio b (0 <= b < 1)\n"
                    "3 - upstream temperature T [K] (> 0)\n"
                    "4 - laminar pressure ratio b_lam (b < b_lam < 1; typically 0.999)",
      .work = "1 - mass flow from node 1 to node 2 [kg/s]\n2 - pressure ratio P_dn / P_up",
      .special = "code 100 for a parameter outside its range; code 75 if an absolute pressure is not positive. "
                 "Above the ratio b_lam the flow is a cubic in the pressure ratio, linear at dp = 0 (finite slope)"};
  struct parameters {
    double c = 1e-8;                        ///< sonic conductance [m^3/(s Pa)]
    double b = 0.3;                         ///< critical pressure ratio
    double t = pneumatic::anr_temperature;  ///< upstream temperature [K]
    double b_lam = 0.999;                   ///< laminar pressure ratio
  };
  parameters p;
  explicit pneumatic_orifice_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test: b_lam close to 1
  /// so that the random states, within +-20 Pa of each other, reach the subsonic law).
  static parameters example() { return {1e-3, 0.3, 300.0, 0.99999}; }
  static pneumatic_orifice from_parameters(std::span<const double> v) {
    return pneumatic_orifice({v[0], v[1], v[2], v[3]});
  }
  void new_integration(element_context& ctx) const {
    if (!(p.c > 0) || !std::isfinite(p.c)) ctx.invalid_parameter("sonic conductance C = " + to_text(p.c) + " must be finite and > 0");
    if (!(p.b >= 0 && p.b < 1)) ctx.invalid_parameter("critical pressure ratio b = " + to_text(p.b) + " must be in [0, 1)");
    if (!(p.t > 0) || !std::isfinite(p.t)) ctx.invalid_parameter("upstream temperature T = " + to_text(p.t) + " must be finite and > 0");
    if (!(p.b_lam > p.b && p.b_lam < 1))
      ctx.invalid_parameter("laminar pressure ratio b_lam = " + to_text(p.b_lam) + " must be in (b, 1)");
  }
  /// psi(y) and dpsi/dy of the regularised ISO 6358 law.
  void psi(double y, double& value, double& slope) const {
    if (y >= 1) {
      value = 1;
      slope = 0;
      return;
    }
    const double yl = (1 - p.b_lam) / (1 - p.b);
    if (y >= yl) {
      value = std::sqrt(y * (2 - y));
      slope = (1 - y) / value;
      return;
    }
    const double s = std::sqrt(yl * (2 - yl)), d = (1 - yl) / s;
    const double a = 0.5 * (3 * s / yl - d), c = (d - s / yl) / (2 * yl * yl);
    value = a * y + c * y * y * y;
    slope = a + 3 * c * y * y;
  }
  /// Mass flow from node 1 to node 2 at the gauge pressures g1, g2 and its derivatives by them. The ratio
  /// 1 - P_dn/P_up is formed as (g_up - g_dn) / P_up, free of the cancellation of 1 - P_dn/P_up near 1.
  void flow(double g1, double g2, double& q, double& dq1, double& dq2) const {
    const double k = p.c * pneumatic::anr_density * std::sqrt(pneumatic::anr_temperature / p.t);
    const bool forward = g1 >= g2;
    const double gup = forward ? g1 : g2, gdn = forward ? g2 : g1;
    const double up = pneumatic::atmosphere + gup, dn = pneumatic::atmosphere + gdn;
    const double y = (gup - gdn) / (up * (1 - p.b));
    double s = 0, ds = 0;
    psi(y, s, ds);
    // q = k P_up psi(y), y = (1 - P_dn/P_up)/(1 - b): dq/dP_up = k (psi + psi' P_dn/(P_up (1 - b))),
    // dq/dP_dn = -k psi' / (1 - b).
    const double q_up = k * (s + ds * dn / (up * (1 - p.b))), q_dn = -k * ds / (1 - p.b);
    if (forward) {
      q = k * up * s;
      dq1 = q_up;
      dq2 = q_dn;
    } else {
      q = -k * up * s;
      dq1 = -q_dn;
      dq2 = -q_up;
    }
  }
  void evaluate(const local_input<pneumatic_orifice>& in, local_output<pneumatic_orifice>& out,
                element_context& ctx) const {
    const double p1 = pneumatic::absolute_pressure(ctx, in.v(0)), p2 = pneumatic::absolute_pressure(ctx, in.v(1));
    double q = 0, d1 = 0, d2 = 0;
    flow(in.v(0), in.v(1), q, d1, d2);
    out.f << q, -q;
    ctx.work[0] = q;
    ctx.work[1] = std::min(p1, p2) / std::max(p1, p2);
    if (out.want_jacobian) out.C << d1, d2, -d1, -d2;
  }
};

/// Descriptions of the pneumatic source types.
namespace pneumatic_source_text {
struct pressure {
  static constexpr std::string_view name = "PNSRC", what = "gauge pressure p [Pa]";
  static constexpr domain dom = domain::pneumatic;
  static constexpr element_help help{
      .title = "constant pressure of a pneumatic node",
      .name = "Ideal pressure source: prescribes the gauge pressure p of its node (supply, reservoir)",
      .field = "pneumatics",
      .dofs = "1 - the driven node [Pa]",
      .parameters = "1 - gauge pressure p [Pa]",
      .work = "1 - mass flow the source delivers into the node [kg/s]",
      .special = "code 100 if p is not finite; code 90 if the node is the ground (the atmosphere), is driven by "
                 "another source or has an initial pressure (e.g. from a chamber)"};
  static constant_wave::parameters example() { return {6e5}; }
};
struct mass_flow {
  static constexpr std::string_view name = "PNQ", what = "mass flow q [kg/s]";
  static constexpr domain dom = domain::pneumatic;
  static constexpr element_help help{.title = "constant mass flow between two pneumatic nodes",
                                     .name = "Ideal mass-flow source: delivers q into node 1, draws it from node 2",
                                     .field = "pneumatics",
                                     .dofs = "1 - node the flow is delivered to [Pa]\n2 - node it is drawn from [Pa]",
                                     .parameters = "1 - mass flow q [kg/s]",
                                     .work = "1 - mass flow q [kg/s]\n2 - pressure difference v1 - v2 [Pa]",
                                     .special = "code 100 if q is not finite"};
  static constant_wave::parameters example() { return {1e-3}; }
};
}  // namespace pneumatic_source_text

/// PNSRC: prescribed gauge pressure of a node.
using pneumatic_pressure_source = potential_source<constant_wave, pneumatic_source_text::pressure>;
/// PNQ: constant mass flow source.
using pneumatic_flow_source = flow_source<constant_wave, pneumatic_source_text::mass_flow>;

}  // namespace pradis::elements
