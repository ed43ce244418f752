#pragma once
/// \file
/// The constraint rows the exact spatial joints (SPH3X, REV3X, UNI3X, CYL3X,
/// PRI3X, FIX3X, PTL3X, PTP3X) are built from, each with its flows G^T mu, its
/// constraint row g(u) and their exact Jacobian (docs/joints.md):
///
/// | row kind            | constraint                        | used by                      |
/// |---------------------|-----------------------------------|------------------------------|
/// | point (3 rows)      | p_B - p_A = 0                     | SPH3X, REV3X, UNI3X, FIX3X   |
/// | line (1 row)        | N . (p_B - p_A) = 0, N = R_a n    | CYL3X, PRI3X, PTL3X, PTP3X   |
/// | perpendicular (1)   | N . M = 0, N = R_a n, M = R_b m   | REV3X, UNI3X, CYL3X, PRI3X, FIX3X |
///
/// Local layout of every exact spatial joint: body a's x, y, z, q1..q3 at 0..5,
/// body b's at 6..11, the hidden q4 of a and b at 12 and 13, the multipliers
/// (velocity-level unknowns of the internal DOFs) from 14 on. A multiplier mu of a
/// row with gradient G (so that dg = G du) contributes the flows mu G^T: forces on
/// the x rows and moments on the q1..q3 rows (the moment m with dg = m . dtheta,
/// dtheta = Theta dq the small rotation of the body). The Jacobian holds the
/// geometric stiffness of the flows at fixed mu (in K), the rows' gradients
/// (in K) and the multiplier columns (in C). No allocation.

#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// The local index of the first multiplier of an exact spatial joint.
inline constexpr int first_multiplier = 14;

/// Zeroes the flows before the rows are added. The Jacobian blocks, when wanted,
/// arrive zeroed (local_output's contract), so the rows only add to them.
template <class Out>
void begin_exact_joint(Out& out) {
  out.f.setZero();
}

/// The point rows p_B - p_A = 0 at local rows r..r+2 with the force lambda (the
/// multipliers at the same local indices): flows -lambda and -rho_A x lambda on A,
/// +lambda and rho_B x lambda on B; geometric stiffness of the moments
/// d(rho x lambda)/dq = [lambda x][rho x] Theta; rows [-I, -dp_A/dq, I, dp_B/dq].
/// Returns d = p_B - p_A.
template <class Out>
spatial::vec3 add_point_rows(const attached_point& a, const attached_point& b, const spatial::vec3& lambda, int r,
                             Out& out) {
  using namespace spatial;
  const attached_point* pts[2] = {&a, &b};
  const double sg[2] = {-1.0, 1.0};
  const vec3 d = b.p - a.p;
  for (int j = 0; j < 2; ++j) {
    out.f.template segment<3>(6 * j) += sg[j] * lambda;
    out.f.template segment<3>(6 * j + 3) += sg[j] * pts[j]->rho.cross(lambda);
  }
  out.f.template segment<3>(r) = d;
  if (!out.want_jacobian) return d;
  for (int j = 0; j < 2; ++j) {
    add_quaternion_columns(out.K, 6 * j + 3, 6 * j + 3, 12 + j, sg[j] * skew(lambda) * skew(pts[j]->rho) * pts[j]->theta);
    out.K.template block<3, 3>(r, 6 * j) += sg[j] * mat3::Identity();
    add_quaternion_columns(out.K, r, 6 * j + 3, 12 + j, sg[j] * pts[j]->dp_dq);
    out.C.template block<3, 3>(6 * j, r) += sg[j] * mat3::Identity();
    out.C.template block<3, 3>(6 * j + 3, r) += sg[j] * skew(pts[j]->rho);
  }
  return d;
}

namespace exact_rows_detail {
/// Adds the 1 x 4 gradient row m^T Theta of a rotational slot to local row r.
template <class Mat>
void add_quaternion_row(Mat& k, int r, int c1, int c4, const spatial::vec3& m, const spatial::mat34& theta) {
  const Eigen::Matrix<double, 1, 4> row = m.transpose() * theta;
  k.template block<1, 3>(r, c1) += row.template leftCols<3>();
  k(r, c4) += row(3);
}
}  // namespace exact_rows_detail

/// A line row N . (p_B - p_A) = 0 at local row r with multiplier mu: the distance
/// of B from the plane through A normal to N = R_a n (a vector fixed in body a).
/// With w = p_B - x_a (x_a body a's reference point), dN = dtheta_a x N:
///
///     dg = N . (dx_b - dx_a) + m_a . dtheta_a + m_b . dtheta_b,
///     m_a = N x w,  m_b = rho_B x N.
///
/// Flows mu (-N, m_a, N, m_b); geometric stiffness at fixed mu:
/// d(-N)/dtheta_a = [N x], dm_a = [w x][N x] dtheta_a + [N x](dx_b - dx_a) - [N x][rho_B x] dtheta_b,
/// dm_b = [N x][rho_B x] dtheta_b - [rho_B x][N x] dtheta_a. Returns g.
template <class Out>
double add_line_row(const attached_point& a, const attached_point& b, const spatial::vec3& n_global, double mu, int r,
                    Out& out) {
  using namespace spatial;
  const vec3 w = b.p - (a.p - a.rho);
  const vec3 ma = n_global.cross(w), mb = b.rho.cross(n_global);
  const double g = n_global.dot(b.p - a.p);
  out.f.template segment<3>(0) -= mu * n_global;
  out.f.template segment<3>(3) += mu * ma;
  out.f.template segment<3>(6) += mu * n_global;
  out.f.template segment<3>(9) += mu * mb;
  out.f(r) = g;
  if (!out.want_jacobian) return g;
  const mat3 sn = skew(n_global), sw = skew(w), sr = skew(b.rho);
  add_quaternion_columns(out.K, 0, 3, 12, mu * sn * a.theta);
  add_quaternion_columns(out.K, 6, 3, 12, -mu * sn * a.theta);
  out.K.template block<3, 3>(3, 0) -= mu * sn;
  out.K.template block<3, 3>(3, 6) += mu * sn;
  add_quaternion_columns(out.K, 3, 3, 12, mu * sw * sn * a.theta);
  add_quaternion_columns(out.K, 3, 9, 13, -mu * sn * sr * b.theta);
  add_quaternion_columns(out.K, 9, 9, 13, mu * sn * sr * b.theta);
  add_quaternion_columns(out.K, 9, 3, 12, -mu * sr * sn * a.theta);
  out.K.template block<1, 3>(r, 0) -= n_global.transpose();
  out.K.template block<1, 3>(r, 6) += n_global.transpose();
  exact_rows_detail::add_quaternion_row(out.K, r, 3, 12, ma, a.theta);
  exact_rows_detail::add_quaternion_row(out.K, r, 9, 13, mb, b.theta);
  out.C.template block<3, 1>(0, r) -= n_global;
  out.C.template block<3, 1>(3, r) += ma;
  out.C.template block<3, 1>(6, r) += n_global;
  out.C.template block<3, 1>(9, r) += mb;
  return g;
}

/// A perpendicular row N . M = 0 at local row r with multiplier mu, N = R_a n fixed
/// in body a and M = R_b m fixed in body b. A turn dtheta_a changes g by
/// dtheta_a . (N x M), a turn of b by dtheta_b . (M x N); the flows are the moments
/// mu (N x M) on a and -mu (N x M) on b, with (dN = -[N x] Theta_a dq_a,
/// dM = -[M x] Theta_b dq_b)
///
///     d(N x M)/dq_a = [M x][N x] Theta_a,   d(N x M)/dq_b = -[N x][M x] Theta_b.
///
/// Returns g.
template <class Out>
double add_perpendicular_row(const attached_point& a, const attached_point& b, const spatial::vec3& n_global,
                             const spatial::vec3& m_global, double mu, int r, Out& out) {
  using namespace spatial;
  const vec3 gm = n_global.cross(m_global);
  out.f.template segment<3>(3) += mu * gm;
  out.f.template segment<3>(9) -= mu * gm;
  const double g = n_global.dot(m_global);
  out.f(r) = g;
  if (!out.want_jacobian) return g;
  const mat3 sm = skew(m_global), sn = skew(n_global);
  const mat34 dga = sm * sn * a.theta, dgb = -(sn * sm * b.theta);
  add_quaternion_columns(out.K, 3, 3, 12, mu * dga);
  add_quaternion_columns(out.K, 3, 9, 13, mu * dgb);
  add_quaternion_columns(out.K, 9, 3, 12, -mu * dga);
  add_quaternion_columns(out.K, 9, 9, 13, -mu * dgb);
  exact_rows_detail::add_quaternion_row(out.K, r, 3, 12, gm, a.theta);
  exact_rows_detail::add_quaternion_row(out.K, r, 9, 13, -gm, b.theta);
  out.C.template block<3, 1>(3, r) += gm;
  out.C.template block<3, 1>(9, r) -= gm;
  return g;
}

/// The reactions the joint exerts on body b once all rows are added: the force
/// -(flows on b's x rows) and the moment about the joint point B,
/// -(flows on b's q rows) + rho_B x (flows on b's x rows).
template <class Out>
std::pair<spatial::vec3, spatial::vec3> joint_reactions_on_b(const attached_point& b, const Out& out) {
  const spatial::vec3 fx = out.f.template segment<3>(6), fq = out.f.template segment<3>(9);
  return {-fx, b.rho.cross(fx) - fq};
}

/// Two unit vectors n1, n2 perpendicular to the unit vector e and to each other
/// (n2 = e x n1): n1 is the coordinate axis least aligned with e, made perpendicular.
inline std::pair<spatial::vec3, spatial::vec3> perpendicular_pair(const spatial::vec3& e) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(e(i)) < std::abs(e(k))) k = i;
  spatial::vec3 t = spatial::vec3::Zero();
  t(k) = 1.0;
  const spatial::vec3 n1 = (t - e.dot(t) * e).normalized();
  return {n1, e.cross(n1)};
}

/// The angle between two vectors [rad], accurate near 0 and pi.
inline double angle_between(const spatial::vec3& x, const spatial::vec3& y) {
  return std::atan2(x.cross(y).norm(), x.dot(y));
}

/// The distance of d from the line along the unit vector e: |d - (d . e) e|.
inline double off_line(const spatial::vec3& d, const spatial::vec3& e) { return (d - d.dot(e) * e).norm(); }

}  // namespace pradis::elements::detail
