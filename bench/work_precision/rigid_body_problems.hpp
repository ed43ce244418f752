#pragma once
/// \file
/// The 3D problems of the work-precision benchmark, written as first-order ODEs for
/// the peers (SUNDIALS IDA and CVODE, Boost.Odeint), beside the pradis models that
/// work_precision.cpp builds from the library's elements:
///
///   freebody  the torque-free asymmetric rigid body of Hairer, Lubich and Wanner
///             (Geometric Numerical Integration, 2nd ed., sections IV.1.2 and VII.5):
///             principal inertias I = (2, 1, 2/3), body angular momentum
///             m0 = (cos 1.1, 0, sin 1.1), started at the identity orientation, to one
///             period T = 10.73146523488280 of the body-frame angular momentum (exact
///             there: omega_b(T) = omega_b(0) = m0 / I). pradis: BODY3 + ROT0.
///   top       the heavy symmetric top of examples/spinning_top (top_model.hpp: BODY3
///             on a penalty spherical joint SPH3 to the ground, k = 1e6 N/m, gravity
///             as F3), to t = 1 s: spin 30 rad/s, released at 30 degrees from the
///             vertical. The peers integrate the same penalty equations.
///   topx      the same top on the exact spherical joint SPH3X (top_parameters::
///             exact_joint); the peers integrate Euler's equations about the tip
///             (top_exact_rhs), y = (q, omega_b).
///
/// State of the peers: y = (q1, q2, q3, q4, w1, w2, w3) for the free body, and
/// y = (x1, x2, x3, x1', x2', x3', q1, q2, q3, q4, w1, w2, w3) for the top, where q is
/// the quaternion with the scalar part q4 last (pradis's convention,
/// pradis/spatial/quaternion.hpp), w = omega_b the body angular velocity and x the
/// displacement of the centre of mass from its start. Kinematics
/// q' = (1/2) q (x) (omega_b, 0) (Hamilton product: R(q)' = R(q) [omega_b x]), whose
/// exact flow keeps |q|; Euler's equations I omega_b' + omega_b x I omega_b = tau_b.
///
/// Both sides are compared through (unit quaternion, omega_b): see compare_state()
/// and rotation_error().

#include <Eigen/Core>
#include <cmath>

#include "pradis/elements/library.hpp"
#include "pradis/spatial/quaternion.hpp"
#include "spinning_top/top_model.hpp"

namespace wp::rigid {

using pradis::spatial::quaternion;
using pradis::spatial::vec3;

/// q' = (1/2) q (x) (w, 0) = (1/2) (q4 w + v x w, -v . w), v = (q1, q2, q3).
inline quaternion quaternion_rate(const double* q, const vec3& w) {
  const vec3 v(q[0], q[1], q[2]);
  quaternion r;
  r.head<3>() = 0.5 * (q[3] * w + v.cross(w));
  r(3) = -0.5 * v.dot(w);
  return r;
}

/// d q' / d q (4 x 4) and d q' / d w (4 x 3) of quaternion_rate.
inline void quaternion_rate_jacobian(const double* q, const vec3& w, Eigen::Matrix4d& dq, Eigen::Matrix<double, 4, 3>& dw) {
  const vec3 v(q[0], q[1], q[2]);
  dq.setZero();
  dq.topLeftCorner<3, 3>() = -0.5 * pradis::spatial::skew(w);
  dq.block<3, 1>(0, 3) = 0.5 * w;
  dq.block<1, 3>(3, 0) = -0.5 * w.transpose();
  dw.topRows<3>() = 0.5 * (q[3] * Eigen::Matrix3d::Identity() + pradis::spatial::skew(v));
  dw.row(3) = -0.5 * v.transpose();
}

// --- freebody ----------------------------------------------------------------

/// Principal inertias of the HLW body (body axes = global axes at t = 0).
inline const vec3 hlw_inertia{2.0, 1.0, 2.0 / 3.0};
/// The period of its body-frame angular momentum (HLW; Landau-Lifshitz section 37).
inline constexpr double hlw_period = 10.73146523488280;
/// Initial body angular velocity m0 / I, m0 = (cos 1.1, 0, sin 1.1).
inline vec3 hlw_omega0() { return vec3(std::cos(1.1), 0.0, std::sin(1.1)).cwiseQuotient(hlw_inertia); }

/// The free body as a pradis model: BODY3 with the HLW inertias (centre of mass at
/// the reference point), started by ROT0 at the identity orientation with the global
/// (= body, at t = 0) angular velocity hlw_omega0().
struct freebody_model {
  using model_type = pradis::model<pradis::elements::rigid_body, pradis::elements::initial_rotation>;
  model_type m;
  std::vector<pradis::dof> x;  ///< the centre of mass
  pradis::rotation_node r;     ///< the body's orientation
  freebody_model() {
    using namespace pradis::elements;
    x = m.add_dofs(3, "x");
    r = m.add_rotation_node("r");
    const vec3 i = hlw_inertia, w0 = hlw_omega0();
    m.add<rigid_body>("body", {1.0, i.x(), i.y(), i.z(), 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    m.add<initial_rotation>("start", {1, 0, 0, 0, w0.x(), w0.y(), w0.z()}, r);
  }
  freebody_model(const freebody_model&) = delete;
  freebody_model& operator=(const freebody_model&) = delete;
};

/// y' of the free body, y = (q, omega_b): Euler's equations without torque.
inline void freebody_rhs(const double* y, double* dy) {
  const vec3 w(y[4], y[5], y[6]);
  const quaternion qd = quaternion_rate(y, w);
  for (int i = 0; i < 4; ++i) dy[i] = qd(i);
  const vec3 wd = (-w.cross(hlw_inertia.cwiseProduct(w))).cwiseQuotient(hlw_inertia);
  for (int i = 0; i < 3; ++i) dy[4 + i] = wd(i);
}

/// df/dy (7 x 7) of freebody_rhs: d omega'/d omega = I^-1 ([I w x] - [w x] I).
inline void freebody_jacobian(const double* y, Eigen::MatrixXd& j) {
  const vec3 w(y[4], y[5], y[6]);
  j.setZero(7, 7);
  Eigen::Matrix4d dq;
  Eigen::Matrix<double, 4, 3> dw;
  quaternion_rate_jacobian(y, w, dq, dw);
  j.topLeftCorner<4, 4>() = dq;
  j.block<4, 3>(0, 4) = dw;
  const Eigen::Matrix3d a = pradis::spatial::skew(hlw_inertia.cwiseProduct(w)) -
                            pradis::spatial::skew(w) * hlw_inertia.asDiagonal().toDenseMatrix();
  j.block<3, 3>(4, 4) = hlw_inertia.cwiseInverse().asDiagonal() * a;
}

// --- top ---------------------------------------------------------------------

/// The top's data, read from the example's scene so that both sides use the same numbers.
struct top_data {
  double m, l, j1, j3, w3, theta0, k, c, g;
  vec3 axis0;  ///< the symmetry axis (body Z) at t = 0
  static top_data from_example() {
    const pradis_examples::spinning_top t;
    return {t.mass, t.l, t.j1, t.j3, t.w3, t.theta0, t.k, t.joint_damping(), pradis_examples::spinning_top::g,
            t.axis0()};
  }
};

/// The tip B of the top of state y = (x, x', q, omega_b): the penalty joint's gap vector
/// p_B = X0 + x + R(q) r from the pivot at the origin [m] (top_rhs).
inline vec3 top_joint_gap(const top_data& d, const double* y) {
  const Eigen::Matrix3d rot = pradis::spatial::rotation_matrix(quaternion(y[6], y[7], y[8], y[9]));
  return d.l * d.axis0 + vec3(y[0], y[1], y[2]) + rot * vec3(0, 0, -d.l);
}

/// y' of the top, y = (x, x', q, omega_b). The tip B = X0 + x + R(q) r, r = (0, 0, -l)
/// (X0 = l axis0, so B starts at the origin), is held at the origin by the joint force
/// F = k p_B + c p_B' (SPH3, flow +F on B: the force on the body is -F); gravity
/// (0, 0, -m g) acts at the centre of mass. m x'' = -F + m g_vec;
/// I omega_b' + omega_b x I omega_b = r x (-R^T F), I = diag(j1, j1, j3).
inline void top_rhs(const top_data& d, const double* y, double* dy) {
  const quaternion q(y[6], y[7], y[8], y[9]);
  const vec3 x(y[0], y[1], y[2]), v(y[3], y[4], y[5]), w(y[10], y[11], y[12]);
  const Eigen::Matrix3d rot = pradis::spatial::rotation_matrix(q);
  const vec3 r(0, 0, -d.l);
  const vec3 pb = top_joint_gap(d, y);
  const vec3 vb = v + rot * w.cross(r);
  const vec3 f = d.k * pb + d.c * vb;
  const vec3 acc = -f / d.m + vec3(0, 0, -d.g);
  const vec3 inertia(d.j1, d.j1, d.j3);
  const vec3 tau = r.cross(-(rot.transpose() * f));
  const vec3 wd = (tau - w.cross(inertia.cwiseProduct(w))).cwiseQuotient(inertia);
  const quaternion qd = quaternion_rate(y + 6, w);
  for (int i = 0; i < 3; ++i) dy[i] = v(i), dy[3 + i] = acc(i), dy[10 + i] = wd(i);
  for (int i = 0; i < 4; ++i) dy[6 + i] = qd(i);
}

/// The initial state of the top: at rest in translation, tilted by theta0 about X,
/// spinning at w3 about its axis.
inline Eigen::VectorXd top_start(const top_data& d) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(13);
  y(6) = std::sin(d.theta0 / 2);
  y(9) = std::cos(d.theta0 / 2);
  y(12) = d.w3;
  return y;
}

/// y' of the top on an exact spherical joint at its tip (topx: SPH3X in pradis, a
/// Ball mobilizer in Simbody), y = (q, omega_b): Euler's equations about the fixed
/// tip, I_O omega_b' + omega_b x I_O omega_b = r_c x R^T (0, 0, -m g), with
/// I_O = diag(j1 + m l^2, j1 + m l^2, j3) (parallel axes) and r_c = (0, 0, l) the
/// centre of mass from the tip in body axes.
inline void top_exact_rhs(const top_data& d, const double* y, double* dy) {
  const quaternion q(y[0], y[1], y[2], y[3]);
  const vec3 w(y[4], y[5], y[6]);
  const Eigen::Matrix3d rot = pradis::spatial::rotation_matrix(q);
  const vec3 inertia(d.j1 + d.m * d.l * d.l, d.j1 + d.m * d.l * d.l, d.j3);
  const vec3 tau = vec3(0, 0, d.l).cross(rot.transpose() * vec3(0, 0, -d.m * d.g));
  const vec3 wd = (tau - w.cross(inertia.cwiseProduct(w))).cwiseQuotient(inertia);
  const quaternion qd = quaternion_rate(y, w);
  for (int i = 0; i < 4; ++i) dy[i] = qd(i);
  for (int i = 0; i < 3; ++i) dy[4 + i] = wd(i);
}

// --- comparison --------------------------------------------------------------

/// The compared state: the unit quaternion (sign chosen with q4 >= 0) and omega_b.
inline Eigen::VectorXd compare_state(const quaternion& q, const vec3& w) {
  Eigen::VectorXd z(7);
  const quaternion u = q / q.norm();
  z.head<4>() = u(3) < 0 ? quaternion(-u) : u;
  z.tail<3>() = w;
  return z;
}

/// max(angle of R(ref)^T R(z) [rad], |w - w_ref|_inf / |w_ref|_inf) for compared
/// states (compare_state). The angle 2 atan2(|vec(c)|, |c4|), c = conj(q_ref) q,
/// stays accurate for small angles (no acos near 1).
inline double rotation_error(const Eigen::VectorXd& z, const Eigen::VectorXd& ref) {
  const quaternion c = pradis::spatial::multiply(pradis::spatial::conjugate(ref.head<4>()), z.head<4>());
  const double angle = 2 * std::atan2(c.head<3>().norm(), std::abs(c(3)));
  const double ew = (z.tail<3>() - ref.tail<3>()).cwiseAbs().maxCoeff() / ref.tail<3>().cwiseAbs().maxCoeff();
  const double e = std::max(angle, ew);
  return std::isfinite(e) ? e : 1e300;
}

}  // namespace wp::rigid
