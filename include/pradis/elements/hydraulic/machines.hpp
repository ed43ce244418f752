#pragma once
/// \file
/// HPUMP and HMOTOR: fixed-displacement pump and motor coupling two hydraulic
/// nodes to a one-dimensional rotation (hydro-mechanical transformer).

#include <array>
#include <cmath>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

namespace hydraulic_detail {
/// The displacement machine shared by HPUMP and HMOTOR. Ports 1 and 2 (pressures p1, p2),
/// shaft 3 (angular speed w). Through flow from port 1 to port 2 and shaft torque
/// (the torque the system applies to the machine):
///   q = D w + Gl (p1 - p2),   T = D (p2 - p1) + cf w.
/// Flows: f1 = q, f2 = -q, f3 = T. Dissipated power f . v = Gl (p1 - p2)^2 + cf w^2 >= 0.
template <class E>
void displacement_machine(double d, double gl, double cf, const local_input<E>& in, local_output<E>& out,
                          element_context& ctx) {
  const double dp = in.v(0) - in.v(1), w = in.v(2);
  const double q = d * w + gl * dp, t = -d * dp + cf * w;
  out.f << q, -q, t;
  ctx.work[0] = q;
  ctx.work[1] = t;
  if (out.want_jacobian) out.C << gl, -gl, d, -gl, gl, -d, -d, d, cf;
}
inline void check_machine(element_context& ctx, double d, double gl, double cf) {
  require_positive(ctx, "displacement D", d);
  require_nonnegative(ctx, "leakage conductance Gl", gl);
  require_nonnegative(ctx, "friction coefficient cf", cf);
}
}  // namespace hydraulic_detail

template <class = void>
struct hydraulic_pump_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using hydraulic_pump = hydraulic_pump_t<>;
/// HPUMP: fixed-displacement pump (port 1 suction, port 2 delivery, DOF 3 shaft rotation):
/// delivered flow q = D w - Gl (p2 - p1), driving torque D (p2 - p1) + cf w.
/// Volumetric efficiency at (w, p2 - p1): 1 - Gl (p2 - p1) / (D w); mechanical efficiency
/// D (p2 - p1) / (D (p2 - p1) + cf w).
template <class>
struct hydraulic_pump_t {
  static constexpr pradis::passport passport{.name = "HPUMP", .ext = 3, .par = 3, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 3> domains{domain::hydraulic, domain::hydraulic, domain::mechanical};
  struct parameters {
    double displacement = 0;  ///< D [m^3/rad] (= cm^3/rev * 1e-6 / (2 pi))
    double leakage = 0;       ///< Gl [m^3/(s Pa)]
    double friction = 0;      ///< cf [N m s/rad]
  };
  static constexpr element_help help{
      .title = "fixed-displacement hydraulic pump driven by a shaft",
      .name = "Fixed-displacement pump: q = D w - Gl (p2 - p1), shaft torque D (p2 - p1) + cf w",
      .field = "hydraulics",
      .dofs = "1 - suction port pressure p1 [Pa]\n2 - delivery port pressure p2 [Pa]\n3 - shaft rotation [rad]",
      .parameters = "1 - displacement D [m^3/rad] (> 0)\n2 - internal leakage conductance Gl [m^3/(s Pa)] (>= 0)\n"
                    "3 - viscous friction coefficient cf [N m s/rad] (>= 0)",
      .work = "1 - flow q from port 1 to port 2 [m^3/s]\n2 - torque the shaft applies to the pump [N m]",
      .special = "code 100 if D is not positive or Gl, cf are negative; lossless with Gl = cf = 0"};
  parameters p;
  explicit hydraulic_pump_t(parameters q) : p(q) {}
  /// Example parameters (scaled units).
  static parameters example() { return {0.8, 0.05, 0.3}; }
  static hydraulic_pump from_parameters(std::span<const double> v) { return hydraulic_pump({v[0], v[1], v[2]}); }
  void new_integration(element_context& ctx) const {
    hydraulic_detail::check_machine(ctx, p.displacement, p.leakage, p.friction);
  }
  void evaluate(const local_input<hydraulic_pump>& in, local_output<hydraulic_pump>& out, element_context& ctx) const {
    hydraulic_detail::displacement_machine(p.displacement, p.leakage, p.friction, in, out, ctx);
  }
};

template <class = void>
struct hydraulic_motor_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using hydraulic_motor = hydraulic_motor_t<>;
/// HMOTOR: fixed-displacement motor (port 1 inlet, port 2 outlet, DOF 3 shaft rotation):
/// absorbed flow q = D w + Gl (p1 - p2), torque on the shaft D (p1 - p2) - cf w (the flow of
/// DOF 3 is its negative). The same equations as HPUMP with the ports named for a motor.
template <class>
struct hydraulic_motor_t {
  static constexpr pradis::passport passport{.name = "HMOTOR", .ext = 3, .par = 3, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 3> domains{domain::hydraulic, domain::hydraulic, domain::mechanical};
  using parameters = hydraulic_pump::parameters;
  static constexpr element_help help{
      .title = "fixed-displacement hydraulic motor driving a shaft",
      .name = "Fixed-displacement motor: q = D w + Gl (p1 - p2), output torque D (p1 - p2) - cf w",
      .field = "hydraulics",
      .dofs = "1 - inlet port pressure p1 [Pa]\n2 - outlet port pressure p2 [Pa]\n3 - shaft rotation [rad]",
      .parameters = "1 - displacement D [m^3/rad] (> 0)\n2 - internal leakage conductance Gl [m^3/(s Pa)] (>= 0)\n"
                    "3 - viscous friction coefficient cf [N m s/rad] (>= 0)",
      .work = "1 - flow q from port 1 to port 2 [m^3/s]\n2 - torque the shaft applies to the motor [N m] "
              "(minus the output torque)",
      .special = "code 100 if D is not positive or Gl, cf are negative; lossless with Gl = cf = 0"};
  parameters p;
  explicit hydraulic_motor_t(parameters q) : p(q) {}
  /// Example parameters (scaled units).
  static parameters example() { return {1.5, 0.02, 0.1}; }
  static hydraulic_motor from_parameters(std::span<const double> v) { return hydraulic_motor({v[0], v[1], v[2]}); }
  void new_integration(element_context& ctx) const {
    hydraulic_detail::check_machine(ctx, p.displacement, p.leakage, p.friction);
  }
  void evaluate(const local_input<hydraulic_motor>& in, local_output<hydraulic_motor>& out,
                element_context& ctx) const {
    hydraulic_detail::displacement_machine(p.displacement, p.leakage, p.friction, in, out, ctx);
  }
};

}  // namespace pradis::elements
