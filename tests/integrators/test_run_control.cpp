// The run driver: multi-stage runs (PRADIS: a run is a list of integration-
// program calls, each new call re-triggers NEWINT; pradis-methods.md sections
// 3 and 4), the NEW/OLD state vector committed on accepted steps only (element
// developer's manual, section 3.3: "NEW = OLD + ..., never X = X + dX"), output
// sampling at OUT, run statistics, and element-recommended steps (STEPMD,
// ignored with IGNORE).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::newint_counter;
using pradis_test::one_time_rejector;
using pradis_test::step_recommender;
using pradis_test::tight_newton;
using pradis_test::velocity_integrator;

namespace {

// velocity_integrator is listed before one_time_rejector: within one evaluation
// it writes NEW before the rejector throws.
using run_model = model<point_mass, linear_spring, linear_damper, initial_displacement, velocity_source,
                        newint_counter, velocity_integrator, one_time_rejector, step_recommender>;

/// Damped oscillator (m = 1, k = 4 pi^2, c = 0.3, u0 = 1) with a NEWINT counter
/// and a velocity integrator on its DOF.
struct oscillator_scene {
  run_model m;
  dof x;
  element_ref<newint_counter> counter;
  element_ref<velocity_integrator> integ;
  oscillator_scene() {
    x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("spring", {4.0 * std::numbers::pi * std::numbers::pi}, x, m.ground());
    m.add<linear_damper>("damper", {0.3}, x, m.ground());
    m.add<initial_displacement>("x0", {1.0}, x);
    counter = m.add<newint_counter>("counter", {}, x);
    integ = m.add<velocity_integrator>("integral", {}, x);
  }
  double integral() { return m.old_state_pool()[m.instance(integ).state_offset]; }
};

run_options stage(double end, double smax = 0.01, double out = 0.0) {
  run_options o;
  o.end = end;
  o.smax = smax;
  o.out = out;
  o.newton = tight_newton(1e-10, 1e-12);
  return o;
}

}  // namespace

TEST_CASE("multi-stage run: END=1 then END=1.5 equals one run to 1.5; NEWINT once per stage") {
  oscillator_scene a, b;
  simulation sa(a.m, stoermer{}), sb(b.m, stoermer{});

  const run_statistics s1 = sa.run(stage(1.0));
  CHECK(sa.time() == 1.0);
  CHECK(a.m.element(a.counter).newint_calls == 1);
  CHECK(a.m.element(a.counter).newint_time == 0.0);
  const run_statistics s2 = sa.run(stage(1.5));
  CHECK(a.m.element(a.counter).newint_calls == 2);
  CHECK(a.m.element(a.counter).newint_time == 1.0);  // NEWINT at the start of the second stage
  const run_statistics sb1 = sb.run(stage(1.5));
  CHECK(b.m.element(b.counter).newint_calls == 1);

  // Same steps: 100 + 50 against 150 (h = SMAX = 0.01, no step control).
  CHECK(s1.steps == 100);
  CHECK(s2.steps == 50);
  CHECK(sb1.steps == 150);
  CHECK(sa.statistics().steps == 150);
  // Same result: the stage boundary only changes the time grid by roundoff
  // (t is set to END exactly after stage 1), so the states agree to ~1e-14.
  CHECK(sa.time() == 1.5);
  CHECK(sb.time() == 1.5);
  CHECK(std::abs(sa.u(a.x) - sb.u(b.x)) < 1e-12);
  CHECK(std::abs(sa.v(a.x) - sb.v(b.x)) < 1e-11);
  CHECK(std::abs(sa.a(a.x) - sb.a(b.x)) < 1e-10);
  CHECK(std::abs(a.integral() - b.integral()) < 1e-12);
  // The state vector persists across stages: the commit hook ran once per
  // accepted step plus once at the zero step.
  CHECK(a.m.element(a.counter).commits == 151);

  // Newmark with the velocity unknown and the trapezoidal relation
  // u_n = u_{n-1} + h (v_{n-1} + v_n) / 2 (true for gamma = 1/2 and for Stoermer):
  // the integral S = sum h v_n kept in the state vector equals
  // u_N - u_0 + h (v_N - v_0) / 2 exactly for a uniform step h.
  CHECK(b.integral() == doctest::Approx(sb.u(b.x) - 1.0 + 0.01 * (sb.v(b.x) - 0.0) / 2.0).epsilon(1e-12));
}

TEST_CASE("state vector: NEW is committed to OLD on accepted steps only") {
  // DOF 'drive' follows VSRC v(t) = 1 + 0.5 sin(2 pi t), u(t) = t + 0.5 (1 - cos(2 pi t)) / (2 pi).
  // VINT integrates v over the accepted steps: S = sum h_i v(t_i), NEW = OLD + h v.
  // REJECT1 throws a singular situation (code 75) on the first attempt of the
  // first step ending after t = 0.5, after VINT has written NEW for that attempt.
  run_model m;
  const dof drive = m.add_dof("drive"), x = m.add_dof("x");
  m.add<velocity_source>("vsrc", {0.5, 1.0, 0.0, 1.0}, drive);
  m.add<linear_spring>("spring", {100.0}, drive, x);
  m.add<point_mass>("mass", {1.0}, x);
  const auto integ = m.add<velocity_integrator>("integral", {}, drive);
  const auto rej = m.add<one_time_rejector>("rejector", {0.5}, x);
  simulation sim(m, newmark{});
  std::vector<double> t;
  sim.on_output([&](const auto& s) { t.push_back(s.time()); });
  const auto st = sim.run(stage(1.5));

  CHECK(st.rejected_steps == 1);
  CHECK(m.work(rej)[0] == 1.0);
  CHECK(static_cast<std::size_t>(st.steps) + 1 == t.size());
  // The step was cut: some accepted steps are shorter than SMAX.
  double hmin = 1;
  for (std::size_t i = 1; i < t.size(); ++i) hmin = std::min(hmin, t[i] - t[i - 1]);
  CHECK(hmin == doctest::Approx(0.005).epsilon(1e-9));

  const auto v = [](double s) { return 1.0 + 0.5 * std::sin(2.0 * std::numbers::pi * s); };
  double riemann = 0;
  for (std::size_t i = 1; i < t.size(); ++i) riemann += (t[i] - t[i - 1]) * v(t[i]);
  const double s_state = m.old_state_pool()[m.instance(integ).state_offset];
  // Exactly the right-endpoint sum over the accepted steps (a commit of the
  // rejected attempt would add ~0.005 * 1.0).
  CHECK(s_state == doctest::Approx(riemann).epsilon(1e-13));
  // Against the analytic integral u(1.5): the right-endpoint rule errs by
  // sum h_i^2 v'(xi_i) / 2, at most (h_max / 2) T max|v'| = 0.005 * 1.5 * pi.
  const double u_end = 1.5 + 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * 1.5)) / (2.0 * std::numbers::pi);
  CHECK(sim.u(drive) == doctest::Approx(u_end).epsilon(1e-14));
  CHECK(std::abs(s_state - u_end) <= 0.005 * 1.5 * std::numbers::pi);
}

TEST_CASE("output sampling at OUT: observer at t0 and exactly at t_start + k OUT") {
  oscillator_scene sc;
  simulation sim(sc.m, newmark{});
  std::vector<double> t;
  sim.on_output([&](const auto& s) { t.push_back(s.time()); });

  // OUT = 0.025 is not a multiple of SMAX = 0.01: steps are clipped to hit it.
  sim.run(stage(1.0, 0.01, 0.025));
  REQUIRE(t.size() == 41);
  CHECK(t[0] == 0.0);
  for (std::size_t k = 1; k < t.size(); ++k) {
    CAPTURE(k);
    CHECK(t[k] == static_cast<double>(k) * 0.025);  // exact, no drift
  }
  // Second stage: sampling restarts from the stage's start time.
  t.clear();
  sim.run(stage(1.5, 0.01, 0.1));
  REQUIRE(t.size() == 5);
  for (std::size_t k = 0; k < t.size(); ++k) {
    CAPTURE(k);
    CHECK(t[k] == 1.0 + static_cast<double>(k + 1) * 0.1);
    CHECK(t[k] == doctest::Approx(1.0 + 0.1 * static_cast<double>(k + 1)).epsilon(1e-15));
  }
  // OUT = 0: after every accepted step.
  t.clear();
  const auto st = sim.run(stage(1.6, 0.01, 0.0));
  CHECK(static_cast<long>(t.size()) == st.steps);
  CHECK(st.steps == 10);
}

TEST_CASE("on_step: called once per accepted step, with the step's time and statistics") {
  oscillator_scene sc;
  simulation sim(sc.m, newmark{});
  std::vector<double> t, h;
  long outputs = 0;
  sim.on_step([&](const auto& s) {
    t.push_back(s.time());
    h.push_back(s.statistics().last_step);
  });
  sim.on_output([&](const auto&) { ++outputs; });
  // OUT = 0.1 with SMAX = 0.01: ten steps per output, so steps and outputs differ.
  const auto st = sim.run(stage(1.0, 0.01, 0.1));
  REQUIRE(static_cast<long>(t.size()) == st.steps);
  CHECK(outputs == 11);  // t0 and ten output times
  double sum = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    CAPTURE(k);
    if (k > 0) CHECK(t[k] > t[k - 1]);
    sum += h[k];
    CHECK(t[k] == doctest::Approx(sum).epsilon(1e-12));  // time advances by the reported step
  }
  CHECK(t.back() == 1.0);
}

TEST_CASE("run statistics and statistic() by output-variable name") {
  oscillator_scene sc;
  simulation sim(sc.m, newmark{});
  const run_statistics s1 = sim.run(stage(0.5));
  CHECK(s1.steps == 50);
  CHECK(s1.rejected_steps == 0);
  CHECK(s1.newton_iterations >= s1.steps);  // at least one correction per step
  CHECK(s1.factorizations >= s1.newton_iterations);  // full Newton (the default): one per iteration
  CHECK(s1.jacobian_evaluations <= s1.evaluations);
  CHECK(s1.evaluations > s1.steps);
  CHECK(s1.last_step == doctest::Approx(0.01).epsilon(1e-9));
  const run_statistics s2 = sim.run(stage(0.8));
  CHECK(s2.steps == 30);
  const run_statistics& all = sim.statistics();
  CHECK(all.steps == 80);
  CHECK(all.newton_iterations == s1.newton_iterations + s2.newton_iterations);
  CHECK(sim.statistic("NSTEP") == 80.0);
  CHECK(sim.statistic("NITTOT") == static_cast<double>(all.newton_iterations));
  CHECK(sim.statistic("NFACT") == static_cast<double>(all.factorizations));
  CHECK(sim.statistic("NJAC") == static_cast<double>(all.jacobian_evaluations));
  CHECK(sim.statistic("NEVAL") == static_cast<double>(all.evaluations));
  CHECK(sim.statistic("NREJ") == 0.0);
  CHECK(sim.statistic("NITER") >= 1.0);
  CHECK(sim.statistic("NITER") <= 12.0);
  CHECK(sim.statistic("STEP") == doctest::Approx(0.01).epsilon(1e-9));
  try {
    (void)sim.statistic("NSTEPS");
    FAIL("unknown statistic accepted");
  } catch (const error& e) {
    CHECK(e.code() == error_code::invalid_option);
    CHECK(e.message().find("NSTEPS") != std::string::npos);
  }
}

TEST_CASE("STEPMD: an element's recommended step bounds every step unless IGNORE") {
  // The element recommends 1e-3 at every call, the zero step included; SMAX = 1e-2.
  struct result {
    std::vector<double> h1, h2;  // steps of stage 1 (to 0.1) and stage 2 (to 0.2)
  };
  auto steps_with = [](bool ignore) {
    run_model m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("spring", {10.0}, x, m.ground());
    m.add<initial_displacement>("x0", {1.0}, x);
    m.add<step_recommender>("stepmd", {1e-3}, x);
    simulation sim(m, newmark{});
    std::vector<double> t;
    sim.on_output([&](const auto& s) { t.push_back(s.time()); });
    run_options o = stage(0.1, 1e-2);
    o.ignore = ignore;
    result r;
    sim.run(o);
    for (std::size_t i = 1; i < t.size(); ++i) r.h1.push_back(t[i] - t[i - 1]);
    const double t1 = t.back();
    t.assign(1, t1);
    o.end = 0.2;
    sim.run(o);
    for (std::size_t i = 1; i < t.size(); ++i) r.h2.push_back(t[i] - t[i - 1]);
    return r;
  };
  auto largest = [](const std::vector<double>& h, std::size_t from) {
    double m = 0;
    for (std::size_t i = from; i < h.size(); ++i) m = std::max(m, h[i]);
    return m;
  };
  SUBCASE("recommendation honoured") {
    const auto r = steps_with(false);
    REQUIRE(r.h1.size() >= 2);
    REQUIRE(r.h2.size() >= 2);
    INFO("first step of stage 1: " << r.h1[0] << ", of stage 2: " << r.h2[0] << "; steps " << r.h1.size() << " + "
                                   << r.h2.size());
    CHECK(largest(r.h1, 1) <= 1e-3 * (1 + 1e-9));
    CHECK(largest(r.h2, 1) <= 1e-3 * (1 + 1e-9));
    // The first step of a stage must honour the recommendation too (made at the
    // zero step, resp. at the last step of the previous stage).
    CHECK(r.h1[0] <= 1e-3 * (1 + 1e-9));
    CHECK(r.h2[0] <= 1e-3 * (1 + 1e-9));
  }
  SUBCASE("IGNORE") {
    const auto r = steps_with(true);
    REQUIRE(r.h1.size() == 10);
    REQUIRE(r.h2.size() == 10);
    for (double hi : r.h1) CHECK(hi == doctest::Approx(1e-2).epsilon(1e-9));
    for (double hi : r.h2) CHECK(hi == doctest::Approx(1e-2).epsilon(1e-9));
  }
}
