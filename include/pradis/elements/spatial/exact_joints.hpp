#pragma once
/// \file
/// SPH3X: exact spherical joint between two bodies in spatial motion. The
/// constraint p_B - p_A = 0 of two body-fixed points joins the model's equations,
/// and the joint force is a Lagrange multiplier (three internal DOFs), instead
/// of SPH3's penalty spring (docs/joints.md).

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/elements/spatial/joints.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

/// SPH3X: spherical (ball) joint that holds point A of body a on point B of body
/// b exactly (p = X0 + x + R(q) r, see SD3). The force lambda that the joint
/// transmits is an internal DOF triple (its velocity-level unknowns, local 14..16).
/// Flows: -lambda on A's x, y, z and -rho_A x lambda on A's q1..q3, +lambda and
/// rho_B x lambda on B's (as SPH3 with F = lambda), and the constraint rows
///
///     F_lambda = p_B - p_A = 0.
///
/// Jacobian: the geometric stiffness of the force lambda held fixed (the
/// rotation of rho under lambda; detail::two_point_flows with dF/dd = 0), the
/// constraint rows d(p_B - p_A)/du = [-I, -dp_A/dq, I, dp_B/dq] in K, and the
/// multiplier columns in C. The rows have a zero diagonal; see LINKX for how the
/// kernel factorises them and tests Newton's convergence (docs/joints.md).
struct exact_spherical_joint {
  static constexpr pradis::passport passport{
      .name = "SPH3X", .ext = 12, .ent = 5, .par = 12, .wrk = 4, .adr = 1, .ign = 3};
  /// A's q1..q3 at local 3..5 with hidden q4 at 12; B's at 9..11 with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "exact spherical joint between two bodies in spatial motion (constraint with multipliers)",
      .name = "Spherical joint: two body-fixed points held together exactly; the joint force is an internal "
              "unknown [N]",
      .field = "mechanics, spatial motion",
      .dofs = detail::joint_dof_help,
      .parameters = detail::joint_geometry_help,
      .work = "1 - gap |p_B - p_A| [m] (the constraint's residual)\n"
              "2 - joint force on body b, X [N]\n"
              "3 - Y [N]\n"
              "4 - Z [N]",
      .special = "Internal DOFs 3..5 (after the two hidden q4): the force lambda on the joint, global X, Y, Z [N] "
                 "(velocity-level unknowns). The points A and B should coincide initially (else the first step closes the gap). Code 100 if a parameter is not finite; code 75 if a quaternion norm "
                 "comes near zero. The constraint rows have a zero diagonal; the joined bodies must carry mass. "
                 "Use HHT or generalized-alpha when the joint force matters: under NEWMARK it may alternate from "
                 "step to step"};

  /// Typed parameters, in PAR order.
  struct parameters {
    detail::joint_geometry geo;  ///< initial positions and joint points (PAR 1..12)
  };
  parameters p;

  explicit exact_spherical_joint(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return parameters{detail::joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}};
  }
  static exact_spherical_joint from_parameters(std::span<const double> v) {
    return exact_spherical_joint(
        parameters{detail::joint_geometry{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]}});
  }
  /// NEWINT: parameter checks (code 100).
  void new_integration(element_context& ctx) const {
    if (!p.geo.finite()) ctx.invalid_parameter("positions and offsets must be finite");
  }
  void evaluate(const local_input<exact_spherical_joint>& in, local_output<exact_spherical_joint>& out,
                element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    const auto [a, b] = p.geo.points(in);
    const vec3 lambda(in.v(14), in.v(15), in.v(16));
    const mat3 zero = mat3::Zero();
    detail::two_point_flows(a, b, lambda, zero, zero, out);  // sets f(0..11), K and C (geometric part)
    const vec3 d = b.p - a.p;
    out.f(12) = 0.0;
    out.f(13) = 0.0;
    out.f.template segment<3>(14) = d;
    ctx.work[0] = d.norm();
    for (int i = 0; i < 3; ++i) ctx.work[static_cast<std::size_t>(i + 1)] = -lambda(i);
    if (!out.want_jacobian) return;
    const detail::attached_point* pts[2] = {&a, &b};
    const double sg[2] = {-1.0, 1.0};
    for (int j = 0; j < 2; ++j) {
      // Constraint rows: d(p_B - p_A)/du of end j.
      out.K.template block<3, 3>(14, 6 * j) += sg[j] * mat3::Identity();
      detail::add_quaternion_columns(out.K, 14, 6 * j + 3, 12 + j, sg[j] * pts[j]->dp_dq);
      // Multiplier columns: the flows' derivative by lambda.
      out.C.template block<3, 3>(6 * j, 14) += sg[j] * mat3::Identity();
      out.C.template block<3, 3>(6 * j + 3, 14) += sg[j] * skew(pts[j]->rho);
    }
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<exact_spherical_joint>& in) const {
    return detail::two_quaternions_admissible(in);
  }
};

}  // namespace pradis::elements
