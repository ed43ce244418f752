#pragma once
/// \file
/// The corotational kinematics of BEAM3 (elements/spatial/beam.hpp): the reference
/// geometry of a straight beam, the local linear stiffnesses, and the strain energy
/// of the corotational Euler-Bernoulli beam with its gradient (the flows) in closed
/// form, written once for any scalar type T (double, or spatial::dual for the exact
/// tangent by forward differentiation of the gradient). docs/rotations.md.

#include <array>
#include <cmath>

#include "pradis/spatial/dual.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// Geometry of a straight beam given by its end points A, B and a vector v of the
/// cross-section's local y axis: the reference frame T0 = [e1 e2 e3] with e1 along
/// A -> B, e2 the part of v normal to e1, e3 = e1 x e2.
struct beam_geometry {
  spatial::vec3 a, b, v;  ///< end points and section vector

  /// Length |B - A|.
  double length() const { return (b - a).norm(); }
  /// Whether v has a part normal to the axis (relative 1e-6).
  bool section_ok() const {
    const spatial::vec3 e1 = (b - a).normalized();
    return (v - v.dot(e1) * e1).norm() > 1e-6 * v.norm() && v.norm() > 0;
  }
  /// T0 = [e1 e2 e3] (columns; local -> global at the reference configuration).
  spatial::mat3 frame() const {
    const spatial::vec3 e1 = (b - a).normalized();
    const spatial::vec3 e2 = (v - v.dot(e1) * e1).normalized();
    spatial::mat3 t;
    t.col(0) = e1;
    t.col(1) = e2;
    t.col(2) = e1.cross(e2);
    return t;
  }
};

/// Stiffnesses of the local linear beam (divided by L0 where it applies).
struct beam_stiffness {
  double ea = 0, gj = 0, eiy = 0, eiz = 0, l0 = 1;  ///< E A, G J, E Iy, E Iz [N, N m^2], L0 [m]
};

/// A quaternion of scalars T (vector part first, scalar last).
template <class T>
using tquat = std::array<T, 4>;
/// A 3-vector of scalars T.
template <class T>
using tvec = std::array<T, 3>;

/// Hamilton product a b, scalar last (as spatial::multiply).
template <class T>
tquat<T> qmul(const tquat<T>& a, const tquat<T>& b) {
  return {a[3] * b[0] + b[3] * a[0] + (a[1] * b[2] - a[2] * b[1]),
          a[3] * b[1] + b[3] * a[1] + (a[2] * b[0] - a[0] * b[2]),
          a[3] * b[2] + b[3] * a[2] + (a[0] * b[1] - a[1] * b[0]),
          a[3] * b[3] - (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])};
}
/// Hamilton product of quaternions of dual numbers: the product is bilinear, so the
/// value is the product of the values and each derivative a' b + a b' (the same
/// result as the generic product, without its temporaries).
template <int N>
tquat<spatial::dual<double, N>> qmul(const tquat<spatial::dual<double, N>>& a, const tquat<spatial::dual<double, N>>& b) {
  tquat<double> av, bv;
  for (std::size_t i = 0; i < 4; ++i) {
    av[i] = a[i].v;
    bv[i] = b[i].v;
  }
  tquat<spatial::dual<double, N>> r;
  const tquat<double> rv = qmul(av, bv);
  for (std::size_t i = 0; i < 4; ++i) r[i].v = rv[i];
  for (std::size_t k = 0; k < static_cast<std::size_t>(N); ++k) {
    const tquat<double> ad{a[0].d[k], a[1].d[k], a[2].d[k], a[3].d[k]}, bd{b[0].d[k], b[1].d[k], b[2].d[k], b[3].d[k]};
    const tquat<double> x = qmul(ad, bv), y = qmul(av, bd);
    for (std::size_t i = 0; i < 4; ++i) r[i].d[k] = x[i] + y[i];
  }
  return r;
}
/// Conjugate.
template <class T>
tquat<T> qconj(const tquat<T>& a) {
  return {-a[0], -a[1], -a[2], a[3]};
}
/// Cross product a x b.
template <class T>
tvec<T> cross(const tvec<T>& a, const tvec<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// Rotation vector (axis times angle) of a unit quaternion with q4 > 0:
/// theta = 2 atan(|v| / q4) v / |v| = (2 h(x) / q4) v with x = |v|^2 / q4^2 and
/// h(x) = atan(sqrt x) / sqrt x, smooth at v = 0 (its series below x = 1e-6).
/// If qbar is given, it receives the adjoint: qbar = (d theta / d q)^T thetabar.
template <class T>
tvec<T> qlog(const tquat<T>& q, const tvec<T>* thetabar = nullptr, tquat<T>* qbar = nullptr) {
  const T vv = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  const T x = vv / (q[3] * q[3]);
  T h, hp;  // h(x) and h'(x)
  if (spatial::value_of(x) < 1e-6) {
    h = T(1.0) - x * (1.0 / 3) + x * x * (1.0 / 5) - x * x * x * (1.0 / 7);
    hp = x * (2.0 / 5) - x * x * (3.0 / 7) - 1.0 / 3;
  } else {
    using std::atan, std::sqrt;
    const T r = sqrt(x);
    h = atan(r) / r;
    hp = (T(1.0) / (1.0 + x) - h) / (2.0 * x);
  }
  const T c = 2.0 * h / q[3];
  if (thetabar) {
    // theta = c v: vbar = c thetabar + (thetabar . v) dc/dv, qbar4 = (thetabar . v) dc/dq4,
    // dc/dv = 4 h' v / q4^3, dc/dq4 = -(2 / q4^2) (h + 2 x h').
    const tvec<T>& tb = *thetabar;
    const T g = tb[0] * q[0] + tb[1] * q[1] + tb[2] * q[2];
    const T gv = 4.0 * hp * g / (q[3] * q[3] * q[3]);
    for (std::size_t i = 0; i < 3; ++i) (*qbar)[i] = c * tb[i] + gv * q[i];
    (*qbar)[3] = -2.0 * g * (h + 2.0 * x * hp) / (q[3] * q[3]);
  }
  return {c * q[0], c * q[1], c * q[2]};
}

/// What the corotational kinematics gives for one state: the strain energy, its
/// gradient (the flows) and the quantities that must stay away from singular values.
template <class T>
struct corotational_state {
  T energy;                     ///< strain energy U [J]
  T stretch;                    ///< l - L0 [m]
  tvec<T> theta_a, theta_b;     ///< local deformational rotations of the ends [rad]
  /// dU/dd (d the chord B - A) [N], then the global moments n_a, n_b = dU/dphi
  /// (phi a small global rotation of the end triad, R -> exp(phi) R) [N m].
  std::array<T, 9> gradient;
  double length = 0;            ///< current chord length l [m]
  double align = 0;             ///< cosine between the mean frame's axis and the chord
  double wa = 0, wb = 0;        ///< scalar parts of the local rotations (cos of half angles)
};

/// The corotational kinematics, the energy and its gradient. d: current chord B - A;
/// ta, tb: the unit quaternions of the end triads (nodal quaternion times the
/// section's reference frame, local -> global).
///
/// Element frame: the mean of the end triads, tm = (ta + tb) / |ta + tb| (tb taken
/// with the sign that makes ta . tb >= 0; this is ta sqrt(conj(ta) tb)), turned by
/// the smallest rotation that puts its first axis on the chord: te = turn tm. Local
/// rotations: the end triads relative to te, theta = log(conj(te) t). Energy of the
/// local linear Euler-Bernoulli beam (axial, torsion, two bending planes). The
/// gradient is the reverse (adjoint) sweep of these steps; with T a dual number
/// whose inputs are seeded, its derivatives are the exact tangent.
template <class T>
corotational_state<T> corotational(const tvec<T>& d, const tquat<T>& ta, const tquat<T>& tb, const beam_stiffness& k) {
  using std::sqrt;
  using spatial::value_of;
  // ---- forward ----
  const double sg = value_of(ta[0] * tb[0] + ta[1] * tb[1] + ta[2] * tb[2] + ta[3] * tb[3]) < 0 ? -1.0 : 1.0;
  tquat<T> m;
  for (std::size_t i = 0; i < 4; ++i) m[i] = ta[i] + sg * tb[i];
  const T hn = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2] + m[3] * m[3]);
  tquat<T> tm;
  for (std::size_t i = 0; i < 4; ++i) tm[i] = m[i] / hn;
  // First axis of the mean triad and the chord direction.
  const tvec<T> ax{tm[3] * tm[3] + tm[0] * tm[0] - tm[1] * tm[1] - tm[2] * tm[2],
                   2.0 * (tm[0] * tm[1] + tm[3] * tm[2]), 2.0 * (tm[0] * tm[2] - tm[3] * tm[1])};
  const T l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const tvec<T> e1{d[0] / l, d[1] / l, d[2] / l};
  const T c = ax[0] * e1[0] + ax[1] * e1[1] + ax[2] * e1[2];
  const T sn = sqrt(2.0 + 2.0 * c);
  const tvec<T> x = cross(ax, e1);
  const tquat<T> turn{x[0] / sn, x[1] / sn, x[2] / sn, (1.0 + c) / sn};
  const tquat<T> te = qmul(turn, tm);
  tquat<T> ra = qmul(qconj(te), ta), rb = qmul(qconj(te), tb);
  const double sa = value_of(ra[3]) < 0 ? -1.0 : 1.0, sb = value_of(rb[3]) < 0 ? -1.0 : 1.0;
  for (std::size_t i = 0; i < 4; ++i) {
    ra[i] = sa * ra[i];
    rb[i] = sb * rb[i];
  }
  corotational_state<T> s;
  s.length = value_of(l);
  s.align = value_of(c);
  s.wa = value_of(ra[3]);
  s.wb = value_of(rb[3]);
  s.theta_a = qlog(ra);
  s.theta_b = qlog(rb);
  s.stretch = l - k.l0;
  const tvec<T>& a = s.theta_a;
  const tvec<T>& b = s.theta_b;
  const T tw = b[0] - a[0];
  const double cy = 2.0 * k.eiy / k.l0, cz = 2.0 * k.eiz / k.l0, ct = k.gj / k.l0;
  s.energy = (0.5 * k.ea / k.l0) * s.stretch * s.stretch + (0.5 * ct) * tw * tw +
             cy * (a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) + cz * (a[2] * a[2] + a[2] * b[2] + b[2] * b[2]);

  // ---- reverse: adjoints (bar) of every step ----
  const T axial = (k.ea / k.l0) * s.stretch;  // dU/dl
  const tvec<T> ma{-ct * tw, cy * (2.0 * a[1] + b[1]), cz * (2.0 * a[2] + b[2])};
  const tvec<T> mb{ct * tw, cy * (a[1] + 2.0 * b[1]), cz * (a[2] + 2.0 * b[2])};
  tquat<T> rab, rbb;
  qlog(ra, &ma, &rab);
  qlog(rb, &mb, &rbb);
  for (std::size_t i = 0; i < 4; ++i) {
    rab[i] = sa * rab[i];
    rbb[i] = sb * rbb[i];
  }
  // p = conj(te) t: tbar += te pbar, tebar += t conj(pbar).
  tquat<T> tab = qmul(te, rab), tbb = qmul(te, rbb);
  const tquat<T> ea = qmul(ta, qconj(rab)), eb = qmul(tb, qconj(rbb));
  tquat<T> teb;
  for (std::size_t i = 0; i < 4; ++i) teb[i] = ea[i] + eb[i];
  // te = turn tm: turnbar = tebar conj(tm), tmbar = conj(turn) tebar.
  const tquat<T> turnb = qmul(teb, qconj(tm));
  tquat<T> tmb = qmul(qconj(turn), teb);
  // turn = (x, 1 + c) / sn, sn = sqrt(2 + 2c), x = ax x e1, c = ax . e1.
  const T snb = -(turnb[0] * x[0] + turnb[1] * x[1] + turnb[2] * x[2] + turnb[3] * (1.0 + c)) / (sn * sn);
  const T cb = (turnb[3] + snb) / sn;
  const tvec<T> xb{turnb[0] / sn, turnb[1] / sn, turnb[2] / sn};
  const tvec<T> e1x = cross(e1, xb), xax = cross(xb, ax);
  const tvec<T> axb{e1x[0] + cb * e1[0], e1x[1] + cb * e1[1], e1x[2] + cb * e1[2]};
  const tvec<T> e1b{xax[0] + cb * ax[0], xax[1] + cb * ax[1], xax[2] + cb * ax[2]};
  // d: l = |d| (bar: axial), e1 = d / l (bar: the part of e1bar normal to e1, over l).
  const T pe = e1b[0] * e1[0] + e1b[1] * e1[1] + e1b[2] * e1[2];
  for (std::size_t i = 0; i < 3; ++i) s.gradient[i] = axial * e1[i] + (e1b[i] - pe * e1[i]) / l;
  // ax(tm), the first column of R(tm).
  tmb[0] += 2.0 * (tm[0] * axb[0] + tm[1] * axb[1] + tm[2] * axb[2]);
  tmb[1] += 2.0 * (tm[0] * axb[1] - tm[1] * axb[0] - tm[3] * axb[2]);
  tmb[2] += 2.0 * (tm[0] * axb[2] - tm[2] * axb[0] + tm[3] * axb[1]);
  tmb[3] += 2.0 * (tm[3] * axb[0] + tm[2] * axb[1] - tm[1] * axb[2]);
  // tm = m / |m|, m = ta + sg tb.
  const T pm = tmb[0] * tm[0] + tmb[1] * tm[1] + tmb[2] * tm[2] + tmb[3] * tm[3];
  for (std::size_t i = 0; i < 4; ++i) {
    const T mbar = (tmb[i] - pm * tm[i]) / hn;
    tab[i] += mbar;
    tbb[i] += sg * mbar;
  }
  // A global rotation phi moves t by (phi / 2, 0) t: dU/dphi = vec(tbar conj(t)) / 2.
  const tquat<T> na = qmul(tab, qconj(ta)), nb = qmul(tbb, qconj(tb));
  for (std::size_t i = 0; i < 3; ++i) {
    s.gradient[3 + i] = 0.5 * na[i];
    s.gradient[6 + i] = 0.5 * nb[i];
  }
  return s;
}

}  // namespace pradis::elements::detail
