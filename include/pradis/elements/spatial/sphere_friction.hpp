#pragma once
/// \file
/// Coulomb stick-slip friction between two body-fixed spheres (CSPHSP): the
/// tangential force at the contact point, its flows on both bodies and its exact
/// Jacobian, with the tangent plane turning with the line of centres.

#include <Eigen/Core>

#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/elements/spatial/contact_law.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// A 3 x 14 derivative in the local layout of two-body elements: body 1's x, y, z
/// at 0..2, q1..q3 at 3..5, body 2's at 6..8 and 9..11, the hidden q4 at 12 and 13.
using mat3x14 = Eigen::Matrix<double, 3, 14>;
using row14 = Eigen::Matrix<double, 1, 14>;

/// d p / d u (or d v / d u', which is the same) of an attached point of body `body` (0 or 1).
inline mat3x14 point_columns(int body, const spatial::mat34& dq) {
  mat3x14 m = mat3x14::Zero();
  m.block<3, 3>(0, 6 * body) = spatial::mat3::Identity();
  m.block<3, 3>(0, 6 * body + 3) = dq.leftCols<3>();
  m.col(12 + body) = dq.col(3);
  return m;
}
/// Only the rotational columns (d v / d u of an attached point: dv_dq).
inline mat3x14 rotation_columns(int body, const spatial::mat34& dq) {
  mat3x14 m = mat3x14::Zero();
  m.block<3, 3>(0, 6 * body + 3) = dq.leftCols<3>();
  m.col(12 + body) = dq.col(3);
  return m;
}

/// Friction of a sphere pair. Inputs: the centres c1, c2 (attached points), the
/// radius r1, the penetration delta and the normal force with its derivatives
/// dN/du, dN/dv; the anchor material points pb1, pb2 (attached points of the
/// last accepted contact point) and the elastic slip z_old. With e the unit vector
/// from c1 to c2, P = I - e e^T, the contact point m = c1 + (r1 - delta/2) e and the
/// trial slip z = P (z_old + pb2 - pb1), friction_state gives the force F on body 2
/// (-F on body 1), applied at m. Adds the flows and, if wanted, K and C to `out`.
struct sphere_pair_friction {
  spatial::vec3 force = spatial::vec3::Zero();  ///< tangential force on body 2 [N]
  spatial::vec3 z_new = spatial::vec3::Zero();  ///< elastic slip after the return mapping [m]
  spatial::vec3 point = spatial::vec3::Zero();  ///< contact point m [m]
  bool stick = true;

  template <class Out>
  sphere_pair_friction(const attached_point& c1, const attached_point& c2, double r1, double delta, double n,
                       const row14& dn_du, const row14& dn_dv, const attached_point& pb1, const attached_point& pb2,
                       const spatial::vec3& z_old, double mu, double kt, Out& out) {
    using namespace spatial;
    const vec3 d = c2.p - c1.p;
    const double l = d.norm();
    const vec3 e = d / l;
    const mat3 pe = mat3::Identity() - e * e.transpose();
    point = c1.p + (r1 - 0.5 * delta) * e;
    const vec3 w = pb2.p - pb1.p, s = z_old + w;
    const vec3 ztr = pe * s;
    const friction_state fr(ztr, mu, kt, n);
    force = fr.force;
    z_new = fr.z_new;
    stick = fr.stick;
    const vec3 arm1 = point - (c1.p - c1.rho), arm2 = point - (c2.p - c2.rho);  // from the reference points
    out.f.template segment<3>(0) += force;
    out.f.template segment<3>(3) += arm1.cross(force);
    out.f.template segment<3>(6) -= force;
    out.f.template segment<3>(9) -= arm2.cross(force);
    if (!out.want_jacobian) return;
    const mat3x14 dc = point_columns(1, c2.dp_dq) - point_columns(0, c1.dp_dq);
    const mat3x14 de = pe * dc / l;
    const row14 ddelta = -e.transpose() * dc;
    const mat3x14 dm = point_columns(0, c1.dp_dq) - 0.5 * e * ddelta + (r1 - 0.5 * delta) * de;
    const mat3x14 dw = point_columns(1, pb2.dp_dq) - point_columns(0, pb1.dp_dq);
    const mat3x14 dz = pe * dw - (de * e.dot(s) + e * (s.transpose() * de));
    const mat3x14 df_du = fr.dforce_dz * dz + fr.dforce_dn * dn_du;
    const mat3x14 df_dv = fr.dforce_dn * dn_dv;
    // Arms: d(arm_k)/du = dm/du - d(reference point k)/du (its x columns).
    mat3x14 darm1 = dm, darm2 = dm;
    darm1.block<3, 3>(0, 0) -= mat3::Identity();
    darm2.block<3, 3>(0, 6) -= mat3::Identity();
    const mat3 fx = skew(force), a1x = skew(arm1), a2x = skew(arm2);
    const mat3x14 k0 = df_du, k1 = a1x * df_du - fx * darm1, k2 = a2x * df_du - fx * darm2;
    out.K.template block<3, 14>(0, 0) += k0;
    out.K.template block<3, 14>(3, 0) += k1;
    out.K.template block<3, 14>(6, 0) -= k0;
    out.K.template block<3, 14>(9, 0) -= k2;
    out.C.template block<3, 14>(0, 0) += df_dv;
    out.C.template block<3, 14>(3, 0) += a1x * df_dv;
    out.C.template block<3, 14>(6, 0) -= df_dv;
    out.C.template block<3, 14>(9, 0) -= a2x * df_dv;
  }
};

}  // namespace pradis::elements::detail
