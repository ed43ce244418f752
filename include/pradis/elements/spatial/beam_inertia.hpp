#pragma once
/// \file
/// BEAMI3: the inertia of a straight spatial beam (linear-interpolation translational
/// mass and lumped rotary inertia of the cross-section), on the DOFs of BEAM3
/// (beam.hpp). docs/rotations.md.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/beam.hpp"
#include "pradis/elements/spatial/beam_kinematics.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

template <class = void>
struct beam_inertia_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using beam_inertia = beam_inertia_t<>;
/// BEAMI3: inertia of a straight beam of density rho and section A, Iy, Iz, J
/// between the points A and B with rotational nodes qa, qb (same DOFs as BEAM3).
/// Translations: the consistent mass of linearly interpolated positions,
/// (m/6) [2 1; 1 2] (m = rho A L0): exact kinetic energy of a linear displacement
/// field under any large motion, a constant matrix (no gyroscopic terms). Rotations:
/// lumped rotary inertia of the cross-section, each node carrying half the beam,
/// J_node = (rho L0 / 2) T0 diag(J, Iy, Iz) T0^T in the node's body frame; the flows
/// are those of a rigid body without mass (BODY3): n = A alpha + omega x (A omega),
/// A = R J_node R^T. The Hermite mass of the bending field is not used: it would
/// couple translations with the rotations of a moving frame.
template <class>
struct beam_inertia_t {
  static constexpr pradis::passport passport{.name = "BEAMI3", .ext = 12, .ent = 2, .par = 14, .wrk = 1, .adr = 1, .ign = 0};
  /// The rotational slots as BEAM3.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "inertia of a beam in spatial motion",
      .name = "Mass and rotary inertia of a straight beam at its two end points and rotational nodes",
      .field = "mechanics, spatial motion",
      .dofs = elastic_beam::help.dofs,
      .parameters = "1 - density rho [kg/m^3] (> 0)\n"
                    "2 - cross-section area A [m^2] (> 0)\n"
                    "3 - second moment of area Iy about the section's local y axis [m^4] (> 0)\n"
                    "4 - second moment of area Iz about the local z axis [m^4] (> 0)\n"
                    "5 - polar moment of the section Ip for the rotary inertia about the axis [m^4] (> 0)\n"
                    "6 - initial X of end A [m]\n"
                    "7 - initial Y of end A [m]\n"
                    "8 - initial Z of end A [m]\n"
                    "9 - initial X of end B [m]\n"
                    "10 - initial Y of end B [m]\n"
                    "11 - initial Z of end B [m] (B must differ from A)\n"
                    "12 - X of a vector giving the section's local y axis (its part normal to A -> B) [-]\n"
                    "13 - Y of that vector [-]\n"
                    "14 - Z of that vector [-]",
      .work = "1 - kinetic energy [J]",
      .special = "code 100 if rho, A, Iy, Iz or Ip is not positive, A and B coincide, the section vector is parallel "
                 "to A -> B or a parameter is not finite; code 75 if a quaternion norm comes near zero"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double rho = 0, a = 0, iy = 0, iz = 0, ip = 0;  ///< rho [kg/m^3]; A [m^2]; Iy, Iz, Ip [m^4]
    double xa = 0, ya = 0, za = 0;                  ///< initial position of end A [m]
    double xb = 1, yb = 0, zb = 0;                  ///< initial position of end B [m]
    double vx = 0, vy = 1, vz = 0;                  ///< vector of the section's local y axis
  };
  parameters p;

  explicit beam_inertia_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {7.0, 0.5, 0.2, 0.1, 0.3, 0.1, -0.2, 0.3, 3.0, 1.5, -1.0, 0.2, 0.3, 1.0}; }
  static beam_inertia from_parameters(std::span<const double> v) {
    return beam_inertia({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12], v[13]});
  }
  /// The reference geometry.
  detail::beam_geometry geometry() const { return {{p.xa, p.ya, p.za}, {p.xb, p.yb, p.zb}, {p.vx, p.vy, p.vz}}; }
  /// Mass rho A L0 [kg].
  double mass() const { return p.rho * p.a * geometry().length(); }
  /// The rotary inertia tensor of one node in its body frame [kg m^2].
  spatial::mat3 node_inertia() const {
    const detail::beam_geometry g = geometry();
    const spatial::mat3 t = g.frame();
    return (0.5 * p.rho * g.length()) * t * spatial::vec3(p.ip, p.iy, p.iz).asDiagonal() * t.transpose();
  }

  /// NEWINT: positive density and section, distinct ends, a usable section vector (code 100).
  /// Animation geometry (io/model_scene.hpp): a line between the two end points.
  template <class Drawer>
  void draw(Drawer& d) const {
    d.line(d.body_point({p.xa, p.ya, p.za}, 0, 0, spatial::vec3::Zero()),
           d.body_point({p.xb, p.yb, p.zb}, 6, 1, spatial::vec3::Zero()));
  }
  void new_integration(element_context& ctx) const {
    for (double x : {p.rho, p.a, p.iy, p.iz, p.ip, p.xa, p.ya, p.za, p.xb, p.yb, p.zb, p.vx, p.vy, p.vz})
      if (!std::isfinite(x)) ctx.invalid_parameter("the parameters must be finite");
    if (!(p.rho > 0)) ctx.invalid_parameter("density rho = " + to_text(p.rho) + " must be > 0");
    if (!(p.a > 0)) ctx.invalid_parameter("area A = " + to_text(p.a) + " must be > 0");
    if (!(p.iy > 0) || !(p.iz > 0) || !(p.ip > 0))
      ctx.invalid_parameter("second moments of area Iy = " + to_text(p.iy) + ", Iz = " + to_text(p.iz) +
                            ", Ip = " + to_text(p.ip) + " must be > 0");
    const detail::beam_geometry g = geometry();
    if (!(g.length() > elastic_beam::min_length)) ctx.invalid_parameter("ends A and B coincide: the length of the beam is zero");
    if (!g.section_ok()) ctx.invalid_parameter("the section vector is zero or parallel to the beam axis A -> B");
  }

  void evaluate(const local_input<beam_inertia>& in, local_output<beam_inertia>& out, element_context& ctx) const {
    using namespace spatial;
    const double m6 = mass() / 6.0;
    const vec3 aa = in.a.head<3>(), ab = in.a.segment<3>(6);
    out.f.setZero();
    out.f.head<3>() = m6 * (2.0 * aa + ab);
    out.f.segment<3>(6) = m6 * (aa + 2.0 * ab);
    const vec3 va = in.v.head<3>(), vb = in.v.segment<3>(6);
    double kinetic = m6 * (va.squaredNorm() + va.dot(vb) + vb.squaredNorm());
    const mat3 j = node_inertia();
    if (out.want_jacobian) {
      out.K.setZero();
      out.C.setZero();
      out.M.setZero();
      for (int i : {0, 6}) {
        out.M.block<3, 3>(i, i) = 2.0 * m6 * mat3::Identity();
        out.M.block<3, 3>(i, 6 - i) = m6 * mat3::Identity();
      }
    }
    for (int node = 0; node < 2; ++node) {
      const int i1 = node == 0 ? 3 : 9, i4 = node == 0 ? 12 : 13;
      const quaternion q(in.u(i1), in.u(i1 + 1), in.u(i1 + 2), in.u(i4));
      const quaternion qd(in.v(i1), in.v(i1 + 1), in.v(i1 + 2), in.v(i4));
      const quaternion qdd(in.a(i1), in.a(i1 + 1), in.a(i1 + 2), in.a(i4));
      const double s = q.squaredNorm();
      if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
      // As BODY3 with m = 0 and the centre of mass at the node (docs/rotations.md).
      const mat3 r = rotation_matrix(q);
      const mat34 e = e_matrix(q);
      const double g = q.dot(qd);
      const vec3 w = (2.0 / s) * (e * qd);
      const vec3 alpha1 = (2.0 / s) * (e * qdd);
      const vec3 alpha = alpha1 - (2.0 * g / s) * w;
      const mat3 a = r * j * r.transpose();
      const vec3 h = a * w;
      out.f.segment<3>(i1) = a * alpha + w.cross(h);
      kinetic += 0.5 * w.dot(h);
      if (!out.want_jacobian) continue;
      const mat3 sw = skew(w), sa = skew(alpha);
      const mat3 dn_dw = -skew(h) + sw * a;
      const mat3 dn_dth = -skew(a * alpha) + a * sa + sw * (-skew(h) + a * sw);
      const mat34 dth_dq = (2.0 / s) * e;
      const mat34 dw_dq = -(2.0 / s) * (e_matrix(qd) + w * q.transpose());
      const mat34 dw_dqd = (2.0 / s) * e;
      const mat34 dal_dq = -(2.0 / s) * e_matrix(qdd) - (2.0 / s) * alpha1 * q.transpose() -
                           (2.0 / s) * w * qd.transpose() - (2.0 * g / s) * dw_dq + (4.0 * g / (s * s)) * w * q.transpose();
      const mat34 dal_dqd = -(2.0 / s) * (w * q.transpose() + g * dw_dqd);
      const mat34 kq = dn_dth * dth_dq + dn_dw * dw_dq + a * dal_dq;
      const mat34 cq = dn_dw * dw_dqd + a * dal_dqd;
      const mat34 mq = a * ((2.0 / s) * e);
      out.K.block<3, 3>(i1, i1) = kq.leftCols<3>();
      out.K.block<3, 1>(i1, i4) = kq.col(3);
      out.C.block<3, 3>(i1, i1) = cq.leftCols<3>();
      out.C.block<3, 1>(i1, i4) = cq.col(3);
      out.M.block<3, 3>(i1, i1) = mq.leftCols<3>();
      out.M.block<3, 1>(i1, i4) = mq.col(3);
    }
    ctx.work[0] = kinetic;
  }

  /// States the checks may use: the quaternion norms are not near zero.
  bool admissible(const local_input<beam_inertia>& in) const {
    return spatial::quaternion(in.u(3), in.u(4), in.u(5), in.u(12)).norm() > 0.2 &&
           spatial::quaternion(in.u(9), in.u(10), in.u(11), in.u(13)).norm() > 0.2;
  }
};

}  // namespace pradis::elements
