#pragma once
// PICTRL: a proportional-integral position controller written outside the library, an
// element type that brings its own node kind (using node_kinds = ...): the integral of
// the position error is the hidden DOF of an integral node (integral_node.hpp).

#include <cmath>
#include <span>

#include <pradis/pradis.hpp>

#include "integral_node.hpp"

namespace pradis_examples {

/// PICTRL: the force of a PI controller that holds DOF 1 (x) at 0, u = -(Kp x + Ki h),
/// where DOF 2 (h) is the time integral of x (the hidden DOF of an integral node that
/// the model adds with model::add_node<integral_node>). Its flow on x is Kp x + Ki h (the
/// controller pulls x back as a spring would); it has no flow on h, whose row is the
/// node's equation.
struct pi_controller {
  static constexpr pradis::passport passport{.name = "PICTRL", .ext = 2, .par = 2, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{
      .title = "PI position controller on a DOF and the integral of its position",
      .name = "Proportional-integral controller force -(Kp x + Ki h), h = integral of x",
      .field = "control",
      .dofs = "1 - controlled displacement x [m]\n2 - its time integral h [m s] (the hidden DOF of an integral node)",
      .parameters = "1 - proportional gain Kp [N/m] (>= 0)\n2 - integral gain Ki [N/(m s)] (>= 0)",
      .work = "1 - controller force -(Kp x + Ki h) [N]",
      .special = "code 100 if a gain is negative or not finite"};
  /// The node kinds a model that lists PICTRL has.
  using node_kinds = pradis::type_list<integral_node>;
  struct parameters {
    double kp = 0;  ///< proportional gain [N/m]
    double ki = 0;  ///< integral gain [N/(m s)]
  };
  parameters p;
  explicit pi_controller(parameters q) : p(q) {}
  /// From the flat PAR list (Kp, Ki).
  static pi_controller from_parameters(std::span<const double> v) { return pi_controller({v[0], v[1]}); }
  /// NEWINT: the gains must be finite and >= 0 (code 100).
  void new_integration(pradis::element_context& ctx) const {
    if (!(p.kp >= 0) || !std::isfinite(p.kp))
      ctx.invalid_parameter("proportional gain Kp = " + pradis::to_text(p.kp) + " must be finite and >= 0");
    if (!(p.ki >= 0) || !std::isfinite(p.ki))
      ctx.invalid_parameter("integral gain Ki = " + pradis::to_text(p.ki) + " must be finite and >= 0");
  }
  void evaluate(const pradis::local_input<pi_controller>& in, pradis::local_output<pi_controller>& out,
                pradis::element_context& ctx) const {
    const double f = p.kp * in.u(0) + p.ki * in.u(1);
    out.f << f, 0.0;
    ctx.work[0] = -f;
    if (out.want_jacobian) out.K << p.kp, p.ki, 0.0, 0.0;
  }
};

}  // namespace pradis_examples
