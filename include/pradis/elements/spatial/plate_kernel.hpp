#pragma once
/// \file
/// The matrices of TRIPL (plate.hpp): the local frame of a triangle in space, the
/// constant-strain membrane (CST) and the Morley constant-curvature bending triangle,
/// in the initial configuration (geometrically linear). docs/plates.md derives them.

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// 12 x 12 and 3 x 6 fixed-size matrices of the plate (no allocation).
using plate_mat12 = Eigen::Matrix<double, 12, 12>;
using plate_vec12 = Eigen::Matrix<double, 12, 1>;
using plate_mat36 = Eigen::Matrix<double, 3, 6>;

/// The geometry of a triangle P1 P2 P3 in space: the local frame (e1 along P1 -> P2,
/// n the normal of the right-handed vertex order, e2 = n x e1), the local 2D vertex
/// coordinates (x, y) relative to the centroid, the area and the side data of the
/// sides k = 0 (1 -> 2), 1 (2 -> 3), 2 (3 -> 1): length, unit tangent t from the first
/// to the second vertex and the in-plane normal m = n x t (pointing into the triangle).
struct plate_geometry {
  spatial::vec3 e1, e2, n;
  std::array<double, 3> x{}, y{};
  double area = 0;
  std::array<double, 3> len{}, tx{}, ty{};  ///< side lengths and local tangent components
  /// Builds the geometry; area is 0 for a degenerate triangle (then nothing else is set).
  plate_geometry(const spatial::vec3& p1, const spatial::vec3& p2, const spatial::vec3& p3) {
    const spatial::vec3 a = p2 - p1, b = p3 - p1, c = a.cross(b);
    const double scale = std::max({a.squaredNorm(), b.squaredNorm(), (p3 - p2).squaredNorm()});
    if (!(c.norm() > 1e-12 * scale)) return;
    area = 0.5 * c.norm();
    e1 = a.normalized();
    n = c.normalized();
    e2 = n.cross(e1);
    const spatial::vec3 g = (p1 + p2 + p3) / 3.0;
    const std::array<spatial::vec3, 3> p{p1, p2, p3};
    for (int i = 0; i < 3; ++i) {
      x[static_cast<std::size_t>(i)] = (p[static_cast<std::size_t>(i)] - g).dot(e1);
      y[static_cast<std::size_t>(i)] = (p[static_cast<std::size_t>(i)] - g).dot(e2);
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t j = (k + 1) % 3;
      const double dx = x[j] - x[k], dy = y[j] - y[k];
      len[k] = std::hypot(dx, dy);
      tx[k] = dx / len[k];
      ty[k] = dy / len[k];
    }
  }
};

/// The Morley triangle: the constant Hessian (w_xx, w_xy, w_yy) of the quadratic
/// deflection w(x, y) = a0 + a1 x + a2 y + w_xx x^2 / 2 + w_xy x y + w_yy y^2 / 2 as a
/// linear map of the bending DOFs (w1, w2, w3, r12, r23, r31), where r_k is the
/// rotation about side k's tangent t (from its first to its second vertex, right-hand
/// rule about t), which equals the slope dw/dm at the side's middle along m = n x t.
/// The six interpolation conditions (three vertex values, three mid-side slopes) form a
/// 6 x 6 system A c = dofs; the Hessian rows of A^-1 are returned.
template <class = void>  // compiled only in units that call it
plate_mat36 morley_hessian(const plate_geometry& g) {
  Eigen::Matrix<double, 6, 6> a;
  for (int i = 0; i < 3; ++i) {
    const double xi = g.x[static_cast<std::size_t>(i)], yi = g.y[static_cast<std::size_t>(i)];
    a.row(i) << 1, xi, yi, 0.5 * xi * xi, xi * yi, 0.5 * yi * yi;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t j = (k + 1) % 3;
    const double xm = 0.5 * (g.x[k] + g.x[j]), ym = 0.5 * (g.y[k] + g.y[j]);
    const double mx = -g.ty[k], my = g.tx[k];  // m = n x t with n = local z
    a.row(static_cast<int>(3 + k)) << 0, mx, my, mx * xm, mx * ym + my * xm, my * ym;
  }
  const Eigen::Matrix<double, 6, 6> inv = a.partialPivLu().inverse();
  return inv.bottomRows<3>();
}

/// The matrices of one plate in global components, for the DOF order x1 y1 z1 x2 y2 z2
/// x3 y3 z3 r12 r23 r31 with the side DOFs already multiplied by their signs:
/// K = T^T (K_membrane + K_bending) T, the consistent pressure load and the maps from
/// the DOFs to the local membrane strain (eps_x, eps_y, gamma_xy) and Hessian.
struct plate_matrices {
  plate_mat12 k;               ///< stiffness, global components
  plate_vec12 load;            ///< consistent load of a unit pressure along n
  Eigen::Matrix<double, 3, 12> strain;   ///< DOFs -> membrane strains
  Eigen::Matrix<double, 3, 12> hessian;  ///< DOFs -> (w_xx, w_xy, w_yy)
};

/// Builds the matrices of a triangle with geometry g, Young's modulus e, Poisson's ratio
/// nu, thickness h and side signs s (the side DOF k is s_k times the rotation about
/// side k's tangent).
template <class = void>  // compiled only in units that call it
void plate_build(const plate_geometry& g, double e, double nu, double h, const std::array<double, 3>& s,
                        plate_matrices& out) {
  // Local DOFs -> global: u_i = e1 . d_i, v_i = e2 . d_i, w_i = n . d_i; r_k = s_k theta_k.
  Eigen::Matrix<double, 3, 12> tu = Eigen::Matrix<double, 3, 12>::Zero(), tv = tu, tw = tu;
  for (int i = 0; i < 3; ++i) {
    tu.block<1, 3>(i, 3 * i) = g.e1.transpose();
    tv.block<1, 3>(i, 3 * i) = g.e2.transpose();
    tw.block<1, 3>(i, 3 * i) = g.n.transpose();
  }
  // Membrane (CST): eps = B [u; v], b_i = y_j - y_k, c_i = x_k - x_j (i, j, k cyclic).
  out.strain.setZero();
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3, k = (i + 2) % 3;
    const double bi = (g.y[j] - g.y[k]) / (2 * g.area), ci = (g.x[k] - g.x[j]) / (2 * g.area);
    const int r = static_cast<int>(i);
    out.strain.row(0) += bi * tu.row(r);
    out.strain.row(1) += ci * tv.row(r);
    out.strain.row(2) += ci * tu.row(r) + bi * tv.row(r);
  }
  // Bending (Morley): (w_xx, w_xy, w_yy) = H [w1 w2 w3 r12 r23 r31].
  const plate_mat36 hm = morley_hessian(g);
  out.hessian = hm.leftCols<3>() * tw;
  for (int k = 0; k < 3; ++k) {
    out.hessian.col(9 + k).setZero();
    out.hessian.col(9 + k) += s[static_cast<std::size_t>(k)] * hm.col(3 + k);
  }
  // Elasticity: membrane forces N = (E h / (1 - nu^2)) D0 eps, moments from curvatures
  // kappa = -(w_xx, w_yy, 2 w_xy) with D h^2 / 12 instead of h; D0 = [1 nu 0; nu 1 0; 0 0 (1 - nu) / 2].
  Eigen::Matrix3d d0;
  d0 << 1, nu, 0, nu, 1, 0, 0, 0, 0.5 * (1 - nu);
  const double cm = e * h / (1 - nu * nu), cb = cm * h * h / 12;
  Eigen::Matrix<double, 3, 12> kappa;
  kappa.row(0) = -out.hessian.row(0);
  kappa.row(1) = -out.hessian.row(2);
  kappa.row(2) = -2 * out.hessian.row(1);
  out.k.noalias() = (g.area * cm) * out.strain.transpose() * d0 * out.strain;
  out.k.noalias() += (g.area * cb) * kappa.transpose() * d0 * kappa;
  // Consistent load of a unit pressure: the mid-side rule, exact for a quadratic w, gives
  // int w dA = (A / 3) sum w_i - (A / 24) sum_k L_k^2 t_k^T Hess t_k.
  Eigen::Matrix<double, 1, 3> q;  // coefficients of (w_xx, w_xy, w_yy) in sum_k L_k^2 t_k^T Hess t_k
  q.setZero();
  for (std::size_t k = 0; k < 3; ++k) {
    const double l2 = g.len[k] * g.len[k];
    q(0) += l2 * g.tx[k] * g.tx[k];
    q(1) += 2 * l2 * g.tx[k] * g.ty[k];
    q(2) += l2 * g.ty[k] * g.ty[k];
  }
  out.load = ((g.area / 3.0) * tw.colwise().sum() - (g.area / 24.0) * q * out.hessian).transpose();
}

}  // namespace pradis::elements::detail
