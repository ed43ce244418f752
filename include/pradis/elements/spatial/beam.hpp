#pragma once
/// \file
/// BEAM3: elastic spatial beam, corotational Euler-Bernoulli, between two points with
/// spatial rotational nodes; BEAMI3: its inertia (linear-interpolation translational
/// mass and lumped rotary inertia of the cross-section). docs/rotations.md.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <type_traits>

#include "pradis/core/element.hpp"
#include "pradis/spatial/dual.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

namespace detail {

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
/// Conjugate.
template <class T>
tquat<T> qconj(const tquat<T>& a) {
  return {-a[0], -a[1], -a[2], a[3]};
}
/// q or -q, whichever has a non-negative scalar part.
template <class T>
tquat<T> qpositive(const tquat<T>& a) {
  if (spatial::value_of(a[3]) < 0) return {-a[0], -a[1], -a[2], -a[3]};
  return a;
}

/// Rotation vector (axis times angle) of a unit quaternion with q4 > 0:
/// theta = 2 atan(|v| / q4) v / |v|, smooth at v = 0 (series of atan(sqrt x)/sqrt x).
template <class T>
tvec<T> qlog(const tquat<T>& q) {
  const T vv = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  const T x = vv / (q[3] * q[3]);
  T h;
  if (spatial::value_of(x) < 1e-6) {
    h = T(1.0) - x * (1.0 / 3) + x * x * (1.0 / 5) - x * x * x * (1.0 / 7);
  } else {
    using std::atan, std::sqrt;
    const T r = sqrt(x);
    h = atan(r) / r;
  }
  const T c = 2.0 * h / q[3];
  return {c * q[0], c * q[1], c * q[2]};
}

/// What the corotational kinematics gives for one state: the strain energy, its
/// deformations and the quantities that must stay away from singular values.
template <class T>
struct corotational_state {
  T energy;                     ///< strain energy [J]
  T stretch;                    ///< l - L0 [m]
  tvec<T> theta_a, theta_b;     ///< local deformational rotations of the ends [rad]
  double length = 0;            ///< current chord length l [m]
  double align = 0;             ///< cosine between the mean frame's axis and the chord
  double wa = 0, wb = 0;        ///< scalar parts of the local rotations (cos of half angles)
};

/// Stiffnesses of the local linear beam (divided by L0 where it applies).
struct beam_stiffness {
  double ea = 0, gj = 0, eiy = 0, eiz = 0, l0 = 1;  ///< E A, G J, E Iy, E Iz [N, N m^2], L0 [m]
};

/// The corotational kinematics and energy. d: current chord B - A; qa, qb: unit
/// nodal quaternions; t0: reference frame quaternion of the section (local -> global).
/// Element frame: the mean of the end triads (half the relative rotation), turned by
/// the smallest rotation that puts its first axis on the chord. Local rotations: the
/// end triads relative to the element frame, as rotation vectors. Energy of the
/// local linear Euler-Bernoulli beam (axial, torsion, two bending planes).
template <class T>
corotational_state<T> corotational(const tvec<T>& d, const tquat<T>& qa, const tquat<T>& qb, const spatial::quaternion& t0,
                                   const beam_stiffness& k) {
  using std::sqrt;
  const tquat<T> t0t{T(t0(0)), T(t0(1)), T(t0(2)), T(t0(3))};
  const tquat<T> ta = qmul(qa, t0t), tb = qmul(qb, t0t);
  // Mean triad: ta times the half of the relative rotation r = conj(ta) tb.
  const tquat<T> r = qpositive(qmul(qconj(ta), tb));
  const T hn = sqrt(2.0 + 2.0 * r[3]);
  const tquat<T> half{r[0] / hn, r[1] / hn, r[2] / hn, (r[3] + 1.0) / hn};
  const tquat<T> tm = qmul(ta, half);
  // First axis of the mean triad and the chord direction.
  const tvec<T> ax{tm[3] * tm[3] + tm[0] * tm[0] - tm[1] * tm[1] - tm[2] * tm[2],
                   2.0 * (tm[0] * tm[1] + tm[3] * tm[2]), 2.0 * (tm[0] * tm[2] - tm[3] * tm[1])};
  const T l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const tvec<T> e1{d[0] / l, d[1] / l, d[2] / l};
  const T c = ax[0] * e1[0] + ax[1] * e1[1] + ax[2] * e1[2];
  const T sn = sqrt(2.0 + 2.0 * c);
  const tquat<T> turn{(ax[1] * e1[2] - ax[2] * e1[1]) / sn, (ax[2] * e1[0] - ax[0] * e1[2]) / sn,
                      (ax[0] * e1[1] - ax[1] * e1[0]) / sn, (1.0 + c) / sn};
  const tquat<T> te = qmul(turn, tm);
  const tquat<T> ra = qpositive(qmul(qconj(te), ta)), rb = qpositive(qmul(qconj(te), tb));
  corotational_state<T> s;
  s.length = spatial::value_of(l);
  s.align = spatial::value_of(c);
  s.wa = spatial::value_of(ra[3]);
  s.wb = spatial::value_of(rb[3]);
  s.theta_a = qlog(ra);
  s.theta_b = qlog(rb);
  s.stretch = l - k.l0;
  const tvec<T>& a = s.theta_a;
  const tvec<T>& b = s.theta_b;
  const T tw = b[0] - a[0];
  s.energy = (0.5 * k.ea / k.l0) * s.stretch * s.stretch + (0.5 * k.gj / k.l0) * tw * tw +
             (2.0 * k.eiy / k.l0) * (a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) +
             (2.0 * k.eiz / k.l0) * (a[2] * a[2] + a[2] * b[2] + b[2] * b[2]);
  return s;
}

}  // namespace detail

/// BEAM3: elastic beam between the points A (x, y, z and rotational node qa) and B
/// (x, y, z and rotational node qb); corotational Euler-Bernoulli formulation (large
/// displacements and rotations, small strains). The element frame follows the chord
/// A -> B and the mean of the end triads; in it a linear beam with axial stiffness
/// EA/L0, torsion GJ/L0 and bending EIy, EIz (end-rotation stiffness EI/L0 [4 2; 2 4])
/// gives the strain energy U. The flows are dU/dx on the translations and the global
/// moments dU/dtheta (a small global rotation theta of a node) on q1, q2, q3, none on
/// q4. The Jacobian is exact: forward-mode automatic differentiation with fixed-size
/// nested dual numbers (spatial/dual.hpp) gives the Hessian of U in (chord, theta_a,
/// theta_b); the chain through theta = (2/s) E(q) q and the non-commuting rotations
/// (-1/2 [n x]) are applied by hand. The reference configuration is the one with
/// identity nodal quaternions; the section's local y axis is given by a vector.
struct elastic_beam {
  static constexpr pradis::passport passport{.name = "BEAM3", .ext = 12, .ent = 2, .par = 15, .wrk = 3, .adr = 1, .ign = 23};
  /// q1..q3 of node A are local DOFs 4..6 (0-based 3..5) with the hidden q4 at 13 (12);
  /// those of node B at 10..12 (9..11) with q4 at 14 (13).
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "elastic beam in spatial motion (corotational Euler-Bernoulli)",
      .name = "Elastic beam with axial, torsional and bending stiffness between two points with spatial rotational nodes",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of end A along X [m]\n"
              "2 - translation of end A along Y [m]\n"
              "3 - translation of end A along Z [m]\n"
              "4 - rotation potential q1 of end A's rotational node (flow: moment about X) [-]\n"
              "5 - q2 of end A (flow: moment about Y) [-]\n"
              "6 - q3 of end A (flow: moment about Z) [-]\n"
              "7 - translation of end B along X [m]\n"
              "8 - translation of end B along Y [m]\n"
              "9 - translation of end B along Z [m]\n"
              "10 - rotation potential q1 of end B's rotational node (flow: moment about X) [-]\n"
              "11 - q2 of end B (flow: moment about Y) [-]\n"
              "12 - q3 of end B (flow: moment about Z) [-]",
      .parameters = "1 - Young's modulus E [Pa] (> 0)\n"
                    "2 - shear modulus G [Pa] (> 0)\n"
                    "3 - cross-section area A [m^2] (> 0)\n"
                    "4 - second moment of area Iy about the section's local y axis [m^4] (> 0)\n"
                    "5 - second moment of area Iz about the local z axis [m^4] (> 0)\n"
                    "6 - torsion constant J [m^4] (> 0)\n"
                    "7 - initial X of end A [m]\n"
                    "8 - initial Y of end A [m]\n"
                    "9 - initial Z of end A [m]\n"
                    "10 - initial X of end B [m]\n"
                    "11 - initial Y of end B [m]\n"
                    "12 - initial Z of end B [m] (B must differ from A)\n"
                    "13 - X of a vector giving the section's local y axis (its part normal to A -> B) [-]\n"
                    "14 - Y of that vector [-]\n"
                    "15 - Z of that vector [-]",
      .work = "1 - initial length L0 [m]\n2 - axial force N [N], positive in tension\n3 - strain energy [J]",
      .special = "code 100 if E, G, A, Iy, Iz or J is not positive, A and B coincide, the section vector is parallel "
                 "to A -> B or a parameter is not finite; code 75 if a quaternion norm or the chord length comes near "
                 "zero or a local rotation reaches 180 degrees (the element is then far beyond small strains). The "
                 "reference configuration has identity nodal quaternions (set initial orientations with ROT0 only "
                 "together with a matching geometry)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double e = 0, g = 0, a = 0, iy = 0, iz = 0, j = 0;  ///< E, G [Pa]; A [m^2]; Iy, Iz, J [m^4]
    double xa = 0, ya = 0, za = 0;                      ///< initial position of end A [m]
    double xb = 1, yb = 0, zb = 0;                      ///< initial position of end B [m]
    double vx = 0, vy = 1, vz = 0;                      ///< vector of the section's local y axis
  };
  parameters p;

  explicit elastic_beam(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test): an
  /// oblique beam with an unsymmetric section.
  static parameters example() { return {2e2, 80, 0.5, 0.2, 0.1, 0.15, 0.1, -0.2, 0.3, 3.0, 1.5, -1.0, 0.2, 0.3, 1.0}; }
  static elastic_beam from_parameters(std::span<const double> v) {
    return elastic_beam({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12], v[13], v[14]});
  }
  /// The reference geometry.
  detail::beam_geometry geometry() const { return {{p.xa, p.ya, p.za}, {p.xb, p.yb, p.zb}, {p.vx, p.vy, p.vz}}; }

  /// NEWINT: positive moduli and section properties, distinct ends, a usable section
  /// vector (code 100); W(1) = L0.
  void new_integration(element_context& ctx) const {
    for (double x : {p.e, p.g, p.a, p.iy, p.iz, p.j, p.xa, p.ya, p.za, p.xb, p.yb, p.zb, p.vx, p.vy, p.vz})
      if (!std::isfinite(x)) ctx.invalid_parameter("the parameters must be finite");
    if (!(p.e > 0)) ctx.invalid_parameter("Young's modulus E = " + to_text(p.e) + " must be > 0");
    if (!(p.g > 0)) ctx.invalid_parameter("shear modulus G = " + to_text(p.g) + " must be > 0");
    if (!(p.a > 0)) ctx.invalid_parameter("area A = " + to_text(p.a) + " must be > 0");
    if (!(p.iy > 0) || !(p.iz > 0))
      ctx.invalid_parameter("second moments of area Iy = " + to_text(p.iy) + ", Iz = " + to_text(p.iz) + " must be > 0");
    if (!(p.j > 0)) ctx.invalid_parameter("torsion constant J = " + to_text(p.j) + " must be > 0");
    const detail::beam_geometry g = geometry();
    const double l0 = g.length();
    if (!(l0 > min_length)) ctx.invalid_parameter("ends A and B coincide: the length of the beam is zero");
    if (!g.section_ok()) ctx.invalid_parameter("the section vector is zero or parallel to the beam axis A -> B");
    ctx.work[0] = l0;
  }

  void evaluate(const local_input<elastic_beam>& in, local_output<elastic_beam>& out, element_context& ctx) const {
    using namespace spatial;
    const quaternion qa(in.u(3), in.u(4), in.u(5), in.u(12)), qb(in.u(9), in.u(10), in.u(11), in.u(13));
    const double sa = qa.squaredNorm(), sb = qb.squaredNorm();
    if (!(sa > lq_near_zero * lq_near_zero) || !(sb > lq_near_zero * lq_near_zero))
      ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    const detail::beam_geometry g = geometry();
    const vec3 d = g.b - g.a + in.u.segment<3>(6) - in.u.head<3>();
    const double l0 = g.length();
    if (!(d.norm() > 1e-6 * l0)) ctx.singular("the chord length of the beam has become close to zero");
    const quaternion t0 = from_matrix(g.frame());
    const detail::beam_stiffness k{p.e * p.a, p.g * p.j, p.e * p.iy, p.e * p.iz, l0};
    const quaternion ua = qa / std::sqrt(sa), ub = qb / std::sqrt(sb);

    if (!out.want_jacobian) {
      using d1 = dual<double, 9>;
      const auto s = state<d1>(d, ua, ub, t0, k);
      check(s, ctx);
      out.f.setZero();
      for (int i = 0; i < 3; ++i) {
        out.f(i) = -s.energy.d[i];
        out.f(6 + i) = s.energy.d[i];
        out.f(3 + i) = s.energy.d[3 + i];
        out.f(9 + i) = s.energy.d[6 + i];
      }
      write_work(s.stretch.v, s.energy.v, k, ctx);
      return;
    }
    using d2 = dual<dual<double, 9>, 9>;
    const auto s = state<d2>(d, ua, ub, t0, k);
    check(s, ctx);
    // Gradient and Hessian of U in (chord d, theta_a, theta_b).
    Eigen::Matrix<double, 9, 1> gr;
    Eigen::Matrix<double, 9, 9> h;
    for (int i = 0; i < 9; ++i) {
      gr(i) = s.energy.v.d[i];
      for (int j = 0; j < 9; ++j) h(i, j) = s.energy.d[i].d[j];
    }
    out.f.setZero();
    out.f.head<3>() = -gr.head<3>();
    out.f.segment<3>(6) = gr.head<3>();
    out.f.segment<3>(3) = gr.segment<3>(3);
    out.f.segment<3>(9) = gr.segment<3>(6);
    write_work(s.stretch.v.v, s.energy.v.v, k, ctx);
    // d(theta)/dq = (2/s) E(q); the moments of a node rotate with it: dn/dtheta = H - (1/2)[n x].
    Eigen::Matrix<double, 9, 9> hh = h;
    hh.block<3, 3>(3, 3) -= 0.5 * skew(gr.segment<3>(3));
    hh.block<3, 3>(6, 6) -= 0.5 * skew(gr.segment<3>(6));
    const mat34 dta = (2.0 / sa) * e_matrix(qa), dtb = (2.0 / sb) * e_matrix(qb);
    // Rows: the flows as functions of (d, theta_a, theta_b): f_xa = -g_d, f_xb = g_d, f_qa = g_ta, f_qb = g_tb.
    constexpr std::array<int, 4> row0{0, 6, 3, 9};
    constexpr std::array<int, 4> grow{0, 0, 3, 6};
    constexpr std::array<double, 4> sign{-1, 1, 1, 1};
    out.K.setZero();
    for (int r = 0; r < 4; ++r) {
      const auto hr = hh.block<3, 9>(grow[static_cast<std::size_t>(r)], 0);
      const double sg = sign[static_cast<std::size_t>(r)];
      const int i0 = row0[static_cast<std::size_t>(r)];
      const mat3 hd = sg * hr.block<3, 3>(0, 0);
      out.K.block<3, 3>(i0, 0) = -hd;
      out.K.block<3, 3>(i0, 6) = hd;
      const Eigen::Matrix<double, 3, 4> ka = sg * hr.block<3, 3>(0, 3) * dta, kb = sg * hr.block<3, 3>(0, 6) * dtb;
      out.K.block<3, 3>(i0, 3) = ka.leftCols<3>();
      out.K.block<3, 1>(i0, 12) = ka.col(3);
      out.K.block<3, 3>(i0, 9) = kb.leftCols<3>();
      out.K.block<3, 1>(i0, 13) = kb.col(3);
    }
  }

  /// States the checks may use: quaternion norms not near zero, the chord at least a
  /// tenth of L0, local rotations below about 170 degrees.
  bool admissible(const local_input<elastic_beam>& in) const {
    using namespace spatial;
    const quaternion qa(in.u(3), in.u(4), in.u(5), in.u(12)), qb(in.u(9), in.u(10), in.u(11), in.u(13));
    if (!(qa.norm() > 0.2) || !(qb.norm() > 0.2)) return false;
    const detail::beam_geometry g = geometry();
    const vec3 d = g.b - g.a + in.u.segment<3>(6) - in.u.head<3>();
    if (!(d.norm() > 0.1 * g.length())) return false;
    const detail::beam_stiffness k{p.e * p.a, p.g * p.j, p.e * p.iy, p.e * p.iz, g.length()};
    const auto s = state<double>(d, qa.normalized(), qb.normalized(), from_matrix(g.frame()), k);
    return s.align > -0.9 && s.wa > 0.1 && s.wb > 0.1;
  }

  /// Lengths below this count as zero [m].
  static constexpr double min_length = 1e-12;

 private:
  /// The corotational state with the chord and small global rotations of the nodes as
  /// the seeded variables (directions 0..2: d; 3..5: theta_a; 6..8: theta_b).
  template <class T>
  static detail::corotational_state<T> state(const spatial::vec3& d, const spatial::quaternion& qa,
                                             const spatial::quaternion& qb, const spatial::quaternion& t0,
                                             const detail::beam_stiffness& k) {
    detail::tvec<T> dd;
    detail::tquat<T> pa, pb, qat, qbt;
    for (int i = 0; i < 3; ++i) dd[static_cast<std::size_t>(i)] = seed<T>(d(i), i);
    for (int i = 0; i < 4; ++i) {
      qat[static_cast<std::size_t>(i)] = T(qa(i));
      qbt[static_cast<std::size_t>(i)] = T(qb(i));
    }
    // A small global rotation phi as the quaternion (phi/2, 1 - |phi|^2/8): exp(phi) to second order.
    for (int i = 0; i < 3; ++i) {
      pa[static_cast<std::size_t>(i)] = 0.5 * seed<T>(0.0, 3 + i);
      pb[static_cast<std::size_t>(i)] = 0.5 * seed<T>(0.0, 6 + i);
    }
    pa[3] = T(1.0) - 0.5 * (pa[0] * pa[0] + pa[1] * pa[1] + pa[2] * pa[2]);
    pb[3] = T(1.0) - 0.5 * (pb[0] * pb[0] + pb[1] * pb[1] + pb[2] * pb[2]);
    return detail::corotational(dd, detail::qmul(pa, qat), detail::qmul(pb, qbt), t0, k);
  }
  /// Variable k with value x in every nesting level of T (double: just x).
  template <class T>
  static T seed(double x, int k) {
    if constexpr (std::is_same_v<T, double>) {
      (void)k;
      return x;
    } else {
      using S = decltype(T{}.v);
      return T::variable(seed<S>(x, k), k);
    }
  }
  /// Code 75 where the kinematics become singular.
  template <class T>
  static void check(const detail::corotational_state<T>& s, element_context& ctx) {
    if (!(s.align > -0.99))
      ctx.singular("the beam's chord has turned against its mean cross-section frame (far beyond small strains)");
    if (!(s.wa > 1e-3) || !(s.wb > 1e-3))
      ctx.singular("a local rotation of the beam's end has reached 180 degrees (far beyond small strains)");
  }
  /// W(2) axial force, W(3) strain energy.
  static void write_work(double stretch, double energy, const detail::beam_stiffness& k, element_context& ctx) {
    ctx.work[1] = k.ea * stretch / k.l0;
    ctx.work[2] = energy;
  }
};

/// BEAMI3: inertia of a straight beam of density rho and section A, Iy, Iz, J
/// between the points A and B with rotational nodes qa, qb (same DOFs as BEAM3).
/// Translations: the consistent mass of linearly interpolated positions,
/// (m/6) [2 1; 1 2] (m = rho A L0): exact kinetic energy of a linear displacement
/// field under any large motion, a constant matrix (no gyroscopic terms). Rotations:
/// lumped rotary inertia of the cross-section, each node carrying half the beam,
/// J_node = (rho L0 / 2) T0 diag(J, Iy, Iz) T0^T in the node's body frame; the flows
/// are those of a rigid body without mass (BODY3): n = A alpha + omega x (A omega),
/// A = R J_node R^T. The Hermite mass of the bending field is not used: it would
/// couple translations with the rotations of a moving frame.
struct beam_inertia {
  static constexpr pradis::passport passport{.name = "BEAMI3", .ext = 12, .ent = 2, .par = 14, .wrk = 1, .adr = 1, .ign = 0};
  /// The rotational slots as BEAM3.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "inertia of a beam in spatial motion",
      .name = "Mass and rotary inertia of a straight beam at its two end points and rotational nodes",
      .field = "mechanics, spatial motion",
      .dofs = elastic_beam::help.dofs,
      .parameters = "1 - density rho [kg/m^3] (> 0)\n"
                    "2 - cross-section area A [m^2] (> 0)\n"
                    "3 - second moment of area Iy about the section's local y axis [m^4] (> 0)\n"
                    "4 - second moment of area Iz about the local z axis [m^4] (> 0)\n"
                    "5 - polar moment of the section Ip for the rotary inertia about the axis [m^4] (> 0)\n"
                    "6 - initial X of end A [m]\n"
                    "7 - initial Y of end A [m]\n"
                    "8 - initial Z of end A [m]\n"
                    "9 - initial X of end B [m]\n"
                    "10 - initial Y of end B [m]\n"
                    "11 - initial Z of end B [m] (B must differ from A)\n"
                    "12 - X of a vector giving the section's local y axis (its part normal to A -> B) [-]\n"
                    "13 - Y of that vector [-]\n"
                    "14 - Z of that vector [-]",
      .work = "1 - kinetic energy [J]",
      .special = "code 100 if rho, A, Iy, Iz or Ip is not positive, A and B coincide, the section vector is parallel "
                 "to A -> B or a parameter is not finite; code 75 if a quaternion norm comes near zero"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double rho = 0, a = 0, iy = 0, iz = 0, ip = 0;  ///< rho [kg/m^3]; A [m^2]; Iy, Iz, Ip [m^4]
    double xa = 0, ya = 0, za = 0;                  ///< initial position of end A [m]
    double xb = 1, yb = 0, zb = 0;                  ///< initial position of end B [m]
    double vx = 0, vy = 1, vz = 0;                  ///< vector of the section's local y axis
  };
  parameters p;

  explicit beam_inertia(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {7.0, 0.5, 0.2, 0.1, 0.3, 0.1, -0.2, 0.3, 3.0, 1.5, -1.0, 0.2, 0.3, 1.0}; }
  static beam_inertia from_parameters(std::span<const double> v) {
    return beam_inertia({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12], v[13]});
  }
  /// The reference geometry.
  detail::beam_geometry geometry() const { return {{p.xa, p.ya, p.za}, {p.xb, p.yb, p.zb}, {p.vx, p.vy, p.vz}}; }
  /// Mass rho A L0 [kg].
  double mass() const { return p.rho * p.a * geometry().length(); }
  /// The rotary inertia tensor of one node in its body frame [kg m^2].
  spatial::mat3 node_inertia() const {
    const detail::beam_geometry g = geometry();
    const spatial::mat3 t = g.frame();
    return (0.5 * p.rho * g.length()) * t * spatial::vec3(p.ip, p.iy, p.iz).asDiagonal() * t.transpose();
  }

  /// NEWINT: positive density and section, distinct ends, a usable section vector (code 100).
  void new_integration(element_context& ctx) const {
    for (double x : {p.rho, p.a, p.iy, p.iz, p.ip, p.xa, p.ya, p.za, p.xb, p.yb, p.zb, p.vx, p.vy, p.vz})
      if (!std::isfinite(x)) ctx.invalid_parameter("the parameters must be finite");
    if (!(p.rho > 0)) ctx.invalid_parameter("density rho = " + to_text(p.rho) + " must be > 0");
    if (!(p.a > 0)) ctx.invalid_parameter("area A = " + to_text(p.a) + " must be > 0");
    if (!(p.iy > 0) || !(p.iz > 0) || !(p.ip > 0))
      ctx.invalid_parameter("second moments of area Iy = " + to_text(p.iy) + ", Iz = " + to_text(p.iz) +
                            ", Ip = " + to_text(p.ip) + " must be > 0");
    const detail::beam_geometry g = geometry();
    if (!(g.length() > elastic_beam::min_length)) ctx.invalid_parameter("ends A and B coincide: the length of the beam is zero");
    if (!g.section_ok()) ctx.invalid_parameter("the section vector is zero or parallel to the beam axis A -> B");
  }

  void evaluate(const local_input<beam_inertia>& in, local_output<beam_inertia>& out, element_context& ctx) const {
    using namespace spatial;
    const double m6 = mass() / 6.0;
    const vec3 aa = in.a.head<3>(), ab = in.a.segment<3>(6);
    out.f.setZero();
    out.f.head<3>() = m6 * (2.0 * aa + ab);
    out.f.segment<3>(6) = m6 * (aa + 2.0 * ab);
    const vec3 va = in.v.head<3>(), vb = in.v.segment<3>(6);
    double kinetic = m6 * (va.squaredNorm() + va.dot(vb) + vb.squaredNorm());
    const mat3 j = node_inertia();
    if (out.want_jacobian) {
      out.K.setZero();
      out.C.setZero();
      out.M.setZero();
      for (int i : {0, 6}) {
        out.M.block<3, 3>(i, i) = 2.0 * m6 * mat3::Identity();
        out.M.block<3, 3>(i, 6 - i) = m6 * mat3::Identity();
      }
    }
    for (int node = 0; node < 2; ++node) {
      const int i1 = node == 0 ? 3 : 9, i4 = node == 0 ? 12 : 13;
      const quaternion q(in.u(i1), in.u(i1 + 1), in.u(i1 + 2), in.u(i4));
      const quaternion qd(in.v(i1), in.v(i1 + 1), in.v(i1 + 2), in.v(i4));
      const quaternion qdd(in.a(i1), in.a(i1 + 1), in.a(i1 + 2), in.a(i4));
      const double s = q.squaredNorm();
      if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
      // As BODY3 with m = 0 and the centre of mass at the node (docs/rotations.md).
      const mat3 r = rotation_matrix(q);
      const mat34 e = e_matrix(q);
      const double g = q.dot(qd);
      const vec3 w = (2.0 / s) * (e * qd);
      const vec3 alpha1 = (2.0 / s) * (e * qdd);
      const vec3 alpha = alpha1 - (2.0 * g / s) * w;
      const mat3 a = r * j * r.transpose();
      const vec3 h = a * w;
      out.f.segment<3>(i1) = a * alpha + w.cross(h);
      kinetic += 0.5 * w.dot(h);
      if (!out.want_jacobian) continue;
      const mat3 sw = skew(w), sa = skew(alpha);
      const mat3 dn_dw = -skew(h) + sw * a;
      const mat3 dn_dth = -skew(a * alpha) + a * sa + sw * (-skew(h) + a * sw);
      const mat34 dth_dq = (2.0 / s) * e;
      const mat34 dw_dq = -(2.0 / s) * (e_matrix(qd) + w * q.transpose());
      const mat34 dw_dqd = (2.0 / s) * e;
      const mat34 dal_dq = -(2.0 / s) * e_matrix(qdd) - (2.0 / s) * alpha1 * q.transpose() -
                           (2.0 / s) * w * qd.transpose() - (2.0 * g / s) * dw_dq + (4.0 * g / (s * s)) * w * q.transpose();
      const mat34 dal_dqd = -(2.0 / s) * (w * q.transpose() + g * dw_dqd);
      const mat34 kq = dn_dth * dth_dq + dn_dw * dw_dq + a * dal_dq;
      const mat34 cq = dn_dw * dw_dqd + a * dal_dqd;
      const mat34 mq = a * ((2.0 / s) * e);
      out.K.block<3, 3>(i1, i1) = kq.leftCols<3>();
      out.K.block<3, 1>(i1, i4) = kq.col(3);
      out.C.block<3, 3>(i1, i1) = cq.leftCols<3>();
      out.C.block<3, 1>(i1, i4) = cq.col(3);
      out.M.block<3, 3>(i1, i1) = mq.leftCols<3>();
      out.M.block<3, 1>(i1, i4) = mq.col(3);
    }
    ctx.work[0] = kinetic;
  }

  /// States the checks may use: the quaternion norms are not near zero.
  bool admissible(const local_input<beam_inertia>& in) const {
    return spatial::quaternion(in.u(3), in.u(4), in.u(5), in.u(12)).norm() > 0.2 &&
           spatial::quaternion(in.u(9), in.u(10), in.u(11), in.u(13)).norm() > 0.2;
  }
};

}  // namespace pradis::elements
