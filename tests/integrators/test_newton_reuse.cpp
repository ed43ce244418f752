// Modified Newton (newton_method::modified, the default): the Jacobian and its
// factorisation are reused across iterations and steps and refreshed on slow
// convergence, on a change of the step's Jacobian coefficients, at each stage,
// and before a failed step is cut (SUNDIALS IDA's strategy: Hindmarsh et al.,
// ACM TOMS 31 (2005) 363, section 2.1). Invariants checked: both methods solve
// the same step equations, so their results agree to the Newton tolerance; on a
// linear model at a constant step one factorisation serves the whole stage;
// iterations that reuse the factorisation evaluate the flows only.

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/integrators/statistics_io.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::tight_newton;

namespace {
/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using newton_reuse_model = pradis::model<point_mass, linear_spring, linear_damper, initial_displacement, planar_inertia,
    planar_link, constant_force, sine_force>;

void build_linear(newton_reuse_model& m) {
  const auto d = m.add_dofs(2, "x");
  m.add<point_mass>("m1", {1.0}, d[0]);
  m.add<point_mass>("m2", {0.5}, d[1]);
  m.add<linear_spring>("k1", {400.0}, d[0], m.ground());
  m.add<linear_spring>("k2", {300.0}, d[0], d[1]);
  m.add<linear_damper>("c1", {0.2}, d[1], m.ground());
  m.add<initial_displacement>("x0", {0.1}, d[0]);
}
/// Two planar bodies joined by a stiff link (LINKD), pulled and shaken: a
/// nonlinear model (the link's direction turns).
void build_two_bodies(newton_reuse_model& m) {
  const auto d = m.add_dofs(6, "DOF ");
  m.add<planar_inertia>("Body 1", {.m = 1.0, .j = 0.1}, d[0], d[1], d[2]);
  m.add<planar_inertia>("Body 2", {.m = 2.0, .j = 0.1}, d[3], d[4], d[5]);
  m.add<planar_link>("Connection", {1, 1, 2, 2, 5e3}, d[0], d[1], d[3], d[4]);
  m.add<constant_force>("Force", {.force = -1e3}, d[4]);
  m.add<sine_force>("Shake", {.amplitude = 50, .frequency = 3, .phase_deg = 0, .offset = 0}, d[3]);
}
run_options options(double end, newton_method method, double h = 1e-3) {
  run_options o{.end = end, .smax = h, .newton = tight_newton(1e-7)};
  o.newton.method = method;
  return o;
}
}  // namespace

TEST_SUITE("integrators/modified Newton") {
  TEST_CASE("on a linear model at a constant step one factorisation serves the whole stage") {
    newton_reuse_model a, b;
    build_linear(a);
    build_linear(b);
    simulation sa(a, newmark{}), sb(b, newmark{});
    const run_statistics mod = sa.run(options(0.5, newton_method::modified));
    const run_statistics full = sb.run(options(0.5, newton_method::full));
    CHECK(mod.steps == 500);
    // The zero step's initial-derivative matrix, then one Newton matrix for the stage.
    CHECK(mod.factorizations == 2);
    CHECK(full.factorizations == full.newton_iterations + 1);
    // Jacobian evaluations: the zero step's two (M and C) and one in the stage;
    // every other evaluation assembles flows only.
    CHECK(mod.jacobian_evaluations == 3);
    CHECK(mod.evaluations > 1000);
    CHECK(sa.statistic("NJAC") == 3.0);
    // Same step equations, both solved to the Newton tolerance.
    for (int d = 1; d <= 2; ++d) {
      CHECK(sa.state().u(d) == doctest::Approx(sb.state().u(d)).epsilon(1e-9));
      CHECK(sa.state().v(d) == doctest::Approx(sb.state().v(d)).epsilon(1e-9));
    }
    // A new stage starts with a fresh Jacobian.
    const run_statistics second = sa.run(options(0.6, newton_method::modified));
    CHECK(second.factorizations == 1);
    // statistics_io prints the new key.
    std::ostringstream os;
    os << sa.statistics();
    CHECK(os.str().find("NJAC=4 ") != std::string::npos);
  }

  TEST_CASE("on a nonlinear model modified Newton agrees with full Newton and factorises far less") {
    newton_reuse_model a, b;
    build_two_bodies(a);
    build_two_bodies(b);
    simulation sa(a, generalized_alpha(0.8)), sb(b, generalized_alpha(0.8));
    const run_statistics mod = sa.run(options(0.3, newton_method::modified));
    const run_statistics full = sb.run(options(0.3, newton_method::full));
    CHECK(mod.steps == full.steps);
    CHECK(mod.rejected_steps == 0);
    CHECK(mod.factorizations * 4 < full.factorizations);
    CHECK(mod.jacobian_evaluations < mod.evaluations / 2);
    // Link force 1e3 N, stiffness 5e3 N/m: the Newton tolerances (1e-7 N,
    // 1e-11 m/s) bound the difference far below the motion (metres).
    double worst = 0;
    for (int d = 1; d < a.dof_count(); ++d) worst = std::max(worst, std::abs(sa.state().u(d) - sb.state().u(d)));
    CHECK(worst < 1e-8);
  }

  TEST_CASE("a step that fails with a kept Jacobian is retried with a fresh one before it is cut") {
    // OUT = 0.035 with SMAX = 0.01: steps 0.01, 0.01, then two of 0.0075 (the
    // coefficients change by 4/3, inside IDA's [0.6, 1/0.6]: the Jacobian is
    // kept). The correction test needs a second, vanishing correction; with
    // ITR = 2 the stale Jacobian's second correction is not small enough on this
    // linear model, the fresh one's is (its first correction solves it exactly).
    newton_reuse_model a, b;
    build_linear(a);
    build_linear(b);
    simulation sa(a, newmark{}), sb(b, newmark{});
    run_options o = options(0.07, newton_method::modified, 0.01);
    o.out = 0.035;
    o.newton.itr = 2;
    const run_statistics mod = sa.run(o);
    o.newton.method = newton_method::full;
    sb.run(o);
    CHECK(mod.jacobian_retries >= 1);
    CHECK(mod.rejected_steps == 0);  // no step was cut
    CHECK(sa.time() == 0.07);
    for (int d = 1; d <= 2; ++d) CHECK(sa.state().u(d) == doctest::Approx(sb.state().u(d)).epsilon(1e-12));
  }

  TEST_CASE("a change of the step beyond the coefficient ratio refreshes the Jacobian") {
    // Error control changes the step often; each change beyond [0.6, 1/0.6]
    // of ca costs a factorisation, smaller ones none.
    newton_reuse_model a;
    build_linear(a);
    simulation sa(a, newmark{});
    run_options o = options(0.5, newton_method::modified, 0.05);
    o.error_control = true;
    o.dabsx = o.drltx = 1e-5;
    const run_statistics st = sa.run(o);
    CHECK(st.factorizations > 2);
    CHECK(st.factorizations < st.steps + st.rejected_steps);
    // coefficient_change = 0: every change of the step refreshes (full Newton's count of refreshes per step at most).
    newton_reuse_model b;
    build_linear(b);
    simulation sb(b, newmark{});
    o.newton.coefficient_change = 0;
    const run_statistics strict = sb.run(o);
    CHECK(strict.factorizations >= st.factorizations);
  }

  TEST_CASE("bad modified-Newton options are refused") {
    newton_reuse_model a;
    build_linear(a);
    simulation sa(a, newmark{});
    run_options o = options(0.1, newton_method::modified);
    o.newton.max_rate = 1.0;
    CHECK_THROWS_WITH_AS(sa.run(o), doctest::Contains("rate limit"), error);
    o.newton.max_rate = 0.9;
    o.newton.coefficient_change = -1;
    CHECK_THROWS_WITH_AS(sa.run(o), doctest::Contains("coefficient change"), error);
  }
}
