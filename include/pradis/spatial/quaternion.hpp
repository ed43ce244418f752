#pragma once
/// \file
/// Quaternion utilities for spatial rotations with NON-normalised quaternions, as
/// the potentials of a PRADIS rotational node: q = (q1, q2, q3, q4), vector part
/// v = (q1, q2, q3), scalar part q4, s = q.q = Lq^2. Every formula below is
/// invariant under q -> c q (c != 0), so it holds for any |q| > 0:
///
///     R(q)  = [ (q4^2 - v.v) I + 2 v v^T + 2 q4 [v x] ] / s      (body -> global)
///     E(q)  = [ q4 I + [v x] , -v ]   (3 x 4),   G(q) = [ q4 I - [v x] , -v ]
///     omega (global) = (2/s) E(q) q',   omega (body) = (2/s) G(q) q' = R^T omega
///     E q = G q = 0,   E E^T = G G^T = s I,   E^T E = G^T G = s I4 - q q^T
///     a global torque n does the virtual work n . dtheta = Q . dq with Q = (2/s) E^T n
///
/// [v x] is the cross-product matrix, [v x] w = v x w. The conventions (Rodrigues'
/// active rotation by phi about the unit axis e for q = (e sin(phi/2), cos(phi/2)),
/// Hamilton product with the scalar last, R(a b) = R(a) R(b)) are checked
/// numerically in tests/spatial/test_quaternion.cpp. References: P. E. Nikravesh,
/// Computer-Aided Analysis of Mechanical Systems (1988), ch. 6; E. J. Haug,
/// Computer Aided Kinematics and Dynamics of Mechanical Systems (1989), ch. 9.
///
/// Everything here works on fixed-size Eigen types and never allocates.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace pradis::spatial {

/// A quaternion (q1, q2, q3, q4): vector part first, scalar part q4 last.
using quaternion = Eigen::Vector4d;
/// A 3-vector.
using vec3 = Eigen::Vector3d;
/// A 3 x 3 matrix.
using mat3 = Eigen::Matrix3d;
/// A 3 x 4 matrix (E(q), G(q)).
using mat34 = Eigen::Matrix<double, 3, 4>;

/// The cross-product matrix [v x]: skew(v) * w = v x w.
inline mat3 skew(const vec3& v) {
  mat3 m;  // element by element: cheaper than a comma initializer in a hot loop
  m(0, 0) = 0, m(0, 1) = -v.z(), m(0, 2) = v.y();
  m(1, 0) = v.z(), m(1, 1) = 0, m(1, 2) = -v.x();
  m(2, 0) = -v.y(), m(2, 1) = v.x(), m(2, 2) = 0;
  return m;
}

/// The identity rotation (0, 0, 0, 1).
inline quaternion identity() { return quaternion(0, 0, 0, 1); }

/// Vector part (q1, q2, q3).
inline vec3 vector_part(const quaternion& q) { return q.head<3>(); }

/// E(q) = [q4 I + [v x], -v]: global angular velocity omega = (2/s) E(q) q'.
/// Linear in q; E(q) p = -E(p) q for any p, and E(q) q = 0.
inline mat34 e_matrix(const quaternion& q) {
  mat34 e;
  e(0, 0) = q(3), e(0, 1) = -q(2), e(0, 2) = q(1), e(0, 3) = -q(0);
  e(1, 0) = q(2), e(1, 1) = q(3), e(1, 2) = -q(0), e(1, 3) = -q(1);
  e(2, 0) = -q(1), e(2, 1) = q(0), e(2, 2) = q(3), e(2, 3) = -q(2);
  return e;
}

/// G(q) = [q4 I - [v x], -v]: body angular velocity omega' = (2/s) G(q) q'.
inline mat34 g_matrix(const quaternion& q) {
  mat34 g;
  g(0, 0) = q(3), g(0, 1) = q(2), g(0, 2) = -q(1), g(0, 3) = -q(0);
  g(1, 0) = -q(2), g(1, 1) = q(3), g(1, 2) = q(0), g(1, 3) = -q(1);
  g(2, 0) = q(1), g(2, 1) = -q(0), g(2, 2) = q(3), g(2, 3) = -q(2);
  return g;
}

/// Rotation matrix R(q) (body -> global) of a non-zero, not necessarily unit, quaternion.
inline mat3 rotation_matrix(const quaternion& q) {
  const double x = q(0), y = q(1), z = q(2), w = q(3);
  const double s = x * x + y * y + z * z + w * w, d = w * w - (x * x + y * y + z * z), t = 2.0 / s;
  mat3 r;
  r(0, 0) = (d + 2 * x * x) / s, r(0, 1) = t * (x * y - w * z), r(0, 2) = t * (x * z + w * y);
  r(1, 0) = t * (x * y + w * z), r(1, 1) = (d + 2 * y * y) / s, r(1, 2) = t * (y * z - w * x);
  r(2, 0) = t * (x * z - w * y), r(2, 1) = t * (y * z + w * x), r(2, 2) = (d + 2 * z * z) / s;
  return r;
}

/// Global angular velocity omega = (2/s) E(q) q'.
inline vec3 global_angular_velocity(const quaternion& q, const quaternion& qdot) {
  return (2.0 / q.squaredNorm()) * (e_matrix(q) * qdot);
}

/// Body angular velocity omega' = (2/s) G(q) q' (= R(q)^T omega).
inline vec3 body_angular_velocity(const quaternion& q, const quaternion& qdot) {
  return (2.0 / q.squaredNorm()) * (g_matrix(q) * qdot);
}

/// Global angular acceleration: d/dt of global_angular_velocity,
/// alpha = (2/s) E(q) q'' - (4 (q.q') / s^2) E(q) q' (the term E(q') q' vanishes).
/// Exact also when |q| changes in time.
inline vec3 global_angular_acceleration(const quaternion& q, const quaternion& qdot, const quaternion& qddot) {
  const double s = q.squaredNorm();
  const mat34 e = e_matrix(q);
  return (2.0 / s) * (e * qddot) - (4.0 * q.dot(qdot) / (s * s)) * (e * qdot);
}

/// The quaternion rate of a global angular velocity: q' = (1/2) E(q)^T omega, the
/// solution of omega = (2/s) E(q) q' with q.q' = 0 (|q| constant).
inline quaternion rate_from_global_angular_velocity(const quaternion& q, const vec3& omega) {
  return 0.5 * (e_matrix(q).transpose() * omega);
}

/// Generalized force on q of a global torque n: Q = (2/s) E(q)^T n, so that
/// Q . dq = n . dtheta for every variation dq (dtheta = (2/s) E(q) dq).
inline quaternion generalized_force(const quaternion& q, const vec3& n) {
  return (2.0 / q.squaredNorm()) * (e_matrix(q).transpose() * n);
}

/// Hamilton product a b, scalar last: R(a b) = R(a) R(b) (first b, then a, both in
/// global axes). |a b| = |a| |b|.
inline quaternion multiply(const quaternion& a, const quaternion& b) {
  const vec3 av = a.head<3>(), bv = b.head<3>();
  quaternion r;
  r.head<3>() = a(3) * bv + b(3) * av + av.cross(bv);
  r(3) = a(3) * b(3) - av.dot(bv);
  return r;
}

/// Conjugate (-v, q4): R(conjugate(q)) = R(q)^T.
inline quaternion conjugate(const quaternion& q) { return quaternion(-q(0), -q(1), -q(2), q(3)); }

/// Relative rotation of node b with respect to node a by the rule of finite rotations:
/// r = conjugate(a) b, so that R(r) = R(a)^T R(b) (b's orientation in a's frame)
/// and multiply(a, r) is parallel to b. |r| = |a| |b|.
inline quaternion relative_rotation(const quaternion& a, const quaternion& b) { return multiply(conjugate(a), b); }

/// Unit quaternion of a rotation by `angle` [rad] about `axis` (any non-zero length;
/// a zero axis gives the identity).
inline quaternion from_axis_angle(const vec3& axis, double angle) {
  const double n = axis.norm();
  if (!(n > 0)) return identity();
  quaternion q;
  q.head<3>() = std::sin(angle / 2) / n * axis;
  q(3) = std::cos(angle / 2);
  return q;
}

/// Axis (unit) and angle in [0, pi] of a rotation.
struct axis_angle {
  vec3 axis = vec3::UnitX();  ///< unit rotation axis (X for the identity)
  double angle = 0;           ///< rotation angle [rad], 0 <= angle <= pi
};

/// Axis and angle of the rotation of a non-zero quaternion. Uses atan2 on (|v|, |q4|),
/// accurate at every angle including 0 and pi (q and -q give the same result).
inline axis_angle to_axis_angle(const quaternion& q) {
  const quaternion p = q(3) < 0 ? quaternion(-q) : q;
  const double vn = p.head<3>().norm();
  axis_angle r;
  if (!(vn > 0)) return r;
  r.axis = p.head<3>() / vn;
  r.angle = 2.0 * std::atan2(vn, p(3));
  return r;
}

/// Unit quaternion (with q4 >= 0) of a rotation matrix, by Shepperd's method: the
/// largest of 1 + trace, 1 + 2 R11 - trace, ... is used as the pivot, so the result
/// is accurate at every angle including pi (S. W. Shepperd, J. Guidance and Control
/// 1 (1978) 223). R must be a rotation matrix (orthogonal, det = +1).
inline quaternion from_matrix(const mat3& r) {
  const double tr = r.trace();
  const double c[4] = {1 + 2 * r(0, 0) - tr, 1 + 2 * r(1, 1) - tr, 1 + 2 * r(2, 2) - tr, 1 + tr};  // 4 q_k^2
  const int k = static_cast<int>(std::max_element(c, c + 4) - c);
  quaternion q;
  const double d = std::sqrt(c[k]);  // 2 |q_k|
  switch (k) {
    case 3:
      q << (r(2, 1) - r(1, 2)) / (2 * d), (r(0, 2) - r(2, 0)) / (2 * d), (r(1, 0) - r(0, 1)) / (2 * d), d / 2;
      break;
    case 0:
      q << d / 2, (r(0, 1) + r(1, 0)) / (2 * d), (r(0, 2) + r(2, 0)) / (2 * d), (r(2, 1) - r(1, 2)) / (2 * d);
      break;
    case 1:
      q << (r(0, 1) + r(1, 0)) / (2 * d), d / 2, (r(1, 2) + r(2, 1)) / (2 * d), (r(0, 2) - r(2, 0)) / (2 * d);
      break;
    default:
      q << (r(0, 2) + r(2, 0)) / (2 * d), (r(1, 2) + r(2, 1)) / (2 * d), d / 2, (r(1, 0) - r(0, 1)) / (2 * d);
      break;
  }
  if (q(3) < 0) q = -q;
  return q / q.norm();
}

/// Rotation matrix of a rotation by `angle` [rad] about `axis` (Rodrigues).
inline mat3 matrix_from_axis_angle(const vec3& axis, double angle) {
  return rotation_matrix(from_axis_angle(axis, angle));
}

}  // namespace pradis::spatial

namespace pradis::spatial {

/// The factor Mu of the hidden fourth potential's flow Mu d(Lq)/dt, Lq = |q|:
/// Mu = DABSI / sqrt(machine epsilon) (PRADIS: DABSI / sqrt(MSHEPS)), about 6.7e6 at
/// the default DABSI = 0.1. Why: the q4 equation holds only this flow, so Newton's
/// residual test |Mu dLq/dt| <= DABSI holds the norm rate to |dLq/dt| <= sqrt(eps)
/// at every accepted step, while the entry Mu q/Lq it puts into the Newton matrix
/// stays within 1/sqrt(eps) of the others. A non-positive DABSI (a purely relative
/// residual test) is replaced by PRADIS's default 0.1.
inline double norm_viscosity(double dabsi) {
  return (dabsi > 0 ? dabsi : 0.1) / 1.4901161193847656e-08;  // sqrt(2.220446049250313e-16)
}

/// Lq below this is "near zero": the orientation is undefined (code 75).
inline constexpr double lq_near_zero = 1e-3;
/// |Lq - 1| above this is "far from 1" (code 75). Lq starts at 1; with the norm
/// equation it changes only by O(h^2 |omega|^2 / 32) (average acceleration) and by
/// at most sqrt(eps) per unit time, so 10 % means the run has gone wrong.
inline constexpr double lq_far_from_one = 0.1;

}  // namespace pradis::spatial
