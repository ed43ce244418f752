#pragma once
/// \file
/// Kinematics of a point attached to a body in spatial motion (a translational point
/// x, y, z and a rotational node q), with the exact derivatives the connecting
/// elements (SD3, RSD3, SPH3, REV3) need for their Jacobians. No allocation.

#include <cmath>
#include <limits>
#include <utility>

#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// A point attached to a body: initial global position X0 of the body's reference
/// point, offset a in the body frame. With the reference point's displacement x and
/// the rotational node q (s = q.q, Theta = (2/s) E(q), R = R(q)):
///
///     p  = X0 + x + rho,        rho = R a
///     v  = x' + omega x rho,    omega = (2/s) E(q) q'
///
/// and, because a variation dq turns the body by dtheta = Theta dq (rho by
/// dtheta x rho), dp/dx = I, dp/dq = -[rho x] Theta, dv/dx' = I,
/// dv/dq' = -[rho x] Theta, dv/dq = -[omega x][rho x] Theta + [rho x] (2/s) (E(q') + omega q^T).
struct attached_point {
  spatial::vec3 p;          ///< global position of the point [m]
  spatial::vec3 v;          ///< global velocity of the point [m/s]
  spatial::mat3 r;          ///< R(q), the body's rotation matrix
  spatial::vec3 rho;        ///< R a: the offset in global axes [m]
  spatial::vec3 omega;      ///< global angular velocity of the body [rad/s]
  spatial::mat34 theta;     ///< Theta = (2/s) E(q): small global rotation per dq
  spatial::mat34 domega_dq; ///< d omega / dq = -(2/s) (E(q') + omega q^T)
  spatial::mat34 dp_dq;     ///< dp/dq = dv/dq'
  spatial::mat34 dv_dq;     ///< dv/dq

  /// Which derivatives a constructor computes; the others hold NaN.
  enum class level {
    none,      ///< p, v, r, rho, omega and theta only (flows only: local_output::want_jacobian false)
    position,  ///< also dp_dq (elements whose Jacobian needs no dv/dq, such as the exact joints)
    all        ///< also domega_dq and dv_dq
  };

  /// Evaluates everything at (x, x', q, q'); q must not be near zero. Without
  /// `derivatives` (flows only: local_output::want_jacobian false) domega_dq, dp_dq
  /// and dv_dq are not computed and hold NaN.
  attached_point(const spatial::vec3& x0, const spatial::vec3& a, const spatial::vec3& x, const spatial::vec3& xd,
                 const spatial::quaternion& q, const spatial::quaternion& qd, bool derivatives = true)
      : attached_point(x0, a, x, xd, q, qd, derivatives ? level::all : level::none) {}
  /// Evaluates (x, x', q, q') with the derivatives of `d` (see level); q must not be near zero.
  attached_point(const spatial::vec3& x0, const spatial::vec3& a, const spatial::vec3& x, const spatial::vec3& xd,
                 const spatial::quaternion& q, const spatial::quaternion& qd, level d) {
    using namespace spatial;
    const double s = q.squaredNorm();
    r = rotation_matrix(q);
    rho = r * a;
    p = x0 + x + rho;
    theta = (2.0 / s) * e_matrix(q);
    omega = theta * qd;
    v = xd + omega.cross(rho);
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (d == level::none) {
      domega_dq.setConstant(nan);
      dp_dq.setConstant(nan);
      dv_dq.setConstant(nan);
      return;
    }
    const mat3 rx = skew(rho);
    dp_dq = -rx * theta;
    if (d == level::position) {
      domega_dq.setConstant(nan);
      dv_dq.setConstant(nan);
      return;
    }
    domega_dq = -(2.0 / s) * (e_matrix(qd) + omega * q.transpose());
    dv_dq = -skew(omega) * rx * theta - rx * domega_dq;
  }
};

/// The quaternion (q1, q2, q3, q4) of a rotational slot whose q1..q3 are at local index
/// i1 and q4 at i4.
template <class V>
spatial::quaternion slot_quaternion(const V& u, int i1, int i4) {
  return spatial::quaternion(u(i1), u(i1 + 1), u(i1 + 2), u(i4));
}

/// Adds the 3 x 4 block b to the rows r..r+2 of a local matrix, columns q1..q3 at
/// c1..c1+2 and q4 at c4.
template <class Mat>
void add_quaternion_columns(Mat& m, int r, int c1, int c4, const spatial::mat34& b) {
  m.template block<3, 3>(r, c1) += b.leftCols<3>();
  m.template block<3, 1>(r, c4) += b.col(3);
}

/// Flows and Jacobian of a force F carried between two attached points A and B (local
/// layout: A's x, y, z, q1, q2, q3 at 0..5, B's at 6..11, A's hidden q4 at 12, B's at 13).
/// The force depends on d = p_B - p_A and d' = v_B - v_A only; the element takes -F on
/// A and +F on B (the system pulls B by -F: F > 0 along d is tension), with the
/// moments about the reference points -rho_A x F on A's q1..q3 and rho_B x F on B's.
/// fd = dF/dd, fdd = dF/dd'. With sign_A = -1, sign_B = +1, for ends i, j:
///
///     d(flow_i)/d(u_j) = sign_i sign_j [I; [rho_i x]] (fd dd/du_j + fdd dd'/du_j)
///                        + (i == j) sign_i [F x][rho_i x] Theta_i   (moment rows, q columns)
template <class Out>
void two_point_flows(const attached_point& a, const attached_point& b, const spatial::vec3& f, const spatial::mat3& fd,
                     const spatial::mat3& fdd, Out& out) {
  using namespace spatial;
  const attached_point* pts[2] = {&a, &b};
  const double sg[2] = {-1.0, 1.0};
  out.f.setZero();
  for (int i = 0; i < 2; ++i) {
    out.f.template segment<3>(6 * i) = sg[i] * f;
    out.f.template segment<3>(6 * i + 3) = sg[i] * pts[i]->rho.cross(f);
  }
  if (!out.want_jacobian) return;  // the blocks arrive zeroed (local_output's contract)
  for (int j = 0; j < 2; ++j) {
    const attached_point& pj = *pts[j];
    const mat3 dku_x = sg[j] * fd;
    const mat34 dku_q = sg[j] * (fd * pj.dp_dq + fdd * pj.dv_dq);
    const mat3 dcv_x = sg[j] * fdd;
    const mat34 dcv_q = sg[j] * (fdd * pj.dp_dq);
    for (int i = 0; i < 2; ++i) {
      const mat3 rx = skew(pts[i]->rho);
      const int r = 6 * i, c = 6 * j;
      out.K.template block<3, 3>(r, c) += sg[i] * dku_x;
      out.K.template block<3, 3>(r + 3, c) += sg[i] * rx * dku_x;
      add_quaternion_columns(out.K, r, c + 3, 12 + j, sg[i] * dku_q);
      add_quaternion_columns(out.K, r + 3, c + 3, 12 + j, sg[i] * rx * dku_q);
      out.C.template block<3, 3>(r, c) += sg[i] * dcv_x;
      out.C.template block<3, 3>(r + 3, c) += sg[i] * rx * dcv_x;
      add_quaternion_columns(out.C, r, c + 3, 12 + j, sg[i] * dcv_q);
      add_quaternion_columns(out.C, r + 3, c + 3, 12 + j, sg[i] * rx * dcv_q);
    }
    add_quaternion_columns(out.K, 6 * j + 3, 6 * j + 3, 12 + j, sg[j] * skew(f) * skew(pj.rho) * pj.theta);
  }
}

/// The two attached points of a two-body connecting element (local layout of
/// two_point_flows) from the local input and the initial positions / offsets (with
/// their derivatives unless `derivatives` is false, see attached_point).
template <class In>
std::pair<attached_point, attached_point> two_points(const In& in, const spatial::vec3& xa0, const spatial::vec3& ra,
                                                     const spatial::vec3& xb0, const spatial::vec3& rb,
                                                     attached_point::level d) {
  return {attached_point(xa0, ra, in.u.template segment<3>(0), in.v.template segment<3>(0),
                         slot_quaternion(in.u, 3, 12), slot_quaternion(in.v, 3, 12), d),
          attached_point(xb0, rb, in.u.template segment<3>(6), in.v.template segment<3>(6),
                         slot_quaternion(in.u, 9, 13), slot_quaternion(in.v, 9, 13), d)};
}
/// two_points with all derivatives, or none without `derivatives`.
template <class In>
std::pair<attached_point, attached_point> two_points(const In& in, const spatial::vec3& xa0, const spatial::vec3& ra,
                                                     const spatial::vec3& xb0, const spatial::vec3& rb,
                                                     bool derivatives = true) {
  return two_points(in, xa0, ra, xb0, rb, derivatives ? attached_point::level::all : attached_point::level::none);
}

/// Whether both quaternions of a two-body element (slots 3/12 and 9/13) are far from zero
/// (the states the finite-difference checks may use).
template <class In>
bool two_quaternions_admissible(const In& in) {
  return slot_quaternion(in.u, 3, 12).norm() > 0.2 && slot_quaternion(in.u, 9, 13).norm() > 0.2;
}

/// Whether both quaternions of a two-body element are above spatial::lq_near_zero (else
/// the element reports code 75 before dividing by s).
template <class In>
bool two_quaternions_admissible_strict(const In& in) {
  return slot_quaternion(in.u, 3, 12).norm() > spatial::lq_near_zero &&
         slot_quaternion(in.u, 9, 13).norm() > spatial::lq_near_zero;
}

}  // namespace pradis::elements::detail
