// The zero step's positions and velocities of the algebraic DOFs (neither mass nor viscosity;
// integrators/algebraic_start.hpp). Before it, a DOF whose initial position was off its
// equation was moved there by the first step, and under error control (first step SMIN =
// 1e-11 s) both drivers ended with code 141 at once: a displaced mass on a spring to a
// massless node held by a second spring, and a static spring loaded by a constant force.
// Answers: springs in series, k = k1 k2 / (k1 + k2), the node at the lever rule n = k1 x /
// (k1 + k2), the harmonic motion x = x0 cos(w t) + (v0 / w) sin(w t), w^2 = k / m (any
// mechanics text, e.g. Meirovitch, Fundamentals of Vibrations, 2001, sections 1.6 and 2.2);
// the static equilibrium u = F / k. Warning texts: algebraic_start.hpp (`give_up`).
// Newton on a root of f(u) = sign(u) |u|^n converges linearly at the rate q = 1 - 1/n
// (Ortega and Rheinboldt, Iterative Solution of Nonlinear Equations in Several Variables,
// 1970, 10.2). Defaults: DABSI = 0.1; a DOF without a domain has nominal potential 1 and
// nominal flow 1.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "dense_test_solver.hpp"
#include "testing/test_support.hpp"
#include "zero_step_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/algebraic_start.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/linalg/sparse_lu.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::count_of;
using pradis_test::observed_run;
using pradis_test::run_outcome;

namespace {

/// A one-DOF position law F = Law::f(u) with dF/du = Law::dfdu(u) (ADR 1, IGN 23: only the K
/// block); it refuses (code 75) the states where Law::refuse(u, t) holds.
template <class Law>
struct ast_law_t {
  static constexpr pradis::passport passport{.name = Law::name, .ext = 1, .par = 0, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "one-DOF position law of an algebraic-start test",
                                     .name = "F = Law::f(u), dF/du = Law::dfdu(u)",
                                     .field = "mechanics",
                                     .dofs = "1 - the DOF",
                                     .parameters = "none",
                                     .work = "none",
                                     .special = "code 75 where Law::refuse(u, t)"};
  struct parameters {};
  parameters p;
  explicit ast_law_t(parameters q = {}) : p(q) {}
  static parameters example() { return {}; }
  static ast_law_t from_parameters(std::span<const double>) { return ast_law_t{}; }
  void evaluate(const local_input<ast_law_t>& in, local_output<ast_law_t>& out, element_context& ctx) const {
    if (Law::refuse(in.u(0), in.t)) ctx.singular("refused");
    out.f(0) = Law::f(in.u(0));
    if (out.want_jacobian) out.K(0, 0) = Law::dfdu(in.u(0));
  }
};

/// A power-law spring towards u = 5: F = sign(w) |w|^n, w = u - 5, n = 1.96; dF/du vanishes at the
/// root, so Newton converges linearly at q = 1 - 1/n.
struct ast_power {
  static constexpr std::string_view name = "ASTPOW";
  static constexpr double n = 1.96, at = 5;
  static double f(double u) { return (u < at ? -1 : 1) * std::pow(std::abs(u - at), n); }
  static double dfdu(double u) { return n * std::pow(std::abs(u - at), n - 1); }
  static bool refuse(double, double) { return false; }
};

/// F = u - 1 with a Jacobian of the wrong sign (-1): every Newton direction raises |F|.
struct ast_wrong_sign {
  static constexpr std::string_view name = "ASTWRONG";
  static double f(double u) { return u - 1; }
  static double dfdu(double) { return -1; }
  static bool refuse(double, double) { return false; }
};

/// F = u - 1 with dF/du = 1e-320 (subnormal): the correction -F / (dF/du) overflows.
struct ast_subnormal {
  static constexpr std::string_view name = "ASTSUB";
  static double f(double u) { return u - 1; }
  static double dfdu(double) { return 1e-320; }
  static bool refuse(double, double) { return false; }
};

/// F = u - 1 that refuses the states within 1e-12 of its root (which Newton's last step reaches).
struct ast_root_refused {
  static constexpr std::string_view name = "ASTROOT";
  static double f(double u) { return u - 1; }
  static double dfdu(double) { return 1; }
  static bool refuse(double u, double) { return std::abs(u - 1) < 1e-12; }
};

/// A 300 N/m spring to the ground, F = 300 u, that refuses the times in (0, 2e-3): the velocities'
/// difference quotients along the motion (at most 1e-3 ahead) meet it; steps of 1e-2 do not.
struct ast_fragile {
  static constexpr std::string_view name = "ASTFRAG";
  static double f(double u) { return 300 * u; }
  static double dfdu(double) { return 300; }
  static bool refuse(double, double t) { return t > 0 && t < 2e-3; }
};

/// A static run of one ast_law_t<Law> on one DOF started at u0, with the one-step (Newmark) or the BDF driver.
template <class Law, bool Bdf, class Solver = linalg::sparse_lu<linalg::automatic_ordering>>
run_outcome ast_law_run(double u0, const run_options& o) {
  using E = ast_law_t<Law>;
  using M = model<E, initial_displacement>;
  M md;
  const dof u = md.add_dof("u");
  md.template add<E>("law", {}, u);
  if (u0 != 0) md.template add<initial_displacement>("u0", {u0}, u);
  if constexpr (Bdf) return observed_run<bdf_simulation<M, Solver>>(md, {u}, o);
  else return observed_run<simulation<M, newmark, Solver>>(md, {u}, o);
}

std::string ast_warning(const std::string& why) {
  return "warning: the positions of the DOFs with neither mass nor viscosity were not solved at the zero step (" +
         why + "): they start at their initial values, and the first step meets their equations";
}

run_options ast_controlled(double end, double tol) { return pradis_test::controlled_run(end, tol, 20); }

template <class M>
using ast_newmark = simulation<M>;
template <class M>
using ast_bdf = bdf_simulation<M>;

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using algebraic_start_model = pradis::model<point_mass, linear_spring, initial_displacement, initial_velocity,
    floating_voltage_dc, inductor, constant_force, planar_rigid_link>;
/// The series springs: mass m at x on k1 to the massless node n, k2 from n to the ground, x(0) = x0,
/// x'(0) = v0. Checks the start and, at every output, the lever rule and the exact motion; returns
/// the largest |x - exact|. With `single`, the mass on one spring of the series stiffness instead
/// (and n on its own spring k2, apart): the same motion of x without a massless DOF in its path.
template <template <class> class Sim>
double ast_series(double tol, bool single = false) {
  constexpr double m = 1, k1 = 100, k2 = 300, x0 = 0.1, v0 = 0.5;
  const double w = std::sqrt(k1 * k2 / (k1 + k2) / m), lever = k1 / (k1 + k2);
  using M = algebraic_start_model;
  M md;
  const dof x = md.add_dof("x"), n = md.add_dof("n");
  md.add<point_mass>("m", {m}, x);
  if (single) md.add<linear_spring>("k", {k1 * k2 / (k1 + k2)}, x, md.ground());
  else md.add<linear_spring>("k1", {k1}, x, n);
  md.add<linear_spring>("k2", {k2}, n, md.ground());
  md.add<initial_displacement>("x0", {x0}, x);
  md.add<initial_velocity>("v0", {v0}, x);
  Sim<M> sim(md);
  std::ostringstream log;
  sim.log().to(log);
  double worst = 0, worst_lever = 0;
  sim.on_output([&](const auto& s) {
    const double t = s.time();
    if (single) {
      worst = std::max(worst, std::abs(s.u(x) - (x0 * std::cos(w * t) + v0 / w * std::sin(w * t))));
      return;
    }
    if (t == 0) {
      CHECK(s.u(n) == doctest::Approx(lever * x0).epsilon(1e-14));
      // dF_n/dt = k1 (v_n - v0) + k2 v_n = 0, from difference quotients of a linear flow.
      CHECK(s.v(n) == doctest::Approx(lever * v0).epsilon(1e-9));
      // The mass's acceleration from the node on its equation: -k1 (x0 - n) / m = -w^2 x0.
      CHECK(s.a(x) == doctest::Approx(-w * w * x0).epsilon(1e-12));
    }
    worst_lever = std::max(worst_lever, std::abs(s.u(n) - lever * s.u(x)));
    worst = std::max(worst, std::abs(s.u(x) - (x0 * std::cos(w * t) + v0 / w * std::sin(w * t))));
  });
  sim.run(ast_controlled(2.0, tol));
  const std::string text = log.str();
  CAPTURE(text);
  CHECK(text.find("warning") == std::string::npos);
  // The node's equation holds to Newton's residual test: |k1 (x - n) - k2 n| <= DABSI + DRLTI (|k1 (x - n)| +
  // |k2 n|) (0.1 and 1e-3 by default), over k1 + k2.
  CHECK(worst_lever < (0.1 + 1e-3 * 2 * k2 * lever * (x0 + v0 / w)) / (k1 + k2));
  return worst;
}

/// Adds the series springs displaced by 0.1 m to md: the mass of 1 kg at x on 100 N/m to the massless node n,
/// 300 N/m from n to the ground. Returns {x, n}.
template <class M>
std::array<dof, 2> ast_displaced_series(M& md) {
  const dof x = md.add_dof("x"), n = md.add_dof("n");
  md.template add<point_mass>("m", {1.0}, x);
  md.template add<linear_spring>("k1", {100.0}, x, n);
  md.template add<linear_spring>("k2", {300.0}, n, md.ground());
  md.template add<initial_displacement>("x0", {0.1}, x);
  return {x, n};
}

/// The DOF classes (checkpoint_data::dof_classes) of the series springs' mass and node after a BDF run to 0.1 s
/// at DRLTX = DABSX = 1e-6.
std::vector<double> ast_series_classes() {
  using M = algebraic_start_model;
  M md;
  const auto [x, n] = ast_displaced_series(md);
  bdf_simulation<M> sim(md);
  sim.run(ast_controlled(0.1, 1e-6));
  CHECK(sim.time() == doctest::Approx(0.1).epsilon(1e-12));
  const auto c = sim.checkpoint().dof_classes;
  return {c[static_cast<std::size_t>(x.index)], c[static_cast<std::size_t>(n.index)]};
}

}  // namespace

TEST_SUITE("integrators/algebraic start") {
  TEST_CASE("a mass on a spring to a massless node held by a second spring runs under error control in both drivers") {
    // Before: code 141 at t = 1e-11 in both drivers (the node moved by 0.025 m in the first step).
    // The massless node costs no accuracy: the mass on one spring of the series stiffness has the same
    // errors. Measured (largest |x - exact| over 20 outputs to t = 2 s, DRLTX = DABSX = 1e-6 / 1e-8):
    // NEWMARK 5.59e-6 / 5.18e-8 m (single spring 5.57e-6 / 6.75e-8), BDF 1.59e-6 / 2.40e-7 m (single
    // spring 1.59e-6 / 2.11e-7; with the default Newton tolerances BDF's error falls less than 10x here).
    const double n6 = ast_series<ast_newmark>(1e-6), n8 = ast_series<ast_newmark>(1e-8);
    const double b6 = ast_series<ast_bdf>(1e-6), b8 = ast_series<ast_bdf>(1e-8);
    const double sn6 = ast_series<ast_newmark>(1e-6, true), sn8 = ast_series<ast_newmark>(1e-8, true);
    const double sb6 = ast_series<ast_bdf>(1e-6, true), sb8 = ast_series<ast_bdf>(1e-8, true);
    CHECK(n6 < 1.5 * sn6 + 1e-9);
    CHECK(n8 < 1.5 * sn8 + 1e-9);
    CHECK(b6 < 1.5 * sb6 + 1e-9);
    CHECK(b8 < 1.5 * sb8 + 1e-9);
    CHECK(n6 < 2e-5);
    CHECK(n8 < n6 / 10);
    CHECK(b6 < 2e-5);
    CHECK(b8 < 1e-6);
    MESSAGE("series springs |x - exact|: NEWMARK ", n6, " / ", n8, " (one spring ", sn6, " / ", sn8, "), BDF ", b6,
            " / ", b8, " (one spring ", sb6, " / ", sb8, ")");
  }

  TEST_CASE("BDF: the velocity of a massless node is left out of its norms, so tight tolerances run") {
    // The node's position is put on its equation to round-off d (about eps |n| = 5e-18 m); its velocity, the
    // position's BDF derivative, then carries about d / h, 5e-7 m/s at the first step (h ~ 1e-11 s), against a
    // tolerance of 1e-10 m/s. Before, BDF ended with code 140 at t = 0 at DRLTX = DABSX = 1e-9 and 1e-10;
    // the node's displacement is the unknown, its velocity only its derivative (driver_core::unused_velocity).
    // Measured (largest |x - exact| over the outputs): 3.2e-8 / 5.0e-9 at 1e-9 / 1e-10, the same mass on one spring of the series stiffness
    // 3.2e-8 / 3.8e-9: the node costs no accuracy here either.
    const double b9 = ast_series<ast_bdf>(1e-9), b10 = ast_series<ast_bdf>(1e-10);
    const double sb9 = ast_series<ast_bdf>(1e-9, true), sb10 = ast_series<ast_bdf>(1e-10, true);
    MESSAGE("BDF |x - exact| at 1e-9 / 1e-10: ", b9, " / ", b10, " (one spring ", sb9, " / ", sb10, ")");
    CHECK(b9 < 1.5 * sb9 + 1e-12);
    CHECK(b10 < 1.5 * sb10 + 1e-12);
    CHECK(b9 < 1e-7);
    CHECK(b10 < b9 / 3);
  }

  TEST_CASE("BDF keeps the velocity of a massless DOF whose velocity is an unknown of its own (its DOF class)") {
    // Classes (driver_core.hpp): 0 other, 1 massless, 2 massless with a velocity that is an unknown of its own
    // (a source current, a node whose potential a source fixes), which BDF keeps in its norms.
    const std::vector<double> springs = ast_series_classes();
    CHECK(springs[0] == 0.0);  // the mass
    CHECK(springs[1] == 1.0);  // the node: its equation fixes its displacement
    // A floating source of V = 5 V across an inductor of L = 0.1 H: the node's row has only the inductor's K and
    // the source current's C entry, and the source's row fixes the node's potential v (its velocity, kind 6 of
    // the zero step); the current, the source's internal DOF, is a velocity-level multiplier (kind 4). The current ramps as i = V t / L, which
    // BDF's fixed steps of 1 ms integrate exactly: 5 A at t = 0.1 s.
    using M = algebraic_start_model;
    M md;
    const dof a = md.add_dof("a");
    md.add<floating_voltage_dc>("V", {5.0}, a, md.ground());
    const auto ind = md.add<inductor>("L", {0.1, 0.0}, a, md.ground());
    bdf_simulation<M> sim(md);
    run_options o;
    o.end = 0.1;
    o.out = 0.01;
    o.smax = o.smin = 1e-3;
    sim.run(o);
    CHECK(md.work(ind)[0] == doctest::Approx(5.0).epsilon(1e-12));
    CHECK(sim.v(a) == doctest::Approx(5.0).epsilon(1e-12));
    const auto c = sim.checkpoint().dof_classes;
    REQUIRE(c.size() == 3);  // ground, a, the source current
    CHECK(c[static_cast<std::size_t>(a.index)] == 2.0);
    CHECK(std::count(c.begin(), c.end(), 2.0) == 2);  // a and the current
  }

  TEST_CASE("a static model (springs and a constant force, no mass or viscosity) starts at its equilibrium") {
    // ground - k1 - a - k2 - b <- F: a = F / k1, b = F / k1 + F / k2, at t = 0 and after. Before: code 141 at
    // t = 1e-11 (NEWMARK) and t = 0 (BDF).
    constexpr double k1 = 100, k2 = 400, f = 2;
    auto run = [&]<template <class> class Sim>() {
      using M = algebraic_start_model;
      M md;
      const dof a = md.add_dof("a"), b = md.add_dof("b");
      md.add<linear_spring>("k1", {k1}, a, md.ground());
      md.add<linear_spring>("k2", {k2}, b, a);
      md.add<constant_force>("F", {f}, b);
      Sim<M> sim(md);
      std::ostringstream log;
      sim.log().to(log);
      int outputs = 0;
      sim.on_output([&](const auto& s) {
        ++outputs;
        CHECK(s.u(a) == doctest::Approx(f / k1).epsilon(1e-14));
        CHECK(s.u(b) == doctest::Approx(f / k1 + f / k2).epsilon(1e-14));
        // NEWMARK's first step (SMIN = 1e-11 s) leaves b's round-off in u, eps |u|, as a velocity of about
        // 2 eps |u| / SMIN that the trapezoidal rule keeps alternating (measured 6.4e-9 m/s; BDF 0).
        CHECK(std::abs(s.v(b)) < 4 * std::numeric_limits<double>::epsilon() * s.u(b) / 1e-11);
      });
      run_options o = ast_controlled(1.0, 1e-6);
      o.smax = 0.05;
      sim.run(o);
      CHECK(outputs == 21);
      const std::string text = log.str();
      CAPTURE(text);
      CHECK(text.find("not solved") == std::string::npos);
    };
    SUBCASE("NEWMARK") { run.template operator()<ast_newmark>(); }
    SUBCASE("BDF") { run.template operator()<ast_bdf>(); }
  }

  TEST_CASE("a group of algebraic DOFs that reaches a constraint is left to the first step; a separate group is solved") {
    // Group 1: the massless point P (px, py) on an exact rigid link (LINKX) from the ground point (0, 0) to
    // (1, 0), k_p from py to the massless node n, k_n from n to the ground, n(0) = 0.5. P's DOFs are columns
    // of the link's constraint row (whose multiplier the zero step's solve does not have), so n, coupled to
    // py, is left with P: n(0) stays 0.5. Group 2: a mass x on k1 to the massless node m, k2 to the ground,
    // x(0) = 0.1: m(0) = k1 x(0) / (k1 + k2) = 0.025. Fixed steps of 1 ms then meet group 1's equations:
    // n = py k_p / (k_p + k_n) and, P being free to turn about the ground point, the springs in series
    // relax to py = n = 0.
    using M = algebraic_start_model;
    M md;
    const dof px = md.add_dof("px"), py = md.add_dof("py"), n = md.add_dof("n");
    const dof x = md.add_dof("x"), mn = md.add_dof("m");
    md.add<planar_rigid_link>("link", {0.0, 0.0, 1.0, 0.0}, md.ground(), md.ground(), px, py);
    md.add<linear_spring>("kp", {200.0}, py, n);
    md.add<linear_spring>("kn", {100.0}, n, md.ground());
    md.add<initial_displacement>("n0", {0.5}, n);
    md.add<point_mass>("mass", {1.0}, x);
    md.add<linear_spring>("k1", {100.0}, x, mn);
    md.add<linear_spring>("k2", {300.0}, mn, md.ground());
    md.add<initial_displacement>("x0", {0.1}, x);
    run_options o;
    o.end = 1e-2;
    o.smax = 1e-3;
    const run_outcome r = observed_run<simulation<M>>(md, {n, mn, py}, o);
    CAPTURE(r.log);
    CHECK(r.log.find("were not solved") == std::string::npos);  // left, not failed
    REQUIRE(r.u0.size() == 3);
    CHECK(r.u0[0] == 0.5);
    CHECK(r.u0[1] == doctest::Approx(0.025).epsilon(1e-14));
    CHECK_FALSE(r.failed);
    CHECK(std::abs(r.u_end[0] - r.u_end[2] * 200.0 / 300.0) < 1e-6);
  }

  TEST_CASE("algebraic_start: 30 iterations at Newton's linear rate keep the initial position (a power-law spring)") {
    // From u = 0: e0 = 5, each step multiplies the error by q = 1 - 1/1.96 = 0.4898 (|F| falls, no
    // halving), so correction k (0-based) is 5 q^k (1 - q) / (1 + |u|) >= 5 q^29 0.51 / 6 = 4.3e-10 >
    // 1e-10 for k <= 29: the loop reaches 30 and the DOF goes back to u = 0 with the warning. Fixed steps
    // of 1 ms then meet F = 0 in the first step's Newton (ITR 60), to its residual test |F| <= DABSI /
    // (1 - DRLTI), so |u - 5| <= (1e-8 / 0.999)^(1 / 1.96) = 8.3e-5. (NEWMARK only: the BDF driver fails
    // with code 140 on such a root, where dF/du vanishes, whatever the start; test_zero_step_warnings.cpp.)
    run_options o;
    o.end = 1e-2;
    o.smax = 1e-3;
    o.newton.itr = 60;
    o.newton.dabsi = 1e-8;
    const run_outcome r = ast_law_run<ast_power, false>(0, o);
    CAPTURE(r.log);
    CHECK(count_of(r.log, ast_warning("no convergence in 30 Newton iterations")) == 1);
    REQUIRE(r.u0.size() == 1);
    CHECK(r.u0[0] == 0.0);
    CHECK(r.v0[0] == 0.0);
    CHECK_FALSE(r.failed);
    CHECK(std::abs(r.u_end[0] - ast_power::at) < std::pow(1e-8 / 0.999, 1 / ast_power::n));
  }

  TEST_CASE("algebraic_start: no step lowers the residual (a Jacobian of the wrong sign)") {
    // From u = 0: F = -1, the correction -F / (dF/du) = -1 leads to u = -t, |F| = 1 + t > 1 and > DABSI for every
    // t = 2^-k: 40 halvings, then u = 0 again. The first step's Newton goes the same wrong way: code 140.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      const run_outcome r =
          bdf ? ast_law_run<ast_wrong_sign, true>(0, ast_controlled(1, 1e-6)) : ast_law_run<ast_wrong_sign, false>(0, ast_controlled(1, 1e-6));
      CAPTURE(r.log);
      CHECK(count_of(r.log, ast_warning("no step lowers the residual")) == 1);
      REQUIRE(r.u0.size() == 1);
      CHECK(r.u0[0] == 0.0);
      CHECK(r.failed);
      CHECK(r.code == error_code::newton_failure);
    }
  }

  TEST_CASE("algebraic_start: a singular matrix (a pair of massless nodes joined only to each other)") {
    // x (mass) - k1 - n - k2 - ground, and p - k3 - q with nothing else on p and q: dF/du on (n, p, q) is
    // singular (p and q float). The warning names sparse_lu's code 131; the first step's Newton matrix is
    // singular too, so the run ends with code 131 at t = 0.
    using M = algebraic_start_model;
    M md;
    const dof x = md.add_dof("x"), n = md.add_dof("n"), p = md.add_dof("p"), q = md.add_dof("q");
    md.add<point_mass>("m", {1.0}, x);
    md.add<linear_spring>("k1", {100.0}, x, n);
    md.add<linear_spring>("k2", {300.0}, n, md.ground());
    md.add<linear_spring>("k3", {50.0}, p, q);
    md.add<initial_displacement>("x0", {0.1}, x);
    const run_outcome r = observed_run<simulation<M>>(md, {n}, ast_controlled(1, 1e-6));
    CAPTURE(r.log);
    CHECK(count_of(r.log, "warning: the positions of the DOFs with neither mass nor viscosity were not solved at the "
                           "zero step (a singular matrix: pradis error 131") == 1);
    REQUIRE(r.u0.size() == 1);
    CHECK(r.u0[0] == 0.0);  // the initial value
    CHECK(r.failed);
    CHECK(r.code == error_code::singular_matrix);
  }

  TEST_CASE("algebraic_start: a non-finite correction (a subnormal stiffness and a user's dense LU)") {
    // dF/du = 1e-320: the dense LU (no pivot check) gives -F / (dF/du) = 1 / 1e-320 = inf.
    using solver = pradis_test::dense_test_solver<>;
    run_options o;
    o.end = 1e-2;
    o.smax = 1e-3;
    const run_outcome r = ast_law_run<ast_subnormal, false, solver>(0, o);
    CAPTURE(r.log);
    CHECK(count_of(r.log, ast_warning("a non-finite correction")) == 1);
    REQUIRE(r.u0.size() == 1);
    CHECK(r.u0[0] == 0.0);
    CHECK(r.failed);  // the first step's correction is not finite either
  }

  TEST_CASE("algebraic_start: an element that refuses the solved state, or the states next to the start") {
    SUBCASE("the root") {
      // u(0) = 1 - 1e-11: the correction 1e-11 / (1 + u) = 5e-12 is below 1e-10 and is taken whatever the
      // residual does, onto u = 1, which the element refuses: back to u(0), the warning. The first step's
      // Newton lands on the root too (F is linear), at every step size: code 75 at SMIN.
      run_options o;
      o.end = 1e-2;
      o.smax = 1e-3;
      const run_outcome r = ast_law_run<ast_root_refused, false>(1 - 1e-11, o);
      CAPTURE(r.log);
      CHECK(count_of(r.log, ast_warning("an element refuses the solved state")) == 1);
      REQUIRE(r.u0.size() == 1);
      CHECK(r.u0[0] == 1 - 1e-11);
      CHECK(r.failed);
      CHECK(r.code == error_code::singular_situation);
    }
    SUBCASE("the velocities' nearby states") {
      // The series springs with k2 the fragile 300 N/m spring: the positions solve (n = x0 / 4), the
      // difference quotients at t <= 1e-3 are refused: back to the initial values, the warning with the
      // element's message. Steps of 1e-2 s then run.
      using E = ast_law_t<ast_fragile>;
      using M = model<point_mass, linear_spring, initial_displacement, E>;
      M md;
      const dof x = md.add_dof("x"), n = md.add_dof("n");
      md.add<point_mass>("m", {1.0}, x);
      md.add<linear_spring>("k1", {100.0}, x, n);
      md.add<E>("k2", {}, n);
      md.add<initial_displacement>("x0", {0.1}, x);
      run_options o;
      o.end = 0.1;
      o.smax = 1e-2;
      const run_outcome r = observed_run<simulation<M>>(md, {n}, o);
      CAPTURE(r.log);
      CHECK(count_of(r.log, "warning: the positions of the DOFs with neither mass nor viscosity were not solved at "
                             "the zero step (an element refuses a state next to the start: ") == 1);
      CHECK(r.log.find("refused") != std::string::npos);
      REQUIRE(r.u0.size() == 1);
      CHECK(r.u0[0] == 0.0);
      CHECK_FALSE(r.failed);
    }
  }

  TEST_CASE("algebraic_start called directly: solves a static spring, and keeps the start when its first "
            "evaluation throws") {
    // A spring k = 100 N/m to the ground under a constant force F = 10 N, no mass: the zero step's position is
    // u = F / k = 0.1 m (static equilibrium). Through the drivers the guard "an element refuses the initial
    // state" is not reached: initial_derivatives has just evaluated the same state with the same Jacobian
    // request. Called directly with an evaluation that throws (as an element whose refusal depends on more than
    // the state would), it restores the initial values and writes the warning.
    using M = model<linear_spring, constant_force>;
    M md;
    const dof a = md.add_dof("a");
    md.add<linear_spring>("k", {100.0}, a, md.ground());
    md.add<constant_force>("F", {10.0}, a);
    std::vector<char> prescribed(static_cast<std::size_t>(md.dof_count()), 0);
    prescribed[static_cast<std::size_t>(md.ground().index)] = 1;  // the ground gets no equation
    assembler<M> as;
    as.build(md, prescribed);
    linalg::sparse_lu<> solver;
    solver.analyze(as.pattern());
    global_state s;
    s.resize(md.dof_count());
    run_statistics stats;
    diagnostics log;
    std::ostringstream os;
    log.to(os);
    auto evaluate = [&](const jacobian_coefficients& c, bool jacobian) {
      as.evaluate(md, s, c, call_info{0.0, 0.0, 0, 0, jacobian, &log});
    };
    evaluate(jacobian_coefficients{1, 0, 0}, true);
    const std::vector<double> kvals(as.values().begin(), as.values().end());
    const std::vector<char> kind(static_cast<std::size_t>(as.equations()), 0);  // algebraic: no mass, no viscosity
    CHECK(pradis::detail::algebraic_start(md, as, solver, s, stats, log, evaluate, kind, kvals, 0.1));
    CHECK(s.u(a.index) == doctest::Approx(0.1).epsilon(1e-14));
    CAPTURE(os.str());
    CHECK(os.str().empty());

    s.u(a.index) = 0.0;
    auto refuse = [&](const jacobian_coefficients&, bool) {
      throw error(error_code::singular_situation, "refused", "K", "k");
    };
    CHECK(pradis::detail::algebraic_start(md, as, solver, s, stats, log, refuse, kind, kvals, 0.1));
    CHECK(s.u(a.index) == 0.0);
    CHECK(count_of(os.str(), ast_warning("an element refuses the initial state")) == 1);
  }

  TEST_CASE("the warning on an initial displacement of a DOF with neither mass nor viscosity") {
    // X0 on the massless node: the node's equation decides its position at the zero step (lever rule).
    using M = algebraic_start_model;
    M md;
    const dof n = ast_displaced_series(md)[1];
    md.add<initial_displacement>("n0", {0.5}, n);
    const run_outcome r = observed_run<simulation<M>>(md, {n}, ast_controlled(0.1, 1e-6));
    CAPTURE(r.log);
    CHECK(count_of(r.log, "warning: the initial displacement set by 'n0' on DOF 'n' is not kept: the DOF has "
                           "neither mass nor viscosity, so its displacement follows from its equation") == 1);
    REQUIRE(r.u0.size() == 1);
    CHECK(r.u0[0] == doctest::Approx(0.025).epsilon(1e-14));
    CHECK_FALSE(r.failed);
  }
}
