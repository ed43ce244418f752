#pragma once
/// \file
/// Exact joints between two bodies in spatial motion that hold a relative
/// orientation or only part of a point: PRI3X (prismatic), FIX3X (fixed), PTL3X
/// (point on a line) and PTP3X (point on a plane). Constraint rows with Lagrange
/// multipliers as internal DOFs (exact_constraint_rows.hpp, docs/joints.md).

#include <cmath>
#include <span>
#include <string_view>
#include <tuple>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/exact_constraint_rows.hpp"
#include "pradis/elements/spatial/exact_joint_shell.hpp"
#include "pradis/elements/spatial/joints.hpp"

/// The parameter lines 13..24 of PRI3X and FIX3X (a joint frame in each body).
#define PRADIS_JOINT_FRAMES_HELP                                                                         \
  "13 - x of the joint axis e_a, body a frame (normalised; non-zero) [-]\n"                             \
  "14 - y of e_a [-]\n"                                                                                  \
  "15 - z of e_a [-]\n"                                                                                  \
  "16 - x of the reference vector t_a, body a frame (not parallel to e_a; made perpendicular) [-]\n"    \
  "17 - y of t_a [-]\n"                                                                                  \
  "18 - z of t_a [-]\n"                                                                                  \
  "19 - x of the joint axis e_b, body b frame (normalised; non-zero) [-]\n"                             \
  "20 - y of e_b [-]\n"                                                                                  \
  "21 - z of e_b [-]\n"                                                                                  \
  "22 - x of the reference vector t_b, body b frame (not parallel to e_b) [-]\n"                        \
  "23 - y of t_b [-]\n"                                                                                  \
  "24 - z of t_b [-] (R_a e_a = R_b e_b and R_a t_a = R_b t_b initially: the two frames coincide)"

namespace pradis::elements {

namespace detail {

/// The work lines 5 and 6 of PRI3X and FIX3X (the frames' misalignment and twist).
#define PRADIS_FRAME_ANGLES_WORK                                                         \
  "5 - misalignment angle between the axes R_a e_a and R_b e_b [rad]\n"                  \
  "6 - twist angle of R_b t_b from R_a t_a about the axis [rad]\n"

/// The three perpendicular rows that hold frame b on frame a (local rows r..r+2):
/// T_a . E_b = 0, N_a . E_b = 0 (the axes parallel) and N_a . T_b = 0 (no twist),
/// E = R e, T = R t, N = R n. Writes the misalignment and twist into work[w], work[w + 1].
template <class Mu, class Out>
void add_frame_rows(const joint_bodies& s, const joint_frame& fa, const joint_frame& fb, const Mu& mu, int k, int r,
                    Out& out, std::span<double> work, std::size_t w) {
  const spatial::vec3 ta = s.a.r * fa.t, na = s.a.r * fa.n, eb = s.b.r * fb.e, tb = s.b.r * fb.t;
  add_perpendicular_row(s.a, s.b, ta, eb, mu(k), r, out);
  add_perpendicular_row(s.a, s.b, na, eb, mu(k + 1), r + 1, out);
  add_perpendicular_row(s.a, s.b, na, tb, mu(k + 2), r + 2, out);
  work[w] = angle_between(s.a.r * fa.e, eb);
  work[w + 1] = std::atan2(na.dot(tb), ta.dot(tb));
}

template <class = void>
struct prismatic_kind_t;
using prismatic_kind = prismatic_kind_t<>;
/// PRI3X's rows: two line rows that keep B on the axis through A along
/// E_a = R_a e_a, and the three frame rows (add_frame_rows). Body b slides along
/// the axis only.
template <class>
struct prismatic_kind_t {
  static constexpr pradis::passport passport{
      .name = "PRI3X", .ext = 12, .ent = 7, .par = 24, .wrk = 10, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact prismatic (slider) joint between two bodies in spatial motion (constraints with multipliers)",
      .name = "Prismatic joint: a body-fixed point of b held on a body-fixed axis of a and b's frame held on a's "
              "exactly; b slides along the axis only",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP PRADIS_JOINT_FRAMES_HELP,
      .work = "1 - distance of B from the axis through A [m] (the constraints' residual)\n"
              "2 - joint force on body b, X [N] (perpendicular to the axis)\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n" PRADIS_FRAME_ANGLES_WORK
              "7 - joint moment on body b about B, about global X [N m]\n"
              "8 - about global Y [N m]\n"
              "9 - about global Z [N m]\n"
              "10 - slide s = R_a e_a . (p_B - p_A) of B along the axis [m]",
      .special = "Internal DOFs 3..4 (after the two hidden q4): the multipliers of the two line constraints [N]; "
                 "5..7: of the three orientation constraints [N m] (velocity-level unknowns). Point B should lie "
                 "on the axis and the frames coincide initially; code 100 if an axis or a reference vector is "
                 "zero, a reference vector is parallel to its axis, or a parameter is not finite; code 75 if a "
                 "quaternion norm comes near zero. The constraint rows have a zero diagonal; the joined bodies "
                 "must carry mass and inertia"};
  static constexpr int force_work = 1, moment_work = 6;
  using parameters = two_frame_parameters;
  parameters p;
  joint_frame fa, fb;  ///< the joint frames of a and b (unit vectors)
  explicit prismatic_kind_t(parameters q) : p(q), fa(q.frame_a()), fb(q.frame_b()) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2},
            0.3, -0.5, 0.8, 1.0, 0.2, -0.1, -0.2, 0.7, 0.4, 0.6, 0.3, 0.5};
  }
  void check(element_context& ctx) const { p.check(ctx); }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    constexpr int r = first_multiplier;
    add_line_row(s.a, s.b, s.a.r * fa.t, mu(0), r, out);
    add_line_row(s.a, s.b, s.a.r * fa.n, mu(1), r + 1, out);
    add_frame_rows(s, fa, fb, mu, 2, r + 2, out, work, 4);
    const spatial::vec3 ua = s.a.r * fa.e, d = s.b.p - s.a.p;
    work[0] = off_line(d, ua);
    work[9] = ua.dot(d);
  }
};

template <class = void>
struct fixed_kind_t;
using fixed_kind = fixed_kind_t<>;
/// FIX3X's rows: the point constraint and the three frame rows: body b is welded
/// to body a.
template <class>
struct fixed_kind_t {
  static constexpr pradis::passport passport{
      .name = "FIX3X", .ext = 12, .ent = 8, .par = 24, .wrk = 9, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact fixed (weld) joint between two bodies in spatial motion (constraints with multipliers)",
      .name = "Fixed joint: a body-fixed point pair held together and b's frame held on a's exactly; the joint "
              "force and moment are internal unknowns",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP PRADIS_JOINT_FRAMES_HELP,
      .work = "1 - gap |p_B - p_A| [m]\n"
              "2 - joint force on body b, X [N]\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n" PRADIS_FRAME_ANGLES_WORK
              "7 - joint moment on body b about B, about global X [N m]\n"
              "8 - about global Y [N m]\n"
              "9 - about global Z [N m]",
      .special = "Internal DOFs 3..5 (after the two hidden q4): the joint force, global X, Y, Z [N]; 6..8: the "
                 "multipliers of the three orientation constraints [N m] (velocity-level unknowns). The joint "
                 "points and the frames should coincide initially; code 100 if an axis or a reference vector is "
                 "zero, a reference vector is parallel to its axis, or a parameter is not finite; code 75 if a "
                 "quaternion norm comes near zero. The constraint rows have a zero diagonal; the joined bodies "
                 "must carry mass and inertia"};
  static constexpr int force_work = 1, moment_work = 6;
  using parameters = two_frame_parameters;
  parameters p;
  joint_frame fa, fb;  ///< the joint frames of a and b (unit vectors)
  explicit fixed_kind_t(parameters q) : p(q), fa(q.frame_a()), fb(q.frame_b()) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return prismatic_kind::example(); }
  void check(element_context& ctx) const { p.check(ctx); }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    constexpr int r = first_multiplier;
    work[0] = add_point_rows(s.a, s.b, spatial::vec3(mu(0), mu(1), mu(2)), r, out).norm();
    add_frame_rows(s, fa, fb, mu, 3, r + 3, out, work, 4);
  }
};

template <class = void>
struct point_on_line_kind_t;
using point_on_line_kind = point_on_line_kind_t<>;
/// PTL3X's rows: two line rows that keep B on the line through A along
/// R_a e (a bead on a wire); b's rotation is free.
template <class>
struct point_on_line_kind_t {
  static constexpr pradis::passport passport{
      .name = "PTL3X", .ext = 12, .ent = 4, .par = 15, .wrk = 5, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact point-on-line constraint between two bodies in spatial motion (with multipliers)",
      .name = "Point on a line: a body-fixed point B of b held on a line through A fixed in body a (a bead on a "
              "wire); the normal force is an internal unknown [N]",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP
                    "13 - x of the line's direction e, body a frame (normalised; non-zero) [-]\n"
                    "14 - y of e [-]\n"
                    "15 - z of e [-] (B should lie on the line initially)",
      .work = "1 - distance of B from the line [m] (the constraints' residual)\n"
              "2 - force on body b, X [N] (perpendicular to the line)\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n"
              "5 - position s = R_a e . (p_B - p_A) of B along the line [m]",
      .special = "Internal DOFs 3..4 (after the two hidden q4): the multipliers of the two line constraints [N] "
                 "(velocity-level unknowns). code 100 if the direction is zero or a parameter is not finite; code "
                 "75 if a quaternion norm comes near zero. The constraint rows have a zero diagonal; body b must "
                 "carry mass"};
  static constexpr int force_work = 1, moment_work = -1;
  using parameters = one_axis_parameters;
  parameters p;
  spatial::vec3 e, n1, n2;  ///< unit direction and two unit normals
  explicit point_on_line_kind_t(parameters q) : p(q), e(unit_axis(q.axis())) {
    std::tie(n1, n2) = perpendicular_pair(e);
  }
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {joint_geometry{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 0.3, -0.5, 0.8};
  }
  void check(element_context& ctx) const { check_joint_vector(ctx, "direction e", p.ex, p.ey, p.ez); }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    constexpr int r = first_multiplier;
    add_line_row(s.a, s.b, s.a.r * n1, mu(0), r, out);
    add_line_row(s.a, s.b, s.a.r * n2, mu(1), r + 1, out);
    const spatial::vec3 ua = s.a.r * e, d = s.b.p - s.a.p;
    work[0] = off_line(d, ua);
    work[4] = ua.dot(d);
  }
};

template <class = void>
struct point_on_plane_kind_t;
using point_on_plane_kind = point_on_plane_kind_t<>;
/// PTP3X's row: one line row that keeps B on the plane through A normal to R_a n
/// (frictionless contact that never lifts off); b's rotation is free.
template <class>
struct point_on_plane_kind_t {
  static constexpr pradis::passport passport{
      .name = "PTP3X", .ext = 12, .ent = 3, .par = 15, .wrk = 4, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact point-on-plane constraint between two bodies in spatial motion (with a multiplier)",
      .name = "Point on a plane: a body-fixed point B of b held on a plane through A fixed in body a; the normal "
              "force is an internal unknown [N] (bilateral: it may pull)",
      .field = "mechanics, spatial motion",
      .dofs = joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP
                    "13 - x of the plane's normal n, body a frame (normalised; non-zero) [-]\n"
                    "14 - y of n [-]\n"
                    "15 - z of n [-] (B should lie on the plane initially)",
      .work = "1 - signed distance R_a n . (p_B - p_A) of B from the plane [m] (the constraint's residual)\n"
              "2 - force on body b, X [N] (along the normal)\n"
              "3 - Y [N]\n"
              "4 - Z [N]",
      .special = "Internal DOF 3 (after the two hidden q4): the multiplier of the plane constraint [N] "
                 "(velocity-level unknown). code 100 if the normal is zero or a parameter is not finite; code 75 "
                 "if a quaternion norm comes near zero. The constraint row has a zero diagonal; body b must carry "
                 "mass"};
  static constexpr int force_work = 1, moment_work = -1;
  using parameters = one_axis_parameters;
  parameters p;
  spatial::vec3 n;  ///< unit normal
  explicit point_on_plane_kind_t(parameters q) : p(q), n(unit_axis(q.axis())) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return point_on_line_kind::example(); }
  void check(element_context& ctx) const { check_joint_vector(ctx, "normal n", p.ex, p.ey, p.ez); }
  template <class Mu, class Out>
  void rows(const joint_bodies& s, const Mu& mu, Out& out, std::span<double> work) const {
    work[0] = add_line_row(s.a, s.b, s.a.r * n, mu(0), first_multiplier, out);
  }
};

}  // namespace detail

/// PRI3X: exact prismatic (slider) joint. Point B of body b stays on the axis
/// through A along E_a = R_a e_a (two line rows, local 14, 15) and b's joint
/// frame (e_b, t_b) stays on a's (e_a, t_a) (three perpendicular rows, local
/// 16..18: T_a . E_b = N_a . E_b = N_a . T_b = 0). Body b slides along the axis.
using exact_prismatic_joint = detail::exact_joint<detail::prismatic_kind>;

/// FIX3X: exact fixed (weld) joint: SPH3X's point rows (local 14..16) and PRI3X's
/// three frame rows (local 17..19). The joint force and moment are the reactions.
using exact_fixed_joint = detail::exact_joint<detail::fixed_kind>;

/// PTL3X: exact point-on-line constraint: B stays on the line through A along
/// R_a e (two line rows n_i . (p_B - p_A) = 0, local 14, 15, n_i perpendicular to e
/// in body a).
using exact_point_on_line = detail::exact_joint<detail::point_on_line_kind>;

/// PTP3X: exact point-on-plane constraint: R_a n . (p_B - p_A) = 0 (local 14).
using exact_point_on_plane = detail::exact_joint<detail::point_on_plane_kind>;

}  // namespace pradis::elements
