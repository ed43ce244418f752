#pragma once
/// \file
/// The flows of a reduced elastic body in large motion (FLEX3,
/// elements/spatial/reduced_body.hpp), written once for any scalar type T (double,
/// or spatial::dual for the exact Jacobian by forward differentiation).
/// docs/reduction.md derives them.

#include <algorithm>
#include <array>
#include <cmath>

#include "pradis/elements/spatial/beam_kinematics.hpp"
#include "pradis/spatial/dual.hpp"

namespace pradis::elements::detail {

/// The state of a reduced body in scalars T: per boundary node its position x
/// (reference plus displacement), velocity v, acceleration a, quaternion q (not
/// necessarily unit) and its first and second time derivatives; the modal
/// coordinates eta and their derivatives.
template <class T, int NB, int NM>
struct reduced_body_state {
  std::array<tvec<T>, NB> x{}, v{}, a{};
  std::array<tquat<T>, NB> q{}, qd{}, qdd{};
  std::array<T, NM> eta{}, etad{}, etadd{};
};

/// The flows of a reduced body: per node the force and the global moment, per
/// mode the generalised force; the strain and kinetic energy; and the smallest
/// scalar part of the nodes' unit rotations relative to node 1 (near 0 at a
/// relative rotation of 180 degrees, where the local rotations are singular).
template <class T, int NB, int NM>
struct reduced_body_flows {
  std::array<tvec<T>, NB> force{}, moment{};
  std::array<T, NM> modal{};
  T strain{}, kinetic{};
  double min_w = 1;
};

/// Global angular velocity (2/s) E(q) q' of a quaternion of scalars T.
template <class T>
tvec<T> angular_velocity_of(const tquat<T>& q, const tquat<T>& qd, const T& s) {
  // E(q) p = q4 p_v + q_v x p_v - p4 q_v.
  const tvec<T> c = cross(tvec<T>{q[0], q[1], q[2]}, tvec<T>{qd[0], qd[1], qd[2]});
  tvec<T> w;
  for (std::size_t i = 0; i < 3; ++i) w[i] = (T(2.0) / s) * (q[3] * qd[i] + c[i] - qd[3] * q[i]);
  return w;
}

/// The flows of a reduced elastic part with stiffness k and mass m (n = 6 NB + NM
/// square, reduced coordinates node by node (ux uy uz rx ry rz) then the modes)
/// whose boundary nodes sit at x0 (3 NB) in the reference configuration, in the
/// floating frame of node 1:
///
/// - local coordinates d: node 1 none; node i > 1 its translation
///   R^T (x_i - x_1) - (X_i - X_1) and its rotation log(R^T R_i) relative to the
///   frame R = R(q_1); the modes as they are; strain energy U = d^T k d / 2 and
///   its exact gradient (forces dU/dx, global moments dU/dphi);
/// - kinetic energy K = nubar^T m nubar / 2 with nubar the nodes' velocities and
///   angular velocities in the frame and the modal rates, and its exact Lagrange
///   equations: p = Rh m Rh^T nu (global momenta), flows
///   Rh m Rh^T (nu' - W nu) + W p, minus omega_i x h_i on each node's moment, minus
///   sum_b p_b x nu_b on node 1's (the orientation dependence of K), where Rh is
///   R on every 3-block and W is [omega_1 x] on every 3-block.
///
/// `with_elastic` = false skips the strain part (for derivatives by v and a).
template <class T, int NB, int NM, class Mat>
reduced_body_flows<T, NB, NM> reduced_body_flows_of(const reduced_body_state<T, NB, NM>& st, const Mat& k,
                                                     const Mat& m, const std::array<double, 3 * NB>& x0,
                                                     bool with_elastic) {
  constexpr int nr = 6 * NB + NM;
  using std::sqrt;
  reduced_body_flows<T, NB, NM> out;
  std::array<T, NB> s;
  std::array<tquat<T>, NB> qh;
  for (std::size_t i = 0; i < NB; ++i) {
    const auto& q = st.q[i];
    s[i] = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    const T r = sqrt(s[i]);
    for (std::size_t j = 0; j < 4; ++j) qh[i][j] = q[j] / r;
  }
  // R = R(q_1) (body -> global), from the unit quaternion.
  const tquat<T>& u = qh[0];
  std::array<std::array<T, 3>, 3> rm;
  rm[0] = {1.0 - 2.0 * (u[1] * u[1] + u[2] * u[2]), 2.0 * (u[0] * u[1] - u[2] * u[3]), 2.0 * (u[0] * u[2] + u[1] * u[3])};
  rm[1] = {2.0 * (u[0] * u[1] + u[2] * u[3]), 1.0 - 2.0 * (u[0] * u[0] + u[2] * u[2]), 2.0 * (u[1] * u[2] - u[0] * u[3])};
  rm[2] = {2.0 * (u[0] * u[2] - u[1] * u[3]), 2.0 * (u[1] * u[2] + u[0] * u[3]), 1.0 - 2.0 * (u[0] * u[0] + u[1] * u[1])};
  const auto to_global = [&rm](const tvec<T>& y) {
    tvec<T> g;
    for (std::size_t i = 0; i < 3; ++i) g[i] = rm[i][0] * y[0] + rm[i][1] * y[1] + rm[i][2] * y[2];
    return g;
  };
  const auto to_local = [&rm](const tvec<T>& y) {
    tvec<T> l;
    for (std::size_t i = 0; i < 3; ++i) l[i] = rm[0][i] * y[0] + rm[1][i] * y[1] + rm[2][i] * y[2];
    return l;
  };
  const auto add_to = [](tvec<T>& a, const tvec<T>& b, double f) {
    for (std::size_t i = 0; i < 3; ++i) a[i] += f * b[i];
  };
  for (auto& f : out.force) f = {T(0.0), T(0.0), T(0.0)};
  for (auto& f : out.moment) f = {T(0.0), T(0.0), T(0.0)};
  for (auto& f : out.modal) f = T(0.0);

  if (with_elastic) {
    std::array<T, nr> d;
    for (auto& x : d) x = T(0.0);
    std::array<tvec<T>, NB> chord;
    std::array<tquat<T>, NB> rel;
    for (std::size_t i = 1; i < NB; ++i) {
      for (std::size_t j = 0; j < 3; ++j) chord[i][j] = st.x[i][j] - st.x[0][j];
      const tvec<T> cl = to_local(chord[i]);
      for (std::size_t j = 0; j < 3; ++j) d[6 * i + j] = cl[j] - (x0[3 * i + j] - x0[j]);
      rel[i] = qmul(qconj(qh[0]), qh[i]);
      if (spatial::value_of(rel[i][3]) < 0)
        for (auto& c : rel[i]) c = -c;
      out.min_w = std::min(out.min_w, spatial::value_of(rel[i][3]));
      const tvec<T> th = qlog(rel[i]);
      for (std::size_t j = 0; j < 3; ++j) d[6 * i + 3 + j] = th[j];
    }
    for (std::size_t j = 0; j < NM; ++j) d[6 * NB + j] = st.eta[j];
    std::array<T, nr> kd;
    for (int i = 0; i < nr; ++i) {
      T acc(0.0);
      for (int j = 6; j < nr; ++j) acc += k(i, j) * d[static_cast<std::size_t>(j)];  // d of node 1 is zero
      kd[static_cast<std::size_t>(i)] = acc;
    }
    T energy(0.0);
    for (std::size_t i = 0; i < nr; ++i) energy += d[i] * kd[i];
    out.strain = 0.5 * energy;
    for (std::size_t i = 1; i < NB; ++i) {
      // Translation: dU/dx_i = R k_t, dU/dx_1 = -R k_t, dU/dphi_1 += (R k_t) x c_i.
      const tvec<T> fi = to_global({kd[6 * i], kd[6 * i + 1], kd[6 * i + 2]});
      add_to(out.force[i], fi, 1.0);
      add_to(out.force[0], fi, -1.0);
      add_to(out.moment[0], cross(fi, chord[i]), 1.0);
      // Rotation: a small global rotation phi of node i turns rel into ((R^T phi) / 2, 0) rel.
      const tvec<T> thbar{kd[6 * i + 3], kd[6 * i + 4], kd[6 * i + 5]};
      tquat<T> qbar;
      (void)qlog(rel[i], &thbar, &qbar);
      tvec<T> wl;
      for (std::size_t c = 0; c < 3; ++c) {
        const tquat<T> e{T(c == 0 ? 0.5 : 0.0), T(c == 1 ? 0.5 : 0.0), T(c == 2 ? 0.5 : 0.0), T(0.0)};
        const tquat<T> dq = qmul(e, rel[i]);
        wl[c] = qbar[0] * dq[0] + qbar[1] * dq[1] + qbar[2] * dq[2] + qbar[3] * dq[3];
      }
      const tvec<T> mi = to_global(wl);
      add_to(out.moment[i], mi, 1.0);
      add_to(out.moment[0], mi, -1.0);
    }
    for (std::size_t j = 0; j < NM; ++j) out.modal[j] = kd[6 * NB + j];
  }

  // Inertia. nu: per node (v_i, omega_i), then the modal rates; nud: (a_i, alpha_i), modal accelerations.
  std::array<tvec<T>, 2 * NB> nu, nud;
  for (std::size_t i = 0; i < NB; ++i) {
    nu[2 * i] = st.v[i];
    nud[2 * i] = st.a[i];
    nu[2 * i + 1] = angular_velocity_of(st.q[i], st.qd[i], s[i]);
    // alpha = (2/s) E(q) q'' - (4 (q.q') / s^2) E(q) q'.
    const tvec<T> a1 = angular_velocity_of(st.q[i], st.qdd[i], s[i]);
    const T g = st.q[i][0] * st.qd[i][0] + st.q[i][1] * st.qd[i][1] + st.q[i][2] * st.qd[i][2] + st.q[i][3] * st.qd[i][3];
    for (std::size_t j = 0; j < 3; ++j) nud[2 * i + 1][j] = a1[j] - (2.0 * g / s[i]) * nu[2 * i + 1][j];
  }
  const tvec<T> w1 = nu[1];
  // Local (frame) vectors: nubar = Rh^T nu and zbar = Rh^T (nu' - W nu).
  std::array<T, nr> nub, zb;
  for (std::size_t b = 0; b < 2 * NB; ++b) {
    const tvec<T> l = to_local(nu[b]);
    const tvec<T> wn = cross(w1, nu[b]);
    tvec<T> z;
    for (std::size_t j = 0; j < 3; ++j) z[j] = nud[b][j] - wn[j];
    const tvec<T> zl = to_local(z);
    for (std::size_t j = 0; j < 3; ++j) {
      nub[3 * b + j] = l[j];
      zb[3 * b + j] = zl[j];
    }
  }
  for (std::size_t j = 0; j < NM; ++j) {
    nub[6 * NB + j] = st.etad[j];
    zb[6 * NB + j] = st.etadd[j];
  }
  std::array<T, nr> yb, fb;  // m nubar and m zbar
  for (int i = 0; i < nr; ++i) {
    T y(0.0), f(0.0);
    for (int j = 0; j < nr; ++j) {
      y += m(i, j) * nub[static_cast<std::size_t>(j)];
      f += m(i, j) * zb[static_cast<std::size_t>(j)];
    }
    yb[static_cast<std::size_t>(i)] = y;
    fb[static_cast<std::size_t>(i)] = f;
  }
  T kin(0.0);
  for (std::size_t i = 0; i < nr; ++i) kin += nub[i] * yb[i];
  out.kinetic = 0.5 * kin;
  for (std::size_t b = 0; b < 2 * NB; ++b) {
    const std::size_t node = b / 2;
    const tvec<T> p = to_global({yb[3 * b], yb[3 * b + 1], yb[3 * b + 2]});
    tvec<T> f = to_global({fb[3 * b], fb[3 * b + 1], fb[3 * b + 2]});
    add_to(f, cross(w1, p), 1.0);
    if (b % 2 == 1) add_to(f, cross(nu[b], p), -1.0);  // - omega_i x h_i
    add_to(out.moment[0], cross(p, nu[b]), -1.0);
    add_to(b % 2 == 0 ? out.force[node] : out.moment[node], f, 1.0);
  }
  for (std::size_t j = 0; j < NM; ++j) out.modal[j] += fb[6 * NB + j];
  return out;
}

}  // namespace pradis::elements::detail
