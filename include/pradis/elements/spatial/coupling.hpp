#pragma once
/// \file
/// SHC3: the elastic shaft coupling between a one-dimensional rotational DOF and a
/// spatial rotational node (the coupling element of PRADIS's Fig. 2). It is the way to
/// drive or load a spatial node from one-dimensional elements: kinematic sources,
/// point masses used as rotational inertias, springs and dampers on an angle.

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
struct shaft_coupling_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using shaft_coupling = shaft_coupling_t<>;
/// SHC3: a short elastic shaft along the fixed global unit axis a. End 1 is a
/// one-dimensional rotational DOF phi (an angle about a, flow: torque about a); end 2 is
/// a spatial rotational node q = (v, w) (q1..q3 external, hidden q4 = w). The node's
/// rotation angle about a is its twist theta = 2 atan2(a.v, w) (the angle of the
/// twist-swing decomposition; the same for a in global or body axes, since R(q) leaves
/// v unchanged). The coupling twist delta = theta - phi is computed as
///
///     delta = 2 atan2(c t - s w, c w + s t),   t = a.v,  (c, s) = (cos, sin)(phi / 2)
///
/// (the twist of the relative rotation conj(r(phi)) q, r(phi) the rotation by phi about
/// a), which stays continuous through any number of revolutions of both ends. With
/// rho2 = t^2 + w^2, g = d delta/dq = (2 / rho2) (w a, -t) and the moment direction
/// m = E(q) g / 2 = (w^2 a + w v x a + t v) / rho2 (m = a while the node only turns
/// about a):
///
///     delta' = m . omega - phi' = g . q' - phi'
///     tau    = k (delta - delta0) + c delta'       (torque in the shaft)
///     flows: -tau on phi;  tau m on q1, q2, q3 (moments about X, Y, Z);  none on q4
///
/// The spring part derives from the potential k (delta - delta0)^2 / 2; the torque acts
/// about a as long as the node does not swing away from a. The twist is undefined where
/// the node has turned 180 degrees about an axis perpendicular to a (t = w = 0): code 75.
/// K (phi and q columns, q4 included) and C, exact (IGN = 3).
template <class>
struct shaft_coupling_t {
  static constexpr pradis::passport passport{.name = "SHC3", .ext = 4, .ent = 1, .par = 6, .wrk = 3, .adr = 1, .ign = 3};
  /// q1..q3 are local DOFs 2..4 (0-based 1..3), the hidden q4 the internal DOF 5 (4).
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{1, 4}}};
  static constexpr element_help help{
      .title = "elastic shaft coupling from a one-dimensional rotation to a spatial rotational node",
      .name = "Torsional spring and damper between an angle about a fixed axis and the twist of a spatial node "
              "about that axis [N m]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - rotation angle phi of the one-dimensional end about the shaft axis [rad] (flow: torque about "
              "the axis [N m])\n"
              "2 - rotation potential q1 of the spatial end's rotational node (flow: moment about X) [-]\n"
              "3 - q2 of the spatial end [-]\n"
              "4 - q3 of the spatial end [-]",
      .parameters = "1 - X component of the shaft axis a, global axes (normalised) [-]\n"
                    "2 - Y component of the shaft axis [-]\n"
                    "3 - Z component of the shaft axis [-]\n"
                    "4 - torsional stiffness k [N m/rad] (> 0)\n"
                    "5 - torsional damping c on the twist rate [N m s/rad] (>= 0)\n"
                    "6 - unstressed twist delta0 [rad]",
      .work = "1 - twist delta = theta - phi of the coupling [rad]\n"
              "2 - twist rate delta' [rad/s]\n"
              "3 - torque tau = k (delta - delta0) + c delta' carried from the spatial end to the "
              "one-dimensional end [N m]",
      .special = "code 100 if the axis is zero, k <= 0, c < 0 or a parameter is not finite; code 75 if the "
                 "quaternion norm comes near zero or the spatial node turns 180 degrees about an axis "
                 "perpendicular to the shaft (the twist is undefined there). The twist must stay within "
                 "+-360 degrees: there it wraps to the other sign"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double ax = 0, ay = 0, az = 1;  ///< shaft axis, global axes (normalised by the element)
    double k = 0;                   ///< torsional stiffness [N m/rad]
    double c = 0;                   ///< torsional damping [N m s/rad]
    double delta0 = 0;              ///< unstressed twist [rad]
  };
  parameters p;

  explicit shaft_coupling_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.0, 2.0, -2.0, 400.0, 3.0, 0.1}; }
  static shaft_coupling from_parameters(std::span<const double> v) {
    return shaft_coupling({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  /// The unit shaft axis.
  spatial::vec3 axis() const { return spatial::vec3(p.ax, p.ay, p.az).normalized(); }

  /// NEWINT: parameter checks (code 100).
  void new_integration(element_context& ctx) const {
    for (double x : {p.ax, p.ay, p.az, p.delta0})
      if (!std::isfinite(x)) ctx.invalid_parameter("the axis and delta0 must be finite");
    if (!(spatial::vec3(p.ax, p.ay, p.az).norm() > 1e-12))
      ctx.invalid_parameter("the shaft axis (" + to_text(p.ax) + ", " + to_text(p.ay) + ", " + to_text(p.az) +
                            ") is zero (zero axis)");
    if (!(p.k > 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and > 0 (k <= 0)");
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping c = " + to_text(p.c) + " must be finite and >= 0 (c < 0)");
  }

  void evaluate(const local_input<shaft_coupling>& in, local_output<shaft_coupling>& out, element_context& ctx) const {
    using namespace spatial;
    const quaternion q = detail::slot_quaternion(in.u, 1, 4), qd = detail::slot_quaternion(in.v, 1, 4);
    const double s = q.squaredNorm();
    if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    const vec3 a = axis();
    const vec3 v = q.head<3>();
    const double w = q(3), t = a.dot(v), rho2 = t * t + w * w;
    if (!(rho2 > 1e-6 * s))
      ctx.singular("the spatial node has turned 180 degrees about an axis perpendicular to the shaft: its twist "
                   "about the shaft axis is undefined");
    const double phi = in.u(0), cs = std::cos(0.5 * phi), sn = std::sin(0.5 * phi);
    const double delta = 2.0 * std::atan2(cs * t - sn * w, cs * w + sn * t);
    quaternion g;
    g << (2.0 * w / rho2) * a, -2.0 * t / rho2;
    const vec3 vxa = v.cross(a);
    const vec3 m = (w * w * a + w * vxa + t * v) / rho2;
    const double rate = g.dot(qd) - in.v(0);
    const double tau = p.k * (delta - p.delta0) + p.c * rate;
    out.f(0) = -tau;
    out.f.segment<3>(1) = tau * m;
    out.f(4) = 0.0;
    ctx.work[0] = delta;
    ctx.work[1] = rate;
    ctx.work[2] = tau;
    if (!out.want_jacobian) return;
    // H = dg/dq (symmetric): [[-4wt/rho2^2 a a^T, 2(t^2 - w^2)/rho2^2 a], [sym, 4tw/rho2^2]].
    const double r4 = rho2 * rho2;
    Eigen::Matrix4d h;
    h.topLeftCorner<3, 3>() = (-4.0 * w * t / r4) * a * a.transpose();
    h.topRightCorner<3, 1>() = (2.0 * (t * t - w * w) / r4) * a;
    h.bottomLeftCorner<1, 3>() = h.topRightCorner<3, 1>().transpose();
    h(3, 3) = 4.0 * t * w / r4;
    const quaternion dtau_dq = p.k * g + p.c * h * qd;  // d tau / dq; d tau / dphi = -k
    // dm/dq = [dn/dv, dn/dw] / rho2 - n (2 t a, 2 w)^T / rho2^2, n = w^2 a + w v x a + t v.
    mat34 dm;
    dm.leftCols<3>() = (-w * skew(a) + v * a.transpose() + t * mat3::Identity()) / rho2;
    dm.col(3) = (2.0 * w * a + vxa) / rho2;
    quaternion drho2;
    drho2 << 2.0 * t * a, 2.0 * w;
    dm -= m * drho2.transpose() / rho2;
    out.K.setZero();
    out.C.setZero();
    // Row 0: -tau.
    out.K(0, 0) = p.k;
    out.K.block<1, 3>(0, 1) = -dtau_dq.head<3>().transpose();
    out.K(0, 4) = -dtau_dq(3);
    out.C(0, 0) = p.c;
    out.C.block<1, 3>(0, 1) = -p.c * g.head<3>().transpose();
    out.C(0, 4) = -p.c * g(3);
    // Rows 1..3: tau m.
    out.K.block<3, 1>(1, 0) = -p.k * m;
    detail::add_quaternion_columns(out.K, 1, 1, 4, mat34(m * dtau_dq.transpose() + tau * dm));
    out.C.block<3, 1>(1, 0) = -p.c * m;
    detail::add_quaternion_columns(out.C, 1, 1, 4, mat34(p.c * m * g.transpose()));
  }
  /// States the checks may use: the quaternion norm is not near zero, the node is not
  /// near the 180-degree swing, and the twist is away from its +-360-degree wrap.
  bool admissible(const local_input<shaft_coupling>& in) const {
    const spatial::quaternion q = detail::slot_quaternion(in.u, 1, 4);
    const double t = axis().dot(q.head<3>()), w = q(3), phi = in.u(0);
    if (!(q.norm() > 0.2) || !(t * t + w * w > 0.1 * q.squaredNorm())) return false;
    const double cs = std::cos(0.5 * phi), sn = std::sin(0.5 * phi);
    return std::abs(std::atan2(cs * t - sn * w, cs * w + sn * t)) < 0.95 * std::numbers::pi;
  }
};

}  // namespace pradis::elements
