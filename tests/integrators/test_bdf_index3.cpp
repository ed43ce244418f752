// The BDF driver (pradis::bdf_simulation, docs/bdf.md) on index-3 models: point masses
// joined by the exact rigid link LINKX (a position constraint with its force as a
// Lagrange multiplier). By default the driver meets the velocity constraint G v = 0
// with the position constraint (the stabilised index-2 form) and tests the velocities
// like any other. In the plain index-3 form the velocities of the constrained DOFs are
// index-2 components: their tolerances are divided by the step in the Newton and error
// tests, as RADAU5 does (Hairer and Wanner, Solving ODEs II, 2nd ed. 1996, section
// VII.8; radau5.f, routine RADCOR). Without that scaling the error test rejected small
// steps as much as large ones (the velocity of the incoming state is projected onto the
// hidden constraint by any step) and tight tolerances drove the step to SMIN.
//  * the planar pendulum of length L released from the horizontal at rest: a quarter
//    of its period is T/4 = sqrt(L / g) K(sin(45 deg)), K the complete elliptic integral
//    of the first kind (Landau and Lifshitz, Mechanics, section 11, problem 1; amplitude
//    90 degrees); at T/4 the mass passes the lowest point (0, -L) with the speed
//    sqrt(2 g L) (energy). Invariants along the run: |r| = L and the energy
//    m |v|^2 / 2 + m g y = 0;
//  * a chain of three links released from the horizontal: the total energy stays zero
//    and every link keeps its length;
//  * the stabilised index-2 form (the default, bdf_options::stabilised_index2; Gear,
//    Gupta and Leimkuhler, J. Comput. Appl. Math. 12-13 (1985) 77-90) against the plain
//    index-3 form on the pendulum: the hidden constraint r . v = 0 and the accuracy;
//  * the stabilised form with three linear solvers (sparse_lu's unchecked solves, a
//    solver with only the two-right-hand-side solve, a user's plain solve()): the same
//    lowest point at T/4;
//  * a pendulum hung from a point driven at constant velocity: by Galilean invariance
//    it moves relative to the hinge as the fixed one; the driver keeps the plain form
//    there (a note in its log);
//  * LINKX's direction state is a guard (GuardStateElement): the driver commits it from
//    the last Newton evaluation of a step, with the same run as when a state of another
//    kind makes it evaluate the converged state.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "dense_test_solver.hpp"
#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using bdf_index3_model = pradis::model<point_mass, planar_rigid_link, constant_force, velocity_source,
    pradis_test::velocity_integrator>;
constexpr double bdf3_g = 9.81;

/// A chain of n links of length l, point masses m at the joints, hinged at the origin and
/// released from rest along +X; x[i], y[i] the displacements of mass i from (l (i + 1), 0).
struct bdf3_chain {
  bdf_index3_model m;
  std::vector<dof> x, y;
  double l, mass;
  bdf3_chain(int n, double l_, double m_) : l(l_), mass(m_) {
    for (int i = 0; i < n; ++i) {
      const std::string k = std::to_string(i + 1);
      x.push_back(m.add_dof("x" + k));
      y.push_back(m.add_dof("y" + k));
      m.add<point_mass>("mx" + k, {mass}, x.back());
      m.add<point_mass>("my" + k, {mass}, y.back());
      m.add<constant_force>("w" + k, {-mass * bdf3_g}, y.back());
      const dof ax = i == 0 ? m.ground() : x[x.size() - 2], ay = i == 0 ? m.ground() : y[y.size() - 2];
      m.add<planar_rigid_link>("link" + k, {i * l, 0.0, (i + 1) * l, 0.0}, ax, ay, x.back(), y.back());
    }
  }
  /// The largest |length - l| over the links and the energy (kinetic plus potential,
  /// zero at the start) of the state of sim.
  template <class Sim>
  std::pair<double, double> invariants(const Sim& sim) const {
    double gap = 0, energy = 0, px = 0, py = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double qx = static_cast<double>(i + 1) * l + sim.u(x[i]), qy = sim.u(y[i]);
      gap = std::max(gap, std::abs(std::hypot(qx - px, qy - py) - l));
      energy += 0.5 * mass * (sim.v(x[i]) * sim.v(x[i]) + sim.v(y[i]) * sim.v(y[i])) + mass * bdf3_g * qy;
      px = qx;
      py = qy;
    }
    return {gap, energy};
  }
};

run_options bdf3_options(double end, double tol) {
  run_options o;
  o.end = end;
  o.smax = end / 20;
  o.smin = 1e-12;
  o.error_control = true;
  o.drltx = tol;  // DABSX defaults to DRLTX
  return o;
}

/// A BDF run of the chain with error control at `tol` up to `end`: its statistics
/// and the worst link gap and energy error (|energy|, zero at the start) over its steps.
struct bdf3_run {
  run_statistics st;
  double worst_gap = 0, worst_energy = 0;
};
template <class Sim>
bdf3_run bdf3_tracked(bdf3_chain& c, Sim& sim, double end, double tol) {
  bdf3_run r;
  sim.on_step([&](const auto& s) {
    const auto [gap, energy] = c.invariants(s);
    r.worst_gap = std::max(r.worst_gap, gap);
    r.worst_energy = std::max(r.worst_energy, std::abs(energy));
  });
  REQUIRE_NOTHROW(r.st = sim.run(bdf3_options(end, tol)));
  return r;
}

/// A user's dense LU with a plain solve() only (no two-right-hand-side or unchecked
/// solve): the BDF corrector falls back to two solve() calls per iteration.
using dense_solve_only = pradis_test::dense_test_solver<Eigen::FullPivLU<Eigen::MatrixXd>>;

/// sparse_lu with its two-right-hand-side solve but without solve_unchecked (the
/// corrector's middle fallback), counting the unchecked solves it never gets.
struct checked_sparse_lu : linalg::sparse_lu<linalg::automatic_ordering> {
  void solve(std::span<double> b) const { sparse_lu::solve(b); }
  void solve(std::span<double> b1, std::span<double> b2) const {
    sparse_lu::solve(b1, b2);
    ++pairs;
  }
  void solve_unchecked(std::span<double>) const = delete;
  void solve_unchecked(std::span<double>, std::span<double>) const = delete;
  mutable long pairs = 0;
};

}  // namespace

TEST_SUITE("integrators/bdf index 3") {
  TEST_CASE("the stabilised form runs with any linear solver: sparse_lu's unchecked solves, its checked pair "
            "solve, or a user's plain solve(), to the same pendulum at T/4") {
    // The pendulum of the cases below at DRLTX = 1e-7 to T/4 (the lowest point, exact
    // from the elliptic integral). The three solvers differ in rounding only.
    const double quarter = std::sqrt(1.0 / bdf3_g) * std::comp_ellint_1(std::sqrt(0.5));
    const double vbottom = std::sqrt(2 * bdf3_g);
    struct result {
      double x, y, vx, vy;
      long steps;
    };
    auto run = [&]<class Solver>(Solver*) {
      bdf3_chain c(1, 1.0, 1.0);
      bdf_simulation<bdf_index3_model, Solver> sim(c.m);
      const run_statistics st = sim.run(bdf3_options(quarter, 1e-7));
      if constexpr (std::is_same_v<Solver, dense_solve_only>) CHECK(sim.solver().solves > 2 * st.newton_iterations - 1);
      if constexpr (std::is_same_v<Solver, checked_sparse_lu>) CHECK(sim.solver().pairs >= st.newton_iterations);
      if constexpr (std::is_same_v<Solver, linalg::sparse_lu<linalg::automatic_ordering>>)
        CHECK(sim.solver().statistics().last_backward_error == -1.0);  // the corrector's last solve: unchecked
      return result{sim.u(c.x[0]), sim.u(c.y[0]), sim.v(c.x[0]), sim.v(c.y[0]), st.steps};
    };
    const result a = run(static_cast<linalg::sparse_lu<linalg::automatic_ordering>*>(nullptr));
    const result b = run(static_cast<checked_sparse_lu*>(nullptr));
    const result d = run(static_cast<dense_solve_only*>(nullptr));
    for (const result& r : {a, b, d}) {
      // The bound of the stabilised case below: steps times DRLTX (measured there 7.2e-8 L, 4.6e-7).
      const double bound = static_cast<double>(r.steps) * 1e-7;
      CHECK(std::max(std::abs(1.0 + r.x), std::abs(r.y + 1.0)) < bound);
      CHECK(std::max(std::abs(r.vx + vbottom), std::abs(r.vy)) / vbottom < bound);
      CHECK(std::abs(r.x - a.x) < 1e-6);
      CHECK(std::abs(r.vx - a.vx) < 1e-5);
    }
  }

  TEST_CASE("the plain index-3 form: an exact rigid pendulum (LINKX) at DRLTX = 1e-7, the lowest point at T/4, "
            "length and energy kept") {
    bdf3_chain c(1, 1.0, 1.0);
    bdf_simulation sim(c.m, bdf_options{.stabilised_index2 = false});
    const double quarter = std::sqrt(c.l / bdf3_g) * std::comp_ellint_1(std::sqrt(0.5));
    // Before the index-2 scaling this run failed at SMIN (step_too_small) after about
    // 1,000 rejected steps.
    const auto [st, worst_gap, worst_energy] = bdf3_tracked(c, sim, quarter, 1e-7);
    // Measured: 125 steps, 4 rejected.
    CHECK(st.steps < 1000);
    CHECK(st.rejected_steps < st.steps / 10);
    // At the lowest point (x = 0, y = -L, v = (-sqrt(2 g L), 0)). Measured: position
    // 7.6e-6 L, velocity 2.7e-5 of the speed: the velocities of the constrained DOFs
    // are tested against DRLTX / h, so the motion is a hundred times DRLTX off or more.
    const double vbottom = std::sqrt(2 * bdf3_g * c.l);
    MESSAGE("plain form: " << st.steps << " steps, " << st.rejected_steps << " rejected; position "
                           << std::max(std::abs(c.l + sim.u(c.x[0])), std::abs(sim.u(c.y[0]) + c.l)) / c.l
                           << " L, velocity "
                           << std::max(std::abs(sim.v(c.x[0]) + vbottom), std::abs(sim.v(c.y[0]))) / vbottom
                           << "; gap " << worst_gap << ", energy " << worst_energy);
    CHECK(std::abs(c.l + sim.u(c.x[0])) < 2e-4 * c.l);
    CHECK(std::abs(sim.u(c.y[0]) + c.l) < 2e-4 * c.l);
    CHECK(std::abs(sim.v(c.x[0]) + vbottom) < 2e-4 * vbottom);
    CHECK(std::abs(sim.v(c.y[0])) < 2e-4 * vbottom);
    // The link is met to the Newton tolerance (measured 5.4e-8 L); the energy, zero
    // at the start, stays within 5.6e-5 m g L (measured).
    CHECK(worst_gap < 1e-6 * c.l);
    CHECK(worst_energy < 5e-4 * c.mass * bdf3_g * c.l);
    // Index-3 constraints: the kept matrix is not formed again from kept blocks
    // (bdf_options::reform_jacobian does not apply, docs/bdf.md "Newton").
    CHECK_FALSE(sim.get_assembler().keeps_blocks());
    CHECK(st.jacobian_evaluations >= st.factorizations);
  }

  TEST_CASE("the stabilised index-2 form meets the hidden constraint r . v = 0 and follows DRLTX; the plain "
            "index-3 form does neither") {
    // The pendulum of the first case to T/4 at DRLTX = 1e-7, both forms. The velocity
    // constraint of |r| = L is r . v = 0 (Gear, Gupta and Leimkuhler 1985).
    struct outcome {
      run_statistics st;
      double pos = 0, vel = 0, hidden = 0;
    };
    const double quarter = std::sqrt(1.0 / bdf3_g) * std::comp_ellint_1(std::sqrt(0.5));
    const double vbottom = std::sqrt(2 * bdf3_g);
    auto run = [&](bool stabilised) {
      bdf3_chain c(1, 1.0, 1.0);
      bdf_simulation sim(c.m, bdf_options{.stabilised_index2 = stabilised});
      outcome o;
      sim.on_step([&](const auto& s) {
        const double rx = 1.0 + s.u(c.x[0]), ry = s.u(c.y[0]);
        o.hidden = std::max(o.hidden, std::abs(rx * s.v(c.x[0]) + ry * s.v(c.y[0])) / vbottom);
      });
      o.st = sim.run(bdf3_options(quarter, 1e-7));
      o.pos = std::max(std::abs(1.0 + sim.u(c.x[0])), std::abs(sim.u(c.y[0]) + 1.0));
      o.vel = std::max(std::abs(sim.v(c.x[0]) + vbottom), std::abs(sim.v(c.y[0]))) / vbottom;
      return o;
    };
    const outcome g = run(true), p = run(false);
    MESSAGE("stabilised: " << g.st.steps << " steps, position error " << g.pos << ", velocity " << g.vel
                           << ", |r . v| / (L v) " << g.hidden << "; plain index 3: " << p.st.steps << " steps, "
                           << p.pos << ", " << p.vel << ", " << p.hidden);
    // Local error control bounds the global error by about the sum of the local errors,
    // steps times DRLTX (docs/bdf.md). Measured: 124 steps, position 7.2e-8 L, velocity
    // 4.6e-7; the plain form: 125 steps, 7.6e-6 and 2.7e-5, above that bound.
    const double bound = static_cast<double>(g.st.steps) * 1e-7;
    CHECK(g.pos < bound);
    CHECK(g.vel < bound);
    // G v = 0 is met to the Newton tolerance, a fraction of DRLTX (measured 6.3e-8; the
    // plain form 1.4e-5).
    CHECK(g.hidden < 1e-7);
    CHECK(p.hidden > 100 * g.hidden);
    CHECK(std::max(p.pos, p.vel) > 10 * std::max(g.pos, g.vel));
  }

  TEST_CASE("a constraint on a driven DOF keeps the plain index-3 form, says so, and stays exact: a pendulum hung "
            "from a point moving at constant velocity (Galilean invariance)") {
    // The hinge moves along X at V = 0.7 m/s (VSRC); relative to it the pendulum moves as
    // the fixed one: at T/4 the mass is at (-L, ... ) below the hinge, i.e. at (V T/4, -L),
    // with velocity (V - sqrt(2 g L), 0).
    bdf_index3_model m;
    const dof hx = m.add_dof("hx"), x = m.add_dof("x"), y = m.add_dof("y");
    constexpr double speed = 0.7;
    m.add<velocity_source>("drive", {0.0, 0.0, 0.0, speed}, hx);
    m.add<point_mass>("mx", {1.0}, x);
    m.add<point_mass>("my", {1.0}, y);
    m.add<constant_force>("w", {-bdf3_g}, y);
    m.add<planar_rigid_link>("link", {0.0, 0.0, 1.0, 0.0}, hx, m.ground(), x, y);
    bdf_simulation sim(m);
    std::ostringstream log;
    sim.log().to(log);
    const double quarter = std::sqrt(1.0 / bdf3_g) * std::comp_ellint_1(std::sqrt(0.5));
    const double vbottom = std::sqrt(2 * bdf3_g);
    sim.run(bdf3_options(quarter, 1e-7));
    CHECK(log.str().find("note: the index-3 constraint 'link' acts on the driven DOF 'hx'") != std::string::npos);
    CHECK(log.str().find("in the plain index-3 form") != std::string::npos);
    // The plain form's accuracy at DRLTX = 1e-7 (the first case: 2e-4).
    CHECK(std::abs(sim.u(x) + 1.0 - speed * quarter) < 2e-4);
    CHECK(std::abs(sim.u(y) + 1.0) < 2e-4);
    CHECK(std::abs(sim.v(x) - speed + vbottom) < 2e-4 * vbottom);
    CHECK(std::abs(sim.v(y)) < 2e-4 * vbottom);
  }

  TEST_CASE("a chain of three exact links (LINKX) at DRLTX = 1e-7 and 1e-9: lengths and energy kept") {
    for (const double tol : {1e-7, 1e-9}) {
      CAPTURE(tol);
      bdf3_chain c(3, 1.0 / 3, 0.5 / 3);
      bdf_simulation sim(c.m);
      const auto [st, worst_gap, worst_energy] = bdf3_tracked(c, sim, 0.5, tol);
      MESSAGE("DRLTX " << tol << ": " << st.steps << " steps, " << st.rejected_steps << " rejected, gap " << worst_gap
                       << " m, energy error " << worst_energy << " J");
      // Measured (the stabilised form, the default): 266 steps, 0 rejected at 1e-7; 569
      // and 6 at 1e-9 (the plain index-3 form: 220 and 3; 480 and 2).
      CHECK(st.rejected_steps < st.steps / 10);
      // Gaps: measured 2.6e-10 and 1.5e-12 m (the plain form: 2.0e-7 and 1.1e-9); energy
      // error 1.5e-6 and 2.1e-8 J (plain: 3.8e-4 and 1.4e-5) against M g L = 4.9 J (M =
      // 0.5 kg, L = 1 m): a few times DRLTX.
      CHECK(worst_gap < 10 * tol);
      CHECK(worst_energy < 20 * tol * 0.5 * bdf3_g);
    }
  }

  TEST_CASE("LINKX's guard state needs no evaluation at the converged state: the same run with one fewer "
            "evaluation per step") {
    // Invariant: LINKX's flows do not read its state (the all-elements test checks the claim),
    // so committing it from the last Newton evaluation of a step, instead of from one more
    // evaluation at the converged state, must leave the run unchanged. The second model adds
    // a state-carrying element without flows (VINT, not a guard), which makes the driver
    // evaluate the converged state after every accepted step.
    using vint_model = bdf_index3_model;
    struct chain {
      vint_model m;
      std::vector<dof> d;
      element_ref<planar_rigid_link> first;
      chain(bool vint) {
        const double l = 1.0 / 3, mass = 0.5 / 3;
        for (int i = 0; i < 3; ++i) {
          const std::string k = std::to_string(i + 1);
          const dof x = m.add_dof("x" + k), y = m.add_dof("y" + k);
          m.add<point_mass>("mx" + k, {mass}, x);
          m.add<point_mass>("my" + k, {mass}, y);
          m.add<constant_force>("w" + k, {-mass * bdf3_g}, y);
          const dof ax = i == 0 ? m.ground() : d[d.size() - 2], ay = i == 0 ? m.ground() : d.back();
          const auto r = m.add<planar_rigid_link>("link" + k, {i * l, 0.0, (i + 1) * l, 0.0}, ax, ay, x, y);
          if (i == 0) first = r;
          d.push_back(x);
          d.push_back(y);
        }
        if (vint) m.add<pradis_test::velocity_integrator>("vint", {}, d[0]);
      }
    };
    chain a(false), b(true);
    bdf_simulation sa(a.m), sb(b.m);
    run_statistics ra, rb;
    REQUIRE_NOTHROW(ra = sa.run(bdf3_options(0.5, 1e-7)));
    REQUIRE_NOTHROW(rb = sb.run(bdf3_options(0.5, 1e-7)));
    CHECK(ra.steps == rb.steps);
    CHECK(ra.newton_iterations == rb.newton_iterations);
    CHECK(ra.factorizations == rb.factorizations);
    CHECK(rb.evaluations - ra.evaluations == rb.steps);
    for (std::size_t i = 0; i < a.d.size(); ++i) {
      CHECK(sa.u(a.d[i]) == sb.u(b.d[i]));
      CHECK(sa.v(a.d[i]) == sb.v(b.d[i]));
    }
    // The committed direction of the first link (from the origin to mass 1) is that of the
    // final state to within the Newton tolerance.
    const double qx = 1.0 / 3 + sa.u(a.d[0]), qy = sa.u(a.d[1]), len = std::hypot(qx, qy);
    const double* old = a.m.old_state_pool().data() + a.m.instance(a.first).state_offset;
    MESSAGE("committed direction off by " << std::hypot(old[0] - qx / len, old[1] - qy / len));
    CHECK(std::hypot(old[0] - qx / len, old[1] - qy / len) < 1e-6);
  }
}
