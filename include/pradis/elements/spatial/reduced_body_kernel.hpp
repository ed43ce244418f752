#pragma once
/// \file
/// The flows and the Jacobian of a reduced elastic body in large motion (FLEX3,
/// elements/spatial/reduced_body.hpp). docs/reduction.md states the formulation.
///
/// Local DOFs of a body with NB boundary nodes and NM modes: node i's x, y, z at
/// 6i..6i+2, its q1..q3 at 6i+3..6i+5 and its hidden q4 at 6 NB + i; mode j at
/// 7 NB + j. Reduced coordinates (the rows and columns of K and M): node i's
/// (ux uy uz rx ry rz) at 6i..6i+5, mode j at 6 NB + j.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "pradis/elements/spatial/beam_kinematics.hpp"
#include "pradis/spatial/dual.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// The rotation matrix (body -> global) of a unit quaternion of scalars T.
template <class T>
std::array<std::array<T, 3>, 3> rotation_of(const tquat<T>& u) {
  std::array<std::array<T, 3>, 3> r;
  r[0] = {1.0 - 2.0 * (u[1] * u[1] + u[2] * u[2]), 2.0 * (u[0] * u[1] - u[2] * u[3]), 2.0 * (u[0] * u[2] + u[1] * u[3])};
  r[1] = {2.0 * (u[0] * u[1] + u[2] * u[3]), 1.0 - 2.0 * (u[0] * u[0] + u[2] * u[2]), 2.0 * (u[1] * u[2] - u[0] * u[3])};
  r[2] = {2.0 * (u[0] * u[2] - u[1] * u[3]), 2.0 * (u[1] * u[2] + u[0] * u[3]), 1.0 - 2.0 * (u[0] * u[0] + u[1] * u[1])};
  return r;
}

/// One boundary node i against the frame of node 1: its deformation d_i and, for
/// given lambda (the generalised forces K d of node i's six coordinates), the
/// gradient of lambda . d_i (the pair's flows).
template <class T>
struct pair_state {
  std::array<T, 6> d{};            ///< translation R^T (x_i - x_1) - (X_i - X_1), rotation log(R^T R_i)
  std::array<tvec<T>, 4> flows{};  ///< force and global moment on node 1, then on node i
  double w = 1;                    ///< scalar part of the unit relative rotation (0 at 180 degrees)
};

/// The pair (node 1, node i) at positions x1, xi and quaternions q1, qi (not
/// necessarily unit), ref = X_i - X_1; lambda (6 numbers) or nullptr for d alone.
/// Written for any scalar T: with dual numbers seeded on the 14 inputs it gives d_i's
/// Jacobian and the pair's geometric stiffness.
template <class T>
pair_state<T> pair_kinematics(const tvec<T>& x1, const tquat<T>& q1, const tvec<T>& xi, const tquat<T>& qi,
                              const std::array<double, 3>& ref, const double* lambda) {
  using std::sqrt;
  pair_state<T> out;
  const T r1 = sqrt(q1[0] * q1[0] + q1[1] * q1[1] + q1[2] * q1[2] + q1[3] * q1[3]);
  const T ri = sqrt(qi[0] * qi[0] + qi[1] * qi[1] + qi[2] * qi[2] + qi[3] * qi[3]);
  tquat<T> u, ui;
  for (std::size_t j = 0; j < 4; ++j) {
    u[j] = q1[j] / r1;
    ui[j] = qi[j] / ri;
  }
  const auto rm = rotation_of(u);
  tvec<T> c;
  for (std::size_t j = 0; j < 3; ++j) c[j] = xi[j] - x1[j];
  for (std::size_t j = 0; j < 3; ++j) out.d[j] = rm[0][j] * c[0] + rm[1][j] * c[1] + rm[2][j] * c[2] - ref[j];
  tquat<T> rel = qmul(qconj(u), ui);
  if (spatial::value_of(rel[3]) < 0)
    for (auto& x : rel) x = -x;
  out.w = spatial::value_of(rel[3]);
  const tvec<T> th = qlog(rel);
  for (std::size_t j = 0; j < 3; ++j) out.d[3 + j] = th[j];
  for (auto& f : out.flows) f = {T(0.0), T(0.0), T(0.0)};
  if (!lambda) return out;
  // Translation: d/dx_i = R l_t, d/dx_1 = -R l_t, d/dphi_1 = (R l_t) x c (R^T turns by -phi_1).
  tvec<T> f;
  for (std::size_t j = 0; j < 3; ++j) f[j] = rm[j][0] * lambda[0] + rm[j][1] * lambda[1] + rm[j][2] * lambda[2];
  const tvec<T> fc = cross(f, c);
  // Rotation: a small global rotation phi of node i turns rel into ((R^T phi) / 2, 0) rel, one of node 1
  // into ((-R^T phi) / 2, 0) rel; qlog's adjoint gives d(lambda_r . theta)/d(rel).
  const tvec<T> thbar{T(lambda[3]), T(lambda[4]), T(lambda[5])};
  tquat<T> qbar;
  (void)qlog(rel, &thbar, &qbar);
  tvec<T> wl;
  for (std::size_t k = 0; k < 3; ++k) {
    const tquat<T> e{T(k == 0 ? 0.5 : 0.0), T(k == 1 ? 0.5 : 0.0), T(k == 2 ? 0.5 : 0.0), T(0.0)};
    const tquat<T> dq = qmul(e, rel);
    wl[k] = qbar[0] * dq[0] + qbar[1] * dq[1] + qbar[2] * dq[2] + qbar[3] * dq[3];
  }
  for (std::size_t j = 0; j < 3; ++j) {
    const T mi = rm[j][0] * wl[0] + rm[j][1] * wl[1] + rm[j][2] * wl[2];
    out.flows[0][j] = -f[j];
    out.flows[1][j] = fc[j] - mi;
    out.flows[2][j] = f[j];
    out.flows[3][j] = mi;
  }
  return out;
}

/// The flows f (local), optionally the Jacobian blocks, W(1) strain energy and W(2)
/// kinetic energy of a reduced body; see reduced_body.hpp for the formulation.
template <int NB, int NM>
struct reduced_body_kernel {
  static constexpr int nr = 6 * NB + NM;  ///< reduced coordinates
  static constexpr int n = 7 * NB + NM;   ///< local DOFs
  using rmat = Eigen::Matrix<double, nr, nr>;
  using rvec = Eigen::Matrix<double, nr, 1>;
  using lvec = Eigen::Matrix<double, n, 1>;
  using lmat = Eigen::Matrix<double, n, n, Eigen::RowMajor>;
  using mat3 = spatial::mat3;
  using vec3 = spatial::vec3;

  /// The local row (and column) of reduced coordinate k: 3-block b = k / 3 is node
  /// b / 2's translation (b even) or rotation (b odd); then the modes.
  static constexpr int local_of(int k) { return k < 6 * NB ? k : k + NB; }

  /// Quaternion of node i from a local vector.
  template <class V>
  static spatial::quaternion quat(const V& x, int i) {
    return {x(6 * i + 3), x(6 * i + 4), x(6 * i + 5), x(6 * NB + i)};
  }

  /// The strain part: flows into f; with K, the exact dF/du into K (added).
  /// Returns {strain energy, smallest relative-rotation scalar part}.
  static std::pair<double, double> elastic(const lvec& u, const rmat& k, const std::array<double, 3 * NB>& x0, lvec& f,
                                           lmat* kk) {
    const auto at = [&u, &x0](int i) {
      tvec<double> x;
      for (int j = 0; j < 3; ++j) x[static_cast<std::size_t>(j)] = x0[static_cast<std::size_t>(3 * i + j)] + u(6 * i + j);
      return x;
    };
    const auto qt = [&u](int i) {
      const spatial::quaternion q = quat(u, i);
      return tquat<double>{q(0), q(1), q(2), q(3)};
    };
    const auto ref = [&x0](int i) {
      const auto b = static_cast<std::size_t>(3 * i);
      return std::array<double, 3>{x0[b] - x0[0], x0[b + 1] - x0[1], x0[b + 2] - x0[2]};
    };
    rvec d = rvec::Zero();
    double min_w = 1;
    for (int i = 1; i < NB; ++i) {
      const auto pk = pair_kinematics(at(0), qt(0), at(i), qt(i), ref(i), nullptr);
      min_w = std::min(min_w, pk.w);
      for (int j = 0; j < 6; ++j) d(6 * i + j) = pk.d[static_cast<std::size_t>(j)];
    }
    for (int j = 0; j < NM; ++j) d(6 * NB + j) = u(7 * NB + j);
    const rvec lambda = k * d;
    for (int j = 0; j < NM; ++j) f(7 * NB + j) += lambda(6 * NB + j);
    // With the Jacobian: each pair with dual numbers seeded on its 14 local inputs (x_1, q_1, x_i, q_i) gives
    // d_i's derivatives B_u and the pair's geometric stiffness (lambda held); the material part is
    // B_phi^T k B_u, B_phi = d's derivatives by the translations and small global rotations. B_u and B_phi
    // are kept per pair in compact columns (14 and 12): their other entries are zero.
    using d14 = spatial::dual<double, 14>;
    std::array<Eigen::Matrix<double, 6, 14>, NB> bu;
    std::array<Eigen::Matrix<double, 6, 12>, NB> bphi;
    std::array<std::array<int, 14>, NB> cols;
    for (int i = 1; i < NB; ++i) {
      const double* lam = lambda.data() + 6 * i;
      if (!kk) {
        add_flows(pair_kinematics(at(0), qt(0), at(i), qt(i), ref(i), lam), i, f);
        continue;
      }
      // Seeds: 0..2 x_1, 3..6 q_1, 7..9 x_i, 10..13 q_i; their local columns.
      auto& col = cols[static_cast<std::size_t>(i)];
      col = {0, 1, 2, 3, 4, 5, 6 * NB, 6 * i, 6 * i + 1, 6 * i + 2, 6 * i + 3, 6 * i + 4, 6 * i + 5, 6 * NB + i};
      tvec<d14> x1, xi;
      tquat<d14> q1, qi;
      const tvec<double> a1 = at(0), ai = at(i);
      const tquat<double> b1 = qt(0), bi = qt(i);
      for (std::size_t j = 0; j < 3; ++j) {
        x1[j] = d14::variable(a1[j], static_cast<int>(j));
        xi[j] = d14::variable(ai[j], static_cast<int>(7 + j));
      }
      for (std::size_t j = 0; j < 4; ++j) {
        q1[j] = d14::variable(b1[j], static_cast<int>(3 + j));
        qi[j] = d14::variable(bi[j], static_cast<int>(10 + j));
      }
      const auto pg = pair_kinematics(x1, q1, xi, qi, ref(i), lam);
      const std::array<int, 4> row{0, 3, 6 * i, 6 * i + 3};
      for (std::size_t b = 0; b < 4; ++b)
        for (std::size_t r = 0; r < 3; ++r) {
          f(row[b] + static_cast<int>(r)) += pg.flows[b][r].v;
          for (std::size_t c = 0; c < 14; ++c) (*kk)(row[b] + static_cast<int>(r), col[c]) += pg.flows[b][r].d[c];
        }
      auto& bui = bu[static_cast<std::size_t>(i)];
      for (std::size_t r = 0; r < 6; ++r)
        for (std::size_t c = 0; c < 14; ++c) bui(static_cast<int>(r), static_cast<int>(c)) = pg.d[r].d[c];
      // B_phi: translations as B_u; rotations: B_u on q times E(q)^T / 2 (the right inverse of (2/s) E(q)).
      auto& bpi = bphi[static_cast<std::size_t>(i)];
      bpi.template middleCols<3>(0) = bui.template middleCols<3>(0);
      bpi.template middleCols<3>(3) = bui.template middleCols<4>(3) * (0.5 * spatial::e_matrix(quat(u, 0)).transpose());
      bpi.template middleCols<3>(6) = bui.template middleCols<3>(7);
      bpi.template middleCols<3>(9) = bui.template middleCols<4>(10) * (0.5 * spatial::e_matrix(quat(u, i)).transpose());
    }
    if (kk) {
      // k B_u (nr x local), then the rows B_phi^T (k B_u) of each pair and of the modes.
      Eigen::Matrix<double, nr, n> kb = Eigen::Matrix<double, nr, n>::Zero();
      for (int i = 1; i < NB; ++i) {
        const Eigen::Matrix<double, nr, 14> part = k.template middleCols<6>(6 * i) * bu[static_cast<std::size_t>(i)];
        for (int c = 0; c < 14; ++c) kb.col(cols[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)]) += part.col(c);
      }
      for (int j = 0; j < NM; ++j) kb.col(7 * NB + j) += k.col(6 * NB + j);
      for (int i = 1; i < NB; ++i) {
        const Eigen::Matrix<double, 12, n> rows =
            bphi[static_cast<std::size_t>(i)].transpose() * kb.template middleRows<6>(6 * i);
        kk->template middleRows<6>(0) += rows.template topRows<6>();
        kk->template middleRows<6>(6 * i) += rows.template bottomRows<6>();
      }
      for (int j = 0; j < NM; ++j) kk->row(7 * NB + j) += kb.row(6 * NB + j);
    }
    return {0.5 * d.dot(lambda), min_w};
  }

  /// Adds a pair's flows (double) into f.
  static void add_flows(const pair_state<double>& pg, int i, lvec& f) {
    const std::array<int, 4> row{0, 3, 6 * i, 6 * i + 3};
    for (std::size_t b = 0; b < 4; ++b)
      for (std::size_t r = 0; r < 3; ++r) f(row[b] + static_cast<int>(r)) += pg.flows[b][r];
  }

  /// [x]-blocks of the 3-blocks of x stacked (nr x 3, zero on the modes).
  static Eigen::Matrix<double, nr, 3> stacked_skew(const rvec& x) {
    Eigen::Matrix<double, nr, 3> s = Eigen::Matrix<double, nr, 3>::Zero();
    for (int b = 0; b < 2 * NB; ++b) s.template middleRows<3>(3 * b) = spatial::skew(x.template segment<3>(3 * b));
    return s;
  }

  /// The inertia part: flows into f; with the blocks, dF/du, dF/dv, dF/da added.
  /// Returns the kinetic energy. nu = (v_i, omega_i, modal rates), nud its time
  /// derivative; A = P m P^T with P = R on every 3-block; the flows
  /// A (nud - W nu) + W A nu - Om A nu - E1 sum_b (A nu)_b x nu_b, W = [omega_1 x] and
  /// Om = [omega_i x] on node i's rotation block, E1 onto node 1's moment.
  static double inertia(const lvec& u, const lvec& v, const lvec& a, const rmat& m, lvec& f, lmat* kk, lmat* cc,
                        lmat* mm) {
    const mat3 r = spatial::rotation_matrix(quat(u, 0));
    rvec nu, nud;
    std::array<Eigen::Matrix<double, 3, 4>, NB> e2s;  // (2/s) E(q_i)
    for (int i = 0; i < NB; ++i) {
      const spatial::quaternion q = quat(u, i), qd = quat(v, i), qdd = quat(a, i);
      e2s[static_cast<std::size_t>(i)] = (2.0 / q.squaredNorm()) * spatial::e_matrix(q);
      nu.template segment<3>(6 * i) = v.template segment<3>(6 * i);
      nud.template segment<3>(6 * i) = a.template segment<3>(6 * i);
      nu.template segment<3>(6 * i + 3) = e2s[static_cast<std::size_t>(i)] * qd;
      nud.template segment<3>(6 * i + 3) = spatial::global_angular_acceleration(q, qd, qdd);
    }
    for (int j = 0; j < NM; ++j) {
      nu(6 * NB + j) = v(7 * NB + j);
      nud(6 * NB + j) = a(7 * NB + j);
    }
    // A = P m P^T, P = R on every 3-block: m's 3-column blocks times R^T, then its 3-row blocks times R.
    rmat am = m;
    for (int b = 0; b < 2 * NB; ++b) am.template middleCols<3>(3 * b) = (am.template middleCols<3>(3 * b) * r.transpose()).eval();
    for (int b = 0; b < 2 * NB; ++b) am.template middleRows<3>(3 * b) = (r * am.template middleRows<3>(3 * b)).eval();
    const vec3 w1 = nu.template segment<3>(3);
    const mat3 sw1 = spatial::skew(w1);
    // W x, Om x and the node-1 term for a vector x.
    const auto wx = [&sw1](const rvec& x) {
      rvec y = rvec::Zero();
      for (int b = 0; b < 2 * NB; ++b) y.template segment<3>(3 * b) = sw1 * x.template segment<3>(3 * b);
      return y;
    };
    const auto omx = [&nu](const rvec& x) {
      rvec y = rvec::Zero();
      for (int i = 0; i < NB; ++i)
        y.template segment<3>(6 * i + 3) = nu.template segment<3>(6 * i + 3).cross(x.template segment<3>(6 * i + 3));
      return y;
    };
    const rvec y = am * nu, z = nud - wx(nu);
    rvec fr = am * z + wx(y) - omx(y);
    for (int b = 0; b < 2 * NB; ++b)
      fr.template segment<3>(3) -= y.template segment<3>(3 * b).cross(nu.template segment<3>(3 * b));
    for (int k = 0; k < nr; ++k) f(local_of(k)) += fr(k);
    const double kinetic = 0.5 * nu.dot(y);
    if (!kk) return kinetic;

    // dF/dnu (nr x nr).
    rmat cn;
    for (int b = 0; b < 2 * NB; ++b) cn.template middleCols<3>(3 * b) = -am.template middleCols<3>(3 * b) * sw1;
    cn.template rightCols<NM>() = rmat::Zero().template rightCols<NM>();
    for (int b = 0; b < 2 * NB; ++b) cn.template middleRows<3>(3 * b) += sw1 * am.template middleRows<3>(3 * b);
    for (int i = 0; i < NB; ++i)
      cn.template middleRows<3>(6 * i + 3) -= spatial::skew(nu.template segment<3>(6 * i + 3)) * am.template middleRows<3>(6 * i + 3);
    cn.template middleCols<3>(3) += am * stacked_skew(nu) - stacked_skew(y);
    for (int i = 0; i < NB; ++i)
      cn.template block<3, 3>(6 * i + 3, 6 * i + 3) += spatial::skew(y.template segment<3>(6 * i + 3));
    for (int b = 0; b < 2 * NB; ++b) {
      cn.template middleRows<3>(3) += spatial::skew(nu.template segment<3>(3 * b)) * am.template middleRows<3>(3 * b);
      cn.template block<3, 3>(3, 3 * b) -= spatial::skew(y.template segment<3>(3 * b));
    }
    // dF/dphi_1 with nu held: dA x = D_x dphi, D_x = A S_x - S_(A x).
    const auto dx = [&am](const rvec& x) -> Eigen::Matrix<double, nr, 3> {
      return am * stacked_skew(x) - stacked_skew(am * x);
    };
    const Eigen::Matrix<double, nr, 3> dnu = dx(nu);
    Eigen::Matrix<double, nr, 3> fphi = dx(z);
    for (int b = 0; b < 2 * NB; ++b) fphi.template middleRows<3>(3 * b) += sw1 * dnu.template middleRows<3>(3 * b);
    for (int i = 0; i < NB; ++i)
      fphi.template middleRows<3>(6 * i + 3) -= spatial::skew(nu.template segment<3>(6 * i + 3)) * dnu.template middleRows<3>(6 * i + 3);
    for (int b = 0; b < 2 * NB; ++b)
      fphi.template middleRows<3>(3) += spatial::skew(nu.template segment<3>(3 * b)) * dnu.template middleRows<3>(3 * b);

    // Chain to the local DOFs, in the reduced row order first.
    Eigen::Matrix<double, nr, n> kr = Eigen::Matrix<double, nr, n>::Zero(), cr = kr, mr = kr;
    for (int i = 0; i < NB; ++i) {
      const spatial::quaternion q = quat(u, i), qd = quat(v, i), qdd = quat(a, i);
      const double s = q.squaredNorm(), g = q.dot(qd);
      const Eigen::Matrix<double, 3, 4>& e2 = e2s[static_cast<std::size_t>(i)];
      const vec3 w = nu.template segment<3>(6 * i + 3), alpha1 = e2 * qdd;
      const Eigen::Matrix<double, 3, 4> dw_dq = -(2.0 / s) * (spatial::e_matrix(qd) + w * q.transpose());
      const Eigen::Matrix<double, 3, 4> dal_dq = -(2.0 / s) * spatial::e_matrix(qdd) - (2.0 / s) * alpha1 * q.transpose() -
                                                 (2.0 / s) * w * qd.transpose() - (2.0 * g / s) * dw_dq +
                                                 (4.0 * g / (s * s)) * w * q.transpose();
      const Eigen::Matrix<double, 3, 4> dal_dqd = -(2.0 / s) * (w * q.transpose() + g * e2);
      const auto cw = cn.template middleCols<3>(6 * i + 3);
      const auto aw = am.template middleCols<3>(6 * i + 3);
      Eigen::Matrix<double, nr, 4> kq = cw * dw_dq + aw * dal_dq;
      if (i == 0) kq += fphi * e2;
      const Eigen::Matrix<double, nr, 4> cq = cw * e2 + aw * dal_dqd, mq = aw * e2;
      const std::array<int, 4> qc{6 * i + 3, 6 * i + 4, 6 * i + 5, 6 * NB + i};
      for (std::size_t c = 0; c < 4; ++c) {
        kr.col(qc[c]) = kq.col(static_cast<Eigen::Index>(c));
        cr.col(qc[c]) = cq.col(static_cast<Eigen::Index>(c));
        mr.col(qc[c]) = mq.col(static_cast<Eigen::Index>(c));
      }
      cr.template middleCols<3>(6 * i) = cn.template middleCols<3>(6 * i);
      mr.template middleCols<3>(6 * i) = am.template middleCols<3>(6 * i);
    }
    for (int j = 0; j < NM; ++j) {
      cr.col(7 * NB + j) = cn.col(6 * NB + j);
      mr.col(7 * NB + j) = am.col(6 * NB + j);
    }
    for (int k = 0; k < nr; ++k) {
      kk->row(local_of(k)) += kr.row(k);
      cc->row(local_of(k)) += cr.row(k);
      mm->row(local_of(k)) += mr.row(k);
    }
    return kinetic;
  }

};

}  // namespace pradis::elements::detail
