#pragma once
/// \file
/// BEAM3: elastic spatial beam, corotational Euler-Bernoulli, between two points with
/// spatial rotational nodes. Its kinematics and energy are in beam_kinematics.hpp,
/// its inertia (BEAMI3) in beam_inertia.hpp. docs/rotations.md.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <type_traits>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/beam_kinematics.hpp"
#include "pradis/spatial/dual.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

template <class = void>
struct elastic_beam_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using elastic_beam = elastic_beam_t<>;
/// BEAM3: elastic beam between the points A (x, y, z and rotational node qa) and B
/// (x, y, z and rotational node qb); corotational Euler-Bernoulli formulation (large
/// displacements and rotations, small strains). The element frame follows the chord
/// A -> B and the mean of the end triads; in it a linear beam with axial stiffness
/// EA/L0, torsion GJ/L0 and bending EIy, EIz (end-rotation stiffness EI/L0 [4 2; 2 4])
/// gives the strain energy U. The flows are dU/dx on the translations and the global
/// moments dU/dtheta (a small global rotation theta of a node) on q1, q2, q3, none on
/// q4. The flows are the closed-form gradient of U (detail::corotational, a reverse
/// sweep of the kinematics); the Jacobian is exact: that gradient evaluated with
/// first-order dual numbers (spatial/dual.hpp) seeded with the chord and a small
/// global rotation phi_b of end B gives d(flows)/d(chord, phi_b), objectivity gives
/// d(flows)/d(phi_a); the chain through phi = (2/s) E(q) q is applied by hand. The reference configuration is the
/// one with identity nodal quaternions; the section's local y axis is given by a vector.
template <class>
struct elastic_beam_t {
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

  explicit elastic_beam_t(parameters q) : p(q) {}
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
  /// Animation geometry (io/model_scene.hpp): a line between the two end points.
  template <class Drawer>
  void draw(Drawer& d) const {
    d.line(d.body_point({p.xa, p.ya, p.za}, 0, 0, spatial::vec3::Zero()),
           d.body_point({p.xb, p.yb, p.zb}, 6, 1, spatial::vec3::Zero()));
  }
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
    const quaternion ta = multiply(qa / std::sqrt(sa), t0), tb = multiply(qb / std::sqrt(sb), t0);

    if (!out.want_jacobian) {
      const auto s = state<double>(d, ta, tb, k);
      check(s, ctx);
      out.f.setZero();
      for (int i = 0; i < 3; ++i) {
        out.f(i) = -s.gradient[static_cast<std::size_t>(i)];
        out.f(6 + i) = s.gradient[static_cast<std::size_t>(i)];
        out.f(3 + i) = s.gradient[static_cast<std::size_t>(3 + i)];
        out.f(9 + i) = s.gradient[static_cast<std::size_t>(6 + i)];
      }
      write_work(s.stretch, s.energy, k, ctx);
      return;
    }
    using d1 = dual<double, 6>;
    const auto s = state<d1>(d, ta, tb, k);
    check(s, ctx);
    // The flows gr in (chord d, phi_a, phi_b) and their derivatives hh there (the
    // moments' derivatives by the rotation of their own node included). The duals
    // carry d/d(chord) and d/d(phi_b); d/d(phi_a) follows from objectivity: turning
    // the whole beam by a small omega (chord by omega x d, both triads by omega) turns
    // the flows g by omega x g, so H_d [-d x] + H_a + H_b = -[g x] (blockwise).
    Eigen::Matrix<double, 9, 1> gr;
    Eigen::Matrix<double, 9, 9> hh;
    for (int i = 0; i < 9; ++i) {
      const auto& gi = s.gradient[static_cast<std::size_t>(i)];
      gr(i) = gi.v;
      for (int j = 0; j < 3; ++j) {
        hh(i, j) = gi.d[static_cast<std::size_t>(j)];
        hh(i, 6 + j) = gi.d[static_cast<std::size_t>(3 + j)];
      }
    }
    hh.middleCols<3>(3) = hh.leftCols<3>() * skew(d) - hh.rightCols<3>();
    for (int b = 0; b < 3; ++b) hh.block<3, 3>(3 * b, 3) -= skew(gr.segment<3>(3 * b));
    out.f.setZero();
    out.f.head<3>() = -gr.head<3>();
    out.f.segment<3>(6) = gr.head<3>();
    out.f.segment<3>(3) = gr.segment<3>(3);
    out.f.segment<3>(9) = gr.segment<3>(6);
    write_work(s.stretch.v, s.energy.v, k, ctx);
    // d(phi)/dq = (2/s) E(q).
    const mat34 dta = (2.0 / sa) * e_matrix(qa), dtb = (2.0 / sb) * e_matrix(qb);
    // Rows: the flows as functions of (d, phi_a, phi_b): f_xa = -g_d, f_xb = g_d, f_qa = g_ta, f_qb = g_tb.
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
    const quaternion t0 = from_matrix(g.frame());
    const auto s = state<double>(d, multiply(qa.normalized(), t0), multiply(qb.normalized(), t0), k);
    return s.align > -0.9 && s.wa > 0.1 && s.wb > 0.1;
  }

  /// Lengths below this count as zero [m].
  static constexpr double min_length = 1e-12;

 private:
  /// The corotational state at the chord d and the end triads ta, tb (unit). For T a
  /// dual number the variables are seeded: directions 0..2 the chord, 3..5 a small
  /// global rotation phi of tb (tb -> (phi / 2, 1) tb, exp(phi) tb to first order,
  /// enough for the first derivatives of the gradient).
  template <class T>
  static detail::corotational_state<T> state(const spatial::vec3& d, const spatial::quaternion& ta,
                                             const spatial::quaternion& tb, const detail::beam_stiffness& k) {
    detail::tvec<T> dd;
    detail::tquat<T> pa, pb;
    for (std::size_t i = 0; i < 4; ++i) {
      pa[i] = T(ta(static_cast<int>(i)));
      pb[i] = T(tb(static_cast<int>(i)));
    }
    if constexpr (std::is_same_v<T, double>) {
      for (int i = 0; i < 3; ++i) dd[static_cast<std::size_t>(i)] = d(i);
    } else {
      for (int i = 0; i < 3; ++i) {
        dd[static_cast<std::size_t>(i)] = T::variable(d(i), i);
        // d tb / d phi_i = (e_i / 2, 0) tb.
        const spatial::quaternion db = 0.5 * spatial::multiply(spatial::quaternion(i == 0, i == 1, i == 2, 0), tb);
        for (std::size_t j = 0; j < 4; ++j) pb[j].d[static_cast<std::size_t>(3 + i)] = db(static_cast<int>(j));
      }
    }
    return detail::corotational(dd, pa, pb, k);
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

}  // namespace pradis::elements
