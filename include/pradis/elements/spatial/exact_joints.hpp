#pragma once
/// \file
/// Exact joints between two bodies in spatial motion that hold a point: SPH3X
/// (spherical), REV3X (revolute), UNI3X (universal), and CYL3X (cylindrical,
/// which holds a line). The constraints join the model's equations and the joint
/// reactions are Lagrange multipliers (internal DOFs), instead of the penalty
/// springs of SPH3 and REV3 (docs/joints.md). PRI3X, FIX3X, PTL3X and PTP3X are in
/// exact_frame_joints.hpp.

#include <algorithm>
#include <span>
#include <string_view>
#include <tuple>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/exact_constraint_rows.hpp"
#include "pradis/elements/spatial/exact_joint_shell.hpp"
#include "pradis/elements/spatial/ground_pivot.hpp"
#include "pradis/elements/spatial/joints.hpp"

/// The parameter lines 13..18 of UNI3X (the cross axes).
#define PRADIS_CROSS_AXES_HELP                                                                  \
  "13 - x of the cross axis e_a fixed in body a, body a frame (normalised; non-zero) [-]\n"    \
  "14 - y of e_a [-]\n"                                                                         \
  "15 - z of e_a [-]\n"                                                                         \
  "16 - x of the cross axis e_b fixed in body b, body b frame (normalised; non-zero) [-]\n"    \
  "17 - y of e_b [-]\n"                                                                         \
  "18 - z of e_b [-] (R_a e_a and R_b e_b should be perpendicular initially)"
/// The parameter lines 13..18 of CYL3X (the sliding axes).
#define PRADIS_SLIDE_AXES_HELP                                                                       \
  "13 - x of the joint axis e_a through A, body a frame (normalised; non-zero) [-]\n"               \
  "14 - y of e_a [-]\n"                                                                              \
  "15 - z of e_a [-]\n"                                                                              \
  "16 - x of the joint axis e_b of body b, body b frame (normalised; non-zero) [-]\n"               \
  "17 - y of e_b [-]\n"                                                                              \
  "18 - z of e_b [-] (R_a e_a and R_b e_b should be parallel initially, and B on the axis through A)"

namespace pradis::elements {

namespace detail {

template <class = void>
struct spherical_kind_t;
using spherical_kind = spherical_kind_t<>;
/// SPH3X's rows: the point constraint p_B - p_A = 0 (multipliers: the force).
template <class>
struct spherical_kind_t {
  /// Models that list SPH3X can hold ground pivots, SPH3X to the ground in reduced form (ground_pivot.hpp).
  using node_kinds = type_list<ground_pivot_kind>;
  static constexpr pradis::passport passport{
      .name = "SPH3X", .ext = 12, .ent = 5, .par = 12, .wrk = 4, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact spherical joint between two bodies in spatial motion (constraint with multipliers)",
      .name = "Spherical joint: two body-fixed points held together exactly; the joint force is an internal "
              "unknown [N]",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = joint_geometry_help,
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
  static constexpr int force_work = 1, moment_work = -1;
  using parameters = point_joint_parameters;
  parameters p;
  explicit spherical_kind_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}};
  }
  void check(element_context&) const {}
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    work[0] = add_point_rows(s.a, s.b, spatial::vec3(mu(0), mu(1), mu(2)), first_multiplier, out).norm();
  }
};

template <class = void>
struct revolute_kind_t;
using revolute_kind = revolute_kind_t<>;
/// REV3X's rows: the point constraint and two perpendicular rows n_i . u_B = 0
/// that keep b's hinge axis u_B = R_b e_b along a's u_A = R_a e_a (n_1, n_2
/// perpendicular to e_a in a).
template <class>
struct revolute_kind_t {
  static constexpr pradis::passport passport{
      .name = "REV3X", .ext = 12, .ent = 7, .par = 18, .wrk = 8, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact revolute (hinge) joint between two bodies in spatial motion (constraints with multipliers)",
      .name = "Revolute joint: a body-fixed point pair held together and two body-fixed hinge axes held parallel "
              "exactly; the joint force and moment are internal unknowns [N, N m]",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = exact_hinge_parameter_help,
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
  static constexpr int force_work = 1, moment_work = 5;
  using parameters = two_axis_parameters;
  parameters p;
  spatial::vec3 ea, n1, n2, eb;  ///< unit e_a, two unit vectors perpendicular to it, unit e_b
  explicit revolute_kind_t(parameters q) : p(q), ea(unit_axis(q.axis_a())), eb(unit_axis(q.axis_b())) {
    std::tie(n1, n2) = perpendicular_pair(ea);
  }
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 0.3, -0.5, 0.8, -0.2, 0.7,
            0.4};
  }
  void check(element_context& ctx) const {
    check_hinge_axis(ctx, "e_a", p.eax, p.eay, p.eaz);
    check_hinge_axis(ctx, "e_b", p.ebx, p.eby, p.ebz);
  }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    constexpr int r = first_multiplier;
    work[0] = add_point_rows(s.a, s.b, spatial::vec3(mu(0), mu(1), mu(2)), r, out).norm();
    const spatial::vec3 ub = s.b.r * eb;
    add_perpendicular_row(s.a, s.b, s.a.r * n1, ub, mu(3), r + 3, out);
    add_perpendicular_row(s.a, s.b, s.a.r * n2, ub, mu(4), r + 4, out);
    work[4] = angle_between(s.a.r * ea, ub);
  }
};

template <class = void>
struct universal_kind_t;
using universal_kind = universal_kind_t<>;
/// UNI3X's rows: the point constraint and one perpendicular row
/// (R_a e_a) . (R_b e_b) = 0 that keeps the two cross axes of the spider at a
/// right angle (a Cardan joint).
template <class>
struct universal_kind_t {
  static constexpr pradis::passport passport{
      .name = "UNI3X", .ext = 12, .ent = 6, .par = 18, .wrk = 8, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact universal (Cardan) joint between two bodies in spatial motion (constraints with multipliers)",
      .name = "Universal joint: a body-fixed point pair held together exactly and two body-fixed cross axes held "
              "at a right angle; the joint force and the moment about the common normal are internal unknowns",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP PRADIS_CROSS_AXES_HELP,
      .work = "1 - gap |p_B - p_A| [m]\n"
              "2 - joint force on body b, X [N]\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n"
              "5 - deviation of the angle between the cross axes from 90 degrees [rad]\n"
              "6 - joint moment on body b about global X (along R_a e_a x R_b e_b) [N m]\n"
              "7 - about global Y [N m]\n"
              "8 - about global Z [N m]",
      .special = "Internal DOFs 3..5 (after the two hidden q4): the joint force, global X, Y, Z [N]; 6: the "
                 "multiplier of the right-angle constraint [N m] (velocity-level unknowns). Body b turns freely "
                 "about R_a e_a and about R_b e_b. The joint points should coincide and the cross axes be "
                 "perpendicular initially; code 100 if a cross axis is zero or a parameter is not finite; code 75 if "
                 "a quaternion norm comes near zero. The constraint rows have a zero diagonal; the joined bodies "
                 "must carry mass and inertia. As for any Cardan joint, b's spin follows a's non-uniformly when the "
                 "shafts are inclined, and the joint locks when the shafts stand at a right angle"};
  static constexpr int force_work = 1, moment_work = 5;
  using parameters = two_axis_parameters;
  parameters p;
  spatial::vec3 ea, eb;  ///< unit cross axes
  explicit universal_kind_t(parameters q) : p(q), ea(unit_axis(q.axis_a())), eb(unit_axis(q.axis_b())) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 0.3, -0.5, 0.8, 0.8, 0.6,
            0.1};
  }
  void check(element_context& ctx) const {
    check_joint_vector(ctx, "cross axis e_a", p.eax, p.eay, p.eaz);
    check_joint_vector(ctx, "cross axis e_b", p.ebx, p.eby, p.ebz);
  }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    constexpr int r = first_multiplier;
    work[0] = add_point_rows(s.a, s.b, spatial::vec3(mu(0), mu(1), mu(2)), r, out).norm();
    const double c = add_perpendicular_row(s.a, s.b, s.a.r * ea, s.b.r * eb, mu(3), r + 3, out);
    work[4] = std::asin(std::clamp(c, -1.0, 1.0));
  }
};

template <class = void>
struct cylindrical_kind_t;
using cylindrical_kind = cylindrical_kind_t<>;
/// CYL3X's rows: two line rows n_i . (p_B - p_A) = 0 that keep B on the axis
/// through A along u_A = R_a e_a, and two perpendicular rows n_i . u_B = 0 that
/// keep u_B = R_b e_b along u_A (n_1, n_2 perpendicular to e_a in a). Body b
/// slides along and turns about the axis.
template <class>
struct cylindrical_kind_t {
  static constexpr pradis::passport passport{
      .name = "CYL3X", .ext = 12, .ent = 6, .par = 18, .wrk = 9, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact cylindrical joint between two bodies in spatial motion (constraints with multipliers)",
      .name = "Cylindrical joint: a body-fixed point of b held on a body-fixed axis of a, and b's axis held "
              "parallel to it exactly; b slides along and turns about the axis",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP PRADIS_SLIDE_AXES_HELP,
      .work = "1 - distance of B from the axis through A [m] (the constraints' residual)\n"
              "2 - joint force on body b, X [N] (perpendicular to the axis)\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n"
              "5 - misalignment angle between u_A and u_B [rad]\n"
              "6 - joint moment on body b about B (perpendicular to the axis), about global X [N m]\n"
              "7 - about global Y [N m]\n"
              "8 - about global Z [N m]\n"
              "9 - slide s = u_A . (p_B - p_A) of B along the axis [m]",
      .special = "Internal DOFs 3..4 (after the two hidden q4): the multipliers of the two line constraints [N]; "
                 "5..6: of the two axis constraints [N m] (velocity-level unknowns). Point B should lie on the "
                 "axis and the axes be parallel initially; code 100 if an axis is zero or a parameter is not "
                 "finite; code 75 if a quaternion norm comes near zero. The constraint rows have a zero diagonal; "
                 "the joined bodies must carry mass and inertia"};
  static constexpr int force_work = 1, moment_work = 5;
  using parameters = two_axis_parameters;
  parameters p;
  spatial::vec3 ea, n1, n2, eb;  ///< unit e_a, two unit vectors perpendicular to it, unit e_b
  explicit cylindrical_kind_t(parameters q) : p(q), ea(unit_axis(q.axis_a())), eb(unit_axis(q.axis_b())) {
    std::tie(n1, n2) = perpendicular_pair(ea);
  }
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 0.3, -0.5, 0.8, -0.2, 0.7,
            0.4};
  }
  void check(element_context& ctx) const {
    check_joint_vector(ctx, "axis e_a", p.eax, p.eay, p.eaz);
    check_joint_vector(ctx, "axis e_b", p.ebx, p.eby, p.ebz);
  }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    constexpr int r = first_multiplier;
    const spatial::vec3 na1 = s.a.r * n1, na2 = s.a.r * n2, ua = s.a.r * ea, ub = s.b.r * eb;
    add_line_row(s.a, s.b, na1, mu(0), r, out);
    add_line_row(s.a, s.b, na2, mu(1), r + 1, out);
    add_perpendicular_row(s.a, s.b, na1, ub, mu(2), r + 2, out);
    add_perpendicular_row(s.a, s.b, na2, ub, mu(3), r + 3, out);
    const spatial::vec3 d = s.b.p - s.a.p;
    work[0] = off_line(d, ua);
    work[4] = angle_between(ua, ub);
    work[8] = ua.dot(d);
  }
};

}  // namespace detail

/// SPH3X: spherical (ball) joint that holds point A of body a on point B of body
/// b exactly (p = X0 + x + R(q) r, see SD3). The force lambda that the joint
/// transmits is an internal DOF triple (its velocity-level unknowns, local 14..16).
/// Flows: -lambda on A's x, y, z and -rho_A x lambda on A's q1..q3, +lambda and
/// rho_B x lambda on B's (as SPH3 with F = lambda), and the constraint rows
///
///     F_lambda = p_B - p_A = 0
///
/// (detail::add_point_rows). The rows have a zero diagonal; see LINKX for how the
/// kernel factorises them and tests Newton's convergence (docs/joints.md).
using exact_spherical_joint = detail::exact_joint<detail::spherical_kind>;

/// REV3X: exact revolute (hinge) joint. SPH3X's three point constraints with
/// their force lambda (local 14..16), and two rotational constraints that keep the
/// hinge axis u_B = R(q_b) e_b of body b perpendicular to two unit vectors n1, n2
/// of body a that are perpendicular to its hinge axis e_a (so u_B stays along
/// u_A = R(q_a) e_a), with multipliers mu_1, mu_2 (local 17, 18):
///
///     c_i = N_i . u_B = 0,   N_i = R(q_a) n_i,   i = 1, 2
///
/// (detail::add_perpendicular_row). The axes must be aligned initially; the
/// rotation about the hinge is free.
using exact_revolute_joint = detail::exact_joint<detail::revolute_kind>;

/// UNI3X: exact universal (Cardan) joint. SPH3X's point constraints and one
/// rotational constraint (R_a e_a) . (R_b e_b) = 0 between a cross axis e_a
/// fixed in body a and e_b fixed in body b; body b keeps two rotational freedoms,
/// about u_A = R_a e_a and about u_B = R_b e_b. The multiplier (local 17) is the
/// moment about the common normal u_A x u_B that the spider transmits.
using exact_universal_joint = detail::exact_joint<detail::universal_kind>;

/// CYL3X: exact cylindrical joint. Point B of body b stays on the axis through
/// point A along u_A = R_a e_a (two line constraints, local 14, 15) and b's axis
/// u_B = R_b e_b stays along u_A (two perpendicular constraints, local 16, 17).
/// Body b keeps the slide along and the turn about the axis.
using exact_cylindrical_joint = detail::exact_joint<detail::cylindrical_kind>;

}  // namespace pradis::elements
