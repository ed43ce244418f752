#pragma once
/// \file
/// R, C and L: the linear passive two-terminal elements of electric circuits in the
/// nodal second-order form (docs/domains-electric-pneumatic.md).
///
/// On an electric DOF the velocity-level unknown v is the node voltage [V], u its
/// time integral (the flux linkage [V s]) and a its time derivative [V/s]; the flow
/// is the current [A] that leaves the node into the element. So a resistor is a
/// viscous block (dF/dv = 1/R), a capacitor an inertia block (dF/da = C) and an
/// inductor a stiffness block (dF/du = 1/L, since L i = u1 - u2 + L i0).

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct resistor_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using resistor = resistor_t<>;
/// R: linear resistor between nodes 1 and 2: current i = (v1 - v2) / R from node 1
/// to node 2. Flows i, -i. Pure viscosity (ADR=2, IGN=3).
template <class>
struct resistor_t {
  static constexpr pradis::passport passport{.name = "R", .ext = 2, .par = 1, .wrk = 1, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::electric, domain::electric};
  static constexpr element_help help{.title = "linear resistor between two nodes",
                                     .name = "Linear electric resistance",
                                     .field = "electric circuits",
                                     .dofs = "1 - node 1 (voltage) [V]\n2 - node 2 (voltage) [V]",
                                     .parameters = "1 - resistance R [Ohm] (> 0)",
                                     .work = "1 - current i = (v1 - v2) / R from node 1 to node 2 [A]",
                                     .special = "code 100 if R <= 0 or R is not finite"};
  struct parameters {
    double r = 1;  ///< resistance R [Ohm]
  };
  parameters p;
  explicit resistor_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {4.7}; }
  static resistor from_parameters(std::span<const double> v) { return resistor({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.r > 0) || !std::isfinite(p.r)) ctx.invalid_parameter("resistance R = " + to_text(p.r) + " must be finite and > 0");
  }
  void evaluate(const local_input<resistor>& in, local_output<resistor>& out, element_context& ctx) const {
    const double g = 1.0 / p.r, i = g * (in.v(0) - in.v(1));
    out.f << i, -i;
    ctx.work[0] = i;
    if (out.want_jacobian) out.C << g, -g, -g, g;
  }
};

template <class = void>
struct capacitor_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using capacitor = capacitor_t<>;
/// C: linear capacitor between nodes 1 and 2: current i = C (v1' - v2') from node 1
/// to node 2. Flows i, -i. Pure inertia (ADR=3). Its initial voltage is that of its
/// nodes (0 unless set, e.g. by V0 on a node).
template <class>
struct capacitor_t {
  static constexpr pradis::passport passport{.name = "C", .ext = 2, .par = 1, .wrk = 2, .adr = 3};
  static constexpr std::array<domain, 2> domains{domain::electric, domain::electric};
  static constexpr element_help help{.title = "linear capacitor between two nodes",
                                     .name = "Linear electric capacitance",
                                     .field = "electric circuits",
                                     .dofs = "1 - node 1 (voltage) [V]\n2 - node 2 (voltage) [V]",
                                     .parameters = "1 - capacitance C [F] (> 0)",
                                     .work = "1 - current i = C d(v1 - v2)/dt from node 1 to node 2 [A]\n"
                                             "2 - charge q = C (v1 - v2) [C]",
                                     .special = "code 100 if C <= 0 or C is not finite"};
  struct parameters {
    double c = 1;  ///< capacitance C [F]
  };
  parameters p;
  explicit capacitor_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {2.2}; }
  static capacitor from_parameters(std::span<const double> v) { return capacitor({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.c > 0) || !std::isfinite(p.c)) ctx.invalid_parameter("capacitance C = " + to_text(p.c) + " must be finite and > 0");
  }
  void evaluate(const local_input<capacitor>& in, local_output<capacitor>& out, element_context& ctx) const {
    const double i = p.c * (in.a(0) - in.a(1));
    out.f << i, -i;
    ctx.work[0] = i;
    ctx.work[1] = p.c * (in.v(0) - in.v(1));
    if (out.want_jacobian) out.M << p.c, -p.c, -p.c, p.c;
  }
};

template <class = void>
struct inductor_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using inductor = inductor_t<>;
/// L: linear inductor between nodes 1 and 2. With u the flux linkage (time integral
/// of the voltage), L di/dt = v1 - v2 integrates to i = (u1 - u2) / L + i0, the
/// current from node 1 to node 2 (i0 at t = 0, where u = 0). Flows i, -i. Pure
/// stiffness (ADR=1, IGN=23): no internal DOF is needed.
template <class>
struct inductor_t {
  static constexpr pradis::passport passport{.name = "L", .ext = 2, .par = 2, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr std::array<domain, 2> domains{domain::electric, domain::electric};
  static constexpr element_help help{.title = "linear inductor between two nodes",
                                     .name = "Linear electric inductance",
                                     .field = "electric circuits",
                                     .dofs = "1 - node 1 (voltage) [V]\n2 - node 2 (voltage) [V]",
                                     .parameters = "1 - inductance L [H] (> 0)\n"
                                                   "2 - initial current i0 from node 1 to node 2 [A]",
                                     .work = "1 - current i = (u1 - u2) / L + i0 from node 1 to node 2 [A]",
                                     .special = "code 100 if L <= 0 or a parameter is not finite. The current "
                                                "follows from the flux linkages u (time integrals of the node "
                                                "voltages, zero at t = 0)"};
  struct parameters {
    double l = 1;   ///< inductance L [H]
    double i0 = 0;  ///< initial current [A]
  };
  parameters p;
  explicit inductor_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.5, 0.2}; }
  static inductor from_parameters(std::span<const double> v) { return inductor({v[0], v[1]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.l > 0) || !std::isfinite(p.l)) ctx.invalid_parameter("inductance L = " + to_text(p.l) + " must be finite and > 0");
    if (!std::isfinite(p.i0)) ctx.invalid_parameter("initial current i0 must be finite");
  }
  void evaluate(const local_input<inductor>& in, local_output<inductor>& out, element_context& ctx) const {
    const double g = 1.0 / p.l, i = g * (in.u(0) - in.u(1)) + p.i0;
    out.f << i, -i;
    ctx.work[0] = i;
    if (out.want_jacobian) out.K << g, -g, -g, g;
  }
};

}  // namespace pradis::elements
