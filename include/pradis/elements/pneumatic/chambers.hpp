#pragma once
/// \file
/// PNVOL, PNCHP and PNCYL: gas chambers with the polytropic ideal-gas law (a
/// nonlinear capacitance): a fixed volume, a volume that follows a piston, and a
/// double-acting cylinder. Mass balance m' = q with m = rho(P) V:
///     q = V rho'(P) P' + rho(P) V'
/// (P absolute pressure, rho(P) = rho0 (P/P0)^(1/n), pneumatic/gas.hpp). The gauge
/// pressure v acts on a piston of area A with the force A v.

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/pneumatic/gas.hpp"

namespace pradis::elements {

template <class = void>
struct gas_chamber_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using gas_chamber = gas_chamber_t<>;
/// PNVOL: gas chamber of fixed volume V on one pneumatic node: q = V rho'(P) P'.
/// Sets the node's initial gauge pressure p0 at the zero step. Blocks C and M.
template <class>
struct gas_chamber_t {
  static constexpr pradis::passport passport{.name = "PNVOL", .ext = 1, .par = 4, .wrk = 4, .adr = 2};
  static constexpr std::array<domain, 1> domains{domain::pneumatic};
  static constexpr element_help help{
      .title = "gas chamber of fixed volume (polytropic ideal gas)",
      .name = "Pneumatic volume: mass balance of air at the polytropic law P / rho^n = const",
      .field = "pneumatics",
      .dofs = "1 - pneumatic node (gauge pressure) [Pa]",
      .parameters = "1 - volume V [m^3] (> 0)\n2 - polytropic exponent n (1 isothermal, 1.4 adiabatic; 1 <= n <= 2)\n"
                    "3 - initial gauge pressure p0 [Pa] (> -101325)\n4 - initial temperature T0 [K] (> 0)",
      .work = "1 - absolute pressure P [Pa]\n2 - density rho [kg/m^3]\n3 - mass of air m = rho V [kg]\n"
              "4 - temperature T = P/(rho R) [K]",
      .special = "code 100 for a parameter outside its range; code 90 if the node has another initial pressure or "
                 "is driven by a source; code 75 if the absolute pressure is not positive. Air, R = 287.05 J/(kg K); "
                 "gauge pressures relative to 101325 Pa"};
  struct parameters {
    double volume = 1e-3;                             ///< V [m^3]
    double n = 1;                                     ///< polytropic exponent
    double p0 = 0;                                    ///< initial gauge pressure [Pa]
    double t0 = pneumatic::anr_temperature;           ///< initial temperature [K]
  };
  parameters p;
  explicit gas_chamber_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test: a large
  /// volume makes the Jacobian entries large against the checker's absolute floor).
  static parameters example() { return {1e4, 1.4, 2e5, 300.0}; }
  static gas_chamber from_parameters(std::span<const double> v) { return gas_chamber({v[0], v[1], v[2], v[3]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.volume > 0) || !std::isfinite(p.volume)) ctx.invalid_parameter("volume V = " + to_text(p.volume) + " must be finite and > 0");
    pneumatic::check_chamber(ctx, p.n, p.p0, p.t0);
  }
  void zero_step(initial_values<1>& iv, element_context&) const { iv.set_velocity(0, p.p0); }
  /// The gas law of the chamber.
  pneumatic::polytropic_gas gas() const { return {pneumatic::atmosphere + p.p0, p.t0, p.n}; }
  void evaluate(const local_input<gas_chamber>& in, local_output<gas_chamber>& out, element_context& ctx) const {
    const pneumatic::polytropic_gas g = gas();
    const double pa = pneumatic::absolute_pressure(ctx, in.v(0));
    const pneumatic::chamber_flow c = pneumatic::chamber_balance(g, pa, in.a(0), p.volume, 0.0);
    out.f(0) = c.q;
    ctx.work[0] = pa;
    ctx.work[1] = c.rho;
    ctx.work[2] = c.rho * p.volume;
    ctx.work[3] = g.temperature(pa, c.rho);
    if (!out.want_jacobian) return;
    out.C(0, 0) = c.dq_dv;
    out.M(0, 0) = c.dq_da;
  }
};

template <class = void>
struct gas_piston_chamber_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using gas_piston_chamber = gas_piston_chamber_t<>;
/// PNCHP: gas chamber closed by a piston of area A: volume V = V0 + A x (x the
/// piston's displacement, positive enlarging the chamber). Mass flow q = V rho' P' +
/// rho A x'; the gas pushes the piston with the force A v (gauge), so the flow on the
/// piston DOF is -A v. Sets the node's initial gauge pressure p0. Blocks K, C, M.
template <class>
struct gas_piston_chamber_t {
  static constexpr pradis::passport passport{.name = "PNCHP", .ext = 2, .par = 5, .wrk = 6, .adr = 1};
  static constexpr std::array<domain, 2> domains{domain::pneumatic, domain::mechanical};
  static constexpr element_help help{
      .title = "gas chamber closed by a moving piston (polytropic ideal gas)",
      .name = "Pneumatic chamber of volume V0 + A x, force A (P - p_atm) on the piston",
      .field = "pneumatics",
      .dofs = "1 - pneumatic node (gauge pressure) [Pa]\n2 - piston displacement x (enlarges the chamber) [m]",
      .parameters = "1 - piston area A [m^2] (> 0)\n2 - volume V0 at x = 0 [m^3] (> 0)\n"
                    "3 - polytropic exponent n (1 isothermal, 1.4 adiabatic; 1 <= n <= 2)\n"
                    "4 - initial gauge pressure p0 [Pa] (> -101325)\n5 - initial temperature T0 [K] (> 0)",
      .work = "1 - absolute pressure P [Pa]\n2 - density rho [kg/m^3]\n3 - mass of air m [kg]\n"
              "4 - temperature T [K]\n5 - volume V [m^3]\n6 - force on the piston A (P - p_atm) [N]",
      .special = "code 100 for a parameter outside its range; code 90 if the node has another initial pressure or "
                 "is driven by a source; code 75 if the volume or the absolute pressure is not positive"};
  struct parameters {
    double area = 1e-3;                      ///< A [m^2]
    double v0 = 1e-4;                        ///< V0 [m^3]
    double n = 1;                            ///< polytropic exponent
    double p0 = 0;                           ///< initial gauge pressure [Pa]
    double t0 = pneumatic::anr_temperature;  ///< initial temperature [K]
  };
  parameters p;
  explicit gas_piston_chamber_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test: a large dead volume
  /// gives sizeable Jacobian entries, a moderate area keeps the flows, and so the round-off of
  /// the differences, small; tests/pneumatic checks realistic sizes with scaled steps).
  static parameters example() { return {0.1, 100.0, 1.4, 1e5, 300.0}; }
  static gas_piston_chamber from_parameters(std::span<const double> v) {
    return gas_piston_chamber({v[0], v[1], v[2], v[3], v[4]});
  }
  void new_integration(element_context& ctx) const {
    if (!(p.area > 0) || !std::isfinite(p.area)) ctx.invalid_parameter("piston area A = " + to_text(p.area) + " must be finite and > 0");
    if (!(p.v0 > 0) || !std::isfinite(p.v0)) ctx.invalid_parameter("volume V0 = " + to_text(p.v0) + " must be finite and > 0");
    pneumatic::check_chamber(ctx, p.n, p.p0, p.t0);
  }
  void zero_step(initial_values<2>& iv, element_context&) const { iv.set_velocity(0, p.p0); }
  void evaluate(const local_input<gas_piston_chamber>& in, local_output<gas_piston_chamber>& out,
                element_context& ctx) const {
    const pneumatic::polytropic_gas g{pneumatic::atmosphere + p.p0, p.t0, p.n};
    const double pa = pneumatic::absolute_pressure(ctx, in.v(0)), vol = p.v0 + p.area * in.u(1);
    if (!(vol > 0)) ctx.singular("the chamber volume " + to_text(vol) + " m^3 is not positive");
    const pneumatic::chamber_flow c = pneumatic::chamber_balance(g, pa, in.a(0), vol, p.area * in.v(1));
    out.f << c.q, -p.area * in.v(0);
    ctx.work[0] = pa;
    ctx.work[1] = c.rho;
    ctx.work[2] = c.rho * vol;
    ctx.work[3] = g.temperature(pa, c.rho);
    ctx.work[4] = vol;
    ctx.work[5] = p.area * in.v(0);
    if (!out.want_jacobian) return;
    out.K << 0, c.dq_dvolume * p.area, 0, 0;
    out.C << c.dq_dv, c.dq_drate * p.area, -p.area, 0;
    out.M << c.dq_da, 0, 0, 0;
  }
  /// States with a positive volume and absolute pressure (for the checks).
  bool admissible(const local_input<gas_piston_chamber>& in) const {
    return p.v0 + p.area * in.u(1) > 0.1 * p.v0 && in.v(0) > -pneumatic::atmosphere;
  }
};

template <class = void>
struct pneumatic_cylinder_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using pneumatic_cylinder = pneumatic_cylinder_t<>;
/// PNCYL: double-acting pneumatic cylinder: chamber A (piston side, area A1, volume
/// VA0 + A1 x) and chamber B (rod side, annulus area A2, volume VB0 - A2 x) on one
/// rod displacement x; rod force F = A1 vA - A2 vB (gauge pressures), flow -F on the
/// rod DOF. Both chambers start at the gauge pressure p0. Blocks K, C, M.
template <class>
struct pneumatic_cylinder_t {
  static constexpr pradis::passport passport{.name = "PNCYL", .ext = 3, .par = 7, .wrk = 5, .adr = 1};
  static constexpr std::array<domain, 3> domains{domain::pneumatic, domain::pneumatic, domain::mechanical};
  static constexpr element_help help{
      .title = "double-acting pneumatic cylinder",
      .name = "Pneumatic cylinder: two polytropic chambers on one rod, force A1 pA - A2 pB (gauge)",
      .field = "pneumatics",
      .dofs = "1 - chamber A node (piston side) [Pa]\n2 - chamber B node (rod side) [Pa]\n"
              "3 - rod displacement x (extends, enlarging chamber A) [m]",
      .parameters = "1 - piston area A1 [m^2] (> 0)\n2 - annulus area A2 [m^2] (> 0)\n"
                    "3 - volume VA0 of chamber A at x = 0 [m^3] (> 0)\n4 - volume VB0 of chamber B at x = 0 [m^3] (> 0)\n"
                    "5 - polytropic exponent n (1 <= n <= 2)\n6 - initial gauge pressure p0 of both chambers [Pa]\n"
                    "7 - initial temperature T0 [K] (> 0)",
      .work = "1 - rod force A1 pA - A2 pB [N]\n2 - absolute pressure in A [Pa]\n3 - absolute pressure in B [Pa]\n"
              "4 - volume of A [m^3]\n5 - volume of B [m^3]",
      .special = "code 100 for a parameter outside its range; code 90 if a chamber node has another initial pressure "
                 "or is driven by a source; code 75 if a volume or an absolute pressure is not positive (the rod "
                 "must stay inside -VA0/A1 < x < VB0/A2)"};
  struct parameters {
    double a1 = 1e-3, a2 = 8e-4;             ///< areas [m^2]
    double va0 = 1e-4, vb0 = 1e-4;           ///< volumes at x = 0 [m^3]
    double n = 1;                            ///< polytropic exponent
    double p0 = 0;                           ///< initial gauge pressure [Pa]
    double t0 = pneumatic::anr_temperature;  ///< initial temperature [K]
  };
  parameters p;
  explicit pneumatic_cylinder_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test; see PNCHP).
  static parameters example() { return {0.1, 0.08, 100.0, 100.0, 1.4, 1e5, 300.0}; }
  static pneumatic_cylinder from_parameters(std::span<const double> v) {
    return pneumatic_cylinder({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
  }
  void new_integration(element_context& ctx) const {
    const std::array<std::pair<const char*, double>, 4> pos{
        {{"piston area A1", p.a1}, {"annulus area A2", p.a2}, {"volume VA0", p.va0}, {"volume VB0", p.vb0}}};
    for (const auto& [what, x] : pos)
      if (!(x > 0) || !std::isfinite(x)) ctx.invalid_parameter(std::string(what) + " = " + to_text(x) + " must be finite and > 0");
    pneumatic::check_chamber(ctx, p.n, p.p0, p.t0);
  }
  void zero_step(initial_values<3>& iv, element_context&) const {
    iv.set_velocity(0, p.p0);
    iv.set_velocity(1, p.p0);
  }
  void evaluate(const local_input<pneumatic_cylinder>& in, local_output<pneumatic_cylinder>& out,
                element_context& ctx) const {
    const pneumatic::polytropic_gas g{pneumatic::atmosphere + p.p0, p.t0, p.n};
    const double pa = pneumatic::absolute_pressure(ctx, in.v(0)), pb = pneumatic::absolute_pressure(ctx, in.v(1));
    const double va = p.va0 + p.a1 * in.u(2), vb = p.vb0 - p.a2 * in.u(2);
    if (!(va > 0) || !(vb > 0))
      ctx.singular("a chamber volume is not positive (VA = " + to_text(va) + ", VB = " + to_text(vb) + " m^3)");
    const pneumatic::chamber_flow ca = pneumatic::chamber_balance(g, pa, in.a(0), va, p.a1 * in.v(2));
    const pneumatic::chamber_flow cb = pneumatic::chamber_balance(g, pb, in.a(1), vb, -p.a2 * in.v(2));
    const double force = p.a1 * in.v(0) - p.a2 * in.v(1);
    out.f << ca.q, cb.q, -force;
    ctx.work[0] = force;
    ctx.work[1] = pa;
    ctx.work[2] = pb;
    ctx.work[3] = va;
    ctx.work[4] = vb;
    if (!out.want_jacobian) return;
    out.K << 0, 0, ca.dq_dvolume * p.a1,  //
        0, 0, -cb.dq_dvolume * p.a2,      //
        0, 0, 0;
    out.C << ca.dq_dv, 0, ca.dq_drate * p.a1,  //
        0, cb.dq_dv, -cb.dq_drate * p.a2,      //
        -p.a1, p.a2, 0;
    out.M << ca.dq_da, 0, 0,  //
        0, cb.dq_da, 0,       //
        0, 0, 0;
  }
  /// States with both volumes above 10 % of their value at x = 0 (for the checks).
  bool admissible(const local_input<pneumatic_cylinder>& in) const {
    return p.va0 + p.a1 * in.u(2) > 0.1 * p.va0 && p.vb0 - p.a2 * in.u(2) > 0.1 * p.vb0;
  }
};

}  // namespace pradis::elements
