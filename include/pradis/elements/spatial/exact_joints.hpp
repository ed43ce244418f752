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

namespace detail {
/// The point constraint p_B - p_A = 0 with its force lambda at local 14..16,
/// shared by SPH3X and REV3X: flows of lambda on both bodies (two_point_flows
/// with dF/dd = 0, which also zeroes K and C), the constraint rows f(14..16) = d
/// and, when wanted, their Jacobian rows in K and the multiplier columns in C.
/// Returns d = p_B - p_A.
template <class Out>
spatial::vec3 exact_point_constraint(const attached_point& a, const attached_point& b, const spatial::vec3& lambda,
                                     Out& out) {
  using namespace spatial;
  const mat3 zero = mat3::Zero();
  two_point_flows(a, b, lambda, zero, zero, out);
  const vec3 d = b.p - a.p;
  out.f.template segment<3>(14) = d;
  if (!out.want_jacobian) return d;
  const attached_point* pts[2] = {&a, &b};
  const double sg[2] = {-1.0, 1.0};
  for (int j = 0; j < 2; ++j) {
    // Constraint rows: d(p_B - p_A)/du of end j.
    out.K.template block<3, 3>(14, 6 * j) += sg[j] * mat3::Identity();
    add_quaternion_columns(out.K, 14, 6 * j + 3, 12 + j, sg[j] * pts[j]->dp_dq);
    // Multiplier columns: the flows' derivative by lambda.
    out.C.template block<3, 3>(6 * j, 14) += sg[j] * mat3::Identity();
    out.C.template block<3, 3>(6 * j + 3, 14) += sg[j] * skew(pts[j]->rho);
  }
  return d;
}
}  // namespace detail

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
                 "(velocity-level unknowns). The points A and B should coincide initially (else the first step "
                 "closes the gap); code 100 if a parameter is not finite; code 75 if a quaternion norm "
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
    const vec3 d = detail::exact_point_constraint(a, b, lambda, out);
    ctx.work[0] = d.norm();
    for (int i = 0; i < 3; ++i) ctx.work[static_cast<std::size_t>(i + 1)] = -lambda(i);
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<exact_spherical_joint>& in) const {
    return detail::two_quaternions_admissible(in);
  }
};

/// REV3X: exact revolute (hinge) joint. SPH3X's three point constraints with
/// their force lambda (local 14..16), and two rotational constraints that keep the
/// hinge axis u_B = R(q_b) e_b of body b perpendicular to two unit vectors n1, n2
/// of body a that are perpendicular to its hinge axis e_a (so u_B stays along
/// u_A = R(q_a) e_a), with multipliers mu_1, mu_2 (local 17, 18):
///
///     c_i = N_i . u_B = 0,   N_i = R(q_a) n_i,   i = 1, 2.
///
/// A turn dtheta_a of body a changes c_i by dtheta_a . (N_i x u_B), a turn of b
/// by dtheta_b . (u_B x N_i); the flows are the gradients of mu . c, moments
/// sum mu_i (N_i x u_B) on a's q1..q3 and sum mu_i (u_B x N_i) on b's. Jacobian
/// (dN = -[N x] Theta_a dq_a, du_B = -[u_B x] Theta_b dq_b):
///
///     d(N_i x u_B)/dq_a = [u_B x][N_i x] Theta_a,   d(N_i x u_B)/dq_b = -[N_i x][u_B x] Theta_b,
///     dc_i/dq_a = (N_i x u_B)^T Theta_a,           dc_i/dq_b = (u_B x N_i)^T Theta_b.
///
/// The axes must be aligned initially (u_A parallel to u_B); the rotation about
/// the hinge is free.
struct exact_revolute_joint {
  static constexpr pradis::passport passport{
      .name = "REV3X", .ext = 12, .ent = 7, .par = 18, .wrk = 8, .adr = 1, .ign = 3};
  /// A's q1..q3 at local 3..5 with hidden q4 at 12; B's at 9..11 with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "exact revolute (hinge) joint between two bodies in spatial motion (constraints with multipliers)",
      .name = "Revolute joint: a body-fixed point pair held together and two body-fixed hinge axes held parallel "
              "exactly; the joint force and moment are internal unknowns [N, N m]",
      .field = "mechanics, spatial motion",
      .dofs = detail::joint_dof_help,
      .parameters = detail::exact_hinge_parameter_help,
      .work = "1 - gap |p_B - p_A| [m]\n"
              "2 - joint force on body b, X [N]\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n"
              "5 - misalignment angle between u_A and u_B [rad]\n"
              "6 - joint moment on body b (perpendicular to the hinge), about global X [N m]\n"
              "7 - about global Y [N m]\n"
              "8 - about global Z [N m]",
      .special = "Internal DOFs 3..5 (after the two hidden q4): the joint force lambda, global X, Y, Z [N]; 6..7: "
                 "the multipliers mu_1, mu_2 of the two axis constraints [N m] (velocity-level unknowns). The "
                 "joint points and the hinge axes should coincide initially; code 100 if a hinge axis is zero or a "
                 "parameter is not finite; code 75 if a quaternion norm comes near zero. The constraint rows have "
                 "a zero diagonal; the joined bodies must carry mass and inertia. Under NEWMARK the joint force "
                 "may alternate from step to step (HHT or generalized-alpha damp it)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    detail::joint_geometry geo;        ///< initial positions and joint points (PAR 1..12)
    double eax = 0, eay = 0, eaz = 1;  ///< hinge axis in body a's frame (PAR 13..15)
    double ebx = 0, eby = 0, ebz = 1;  ///< hinge axis in body b's frame (PAR 16..18)
  };
  parameters p;
  spatial::vec3 n1, n2;  ///< unit vectors of body a perpendicular to e_a
  spatial::vec3 eb;      ///< unit hinge axis of body b

  explicit exact_revolute_joint(parameters q) : p(q) {
    const spatial::vec3 ea = detail::unit_axis(spatial::vec3(q.eax, q.eay, q.eaz));
    eb = detail::unit_axis(spatial::vec3(q.ebx, q.eby, q.ebz));
    // n1: the unit axis least aligned with e_a, made perpendicular; n2 = e_a x n1.
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(ea(i)) < std::abs(ea(k))) k = i;
    spatial::vec3 t = spatial::vec3::Zero();
    t(k) = 1.0;
    n1 = detail::unit_axis(t - ea.dot(t) * ea);
    n2 = ea.cross(n1);
  }
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return parameters{detail::joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2},
                      0.3, -0.5, 0.8, -0.2, 0.7, 0.4};
  }
  static exact_revolute_joint from_parameters(std::span<const double> v) {
    return exact_revolute_joint(
        parameters{detail::joint_geometry{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]},
                   v[12], v[13], v[14], v[15], v[16], v[17]});
  }
  /// NEWINT: parameter checks (code 100).
  void new_integration(element_context& ctx) const {
    if (!p.geo.finite()) ctx.invalid_parameter("positions and offsets must be finite");
    detail::check_hinge_axis(ctx, "e_a", p.eax, p.eay, p.eaz);
    detail::check_hinge_axis(ctx, "e_b", p.ebx, p.eby, p.ebz);
  }
  void evaluate(const local_input<exact_revolute_joint>& in, local_output<exact_revolute_joint>& out,
                element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    const auto [a, b] = p.geo.points(in);
    const vec3 lambda(in.v(14), in.v(15), in.v(16));
    const vec3 d = detail::exact_point_constraint(a, b, lambda, out);
    const mat3 ra = rotation_matrix(detail::slot_quaternion(in.u, 3, 12));
    const vec3 ub = rotation_matrix(detail::slot_quaternion(in.u, 9, 13)) * eb;
    const vec3 nn[2] = {ra * n1, ra * n2};
    const double mu[2] = {in.v(17), in.v(18)};
    vec3 moment_a = vec3::Zero();
    for (int i = 0; i < 2; ++i) {
      const vec3 g = nn[i].cross(ub);  // d c_i / d theta_a; -g = d c_i / d theta_b
      moment_a += mu[i] * g;
      out.f(17 + i) = nn[i].dot(ub);
    }
    out.f.template segment<3>(3) += moment_a;
    out.f.template segment<3>(9) -= moment_a;
    const vec3 ua = ra * detail::unit_axis(vec3(p.eax, p.eay, p.eaz));
    ctx.work[0] = d.norm();
    for (int i = 0; i < 3; ++i) {
      ctx.work[static_cast<std::size_t>(i + 1)] = -lambda(i);
      ctx.work[static_cast<std::size_t>(i + 5)] = moment_a(i);  // moment on b = -(flows on b's rows)
    }
    ctx.work[4] = std::atan2(ua.cross(ub).norm(), ua.dot(ub));
    if (!out.want_jacobian) return;
    const mat3 sub = skew(ub);
    for (int i = 0; i < 2; ++i) {
      const mat3 sn = skew(nn[i]);
      const vec3 g = nn[i].cross(ub);
      // Geometric stiffness of the moments mu_i g (a's rows) and -mu_i g (b's rows).
      const mat34 dga = sub * sn * a.theta, dgb = -(sn * sub * b.theta);
      detail::add_quaternion_columns(out.K, 3, 3, 12, mu[i] * dga);
      detail::add_quaternion_columns(out.K, 3, 9, 13, mu[i] * dgb);
      detail::add_quaternion_columns(out.K, 9, 3, 12, -mu[i] * dga);
      detail::add_quaternion_columns(out.K, 9, 9, 13, -mu[i] * dgb);
      // Constraint row c_i: (g^T Theta_a) on a's q, (-g^T Theta_b) on b's q.
      const Eigen::Matrix<double, 1, 4> ra_row = g.transpose() * a.theta, rb_row = -g.transpose() * b.theta;
      out.K.template block<1, 3>(17 + i, 3) += ra_row.template leftCols<3>();
      out.K(17 + i, 12) += ra_row(3);
      out.K.template block<1, 3>(17 + i, 9) += rb_row.template leftCols<3>();
      out.K(17 + i, 13) += rb_row(3);
      // Multiplier columns.
      out.C.template block<3, 1>(3, 17 + i) += g;
      out.C.template block<3, 1>(9, 17 + i) -= g;
    }
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<exact_revolute_joint>& in) const {
    return detail::two_quaternions_admissible(in);
  }
};

}  // namespace pradis::elements
