// BEAM3 (corotational Euler-Bernoulli beam) and BEAMI3 (its inertia) on the
// cantilever benchmarks of Euler-Bernoulli theory (S. P. Timoshenko and J. M. Gere,
// Mechanics of Materials; the frequency constant 1.87510407 of the clamped-free beam
// from its characteristic equation cos(bL) cosh(bL) = -1): the static tip deflection
// P L^3 / (3 E I) in both bending planes, the first bending frequency
// (1.87510407^2 / L^2) sqrt(E I / (rho A)) of the element matrices and of a transient
// free vibration (BEAMI3 through the integrator), and the end moment
// M = 2 pi E I / L that rolls the cantilever into a full circle (the tip returns to
// the root and turns by 360 degrees: a pure moment bends an elastic rod into a
// circular arc of radius E I / M). Bad input: codes 100 and 101 with element,
// instance and message.

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "../elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

namespace {
using pradis_spatial_tests::pi;

/// Cantilever data: length 1 m along X, section vector along Y, E Iy = 1, E Iz = 2.
struct section {
  double e = 1e4, g = 4e3, a = 0.03, iy = 1e-4, iz = 2e-4, j = 1.5e-4, rho = 100;
};

/// A cantilever of n BEAM3 elements (and BEAMI3 if with_inertia) clamped at x = 0 (root node: q1..q3 on the ground).
template <class Model, bool with_inertia = false>
struct cantilever {
  Model m;
  std::vector<std::array<dof, 3>> x;  // translations of nodes 1..n
  std::vector<rotation_node> r;       // rotational nodes 1..n
  explicit cantilever(int n, section s = {}) {
    const rotation_node root = m.add_rotation_node("r0", m.ground(), m.ground(), m.ground());
    for (int i = 1; i <= n; ++i) {
      const auto d = m.add_dofs(3, "x" + std::to_string(i));
      x.push_back({d[0], d[1], d[2]});
      r.push_back(m.add_rotation_node("r" + std::to_string(i)));
    }
    const double le = 1.0 / n;
    for (int i = 0; i < n; ++i) {
      const double xa = i * le, xb = (i + 1) * le;
      const dof g = m.ground();
      const std::array<dof, 3> xa_d = i == 0 ? std::array<dof, 3>{g, g, g} : x[static_cast<std::size_t>(i - 1)];
      const rotation_node ra = i == 0 ? root : r[static_cast<std::size_t>(i - 1)];
      const auto& xb_d = x[static_cast<std::size_t>(i)];
      const rotation_node rb = r[static_cast<std::size_t>(i)];
      m.template add<elastic_beam>("beam" + std::to_string(i + 1),
                                   {s.e, s.g, s.a, s.iy, s.iz, s.j, xa, 0, 0, xb, 0, 0, 0, 1, 0}, xa_d[0], xa_d[1],
                                   xa_d[2], ra, xb_d[0], xb_d[1], xb_d[2], rb);
      if constexpr (with_inertia)
        m.template add<beam_inertia>("mass" + std::to_string(i + 1),
                                     {s.rho, s.a, s.iy, s.iz, s.iy + s.iz, xa, 0, 0, xb, 0, 0, 0, 1, 0}, xa_d[0], xa_d[1],
                                     xa_d[2], ra, xb_d[0], xb_d[1], xb_d[2], rb);
    }
  }
  const std::array<dof, 3>& tip() const { return x.back(); }
  rotation_node tip_rotation() const { return r.back(); }
};

/// The slender steel bar of the frequency tests, 10 mm x 20 mm (L / h = 50).
constexpr section steel{.e = 2.1e11, .g = 8.1e10, .a = 2e-4, .iy = 0.01 * 0.008 / 12 * 1e-3, .iz = 0.02 * 1e-6 / 12,
                        .j = 4.6e-9, .rho = 7850};
/// Newton tolerances for the steel bar (axial stiffness E A = 4.2e7 N: round-off of the flows ~1e-8 N; loads ~0.1 N).
constexpr newton_options steel_newton{.dabsu = 1e-9, .drltu = 0, .dabsi = 1e-7, .drlti = 0, .itr = 8};
/// Newton tolerances far below the accuracy the tests check (forces of order 1e-4 .. 10 N).
constexpr newton_options tight{.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-11, .drlti = 0, .itr = 8};
}  // namespace

/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using beam_model = pradis::model<elastic_beam, spatial_force, beam_inertia, body_torque>;
TEST_SUITE("spatial/beam") {
  TEST_CASE("cantilever, 10 BEAM3: static tip deflection P L^3 / (3 E I) in both bending planes") {
    const section s;
    cantilever<beam_model> c(10);
    const double p = 1e-4;  // tip deflection 1e-4 L: geometric nonlinearity ~1e-8
    c.m.add<spatial_force>("load", {0, p, p, 0, 0, 0, 0, 0}, c.tip()[0], c.tip()[1], c.tip()[2]);
    simulation sim(c.m);
    sim.run({.end = 1.0, .smax = 0.5, .newton = tight});
    const double uz = sim.u(c.tip()[2]), uy = sim.u(c.tip()[1]);
    const double exact_z = p / (3 * s.e * s.iy), exact_y = p / (3 * s.e * s.iz);  // L = 1
    MESSAGE("tip deflection errors: z ", uz / exact_z - 1, ", y ", uy / exact_y - 1);
    CHECK(std::abs(uz / exact_z - 1) < 1e-3);
    CHECK(std::abs(uy / exact_y - 1) < 1e-3);
    // The tip slope P L^2 / (2 E I) about -Y (bending in the X-Z plane): theta = 2 q2 / q4 for small angles.
    const quaternion q = node_quaternion(sim, c.tip_rotation());
    CHECK(std::abs(-2 * q(1) / q(3) / (p / (2 * s.e * s.iy)) - 1) < 1e-3);
  }

  TEST_CASE("cantilever, 10 BEAM3 + BEAMI3: first bending frequency of the element matrices in both planes") {
    // Stiffness and mass from the elements' Jacobians at the reference state, the DOFs of the free nodes
    // (x, y, z, theta): at identity quaternions dtheta/dq = 2 E(q) = 2 [I 0]. A slender steel bar, 10 mm x 20 mm
    // (L / h = 50): BEAMI3 includes the rotary inertia of the section (a Rayleigh beam), which lowers the
    // frequency below the Euler-Bernoulli value by about (r / L)^2 times a constant.
    const section s = steel;
    const int n = 10, nd = 6 * n;
    const double le = 1.0 / n;
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(nd, nd), mm = Eigen::MatrixXd::Zero(nd, nd);
    for (int i = 0; i < n; ++i) {
      const double xa = i * le, xb = (i + 1) * le;
      const elastic_beam b({s.e, s.g, s.a, s.iy, s.iz, s.j, xa, 0, 0, xb, 0, 0, 0, 1, 0});
      const beam_inertia bi({s.rho, s.a, s.iy, s.iz, s.iy + s.iz, xa, 0, 0, xb, 0, 0, 0, 1, 0});
      local_input<elastic_beam> in;
      in.u(12) = in.u(13) = 1.0;  // identity quaternions
      local_input<beam_inertia> ini;
      ini.u = in.u;
      local_output<elastic_beam> out;
      local_output<beam_inertia> outi;
      std::array<double, 3> wb{}, wi{};
      element_context cb("BEAM3", "b"), ci("BEAMI3", "m");
      cb.work = wb;
      ci.work = wi;
      b.new_integration(cb);
      b.evaluate(in, out, cb);
      bi.evaluate(ini, outi, ci);
      for (int r = 0; r < 12; ++r)
        for (int q = 0; q < 12; ++q) {
          const int gr = 6 * (i - 1) + r, gq = 6 * (i - 1) + q;
          if (gr < 0 || gq < 0) continue;
          const double scale = (q % 6) >= 3 ? 0.5 : 1.0;  // columns by theta instead of q
          k(gr, gq) += scale * out.K(r, q);
          mm(gr, gq) += scale * outi.M(r, q);
        }
    }
    CHECK((k - k.transpose()).norm() < 1e-9 * k.norm());
    CHECK((mm - mm.transpose()).norm() < 1e-12 * mm.norm());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(k, mm, Eigen::EigenvaluesOnly);
    const double lambda = 1.87510407 * 1.87510407;
    const double fz = lambda * std::sqrt(s.e * s.iy / (s.rho * s.a)) / (2 * pi);  // L = 1
    const double fy = lambda * std::sqrt(s.e * s.iz / (s.rho * s.a)) / (2 * pi);
    const double f1 = std::sqrt(es.eigenvalues()(0)) / (2 * pi), f2 = std::sqrt(es.eigenvalues()(1)) / (2 * pi);
    // Iz < Iy: the lowest mode bends about z (in the X-Y plane), the second about y.
    MESSAGE("first bending frequencies: ", f1, " Hz (exact ", fy, "), ", f2, " Hz (exact ", fz, "); errors ",
            f1 / fy - 1, ", ", f2 / fz - 1);
    CHECK(std::abs(f1 / fy - 1) < 5e-3);
    CHECK(std::abs(f2 / fz - 1) < 5e-3);
  }

  TEST_CASE("cantilever, 10 BEAM3 + BEAMI3 in a transient: free vibration after a step load at the first frequency") {
    // A constant tip force from t = 0 on the straight bar at rest: the tip oscillates about the static
    // deflection P L^3 / (3 E Iz) (97% of it in the first mode); the period from the upward crossings of that
    // level over two periods. Newmark average acceleration at h = T/100 lengthens the period by Omega^2/12 = 3.3e-4.
    const section s = steel;
    cantilever<beam_model, true> c(10, s);
    const double p = 3 * s.e * s.iz * 1e-4;  // static tip deflection 1e-4 L
    c.m.add<spatial_force>("load", {0, p, 0, 0, 0, 0, 0, 0}, c.tip()[0], c.tip()[1], c.tip()[2]);
    const double f_exact = 1.87510407 * 1.87510407 * std::sqrt(s.e * s.iz / (s.rho * s.a)) / (2 * pi);
    const double period = 1 / f_exact, h = period / 100, level = 1e-4;
    simulation sim(c.m);
    std::vector<double> crossings;
    double t_prev = 0, u_prev = 0;
    for (int k = 1; k <= 230; ++k) {
      sim.run({.end = k * h, .smax = h, .smin = h / 64, .newton = steel_newton});
      const double u = sim.u(c.tip()[1]), t = sim.time();
      if (u_prev < level && u >= level && t_prev > 0)
        crossings.push_back(t_prev + (level - u_prev) / (u - u_prev) * (t - t_prev));
      t_prev = t;
      u_prev = u;
    }
    REQUIRE(crossings.size() >= 2);
    const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    MESSAGE("transient first period ", measured, " s vs Euler-Bernoulli ", period, " s: relative error ",
            measured / period - 1);
    CHECK(std::abs(measured / period - 1) < 5e-3);
  }

  TEST_CASE("cantilever, 10 BEAM3: an end moment 2 pi E I / L, ramped, rolls it into a full circle") {
    const section s;
    cantilever<beam_model> c(10);
    const double mfull = 2 * pi * s.e * s.iy;  // L = 1; about the tip's body Y (global Y throughout)
    // M(t) = M/2 (1 - cos(pi t)): 0 at t = 0, M at t = 1.
    c.m.add<body_torque>("moment", {0, mfull / 2, 0, 0, mfull / 2, 0, 0.5, -90}, c.tip_rotation());
    simulation sim(c.m);
    sim.run({.end = 1.0, .smax = 0.02, .newton = tight});
    const double gap = std::hypot(1.0 + sim.u(c.tip()[0]), sim.u(c.tip()[1]), sim.u(c.tip()[2]));
    const quaternion q = node_quaternion(sim, c.tip_rotation());
    const double turn = to_axis_angle(q).angle;  // the tip turned by 360 degrees: back to the identity
    MESSAGE("roll-up: tip gap ", gap, " L, tip orientation off the identity by ", turn, " rad");
    CHECK(gap < 1e-2);
    CHECK(std::abs(turn) < 1e-2);
    CHECK(q(3) < 0);  // a continuous path of quaternions through 360 degrees ends at -identity
  }

  TEST_CASE("BEAM3 and BEAMI3 refuse a zero length and non-positive moduli or sections (100), a wrong count (101)") {
    const section s;
    auto run_error = [](auto build) {
      beam_model m;
      const auto d = m.add_dofs(6);
      build(m, std::array<dof, 3>{d[0], d[1], d[2]}, m.add_rotation_node("ra"), std::array<dof, 3>{d[3], d[4], d[5]},
            m.add_rotation_node("rb"));
      simulation sim(m);
      return error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); });
    };
    auto beam = [&](elastic_beam::parameters bp) {
      return run_error([&](auto& m, auto xa, auto ra, auto xb, auto rb) {
        m.template add<elastic_beam>("b1", bp, xa[0], xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
      });
    };
    const elastic_beam::parameters ok{s.e, s.g, s.a, s.iy, s.iz, s.j, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    auto with = [&](int k, double v) {  // ok with PAR(k + 1) replaced by v
      std::array<double, 15> a{ok.e, ok.g, ok.a, ok.iy, ok.iz, ok.j, ok.xa, ok.ya, ok.za, ok.xb, ok.yb, ok.zb, ok.vx, ok.vy, ok.vz};
      a[static_cast<std::size_t>(k)] = v;
      return elastic_beam::from_parameters(a).p;
    };
    check_error(beam(with(9, 0.0)), error_code::invalid_parameter, "BEAM3", "b1", "coincide");
    check_error(beam(with(0, 0.0)), error_code::invalid_parameter, "BEAM3", "b1", "Young's modulus");
    check_error(beam(with(1, -1.0)), error_code::invalid_parameter, "BEAM3", "b1", "shear modulus");
    check_error(beam(with(2, -1.0)), error_code::invalid_parameter, "BEAM3", "b1", "area A");
    check_error(beam(with(3, 0.0)), error_code::invalid_parameter, "BEAM3", "b1", "second moments");
    check_error(beam(with(4, -1e-4)), error_code::invalid_parameter, "BEAM3", "b1", "second moments");
    check_error(beam(with(5, 0.0)), error_code::invalid_parameter, "BEAM3", "b1", "torsion constant");
    check_error(beam(with(13, 0.0)), error_code::invalid_parameter, "BEAM3", "b1", "parallel");  // v = 0
    auto inertia = [&](beam_inertia::parameters bp) {
      return run_error([&](auto& m, auto xa, auto ra, auto xb, auto rb) {
        m.template add<beam_inertia>("m1", bp, xa[0], xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
      });
    };
    check_error(inertia({s.rho, s.a, s.iy, s.iz, s.j, 1, 0, 0, 1, 0, 0, 0, 1, 0}), error_code::invalid_parameter,
                "BEAMI3", "m1", "coincide");
    check_error(inertia({0, s.a, s.iy, s.iz, s.j, 0, 0, 0, 1, 0, 0, 0, 1, 0}), error_code::invalid_parameter, "BEAMI3",
                "m1", "density");
    check_error(inertia({s.rho, s.a, -1, s.iz, s.j, 0, 0, 0, 1, 0, 0, 0, 1, 0}), error_code::invalid_parameter,
                "BEAMI3", "m1", "second moments");
    beam_model m0;
    const auto d = m0.add_dofs(12);
    const std::array<double, 7> seven{};
    for (const char* name : {"BEAM3", "BEAMI3"}) {
      CAPTURE(name);
      check_error(error_from([&] { m0.add_by_name(name, std::string("n") + name, d, seven); }),
                  error_code::parameter_count, name, std::string("n") + name, "got 7 parameters");
    }
  }
}
