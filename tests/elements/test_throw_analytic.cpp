// THROW (elements/spatial/crank_throw.hpp) against analytic answers: the static compliance of its free end B with
// the front web root A clamped, by linear Euler-Bernoulli frame theory, and the inertia tensor about A its
// inertia flows produce under a rigid angular acceleration, by the moments of inertia of homogeneous solids.
// (THROWP's analytic check, the deflection of the middle of the pin, is in test_composite.cpp.)
//
// The throw, coordinates relative to A = (x0, 0, 0): front web A -> N1 = (0, r, 0), crank pin N1 -> N2 =
// (L/2, r, 0) -> N3 = (L, r, 0), rear web N3 -> B = (L, 0, 0); B lies on the shaft axis X, like A. Webs of
// width b (along Z) and thickness t (along X), a round pin of diameter d (crank_throw_parts).

#include <doctest/doctest.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "element_test_support.hpp"
#include "pradis/elements/spatial/crank_throw.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

using throw_analytic_t = crank_throw;
constexpr int throw_analytic_n = element_traits<throw_analytic_t>::n;

/// THROW's nodes A, N1, N2, N3, B in its local DOFs (crank_throw_spec::nodes, written out: x, q1, hidden q4).
struct throw_analytic_node {
  int x, q1, q4;
};
constexpr std::array<throw_analytic_node, 5> throw_analytic_nodes{
    {{0, 3, 12}, {14, 17, 20}, {21, 24, 27}, {28, 31, 34}, {6, 9, 13}}};

/// A shape of the throw (the arguments of crank_throw_parts; steel, its default E, G, rho).
struct throw_analytic_shape {
  double x0, r, length, d, b, t;
};
/// The throw of examples/crankshaft (r = 40 mm, pin 45 mm x 40 mm, webs 80 mm x 20 mm), and a longer, more
/// slender one with other ratios (a long pin: pin bending and web torsion matter more).
constexpr std::array<throw_analytic_shape, 2> throw_analytic_shapes{
    {{0.08, 0.04, 0.04, 0.045, 0.08, 0.02}, {0.3, 0.1, 0.3, 0.05, 0.12, 0.03}}};

/// A THROW of that shape, its NEWINT done, with its own work vector.
struct throw_analytic_instance {
  throw_analytic_t element;
  std::vector<double> work = std::vector<double>(static_cast<std::size_t>(throw_analytic_t::passport.wrk), 0.0);
  element_context ctx{throw_analytic_t::passport.name, "throw"};
  explicit throw_analytic_instance(const throw_analytic_shape& s)
      : element(throw_analytic_t::parameters{crank_throw_parts(s.x0, s.r, s.length, s.d, s.b, s.t)}) {
    ctx.work = work;
    ctx.npar = throw_analytic_t::passport.par;
    element.new_integration(ctx);
  }
  local_output<throw_analytic_t> evaluate(const local_input<throw_analytic_t>& in, bool jacobian) {
    local_output<throw_analytic_t> out;
    out.want_jacobian = jacobian;
    element.evaluate(in, out, ctx);
    return out;
  }
};

/// The undeformed state: every displacement and q1..q3 zero, the hidden q4 of the five nodes 1 (identity).
local_input<throw_analytic_t> throw_analytic_rest() {
  local_input<throw_analytic_t> in;
  for (const auto& nd : throw_analytic_nodes) in.u(nd.q4) = 1.0;
  return in;
}

/// The free DOFs with A clamped (the q4 held at 1): B's x, y, z, q1, q2, q3 first, then those of N1, N2, N3.
std::array<int, 24> throw_analytic_free_dofs() {
  std::array<int, 24> fr{};
  std::size_t k = 0;
  for (const std::size_t i : {4u, 1u, 2u, 3u}) {
    for (int j = 0; j < 3; ++j) fr[k++] = throw_analytic_nodes[i].x + j;
    for (int j = 0; j < 3; ++j) fr[k++] = throw_analytic_nodes[i].q1 + j;
  }
  return fr;
}

}  // namespace

TEST_SUITE("elements/throw") {
  TEST_CASE("THROW clamped at A: the compliance of its end B is that of linear Euler-Bernoulli frame theory") {
    // Reference: the unit-load method / Castigliano's second theorem for a statically determinate frame
    // (Timoshenko, Strength of Materials, Part I, the chapter on strain energy: Castigliano's theorem; Roark's
    // Formulas for Stress and Strain, the energy methods of its chapter on analytical methods). Clamped at A,
    // the throw is a cantilever frame: a load at B (force F, moment M) gives at a section at p the force F and
    // the moment M + (B - p) x F, so U = sum over members of int (N^2 / EA + T^2 / GJ + M2^2 / EI2 + M3^2 / EI3)
    // / 2 ds (Euler-Bernoulli: no shear deformation, as BEAM3), and B's compliance is C = d^2 U / dP^2 with
    // P = (Fx, Fy, Fz, Mx, My, Mz). The members' stiffnesses (crank_throw_parts): a web (axis Y, section
    // t along X by b along Z) bends about X with E Iwx, Iwx = t b^3 / 12, about Z with E Iwz, Iwz = b t^3 / 12,
    // twists with G Jw, Jw = b t^3 / 3 (1 - 0.63 t / b), stretches with E Aw, Aw = b t; the pin (axis X)
    // bends with E Ip, Ip = pi d^4 / 64, twists with G Jp, Jp = 2 Ip, stretches with E Ap, Ap = pi d^2 / 4.
    //
    // In-plane loads Fx, Fy, Mz (only bending about Z and axial force): moment about Z and axial force
    //   front web (0, s, 0), s in 0..r: Mz + L Fy + s Fx,     N = Fy;
    //   pin (xi, r, 0), xi in 0..L:      Mz + (L - xi) Fy + r Fx, N = Fx;
    //   rear web (L, y, 0), y in 0..r:   Mz + y Fx,           N = Fy;
    // whence
    //   C(Fx, Fx) = 2 r^3 / (3 E Iwz) + r^2 L / (E Ip) + L / (E Ap)
    //   C(Fy, Fy) = L^2 r / (E Iwz) + L^3 / (3 E Ip) + 2 r / (E Aw)
    //   C(Mz, Mz) = 2 r / (E Iwz) + L / (E Ip)
    //   C(Fx, Fy) = L r^2 / (2 E Iwz) + r L^2 / (2 E Ip)
    //   C(Fx, Mz) = r^2 / (E Iwz) + r L / (E Ip)
    //   C(Fy, Mz) = L r / (E Iwz) + L^2 / (2 E Ip).
    // Out-of-plane loads Fz, Mx, My: moments about X and Y (no axial force)
    //   front web: (Mx - s Fz, My - L Fz)        (X: web bending E Iwx, Y: web torsion G Jw);
    //   pin:       (Mx - r Fz, My - (L - xi) Fz) (X: pin torsion G Jp, Y: pin bending E Ip);
    //   rear web:  (Mx - y Fz, My)               (X: web bending, Y: web torsion);
    // whence
    //   C(Fz, Fz) = 2 r^3 / (3 E Iwx) + L^2 r / (G Jw) + r^2 L / (G Jp) + L^3 / (3 E Ip)
    //   C(Mx, Mx) = 2 r / (E Iwx) + L / (G Jp)     (the throw's torsional flexibility about the shaft axis)
    //   C(My, My) = 2 r / (G Jw) + L / (E Ip)
    //   C(Fz, Mx) = -(r^2 / (E Iwx) + r L / (G Jp))
    //   C(Fz, My) = -(L r / (G Jw) + L^2 / (2 E Ip))
    //   C(Mx, My) = 0,
    // and no coupling between the in-plane and the out-of-plane loads (the throw is plane and the sections are
    // symmetric about it).
    //
    // THROW's tangent at the undeformed state is that linear frame's stiffness (the corotational BEAM3 is
    // stress-free there, so no geometric stiffness), with the rotational unknowns q = theta / 2 (q4 = 1, flows
    // on q1..q3 are global moments): theta = 2 q. The cubic Hermite bending and the linear axial and twist
    // fields of BEAM3 are the exact solutions of a member loaded at its ends only, so the nodal values carry no
    // discretisation error: the only error is round-off amplified by the conditioning of the 24 x 24 stiffness
    // (measured: 3e-14 and 4e-13 of sqrt(C_ii C_jj) for the two shapes). Tolerance 1e-10 relative to
    // sqrt(C_ii C_jj), as THROWP's analytic check.
    const std::array<int, 24> fr = throw_analytic_free_dofs();
    for (const throw_analytic_shape& sh : throw_analytic_shapes) {
      CAPTURE(sh.r);
      CAPTURE(sh.length);
      throw_analytic_instance th(sh);
      const local_input<throw_analytic_t> rest = throw_analytic_rest();
      const local_output<throw_analytic_t> out = th.evaluate(rest, true);
      Eigen::Matrix<double, 24, 24> kf;
      for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 24; ++j) kf(i, j) = out.K(fr[static_cast<std::size_t>(i)], fr[static_cast<std::size_t>(j)]);
      // The unit loads at B (the first six free DOFs: Fx, Fy, Fz along X, Y, Z, then the moments Mx, My, Mz).
      Eigen::Matrix<double, 24, 6> loads = Eigen::Matrix<double, 24, 6>::Zero();
      loads.topRows<6>().setIdentity();
      const Eigen::Matrix<double, 24, 6> u = kf.fullPivLu().solve(loads);
      Eigen::Matrix<double, 6, 6> c_throw = u.topRows<6>();
      c_throw.bottomRows<3>() *= 2.0;  // theta = 2 q

      // Beam theory.
      const auto pp = crank_throw_parts(sh.x0, sh.r, sh.length, sh.d, sh.b, sh.t);
      const auto& web = std::get<0>(pp);
      const auto& pin = std::get<2>(pp);
      const double e = web.e, g = web.g, r = sh.r, L = sh.length;
      const double pi = std::numbers::pi;
      const double iwx = sh.t * std::pow(sh.b, 3) / 12, iwz = sh.b * std::pow(sh.t, 3) / 12,
                   jw = sh.b * std::pow(sh.t, 3) / 3 * (1 - 0.63 * sh.t / sh.b), aw = sh.b * sh.t;
      const double ip = pi * std::pow(sh.d, 4) / 64, jp = 2 * ip, ap = pi * sh.d * sh.d / 4;
      // The parts carry the sections derived above (web: local y = X, so Iy = Iwx; pin: round).
      REQUIRE(web.iy == doctest::Approx(iwx).epsilon(1e-14));
      REQUIRE(web.iz == doctest::Approx(iwz).epsilon(1e-14));
      REQUIRE(pin.j == doctest::Approx(jp).epsilon(1e-14));
      Eigen::Matrix<double, 6, 6> c_theory = Eigen::Matrix<double, 6, 6>::Zero();
      enum { fx, fy, fz, mx, my, mz };
      c_theory(fx, fx) = 2 * r * r * r / (3 * e * iwz) + r * r * L / (e * ip) + L / (e * ap);
      c_theory(fy, fy) = L * L * r / (e * iwz) + L * L * L / (3 * e * ip) + 2 * r / (e * aw);
      c_theory(mz, mz) = 2 * r / (e * iwz) + L / (e * ip);
      c_theory(fx, fy) = L * r * r / (2 * e * iwz) + r * L * L / (2 * e * ip);
      c_theory(fx, mz) = r * r / (e * iwz) + r * L / (e * ip);
      c_theory(fy, mz) = L * r / (e * iwz) + L * L / (2 * e * ip);
      c_theory(fz, fz) = 2 * r * r * r / (3 * e * iwx) + L * L * r / (g * jw) + r * r * L / (g * jp) +
                         L * L * L / (3 * e * ip);
      c_theory(mx, mx) = 2 * r / (e * iwx) + L / (g * jp);
      c_theory(my, my) = 2 * r / (g * jw) + L / (e * ip);
      c_theory(fz, mx) = -(r * r / (e * iwx) + r * L / (g * jp));
      c_theory(fz, my) = -(L * r / (g * jw) + L * L / (2 * e * ip));
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < i; ++j) c_theory(i, j) = c_theory(j, i);

      double worst = 0;
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          const double scale = std::sqrt(c_theory(i, i) * c_theory(j, j));
          const double rel = std::abs(c_throw(i, j) - c_theory(i, j)) / scale;
          worst = std::max(worst, rel);
          INFO("C(", i, ", ", j, "): THROW ", c_throw(i, j), ", beam theory ", c_theory(i, j));
          CHECK(rel <= 1e-10);
        }
      MESSAGE("THROW r = ", r, ", L = ", L, ": torsional compliance about the shaft axis ", c_throw(mx, mx),
              " rad/(N m), beam theory ", c_theory(mx, mx), "; tip compliance along Z ", c_throw(fz, fz),
              " m/N, beam theory ", c_theory(fz, fz), "; largest difference over the 36 entries ", worst,
              " of sqrt(C_ii C_jj)");

      // The flows (evaluated without the Jacobian: the closed-form gradient of BEAM3, another code path than
      // the dual-number tangent) at the linear displacements of a small load balance that load to first order:
      // the load is a torque about the shaft axis with a force across it (Mx = 100 N m with Fz = 1 kN, scaled
      // to a largest rotation theta of 1e-5 rad, then of 5e-6 rad). What remains is the geometric nonlinearity
      // of the corotational beams, of second order in the displacements (chiefly the stretch of a member whose
      // chord turns by theta, EA theta^2 / 2: EA ~ 3e8 N, so ~1e-2 N at theta = 1e-5 rad, against loads of
      // 10..100 N): halving the load must quarter the residual, to within the third-order terms (relative
      // O(theta) = 1e-5) and the round-off of the flows (~1e-7 N at rest against residuals of ~5e-3 N: 2e-5).
      // Measured: 4.0000 to 1e-5 for both shapes; tolerance 1e-3 on the ratio.
      Eigen::Matrix<double, 24, 1> load_dir = Eigen::Matrix<double, 24, 1>::Zero();
      load_dir(fz) = 1000.0;
      load_dir(mx) = 100.0;
      const Eigen::Matrix<double, 24, 1> u_dir = kf.fullPivLu().solve(load_dir);
      double rot_dir = 0;
      for (int i = 0; i < 4; ++i) rot_dir = std::max(rot_dir, 2 * u_dir.segment<3>(6 * i + 3).cwiseAbs().maxCoeff());
      std::array<double, 2> residual{};
      for (std::size_t k = 0; k < 2; ++k) {
        const double theta = k == 0 ? 1e-5 : 5e-6;
        const Eigen::Matrix<double, 24, 1> load = theta / rot_dir * load_dir, us = theta / rot_dir * u_dir;
        local_input<throw_analytic_t> in = rest;
        for (int i = 0; i < 24; ++i) in.u(fr[static_cast<std::size_t>(i)]) = us(i);
        const local_output<throw_analytic_t> fo = th.evaluate(in, false);
        Eigen::Matrix<double, 24, 1> fl;
        for (int i = 0; i < 24; ++i) fl(i) = fo.f(fr[static_cast<std::size_t>(i)]);
        residual[k] = (fl - load).cwiseAbs().maxCoeff();
        // B's motion under that load by beam theory (uz and theta_x from the compliance entries above).
        CHECK(us(fz) == doctest::Approx(c_theory(fz, fz) * load(fz) + c_theory(fz, mx) * load(mx)).epsilon(1e-10));
        CHECK(2 * us(mx) == doctest::Approx(c_theory(mx, fz) * load(fz) + c_theory(mx, mx) * load(mx)).epsilon(1e-10));
      }
      INFO("largest residual of the flows: ", residual[0], " at theta = 1e-5, ", residual[1], " at 5e-6 (ratio ",
           std::to_string(residual[0] / residual[1]), ")");
      CHECK(residual[1] > 0);
      CHECK(std::abs(residual[0] / residual[1] - 4.0) <= 1e-3);
    }
  }

  TEST_CASE("THROW's inertia flows under a rigid angular acceleration give the inertia tensor of its webs and pin") {
    // Reference: the moments of inertia of homogeneous solids (e.g. Meriam & Kraige, Engineering Mechanics:
    // Dynamics, Table D/4: a rectangular block with sides a and c across the axis, about an axis through its
    // centre, m (a^2 + c^2) / 12 (a web about X: sides r and b); a solid cylinder of radius R and length l
    // about its axis m R^2 / 2, about a transverse axis through its centre m (3 R^2 + l^2) / 12) and the
    // parallel-axis theorem. The solid: two webs, plates of mass
    // mw = rho b t r centred at (0, r/2, 0) and (L, r/2, 0), and the pin, a cylinder of mass mp = rho pi d^2 L / 4
    // centred at (L/2, r, 0) (coordinates relative to A; the solids overlap at the corners as the model's
    // centrelines meet there). About A:
    //   Ixx = 2 mw (r^2 / 3 + b^2 / 12) + mp (r^2 + d^2 / 8)      (the throw's inertia about the shaft axis)
    //   Iyy = 2 mw (b^2 + t^2) / 12 + mw L^2 + mp (d^2 / 16 + L^2 / 3)
    //   Izz = 2 mw (r^2 / 3 + t^2 / 12) + mw L^2 + mp (r^2 + d^2 / 16 + L^2 / 3)
    //   Ixy = -sum m xc yc = -(mw L r / 2 + mp L r / 2),  Ixz = Iyz = 0
    // (the centroidal products vanish by symmetry), the mass m = 2 mw + mp and the first moments
    // m (xc, yc, zc) = (mw L + mp L / 2, mw r + mp r, 0).
    //
    // A rigid motion at rest (v = 0) with angular acceleration alpha about A: each node's translation
    // accelerates by alpha x (p - A), its rotation by alpha, i.e. q'' = alpha / 2 on q1..q3 (q4 = 1). The
    // inertia flows must then sum to the resultant force m alpha x (c - A), and their moment about A
    // (sum of (p_i - A) x f_i over the nodes' forces plus the nodes' moments) to I_A alpha. BEAMI3's
    // consistent mass of linear interpolation integrates the product of two linear fields exactly (position
    // and acceleration are linear along a member) and its rotary inertia, half the beam's rho L T0 diag(Ip,
    // Iy, Iz) T0^T at each end, with Ip = Iy + Iz as THROW sets it, is the section's own: the answer is exact
    // up to round-off (measured ~1e-16 relative; tolerance 1e-12 of the largest entry). The same from the
    // mass matrix, M a, which the integrator uses.
    for (const throw_analytic_shape& sh : throw_analytic_shapes) {
      CAPTURE(sh.r);
      CAPTURE(sh.length);
      throw_analytic_instance th(sh);
      const double rho = std::get<1>(crank_throw_parts(sh.x0, sh.r, sh.length, sh.d, sh.b, sh.t)).rho;
      const double r = sh.r, L = sh.length, b = sh.b, t = sh.t, d = sh.d;
      const double mw = rho * b * t * r, mp = rho * std::numbers::pi * d * d / 4 * L;
      Eigen::Matrix3d i_theory;
      const double ixy = -(mw * L * r / 2 + mp * L * r / 2);
      i_theory << 2 * mw * (r * r / 3 + b * b / 12) + mp * (r * r + d * d / 8), ixy, 0,  //
          ixy, 2 * mw * (b * b + t * t) / 12 + mw * L * L + mp * (d * d / 16 + L * L / 3), 0,  //
          0, 0, 2 * mw * (r * r / 3 + t * t / 12) + mw * L * L + mp * (r * r + d * d / 16 + L * L / 3);
      const double mass = 2 * mw + mp;
      const Eigen::Vector3d first_moment(mw * L + mp * L / 2, mw * r + mp * r, 0);
      // The nodes' positions relative to A: A, N1, N2, N3, B.
      const std::array<Eigen::Vector3d, 5> pos{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, r, 0),
                                               Eigen::Vector3d(L / 2, r, 0), Eigen::Vector3d(L, r, 0),
                                               Eigen::Vector3d(L, 0, 0)};
      const double scale = i_theory.cwiseAbs().maxCoeff();
      for (int axis = 0; axis < 3; ++axis) {
        CAPTURE(axis);
        const Eigen::Vector3d alpha = 10.0 * Eigen::Vector3d::Unit(axis);  // rad/s^2
        local_input<throw_analytic_t> in = throw_analytic_rest();
        for (std::size_t i = 0; i < 5; ++i) {
          in.a.segment<3>(throw_analytic_nodes[i].x) = alpha.cross(pos[i]);
          in.a.segment<3>(throw_analytic_nodes[i].q1) = alpha / 2;
        }
        const local_output<throw_analytic_t> flows = th.evaluate(in, false);
        const local_output<throw_analytic_t> with_m = th.evaluate(in, true);
        const Eigen::Matrix<double, throw_analytic_n, 1> ma = with_m.M * in.a;
        const Eigen::Vector3d moment_theory = i_theory * alpha;
        const Eigen::Vector3d force_theory = alpha.cross(first_moment);
        for (const bool from_matrix : {false, true}) {
          CAPTURE(from_matrix);
          const Eigen::Matrix<double, throw_analytic_n, 1>& f = from_matrix ? ma : flows.f;
          Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
          for (std::size_t i = 0; i < 5; ++i) {
            const Eigen::Vector3d fi = f.segment<3>(throw_analytic_nodes[i].x);
            force += fi;
            moment += pos[i].cross(fi) + f.segment<3>(throw_analytic_nodes[i].q1);
          }
          INFO("moment about A ", moment.transpose(), ", theory ", moment_theory.transpose());
          INFO("resultant force ", force.transpose(), ", theory ", force_theory.transpose());
          CHECK((moment - moment_theory).cwiseAbs().maxCoeff() <= 1e-12 * scale * alpha.norm());
          CHECK((force - force_theory).cwiseAbs().maxCoeff() <= 1e-12 * mass * std::max(r, L) * alpha.norm());
          if (axis == 0 && !from_matrix)
            MESSAGE("THROW r = ", r, ", L = ", L, ": inertia about the shaft axis from its flows ",
                    moment(0) / alpha(0), " kg m^2, theory ", i_theory(0, 0), " kg m^2; Ixy ", moment(1) / alpha(0),
                    ", theory ", ixy, " (mass ", mass, " kg); largest moment difference ",
                    (moment - moment_theory).cwiseAbs().maxCoeff() / (scale * alpha.norm()), " of Imax alpha");
        }
      }
    }
  }
}
