#pragma once
/// \file
/// SD3 (translational spring-damper between points of two bodies) and RSD3
/// (rotational spring-damper between two rotational nodes) for spatial motion.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

template <class = void>
struct spatial_spring_damper_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using spatial_spring_damper = spatial_spring_damper_t<>;
/// SD3: linear spring-damper between a point A of body a and a point B of body b in
/// spatial motion, acting along the line AB. Each end is a translational point
/// (x, y, z: the displacements of the body's reference point, initially at X0) and a
/// rotational node (q1, q2, q3, hidden q4); the attachment point is given by its offset
/// r in the body frame. An end on the ground (all six DOFs connected to node 0) is the
/// fixed point X0 + r. With p = X0 + x + R(q) r, d = p_B - p_A, L = |d|, e = d / L,
/// L' = e . d':
///
///     T = k (L - L0) + c L'              (tension, > 0 pulls A and B together)
///     flows: -T e on A's x, y, z; -rho_A x (T e) on A's q1..q3 (rho_A = R(q_A) r_A);
///            +T e on B's x, y, z; +rho_B x (T e) on B's q1..q3; none on the q4.
///
/// dF/dd = e (k e + c (d' - e L') / L)^T + (T / L)(I - e e^T), dF/dd' = c e e^T; the
/// chain through the attached points is in detail::two_point_flows. K and C (IGN=3).
template <class>
struct spatial_spring_damper_t {
  static constexpr pradis::passport passport{.name = "SD3", .ext = 12, .ent = 2, .par = 15, .wrk = 3, .adr = 1, .ign = 3};
  /// A's q1..q3 are local DOFs 4..6 (0-based 3..5) with hidden q4 at 12; B's 10..12 (9..11) with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "spring-damper between points of two bodies in spatial motion",
      .name = "Linear spring and viscous damper along the line between two body-fixed points [N]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of body a's reference point along X [m]\n"
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
              "12 - q3 of body b [-] (connect DOFs 1-6 or 7-12 to the ground for a fixed end)",
      .parameters = "1 - initial X of body a's reference point [m]\n"
                    "2 - initial Y of body a's reference point [m]\n"
                    "3 - initial Z of body a's reference point [m]\n"
                    "4 - x of attachment point A from a's reference point, body a frame [m]\n"
                    "5 - y of A, body a frame [m]\n"
                    "6 - z of A, body a frame [m]\n"
                    "7 - initial X of body b's reference point [m]\n"
                    "8 - initial Y of body b's reference point [m]\n"
                    "9 - initial Z of body b's reference point [m]\n"
                    "10 - x of attachment point B from b's reference point, body b frame [m]\n"
                    "11 - y of B, body b frame [m]\n"
                    "12 - z of B, body b frame [m]\n"
                    "13 - stiffness k [N/m] (>= 0)\n"
                    "14 - unstressed length L0 [m] (>= 0)\n"
                    "15 - damping coefficient c on the rate of length change [N s/m] (>= 0)",
      .work = "1 - current length L [m]\n2 - rate of length change L' [m/s]\n3 - tension T = k (L - L0) + c L' [N]",
      .special = "code 100 if k < 0, L0 < 0, c < 0 or a parameter is not finite; code 75 if the length AB becomes "
                 "close to zero (its direction is undefined) or a quaternion norm comes near zero"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double xa0 = 0, ya0 = 0, za0 = 0;  ///< initial global position of body a's reference point [m]
    double rax = 0, ray = 0, raz = 0;  ///< attachment point A in body a's frame [m]
    double xb0 = 0, yb0 = 0, zb0 = 0;  ///< initial global position of body b's reference point [m]
    double rbx = 0, rby = 0, rbz = 0;  ///< attachment point B in body b's frame [m]
    double k = 0;                      ///< stiffness [N/m]
    double l0 = 0;                     ///< unstressed length [m]
    double c = 0;                      ///< damping coefficient [N s/m]
  };
  parameters p;
  /// Lengths below min_length * max(1, L0) are "close to zero" (code 75).
  static constexpr double min_length = 1e-9;

  explicit spatial_spring_damper_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2, 800.0, 0.7, 15.0}; }
  static spatial_spring_damper from_parameters(std::span<const double> v) {
    return spatial_spring_damper({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12],
                                  v[13], v[14]});
  }
  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): the spring as a line between its
  /// attachment points, and each body's arm from its reference point to them.
  template <class Drawer>
  void draw(Drawer& d) const {
    const spatial::vec3 xa{p.xa0, p.ya0, p.za0}, xb{p.xb0, p.yb0, p.zb0};
    const int a = d.body_point(xa, 0, 0, {p.rax, p.ray, p.raz});
    const int b = d.body_point(xb, 6, 1, {p.rbx, p.rby, p.rbz});
    d.line(d.body_point(xa, 0, 0, spatial::vec3::Zero()), a);
    d.line(a, b);
    d.line(b, d.body_point(xb, 6, 1, spatial::vec3::Zero()));
  }
  void new_integration(element_context& ctx) const {
    for (double x : {p.xa0, p.ya0, p.za0, p.rax, p.ray, p.raz, p.xb0, p.yb0, p.zb0, p.rbx, p.rby, p.rbz})
      if (!std::isfinite(x)) ctx.invalid_parameter("positions and offsets must be finite");
    if (!(p.k >= 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and >= 0 (k < 0)");
    if (!(p.l0 >= 0) || !std::isfinite(p.l0))
      ctx.invalid_parameter("unstressed length L0 = " + to_text(p.l0) + " must be finite and >= 0 (L0 < 0)");
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping c = " + to_text(p.c) + " must be finite and >= 0 (c < 0)");
  }
  void evaluate(const local_input<spatial_spring_damper>& in, local_output<spatial_spring_damper>& out,
                element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    const auto [a, b] = detail::two_points(in, vec3(p.xa0, p.ya0, p.za0), vec3(p.rax, p.ray, p.raz),
                                           vec3(p.xb0, p.yb0, p.zb0), vec3(p.rbx, p.rby, p.rbz));
    const vec3 d = b.p - a.p, dd = b.v - a.v;
    const double l = d.norm();
    if (!(l > min_length * std::max(1.0, p.l0))) ctx.singular("the length AB has become close to zero");
    const vec3 e = d / l;
    const double ld = e.dot(dd);
    const double t = p.k * (l - p.l0) + p.c * ld;
    ctx.work[0] = l;
    ctx.work[1] = ld;
    ctx.work[2] = t;
    const mat3 pe = mat3::Identity() - e * e.transpose();
    const vec3 dld_dd = (dd - e * ld) / l;
    const mat3 fd = e * (p.k * e + p.c * dld_dd).transpose() + (t / l) * pe;
    const mat3 fdd = p.c * e * e.transpose();
    detail::two_point_flows(a, b, vec3(t * e), fd, fdd, out);
  }
  /// States the checks may use: both quaternion norms are not near zero and A, B are apart.
  bool admissible(const local_input<spatial_spring_damper>& in) const {
    if (!detail::two_quaternions_admissible(in)) return false;
    const auto [a, b] = detail::two_points(in, spatial::vec3(p.xa0, p.ya0, p.za0), spatial::vec3(p.rax, p.ray, p.raz),
                                           spatial::vec3(p.xb0, p.yb0, p.zb0), spatial::vec3(p.rbx, p.rby, p.rbz));
    return (b.p - a.p).norm() > 0.05;
  }
};

namespace detail {
/// The rotation vector theta (global axes) of R(b) R(a)^T = R(b conj(a)), the rotation
/// that carries body a's orientation into body b's (the relative rotation conj(a) b of
/// the rule of finite rotations, expressed in global axes: theta = R(a) theta_a), with
/// the angle phi = |theta| in [0, pi], and the inverse left Jacobian of SO(3)
/// Jinv = I - [theta x] / 2 + beta [theta x]^2, beta = (1 - (phi / 2) cot(phi / 2)) / phi^2,
/// so that a small rotation dphi applied to R(b) R(a)^T changes theta by Jinv dphi.
struct relative_rotation_vector {
  spatial::vec3 theta;  ///< rotation vector [rad], global axes
  double phi = 0;       ///< angle |theta| [rad]
  spatial::mat3 jinv;   ///< inverse left Jacobian at theta
  spatial::mat3 rel;    ///< R(b) R(a)^T

  /// From the (not necessarily unit) quaternions of the two nodes.
  relative_rotation_vector(const spatial::quaternion& qa, const spatial::quaternion& qb) {
    using namespace spatial;
    quaternion r = multiply(qb, conjugate(qa));
    if (r(3) < 0) r = -r;
    const double vn = r.head<3>().norm();
    phi = 2.0 * std::atan2(vn, r(3));
    theta = (vn > 0 ? phi / vn : 2.0 / r(3)) * r.head<3>();
    const double beta = phi < 1e-4 ? 1.0 / 12.0 + phi * phi / 720.0
                                   : (1.0 - 0.5 * phi / std::tan(0.5 * phi)) / (phi * phi);
    const mat3 tx = skew(theta);
    jinv = mat3::Identity() - 0.5 * tx + beta * tx * tx;
    rel = rotation_matrix(r);
  }
};
}  // namespace detail

template <class = void>
struct rotational_spring_damper_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using rotational_spring_damper = rotational_spring_damper_t<>;
/// RSD3: linear rotational spring-damper between two spatial rotational nodes a and b
/// (either may be the fully fixed node: q1..q3 all on the ground). With theta the
/// rotation vector of the relative rotation conj(q_a) q_b (rule of finite rotations),
/// expressed in global axes (the rotation vector of R(b) R(a)^T, angle in [0, pi]), and
/// omega_rel = omega_b - omega_a:
///
///     M = k theta + c omega_rel        (the moment on b is -M, on a +M)
///     flows: -M on a's q1..q3, +M on b's q1..q3, none on the q4
///
/// dtheta/dq_b = Jinv Theta_b, dtheta/dq_a = -Jinv R(b) R(a)^T Theta_a (Theta = (2/s) E(q),
/// Jinv the inverse left Jacobian of SO(3)), d omega/dq' = Theta,
/// d omega/dq = -(2/s) (E(q') + omega q^T). The potential is k phi^2 / 2: the moment
/// jumps from k pi e to -k pi e where the relative angle passes 180 degrees.
template <class>
struct rotational_spring_damper_t {
  static constexpr pradis::passport passport{.name = "RSD3", .ext = 6, .ent = 2, .par = 2, .wrk = 4, .adr = 1, .ign = 3};
  /// a's q1..q3 are local DOFs 1..3 (0-based 0..2) with hidden q4 at 6; b's 4..6 (3..5) with q4 at 7.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{0, 6}, {3, 7}}};
  static constexpr element_help help{
      .title = "rotational spring-damper between two spatial rotational nodes",
      .name = "Linear torsional spring and viscous damper on the relative rotation of two rotational nodes [N m]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - rotation potential q1 of node a (flow: moment about X) [-]\n"
              "2 - q2 of node a [-]\n"
              "3 - q3 of node a [-]\n"
              "4 - rotation potential q1 of node b [-]\n"
              "5 - q2 of node b [-]\n"
              "6 - q3 of node b [-] (connect DOFs 1-3 or 4-6 to the ground for a fixed end)",
      .parameters = "1 - rotational stiffness k [N m/rad] (>= 0)\n"
                    "2 - rotational damping coefficient c [N m s/rad] (>= 0)",
      .work = "1 - relative rotation angle phi [rad], 0..pi\n"
              "2 - moment on node b about global X, -(k theta + c omega_rel) [N m]\n"
              "3 - moment on node b about global Y [N m]\n"
              "4 - moment on node b about global Z [N m]",
      .special = "code 100 if k < 0, c < 0 or a parameter is not finite; code 75 if a quaternion norm comes near "
                 "zero. The relative angle must stay below 180 degrees: there the shortest rotation vector, and "
                 "with it the moment, changes sign"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double k = 0;  ///< rotational stiffness [N m/rad]
    double c = 0;  ///< rotational damping [N m s/rad]
  };
  parameters p;

  explicit rotational_spring_damper_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {50.0, 2.5}; }
  static rotational_spring_damper from_parameters(std::span<const double> v) {
    return rotational_spring_damper({v[0], v[1]});
  }
  /// NEWINT: parameter checks (code 100).
  void new_integration(element_context& ctx) const {
    if (!(p.k >= 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and >= 0 (k < 0)");
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping c = " + to_text(p.c) + " must be finite and >= 0 (c < 0)");
  }
  void evaluate(const local_input<rotational_spring_damper>& in, local_output<rotational_spring_damper>& out,
                element_context& ctx) const {
    using namespace spatial;
    const quaternion qa = detail::slot_quaternion(in.u, 0, 6), qb = detail::slot_quaternion(in.u, 3, 7);
    const quaternion va = detail::slot_quaternion(in.v, 0, 6), vb = detail::slot_quaternion(in.v, 3, 7);
    const double sa = qa.squaredNorm(), sb = qb.squaredNorm();
    if (!(sa > lq_near_zero * lq_near_zero) || !(sb > lq_near_zero * lq_near_zero))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    const detail::relative_rotation_vector rr(qa, qb);
    const mat34 tha = (2.0 / sa) * e_matrix(qa), thb = (2.0 / sb) * e_matrix(qb);
    const vec3 wa = tha * va, wb = thb * vb;
    const vec3 mom = p.k * rr.theta + p.c * (wb - wa);
    out.f.setZero();
    out.f.head<3>() = -mom;
    out.f.segment<3>(3) = mom;
    ctx.work[0] = rr.phi;
    for (int i = 0; i < 3; ++i) ctx.work[static_cast<std::size_t>(i + 1)] = -mom(i);
    if (!out.want_jacobian) return;
    const mat34 dwa = -(2.0 / sa) * (e_matrix(va) + wa * qa.transpose());
    const mat34 dwb = -(2.0 / sb) * (e_matrix(vb) + wb * qb.transpose());
    const mat34 dma = -p.k * rr.jinv * rr.rel * tha - p.c * dwa;  // dM/dq_a
    const mat34 dmb = p.k * rr.jinv * thb + p.c * dwb;             // dM/dq_b
    out.K.setZero();
    out.C.setZero();
    for (int i = 0; i < 2; ++i) {
      const double sg = i == 0 ? -1.0 : 1.0;
      detail::add_quaternion_columns(out.K, 3 * i, 0, 6, sg * dma);
      detail::add_quaternion_columns(out.K, 3 * i, 3, 7, sg * dmb);
      detail::add_quaternion_columns(out.C, 3 * i, 0, 6, -sg * p.c * tha);
      detail::add_quaternion_columns(out.C, 3 * i, 3, 7, sg * p.c * thb);
    }
  }
  /// States the checks may use: quaternion norms not near zero, relative angle below 0.95 pi.
  bool admissible(const local_input<rotational_spring_damper>& in) const {
    const spatial::quaternion qa = detail::slot_quaternion(in.u, 0, 6), qb = detail::slot_quaternion(in.u, 3, 7);
    return qa.norm() > 0.2 && qb.norm() > 0.2 && detail::relative_rotation_vector(qa, qb).phi < 0.95 * std::numbers::pi;
  }
};

}  // namespace pradis::elements
