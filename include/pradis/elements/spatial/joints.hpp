#pragma once
/// \file
/// SPH3 (spherical joint) and REV3 (revolute joint) between two bodies in spatial
/// motion, as stiff penalty couplings: a spring-damper on the mismatch of two
/// attachment points and, for REV3, on the misalignment of two hinge axes. The
/// constraint is met to O(load / stiffness): a gap of F / k at a transmitted force F.

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/spatial/quaternion.hpp"

/// The parameter lines 1..12 (the joint geometry) of the help texts of the spatial
/// joints (SPH3, REV3 and the exact joints), a string literal so that each element
/// appends its own lines at compile time.
#define PRADIS_JOINT_GEOMETRY_HELP \
    "1 - initial X of body a's reference point [m]\n" \
    "2 - initial Y of body a's reference point [m]\n" \
    "3 - initial Z of body a's reference point [m]\n" \
    "4 - x of joint point A from a's reference point, body a frame [m]\n" \
    "5 - y of A, body a frame [m]\n" \
    "6 - z of A, body a frame [m]\n" \
    "7 - initial X of body b's reference point [m]\n" \
    "8 - initial Y of body b's reference point [m]\n" \
    "9 - initial Z of body b's reference point [m]\n" \
    "10 - x of joint point B from b's reference point, body b frame [m]\n" \
    "11 - y of B, body b frame [m]\n" \
    "12 - z of B, body b frame [m]\n"

/// The parameter lines 13..18 (the hinge axes) of the help texts of REV3 and REV3X.
#define PRADIS_HINGE_AXES_HELP \
    "13 - x of the hinge axis e_a, body a frame (normalised; any non-zero length) [-]\n" \
    "14 - y of e_a [-]\n" \
    "15 - z of e_a [-]\n" \
    "16 - x of the hinge axis e_b, body b frame (normalised; any non-zero length) [-]\n" \
    "17 - y of e_b [-]\n" \
    "18 - z of e_b [-]\n"

namespace pradis::elements {

namespace detail {
/// The geometry of a joint: initial reference-point positions and attachment offsets.
struct joint_geometry {
  double xa0 = 0, ya0 = 0, za0 = 0;  ///< initial global position of body a's reference point [m]
  double rax = 0, ray = 0, raz = 0;  ///< joint point A in body a's frame [m]
  double xb0 = 0, yb0 = 0, zb0 = 0;  ///< initial global position of body b's reference point [m]
  double rbx = 0, rby = 0, rbz = 0;  ///< joint point B in body b's frame [m]
  /// Whether every entry is finite.
  bool finite() const {
    for (double x : {xa0, ya0, za0, rax, ray, raz, xb0, yb0, zb0, rbx, rby, rbz})
      if (!std::isfinite(x)) return false;
    return true;
  }
  /// Animation geometry (io/model_scene.hpp): each body's arm, a line from its
  /// reference point to its joint point (a chain of bodies shows as a polyline).
  template <class Drawer>
  void draw(Drawer& d) const {
    const spatial::vec3 xa{xa0, ya0, za0}, xb{xb0, yb0, zb0};
    d.line(d.body_point(xa, 0, 0, spatial::vec3::Zero()), d.body_point(xa, 0, 0, {rax, ray, raz}));
    d.line(d.body_point(xb, 6, 1, spatial::vec3::Zero()), d.body_point(xb, 6, 1, {rbx, rby, rbz}));
  }
  /// The two attached points of a two-body element (without their derivatives when
  /// `derivatives` is false: see attached_point).
  template <class In>
  std::pair<attached_point, attached_point> points(const In& in, bool derivatives = true) const {
    return points(in, derivatives ? attached_point::level::all : attached_point::level::none);
  }
  /// The two attached points with the derivatives of `d` (attached_point::level).
  template <class In>
  std::pair<attached_point, attached_point> points(const In& in, attached_point::level d) const {
    return two_points(in, spatial::vec3(xa0, ya0, za0), spatial::vec3(rax, ray, raz), spatial::vec3(xb0, yb0, zb0),
                      spatial::vec3(rbx, rby, rbz), d);
  }
};

/// The DOF lines of the help texts of SPH3 and REV3.
inline constexpr std::string_view joint_dof_help =
    "1 - translation of body a's reference point along X [m]\n"
    "2 - along Y [m]\n"
    "3 - along Z [m]\n"
    "4 - rotation potential q1 of body a's rotational node (flow: moment about X) [-]\n"
    "5 - q2 of body a [-]\n"
    "6 - q3 of body a [-]\n"
    "7 - translation of body b's reference point along X [m]\n"
    "8 - along Y [m]\n"
    "9 - along Z [m]\n"
    "10 - rotation potential q1 of body b's rotational node [-]\n"
    "11 - q2 of body b [-]\n"
    "12 - q3 of body b [-] (connect DOFs 1-6 or 7-12 to the ground for a joint to the ground)";
/// The parameter lines 1..12 (the joint geometry) alone, for joints without further
/// parameters (SPH3X).
inline constexpr std::string_view joint_geometry_help = PRADIS_JOINT_GEOMETRY_HELP;
/// The parameter lines 1..18 (joint geometry and hinge axes) alone, for REV3X.
inline constexpr std::string_view exact_hinge_parameter_help = PRADIS_JOINT_GEOMETRY_HELP PRADIS_HINGE_AXES_HELP;
/// The parameter lines of the help text of SPH3.
inline constexpr std::string_view spherical_joint_parameter_help =
    PRADIS_JOINT_GEOMETRY_HELP
    "13 - penalty stiffness k on the gap p_B - p_A [N/m] (> 0)\n"
    "14 - penalty damping c on the gap rate [N s/m] (>= 0)";

/// The translational penalty coupling shared by SPH3 and REV3: the force
/// F = k d + c d' on the gap d = p_B - p_A between the joint points, with its flows and
/// exact Jacobian (detail::two_point_flows; sets out.f, and out.K, out.C when wanted).
/// Returns the two attached points (for the rotational part of REV3) and F.
template <class In, class Out>
std::pair<attached_point, attached_point> point_coupling(const joint_geometry& geo, double k, double c, const In& in,
                                                         Out& out, spatial::vec3& f) {
  auto ab = geo.points(in, out.want_jacobian);  // the flows use no derivative of the points
  const spatial::vec3 d = ab.second.p - ab.first.p;
  f = k * d + c * (ab.second.v - ab.first.v);
  two_point_flows(ab.first, ab.second, f, k * spatial::mat3::Identity(), c * spatial::mat3::Identity(), out);
  return ab;
}
/// v / |v| for a finite non-zero v, else v unchanged (new_integration reports it).
inline spatial::vec3 unit_axis(const spatial::vec3& v) {
  const double n = v.norm();
  return n > 0 && std::isfinite(n) ? spatial::vec3(v / n) : v;
}
/// Code 100 unless the hinge axis (x, y, z) is finite and non-zero.
inline void check_hinge_axis(element_context& ctx, const char* which, double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  if (!(n > 0) || !std::isfinite(n))
    ctx.invalid_parameter(std::string("hinge axis ") + which + " = (" + to_text(x) + ", " + to_text(y) + ", " +
                          to_text(z) + ") must be finite and non-zero (zero hinge axis or not finite)");
}
}  // namespace detail

template <class = void>
struct spherical_joint_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using spherical_joint = spherical_joint_t<>;
/// SPH3: spherical (ball) joint between point A of body a and point B of body b, as a
/// stiff isotropic spring-damper on the gap d = p_B - p_A (p = X0 + x + R(q) r, see
/// SD3): F = k d + c d', -F on A's x, y, z and -rho_A x F on A's q1..q3, +F and
/// rho_B x F on B's. A transmitted force F opens the gap by |F| / k: k is a penalty
/// parameter, to be chosen so that this is negligible (and c ~ 0.1 ... 1 x 2 sqrt(k m)
/// to damp the joint's own stiff mode, whose frequency is about sqrt(k / m)).
template <class>
struct spherical_joint_t {
  static constexpr pradis::passport passport{.name = "SPH3", .ext = 12, .ent = 2, .par = 14, .wrk = 4, .adr = 1, .ign = 3};
  /// A's q1..q3 at local 3..5 with hidden q4 at 12; B's at 9..11 with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "spherical joint (penalty) between two bodies in spatial motion",
      .name = "Spherical joint: stiff isotropic spring-damper on the gap between two body-fixed points [N]",
      .field = "mechanics, spatial motion",
      .dofs = detail::joint_dof_help,
      .parameters = detail::spherical_joint_parameter_help,
      .work = "1 - gap |p_B - p_A| [m]\n2 - joint force on body b, X [N]\n3 - Y [N]\n4 - Z [N]",
      .special = "code 100 if k <= 0, c < 0 or a parameter is not finite; code 75 if a quaternion norm comes near "
                 "zero. The constraint holds to |F| / k (F the transmitted force)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    detail::joint_geometry geo;  ///< initial positions and joint points (PAR 1..12)
    double k = 0;                ///< penalty stiffness [N/m]
    double c = 0;                ///< penalty damping [N s/m]
  };
  parameters p;

  explicit spherical_joint_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 800.0, 15.0};
  }
  static spherical_joint from_parameters(std::span<const double> v) {
    return spherical_joint({{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]}, v[12], v[13]});
  }
  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): the arms of the two bodies.
  template <class Drawer>
  void draw(Drawer& d) const {
    p.geo.draw(d);
  }
  void new_integration(element_context& ctx) const {
    if (!p.geo.finite()) ctx.invalid_parameter("positions and offsets must be finite");
    if (!(p.k > 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and > 0 (k <= 0)");
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping c = " + to_text(p.c) + " must be finite and >= 0 (c < 0)");
  }
  void evaluate(const local_input<spherical_joint>& in, local_output<spherical_joint>& out, element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    vec3 f;
    const auto [a, b] = detail::point_coupling(p.geo, p.k, p.c, in, out, f);
    ctx.work[0] = (b.p - a.p).norm();
    for (int i = 0; i < 3; ++i) ctx.work[static_cast<std::size_t>(i + 1)] = -f(i);
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<spherical_joint>& in) const { return detail::two_quaternions_admissible(in); }
};

template <class = void>
struct revolute_joint_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using revolute_joint = revolute_joint_t<>;
/// REV3: revolute (hinge) joint between body a and body b, as a stiff penalty coupling.
/// The translational part is SPH3's (detail::point_coupling): F = k d + c d' on the gap
/// d = p_B - p_A of the joint points, -F on A's x, y, z and -rho_A x F on A's q1..q3, +F
/// and rho_B x F on B's. The rotational part aligns the hinge axes u_A = R(q_a) e_a and
/// u_B = R(q_b) e_b (e_a, e_b the unit hinge axes in the body frames, normalised from
/// the parameters) and damps the relative angular velocity w = omega_b - omega_a
/// perpendicular to u_A:
///
///     M = kr (u_A x u_B) + cr P w,     P = I - u_A u_A^T
///     moment on b: -M, on a: +M;  flows: -M on a's q1..q3, +M on b's q1..q3, none on the q4
///
/// The stiffness part derives from the potential V = kr (1 - u_A . u_B): |M| = kr sin(phi)
/// for a misalignment angle phi, kr phi for small phi; phi = 180 degrees (axes
/// anti-parallel) is an unstable equilibrium. A relative rotation about u_A = u_B gives
/// u_A x u_B = 0 and P w = 0: the rotation about the hinge is free. The damping power
/// -cr w^T P w <= 0 (P symmetric, positive semidefinite) is dissipative. Jacobians
/// (du = -[u x] Theta dq, Theta = (2/s) E(q), d omega/dq = -(2/s)(E(q') + omega q^T)):
///
///     dM/dq_a  = kr [u_B x][u_A x] Theta_a + cr ((u_A . w) I + u_A w^T)[u_A x] Theta_a
///                - cr P d omega_a/dq_a
///     dM/dq_b  = -kr [u_A x][u_B x] Theta_b + cr P d omega_b/dq_b
///     dM/dq_a' = -cr P Theta_a,   dM/dq_b' = cr P Theta_b
///
/// The joint holds to O(load / stiffness): a gap |F| / k, a misalignment |M_perp| / kr.
template <class>
struct revolute_joint_t {
  static constexpr pradis::passport passport{.name = "REV3", .ext = 12, .ent = 2, .par = 22, .wrk = 8, .adr = 1, .ign = 3};
  /// A's q1..q3 at local 3..5 with hidden q4 at 12; B's at 9..11 with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "revolute (hinge) joint (penalty) between two bodies in spatial motion",
      .name = "Revolute joint: stiff spring-damper on the gap between two body-fixed points and on the "
              "misalignment of two body-fixed hinge axes [N, N m]",
      .field = "mechanics, spatial motion",
      .dofs = detail::joint_dof_help,
      .parameters = PRADIS_JOINT_GEOMETRY_HELP
                    PRADIS_HINGE_AXES_HELP
                    "19 - penalty stiffness k on the gap p_B - p_A [N/m] (> 0)\n"
                    "20 - penalty damping c on the gap rate [N s/m] (>= 0)\n"
                    "21 - rotational penalty stiffness kr on the misalignment u_A x u_B [N m/rad] (> 0)\n"
                    "22 - rotational penalty damping cr on the relative angular velocity perpendicular to u_A "
                    "[N m s/rad] (>= 0)",
      .work = "1 - gap |p_B - p_A| [m]\n"
              "2 - joint force on body b, X [N]\n"
              "3 - Y [N]\n"
              "4 - Z [N]\n"
              "5 - misalignment angle phi between u_A and u_B [rad], 0..pi\n"
              "6 - aligning moment on body b, -(kr u_A x u_B + cr P w), about global X [N m]\n"
              "7 - about global Y [N m]\n"
              "8 - about global Z [N m]",
      .special = "code 100 if k <= 0, c < 0, kr <= 0, cr < 0, a hinge axis is zero or a parameter is not finite; "
                 "code 75 if a quaternion norm comes near zero. The constraint holds to |F| / k and |M| / kr (F, M "
                 "the transmitted force and moment perpendicular to the axis); anti-parallel axes (phi = 180 "
                 "degrees) are an unstable equilibrium"};

  /// Typed parameters, in PAR order.
  struct parameters {
    detail::joint_geometry geo;         ///< initial positions and joint points (PAR 1..12)
    double eax = 0, eay = 0, eaz = 0;   ///< hinge axis in body a's frame (PAR 13..15)
    double ebx = 0, eby = 0, ebz = 0;   ///< hinge axis in body b's frame (PAR 16..18)
    double k = 0;                       ///< penalty stiffness [N/m]
    double c = 0;                       ///< penalty damping [N s/m]
    double kr = 0;                      ///< rotational penalty stiffness [N m/rad]
    double cr = 0;                      ///< rotational penalty damping [N m s/rad]
  };
  parameters p;
  spatial::vec3 ea;  ///< unit hinge axis in body a's frame
  spatial::vec3 eb;  ///< unit hinge axis in body b's frame

  explicit revolute_joint_t(parameters q)
      : p(q), ea(detail::unit_axis(spatial::vec3(q.eax, q.eay, q.eaz))), eb(detail::unit_axis(spatial::vec3(q.ebx, q.eby, q.ebz))) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 0.3, -0.5, 0.8, -0.2, 0.7, 0.4,
            800.0, 15.0, 60.0, 3.0};
  }
  static revolute_joint from_parameters(std::span<const double> v) {
    return revolute_joint({{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]},
                           v[12], v[13], v[14], v[15], v[16], v[17], v[18], v[19], v[20], v[21]});
  }
  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): the arms of the two bodies.
  template <class Drawer>
  void draw(Drawer& d) const {
    p.geo.draw(d);
  }
  void new_integration(element_context& ctx) const {
    if (!p.geo.finite()) ctx.invalid_parameter("positions and offsets must be finite");
    detail::check_hinge_axis(ctx, "e_a", p.eax, p.eay, p.eaz);
    detail::check_hinge_axis(ctx, "e_b", p.ebx, p.eby, p.ebz);
    if (!(p.k > 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and > 0 (k <= 0)");
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping c = " + to_text(p.c) + " must be finite and >= 0 (c < 0)");
    if (!(p.kr > 0) || !std::isfinite(p.kr))
      ctx.invalid_parameter("rotational stiffness kr = " + to_text(p.kr) + " must be finite and > 0 (kr <= 0)");
    if (!(p.cr >= 0) || !std::isfinite(p.cr))
      ctx.invalid_parameter("rotational damping cr = " + to_text(p.cr) + " must be finite and >= 0 (cr < 0)");
  }
  void evaluate(const local_input<revolute_joint>& in, local_output<revolute_joint>& out, element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    vec3 f;
    const auto [a, b] = detail::point_coupling(p.geo, p.k, p.c, in, out, f);
    const vec3 ua = rotation_matrix(detail::slot_quaternion(in.u, 3, 12)) * ea;
    const vec3 ub = rotation_matrix(detail::slot_quaternion(in.u, 9, 13)) * eb;
    const vec3 w = b.omega - a.omega, cx = ua.cross(ub);
    const mat3 pa = mat3::Identity() - ua * ua.transpose();
    const vec3 mom = p.kr * cx + p.cr * (pa * w);
    out.f.template segment<3>(3) -= mom;
    out.f.template segment<3>(9) += mom;
    ctx.work[0] = (b.p - a.p).norm();
    ctx.work[4] = std::atan2(cx.norm(), ua.dot(ub));
    for (int i = 0; i < 3; ++i) {
      ctx.work[static_cast<std::size_t>(i + 1)] = -f(i);
      ctx.work[static_cast<std::size_t>(i + 5)] = -mom(i);
    }
    if (!out.want_jacobian) return;
    const mat3 sa = skew(ua), sb = skew(ub);
    const mat34 dma = p.kr * sb * sa * a.theta + p.cr * (ua.dot(w) * mat3::Identity() + ua * w.transpose()) * sa * a.theta -
                      p.cr * pa * a.domega_dq;                              // dM/dq_a
    const mat34 dmb = -p.kr * sa * sb * b.theta + p.cr * pa * b.domega_dq;  // dM/dq_b
    const mat34 dva = -p.cr * pa * a.theta, dvb = p.cr * pa * b.theta;     // dM/dq_a', dM/dq_b'
    for (int i = 0; i < 2; ++i) {
      const double sg = i == 0 ? -1.0 : 1.0;
      const int r = 6 * i + 3;
      detail::add_quaternion_columns(out.K, r, 3, 12, sg * dma);
      detail::add_quaternion_columns(out.K, r, 9, 13, sg * dmb);
      detail::add_quaternion_columns(out.C, r, 3, 12, sg * dva);
      detail::add_quaternion_columns(out.C, r, 9, 13, sg * dvb);
    }
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<revolute_joint>& in) const { return detail::two_quaternions_admissible(in); }

};

}  // namespace pradis::elements

