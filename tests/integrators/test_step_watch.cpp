// The step budget of a stage (run_options::max_steps, NSTEPMAX; error code 142)
// and the crawl warning (integrators/step_watch.hpp), in both drivers.
// Invariants: a stage stopped by its budget keeps the state it reached, so that a
// next stage continues from there exactly as one uninterrupted run of the same
// fixed steps; a stage whose step budget equals the steps it needs ends normally.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::tight_newton;

namespace {

/// Recommends the step h (STEPMD) from the time t_on on; no flow. It stands for a
/// singular state that holds the step far below the stage's steps.
struct late_step_limit {
  static constexpr pradis::passport passport{.name = "LATESTEP", .ext = 1, .par = 2, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "test: recommends a small step from a time on",
                                             .name = "Test element recommending a maximum step from t_on on",
                                             .field = "tests",
                                             .dofs = "1 - any DOF",
                                             .parameters = "1 - t_on [s]\n2 - recommended step [s]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double t_on = 0, h = 0;
  };
  parameters p;
  explicit late_step_limit(parameters q) : p(q) {}
  static late_step_limit from_parameters(std::span<const double> v) { return late_step_limit({v[0], v[1]}); }
  void evaluate(const pradis::local_input<late_step_limit>&, pradis::local_output<late_step_limit>& out,
                pradis::element_context& ctx) const {
    if (ctx.time >= p.t_on) ctx.recommend_step(p.h);
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

using watch_model = model<point_mass, linear_spring, linear_damper, initial_displacement, late_step_limit>;

/// Damped oscillator m = 1, k = 4 pi^2, c = 0.3, u(0) = 1; with `limit`, a late_step_limit
/// recommending h_limit (1e-7 s) from t_on (0.05 s) on.
struct watched_oscillator {
  watch_model m;
  dof x;
  explicit watched_oscillator(bool limit = false, double t_on = 0.05, double h_limit = 1e-7) {
    x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("spring", {4.0 * std::numbers::pi * std::numbers::pi}, x, m.ground());
    m.add<linear_damper>("damper", {0.3}, x, m.ground());
    m.add<initial_displacement>("x0", {1.0}, x);
    if (limit) m.add<late_step_limit>("limit", {t_on, h_limit}, x);
  }
};

run_options budget_stage(double end, long max_steps) {
  run_options o;
  o.end = end;
  o.smax = 0.01;
  o.newton = tight_newton(1e-10, 1e-12);
  o.max_steps = max_steps;
  return o;
}

/// Runs `f` and returns the pradis::error it throws (its code is checked by the caller).
template <class F>
error thrown_by(F&& f) {
  try {
    f();
  } catch (const error& e) {
    return e;
  }
  FAIL("no pradis::error was thrown");
  return error(error_code::invalid_model, "unreachable");
}

/// Runs the stage o on a.m with the BDF driver or NEWMARK; checks that it ends with code 142
/// (its step budget) and returns its log, in t_end the time the driver reached.
std::string budget_log(watched_oscillator& a, const run_options& o, bool bdf, double& t_end) {
  std::ostringstream log;
  const auto run = [&](auto& s) {
    s.log().to(log);
    CHECK(thrown_by([&] { s.run(o); }).code() == error_code::step_budget);
    t_end = s.time();
  };
  if (bdf) {
    bdf_simulation s(a.m);
    run(s);
  } else {
    simulation s(a.m, newmark{});
    run(s);
  }
  return log.str();
}

}  // namespace

TEST_SUITE("integrators/step_watch") {
  TEST_CASE("NSTEPMAX: a stage that reaches its step budget before END ends with code 142 where it is") {
    watched_oscillator a, b;
    simulation sa(a.m, newmark{}), sb(b.m, newmark{});
    std::vector<double> out_t;
    sa.on_output([&](const auto& s) { out_t.push_back(s.time()); });
    const error e = thrown_by([&] { sa.run(budget_stage(1.0, 30)); });
    CHECK(e.code() == error_code::step_budget);
    CHECK(static_cast<int>(e.code()) == 142);
    INFO(e.what());
    CHECK(std::string(e.what()).find("the stage used up its NSTEPMAX = 30 accepted steps at t = 0.3") !=
          std::string::npos);
    CHECK(std::string(e.what()).find("before END = 1") != std::string::npos);
    CHECK(sa.time() == doctest::Approx(0.3).epsilon(1e-12));
    CHECK(sa.statistics().steps == 30);
    // The output of the last accepted step was written before the stop.
    REQUIRE(!out_t.empty());
    CHECK(out_t.back() == doctest::Approx(0.3).epsilon(1e-12));

    // A next stage goes on from t = 0.3; with the same fixed steps it ends where one run ends.
    sa.run(budget_stage(1.0, 0));
    sb.run(budget_stage(1.0, 0));
    CHECK(sa.time() == 1.0);
    CHECK(sa.statistics().steps == sb.statistics().steps);
    CHECK(std::abs(sa.u(a.x) - sb.u(b.x)) < 1e-12);
    CHECK(std::abs(sa.v(a.x) - sb.v(b.x)) < 1e-12);
  }

  TEST_CASE("NSTEPMAX equal to the steps a stage needs ends the stage normally") {
    watched_oscillator a;
    simulation sa(a.m, newmark{});
    const run_statistics st = sa.run(budget_stage(1.0, 100));
    CHECK(st.steps == 100);
    CHECK(sa.time() == 1.0);
  }

  TEST_CASE("NSTEPMAX under BDF: code 142 after the budget, the stage's time kept") {
    watched_oscillator a;
    bdf_simulation sa(a.m);
    run_options o = budget_stage(1.0, 25);
    o.drltx = 1e-8;
    const error e = thrown_by([&] { sa.run(o); });
    CHECK(e.code() == error_code::step_budget);
    CHECK(sa.statistics().steps == 25);
    CHECK(sa.time() > 0.0);
    CHECK(sa.time() < 1.0);
    // The next stage finishes from there; the displacement against the exact damped
    // oscillation u = e^(-zeta w t) (cos wd t + zeta w / wd sin wd t) at t = 1.
    o.max_steps = 0;
    sa.run(o);
    const double w = 2 * std::numbers::pi, zw = 0.15, wd = std::sqrt(w * w - zw * zw);
    const double exact = std::exp(-zw) * (std::cos(wd) + zw / wd * std::sin(wd));
    CHECK(std::abs(sa.u(a.x) - exact) < 1e-6);
  }

  TEST_CASE("NSTEPMAX < 0 is refused by both drivers") {
    watched_oscillator a, b;
    simulation sa(a.m, newmark{});
    bdf_simulation sb(b.m);
    for (const error& e :
         {thrown_by([&] { sa.run(budget_stage(1.0, -1)); }), thrown_by([&] { sb.run(budget_stage(1.0, -1)); })}) {
      CHECK(e.code() == error_code::invalid_option);
      CHECK(std::string(e.what()).find("NSTEPMAX = -1 must be >= 0 (0: no limit)") != std::string::npos);
    }
  }

  TEST_CASE("crawl warning: once per stage, after a window of 10,000 steps whose mean is below 1e-3 of the largest") {
    // Steps of up to SMAX = 0.01 s until t = 0.05 s, then steps of 1e-7 s that an element
    // recommends: the warning comes at the end of the first or second window of 10,000 steps
    // (the first holds the steps before t = 0.05 s too), the budget stops the stage at 25,000.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      watched_oscillator a(true);
      run_options o = budget_stage(1.0, 25000);
      o.drltx = 1e-6;
      double t_end = 0;
      const std::string text = budget_log(a, o, bdf, t_end);
      INFO(text);
      const auto first = text.find("warning: the run crawls: the last 10000 accepted steps were on average below "
                                   "0.001 of the stage's largest step");
      REQUIRE(first != std::string::npos);
      CHECK(text.find("the run crawls", first + 20) == std::string::npos);  // once per stage
      const std::string at = "(now h = 1e-07 at t = ";
      const auto where = text.find(at, first);
      REQUIRE(where != std::string::npos);
      const double t_warn = std::stod(text.substr(where + at.size()));
      CHECK(t_warn >= 0.05);
      CHECK(t_warn <= 0.06 + 2e-3);
      // The stage's 25,000 steps include those before the crawl.
      CHECK(t_end > t_warn);
      CHECK(t_end < t_warn + 25000 * 1e-7);
      CHECK(text.find("an element's recommended step (STEPMD) 1e-07 sets the step") != std::string::npos);
      CHECK(text.find("NSTEPMAX") != std::string::npos);
    }
  }

  TEST_CASE("crawl warning: a stage held at SMIN from its start, by a recommended step below SMIN") {
    // An element recommends 1e-13 s from t = 0, below SMIN = 1e-9 s: every step is SMIN, the
    // stage's largest too, so only the floor criterion (mean below 2 SMIN, SMIN <= 1e-3 SMAX)
    // sees it. Found by mutating a model file: XSRC at 1e30 Hz held NEWMARK at SMIN = 1e-11 s
    // for 6 million steps without a line.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      watched_oscillator a(true, 0.0, 1e-13);
      run_options o = budget_stage(1.0, 12000);
      o.smin = 1e-9;
      o.drltx = 1e-6;
      double t_end = 0;
      const std::string text = budget_log(a, o, bdf, t_end);
      CHECK(t_end == doctest::Approx(12000 * 1e-9).epsilon(1e-6));
      INFO(text);
      const auto first = text.find("warning: the run crawls: the last 10000 accepted steps were held at SMIN = "
                                   "1e-09 (on average below twice it; SMAX = 0.01) (now h = 1e-09 at t = ");
      REQUIRE(first != std::string::npos);
      CHECK(text.find("the run crawls", first + 20) == std::string::npos);
      CHECK(text.find("the stage needs about 999990000 more steps") != std::string::npos);
      CHECK(text.find("an element's recommended step (STEPMD) 1e-13 sets the step") != std::string::npos);
      CHECK(text.find("An element that recommends a step below SMIN") != std::string::npos);
    }
  }

  TEST_CASE("no crawl warning at SMIN when SMIN is not 1e-3 of SMAX or less, nor at SMAX") {
    // The same element, with SMIN = 2e-6 s and SMAX = 1e-3 s: the steps stay at SMIN, but
    // SMAX / SMIN = 500 is no 1000-fold drop; no warning.
    watched_oscillator a(true, 0.0, 1e-13);
    std::ostringstream log;
    simulation s(a.m, newmark{});
    s.log().to(log);
    run_options o = budget_stage(0.024, 0);  // 12,000 steps of SMIN
    o.smin = 2e-6;
    o.smax = 1e-3;
    s.run(o);
    CHECK(s.statistics().steps >= 12000);
    CHECK(log.str().find("crawls") == std::string::npos);
  }

  TEST_CASE("a stage that needs more steps of SMAX than its NSTEPMAX is warned of at its start, in both drivers") {
    // END = 1, SMAX = 0.01: at least 100 steps. NSTEPMAX = 30 cannot reach END; the warning
    // comes before the first step, and the stage then ends with code 142 as it says.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      watched_oscillator a;
      run_options o = budget_stage(1.0, 30);
      o.drltx = 1e-6;
      double t_end = 0;
      const std::string text = budget_log(a, o, bdf, t_end);
      INFO(text);
      const auto warned = text.find("warning: the stage needs at least 100 steps to END = 1 (from t = 0 in steps of at "
                                    "most SMAX = 0.01), more than its NSTEPMAX = 30: it will end with code 142 "
                                    "before END");
      CHECK(warned != std::string::npos);
      CHECK(warned < text.find("NSTEPMAX = 30 accepted steps"));  // before the error
    }
    // NSTEPMAX = 100, exactly the steps of SMAX the stage needs: no warning, and it ends normally.
    watched_oscillator b;
    std::ostringstream log;
    simulation s(b.m, newmark{});
    s.log().to(log);
    s.run(budget_stage(1.0, 100));
    CHECK(s.time() == 1.0);
    CHECK(log.str().find("needs at least") == std::string::npos);
  }

  TEST_CASE("a stage of more than 1e8 steps of SMAX gets a note at its start") {
    // The note of stage_start_text (step_watch.hpp), from the step count (END - t) / SMAX alone.
    using pradis::detail::stage_start_text;
    CHECK(stage_start_text(0.0, 0.1, 1e-9, 0) == "");  // 1e8 steps: not above the bound
    CHECK(stage_start_text(0.0, 1.0, 1e-9, 0) ==
          "note: the stage needs at least 1000000000 steps to END = 1 (from t = 0 in steps of at most SMAX = 1e-09); a "
          "larger SMAX or a nearer END shortens it, NSTEPMAX (run_options::max_steps) ends a stage after that many "
          "steps");
    // With a budget below the count, the warning instead; with a budget above it, the note.
    CHECK(stage_start_text(0.5, 1.0, 1e-9, 1000).find("warning: the stage needs at least 500000000 steps") == 0);
    CHECK(stage_start_text(0.5, 1.0, 1e-9, 1000000000).find("note: the stage needs at least 500000000 steps") == 0);
    // Through both drivers: an observer stops the run after its first step; the note was written before it.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      watched_oscillator a;
      std::ostringstream log;
      const run_options o = budget_stage(2e6, 0);  // 2e8 steps of SMAX = 0.01
      struct stop_run {};
      const auto stop = [](const auto&) { throw stop_run{}; };
      bool stopped = false;
      try {
        if (bdf) {
          bdf_simulation s(a.m);
          s.log().to(log);
          s.on_step(stop);
          s.run(o);
        } else {
          simulation s(a.m, newmark{});
          s.log().to(log);
          s.on_step(stop);
          s.run(o);
        }
      } catch (const stop_run&) {
        stopped = true;
      }
      CHECK(stopped);
      CHECK(log.str().find("note: the stage needs at least 200000000 steps to END = 2000000 (from t = 0 in steps of at "
                           "most SMAX = 0.01); a larger SMAX") != std::string::npos);
    }
  }

  TEST_CASE("no crawl warning where the steps stay within 1e-3 of the stage's largest") {
    watched_oscillator a;
    std::ostringstream log;
    simulation s(a.m, newmark{});
    s.log().to(log);
    run_options o = budget_stage(200.0, 0);  // 20,000 steps of SMAX
    s.run(o);
    CHECK(log.str().find("crawls") == std::string::npos);
  }
}
