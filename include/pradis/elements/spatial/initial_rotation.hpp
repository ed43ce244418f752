#pragma once
/// \file
/// ROT0: initial orientation and angular velocity of a spatial rotational node (zero step only).

#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

template <class = void>
struct initial_rotation_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using initial_rotation = initial_rotation_t<>;
/// ROT0: sets the initial orientation of a spatial rotational node, a rotation by
/// `angle` about `axis` (global axes), and its initial global angular velocity omega:
/// q = (e sin(angle/2), cos(angle/2)) and q' = (1/2) E(q)^T omega (so q . q' = 0).
/// It writes the hidden q4 and q4' always, and q1..q3 and their rates where they are
/// not zero (a zero component may be fixed to the ground). Produces no flow.
template <class>
struct initial_rotation_t {
  static constexpr pradis::passport passport{.name = "ROT0", .ext = 3, .ent = 1, .par = 7, .wrk = 4, .adr = 1, .ign = 23};
  /// q1..q3 are local DOFs 1..3, the hidden q4 the internal DOF 4.
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{0, 3}}};
  static constexpr element_help help{
      .title = "initial orientation and angular velocity of a spatial rotational node",
      .name = "Initial-condition element: orientation (axis and angle) and global angular velocity at t = 0",
      .field = "mechanics, spatial motion",
      .dofs = "1 - rotation potential q1 of the node [-]\n"
              "2 - rotation potential q2 [-]\n"
              "3 - rotation potential q3 [-]",
      .parameters = "1 - rotation axis, X component (global) [-]\n"
                    "2 - rotation axis, Y component [-]\n"
                    "3 - rotation axis, Z component [-] (any length; not zero unless the angle is 0)\n"
                    "4 - rotation angle about the axis [deg]\n"
                    "5 - initial angular velocity about X (global) [rad/s]\n"
                    "6 - initial angular velocity about Y [rad/s]\n"
                    "7 - initial angular velocity about Z [rad/s]",
      .work = "1 - initial q1 applied\n2 - initial q2 applied\n3 - initial q3 applied\n4 - initial q4 applied",
      .special = "code 100 if the axis is zero with a non-zero angle, a parameter is not finite, or a value is "
                 "changed after the zero step; code 90 if another element set different initial values on the node "
                 "or a non-zero component is fixed to the ground"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double ex = 1, ey = 0, ez = 0;     ///< rotation axis (global) [-]
    double angle_deg = 0;              ///< rotation angle [deg]
    double wx = 0, wy = 0, wz = 0;     ///< global angular velocity [rad/s]
  };
  parameters p;

  explicit initial_rotation_t(parameters q) : p(q) {}
  /// Parameters from an initial rotation matrix (body -> global) and a global angular velocity.
  static parameters from_matrix(const spatial::mat3& r, const spatial::vec3& omega = spatial::vec3::Zero()) {
    const spatial::axis_angle aa = spatial::to_axis_angle(spatial::from_matrix(r));
    return {aa.axis.x(), aa.axis.y(), aa.axis.z(), aa.angle * 180 / std::numbers::pi, omega.x(), omega.y(), omega.z()};
  }
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.0, 2.0, -0.5, 40.0, 0.3, -0.2, 1.0}; }
  static initial_rotation from_parameters(std::span<const double> v) {
    return initial_rotation({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
  }
  /// The initial quaternion.
  spatial::quaternion quaternion() const {
    return spatial::from_axis_angle({p.ex, p.ey, p.ez}, p.angle_deg * std::numbers::pi / 180);
  }
  /// The initial quaternion rate.
  spatial::quaternion rate() const {
    return spatial::rate_from_global_angular_velocity(quaternion(), {p.wx, p.wy, p.wz});
  }

  void new_integration(element_context& ctx) const {
    for (double x : {p.ex, p.ey, p.ez, p.angle_deg, p.wx, p.wy, p.wz})
      if (!std::isfinite(x)) ctx.invalid_parameter("axis, angle and angular velocity must be finite");
    if (p.angle_deg != 0 && !(std::hypot(p.ex, p.ey, p.ez) > 0))
      ctx.invalid_parameter("the rotation axis is zero but the angle is not");
    if (ctx.nstep > 0) {
      const spatial::quaternion q = quaternion();
      for (int k = 0; k < 4; ++k)
        if (ctx.work[static_cast<std::size_t>(k)] != q(k))
          ctx.invalid_parameter("the initial orientation cannot be changed after the zero step");
    }
  }
  void zero_step(initial_values<4>& iv, element_context& ctx) const {
    const spatial::quaternion q = quaternion(), qd = rate();
    for (int k = 0; k < 4; ++k) {
      if (k == 3 || q(k) != 0) iv.set_displacement(k, q(k));
      if (k == 3 || qd(k) != 0) iv.set_velocity(k, qd(k));
      ctx.work[static_cast<std::size_t>(k)] = q(k);
    }
  }
  /// It has no flow, so nothing of it turns against its node (core/element.hpp, HasBodyFixedFlows).
  bool body_fixed_flows() const noexcept { return true; }
  /// No flow and no Jacobian entry after the zero step: the assembler skips it (core/element.hpp, InertElement).
  static constexpr bool inert = true;
  void evaluate(const local_input<initial_rotation>&, local_output<initial_rotation>& out, element_context&) const {
    if (out.want_jacobian) out.K.setZero();
  }
};

}  // namespace pradis::elements
