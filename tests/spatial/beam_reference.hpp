#pragma once
// A reference tangent of BEAM3 computed independently of the element's closed-form
// gradient: the strain energy U of the corotational beam (the formulation of
// docs/rotations.md, with the mean triad written as ta sqrt(conj(ta) tb)) in nested
// dual numbers dual<dual<double, 9>, 9>, which give its gradient and Hessian H in
// (chord d, phi_a, phi_b) by forward differentiation twice (the rotations perturbed
// as the quaternion (phi/2, 1 - |phi|^2/8), exp(phi) to second order, times the end
// triad). The derivative of a moment by the rotation of its own node is then
// H - (1/2) [n x] (exp(psi) exp(phi) = exp(psi + phi + (1/2) psi x phi + ...)), and
// the chain to the potentials is dphi/dq = (2/s) E(q). This was BEAM3's own tangent
// before the closed-form gradient; it is slow (about 10 times the element) and kept
// here to check the element.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <type_traits>

#include "pradis/elements/spatial/beam.hpp"

namespace pradis_beam_reference {

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::elements::detail;
using pradis::spatial::dual;

/// q or -q, whichever has a non-negative scalar part.
template <class T>
tquat<T> qpositive(const tquat<T>& a) {
  if (spatial::value_of(a[3]) < 0) return {-a[0], -a[1], -a[2], -a[3]};
  return a;
}

/// The strain energy of the corotational beam (docs/rotations.md). d: chord; qa, qb:
/// unit nodal quaternions; t0: reference frame of the section.
template <class T>
T energy(const tvec<T>& d, const tquat<T>& qa, const tquat<T>& qb, const spatial::quaternion& t0,
         const beam_stiffness& k) {
  using std::sqrt;
  const tquat<T> t0t{T(t0(0)), T(t0(1)), T(t0(2)), T(t0(3))};
  const tquat<T> ta = qmul(qa, t0t), tb = qmul(qb, t0t);
  const tquat<T> r = qpositive(qmul(qconj(ta), tb));
  const T hn = sqrt(2.0 + 2.0 * r[3]);
  const tquat<T> half{r[0] / hn, r[1] / hn, r[2] / hn, (r[3] + 1.0) / hn};
  const tquat<T> tm = qmul(ta, half);
  const tvec<T> ax{tm[3] * tm[3] + tm[0] * tm[0] - tm[1] * tm[1] - tm[2] * tm[2],
                   2.0 * (tm[0] * tm[1] + tm[3] * tm[2]), 2.0 * (tm[0] * tm[2] - tm[3] * tm[1])};
  const T l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const tvec<T> e1{d[0] / l, d[1] / l, d[2] / l};
  const T c = ax[0] * e1[0] + ax[1] * e1[1] + ax[2] * e1[2];
  const T sn = sqrt(2.0 + 2.0 * c);
  const tquat<T> turn{(ax[1] * e1[2] - ax[2] * e1[1]) / sn, (ax[2] * e1[0] - ax[0] * e1[2]) / sn,
                      (ax[0] * e1[1] - ax[1] * e1[0]) / sn, (1.0 + c) / sn};
  const tquat<T> te = qmul(turn, tm);
  const tvec<T> a = qlog(qpositive(qmul(qconj(te), ta))), b = qlog(qpositive(qmul(qconj(te), tb)));
  const T stretch = l - k.l0, tw = b[0] - a[0];
  return (0.5 * k.ea / k.l0) * stretch * stretch + (0.5 * k.gj / k.l0) * tw * tw +
         (2.0 * k.eiy / k.l0) * (a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) +
         (2.0 * k.eiz / k.l0) * (a[2] * a[2] + a[2] * b[2] + b[2] * b[2]);
}

/// Variable k with value x in every nesting level of T.
template <class T>
T seed(double x, int k) {
  if constexpr (std::is_same_v<T, double>) {
    (void)k;
    return x;
  } else {
    using S = decltype(T{}.v);
    return T::variable(seed<S>(x, k), k);
  }
}

/// Flows f and stiffness block K of BEAM3 e at the potentials u (the element's layout).
struct reference_result {
  Eigen::Matrix<double, 14, 1> f;
  Eigen::Matrix<double, 14, 14> K;
};
inline reference_result evaluate(const elastic_beam& e, const Eigen::Matrix<double, 14, 1>& u) {
  using namespace spatial;
  using d2 = dual<dual<double, 9>, 9>;
  const quaternion qa(u(3), u(4), u(5), u(12)), qb(u(9), u(10), u(11), u(13));
  const double sa = qa.squaredNorm(), sb = qb.squaredNorm();
  const beam_geometry g = e.geometry();
  const vec3 d = g.b - g.a + u.segment<3>(6) - u.head<3>();
  const beam_stiffness k{e.p.e * e.p.a, e.p.g * e.p.j, e.p.e * e.p.iy, e.p.e * e.p.iz, g.length()};
  const quaternion ua = qa / std::sqrt(sa), ub = qb / std::sqrt(sb);
  tvec<d2> dd;
  tquat<d2> pa, pb, qat, qbt;
  for (int i = 0; i < 3; ++i) dd[static_cast<std::size_t>(i)] = seed<d2>(d(i), i);
  for (int i = 0; i < 4; ++i) {
    qat[static_cast<std::size_t>(i)] = d2(ua(i));
    qbt[static_cast<std::size_t>(i)] = d2(ub(i));
  }
  for (int i = 0; i < 3; ++i) {
    pa[static_cast<std::size_t>(i)] = 0.5 * seed<d2>(0.0, 3 + i);
    pb[static_cast<std::size_t>(i)] = 0.5 * seed<d2>(0.0, 6 + i);
  }
  pa[3] = d2(1.0) - 0.5 * (pa[0] * pa[0] + pa[1] * pa[1] + pa[2] * pa[2]);
  pb[3] = d2(1.0) - 0.5 * (pb[0] * pb[0] + pb[1] * pb[1] + pb[2] * pb[2]);
  const d2 en = energy(dd, qmul(pa, qat), qmul(pb, qbt), from_matrix(g.frame()), k);
  Eigen::Matrix<double, 9, 1> gr;
  Eigen::Matrix<double, 9, 9> h;
  for (int i = 0; i < 9; ++i) {
    gr(i) = en.v.d[static_cast<std::size_t>(i)];
    for (int j = 0; j < 9; ++j) h(i, j) = en.d[static_cast<std::size_t>(i)].d[static_cast<std::size_t>(j)];
  }
  reference_result r;
  r.f.setZero();
  r.f.head<3>() = -gr.head<3>();
  r.f.segment<3>(6) = gr.head<3>();
  r.f.segment<3>(3) = gr.segment<3>(3);
  r.f.segment<3>(9) = gr.segment<3>(6);
  Eigen::Matrix<double, 9, 9> hh = h;
  hh.block<3, 3>(3, 3) -= 0.5 * skew(gr.segment<3>(3));
  hh.block<3, 3>(6, 6) -= 0.5 * skew(gr.segment<3>(6));
  const mat34 dta = (2.0 / sa) * e_matrix(qa), dtb = (2.0 / sb) * e_matrix(qb);
  constexpr std::array<int, 4> row0{0, 6, 3, 9};
  constexpr std::array<int, 4> grow{0, 0, 3, 6};
  constexpr std::array<double, 4> sign{-1, 1, 1, 1};
  r.K.setZero();
  for (std::size_t q = 0; q < 4; ++q) {
    const Eigen::Matrix<double, 3, 9> hr = sign[q] * hh.block<3, 9>(grow[q], 0);
    r.K.block<3, 3>(row0[q], 0) = -hr.leftCols<3>();
    r.K.block<3, 3>(row0[q], 6) = hr.leftCols<3>();
    const Eigen::Matrix<double, 3, 4> ka = hr.block<3, 3>(0, 3) * dta, kb = hr.block<3, 3>(0, 6) * dtb;
    r.K.block<3, 3>(row0[q], 3) = ka.leftCols<3>();
    r.K.block<3, 1>(row0[q], 12) = ka.col(3);
    r.K.block<3, 3>(row0[q], 9) = kb.leftCols<3>();
    r.K.block<3, 1>(row0[q], 13) = kb.col(3);
  }
  return r;
}

}  // namespace pradis_beam_reference
