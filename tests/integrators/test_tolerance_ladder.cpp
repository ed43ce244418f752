// The tolerance ladder (integrators/tolerance_ladder.hpp) and the one-call print
// of the run statistics (integrators/statistics_io.hpp).
//
// Reference problem: the undamped oscillator m u'' + k u = 0, m = 1, k = 4,
// u(0) = 1, v(0) = 0, with the exact solution u = cos(2 t), v = -2 sin(2 t).

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/statistics_io.hpp"
#include "pradis/integrators/tolerance_ladder.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
using osc_model = model<point_mass, linear_spring, initial_displacement>;

osc_model oscillator(dof& x) {
  osc_model m;
  x = m.add_dof("x");
  m.add<point_mass>("mass", {.m = 1.0}, x);
  m.add<linear_spring>("spring", {.k = 4.0}, x, m.ground());
  m.add<initial_displacement>("x0", {.u0 = 1.0}, x);
  return m;
}

constexpr double t_end = 3.0;

/// The exact final state u = cos(2 t), v = -2 sin(2 t) on DOF x (ground: 0).
global_state exact_state(const osc_model& m, dof x) {
  global_state s;
  s.resize(m.dof_count());
  s.u(x.index) = std::cos(2 * t_end);
  s.v(x.index) = -2 * std::sin(2 * t_end);
  return s;
}

const run_options base{.end = t_end, .smax = 0.1, .smin = 1e-9};
}  // namespace

TEST_SUITE("integrators/tolerance_ladder") {
  TEST_CASE("the achieved error falls monotonically down the ladder and matches the error against the exact solution") {
    dof x;
    const osc_model m = oscillator(x);
    const global_state exact = exact_state(m, x);
    ladder_options lo;
    lo.tolerances = {1e-6, 1e-2, 1e-3, 1e-4, 1e-5};  // any order: run loosest first
    const ladder_result r = tolerance_ladder(m, base, newmark{}, lo);
    REQUIRE(r.rungs.size() == 5);
    CHECK(r.scheme == "NEWMARK");
    CHECK(r.reference.tolerance == doctest::Approx(1e-8));
    const double ref_true = ladder_state_error(r.reference.final_state, exact);
    for (std::size_t i = 0; i < r.rungs.size(); ++i) {
      const ladder_rung& g = r.rungs[i];
      CHECK(g.tolerance == doctest::Approx(std::pow(10.0, -2.0 - static_cast<double>(i))));
      CHECK(g.stats.steps > 0);
      CHECK(g.stats.factorizations > 0);
      CHECK(g.cpu_s >= 0);
      const double true_error = ladder_state_error(g.final_state, exact);
      // The reference is far better than every rung, so the error measured
      // against it is the true error within 10 %.
      CHECK(ref_true < 0.05 * true_error);
      CHECK(g.error == doctest::Approx(true_error).epsilon(0.1));
      if (i > 0) {
        CHECK(g.error < r.rungs[i - 1].error);  // monotonic
        CHECK(g.stats.steps > r.rungs[i - 1].stats.steps);
      } else {
        CHECK(std::isnan(g.time_per_digit));
      }
    }
    // Four decades of tolerance buy at least two decades of error.
    CHECK(r.rungs.back().error < 1e-2 * r.rungs.front().error);
  }

  TEST_CASE("the printed table has one line per rung with the measured figures") {
    dof x;
    const osc_model m = oscillator(x);
    ladder_options lo;
    lo.tolerances = {1e-2, 1e-3};
    lo.reference_factor = 1.0;  // the tightest rung is its own reference: error 0
    lo.repeats = 2;
    const ladder_result r = tolerance_ladder(m, base, stoermer{}, lo);
    REQUIRE(r.rungs.size() == 2);
    CHECK(r.rungs[1].error == 0.0);
    CHECK(r.rungs[0].error > 0.0);
    std::ostringstream os;
    r.print(os);
    const std::string text = os.str();
    CHECK(text.find("tolerance ladder (SHTERM), reference DRLTX = 1.0e-03") == 0);
    CHECK(text.find("exact") != std::string::npos);
    CHECK(text.find(std::to_string(r.rungs[0].stats.steps)) != std::string::npos);
    long lines = 0;
    for (char c : text) lines += c == '\n';
    CHECK(lines == 2 + 2);  // title, column header, two rungs
  }

  TEST_CASE("bad ladders are refused with an error naming the option") {
    dof x;
    const osc_model m = oscillator(x);
    auto refused = [&](const ladder_options& lo, const std::string& name) {
      try {
        (void)tolerance_ladder(m, base, newmark{}, lo);
        FAIL("accepted a bad ladder, expected an error naming " << name);
      } catch (const error& e) {
        CHECK(e.code() == error_code::invalid_option);
        CHECK_MESSAGE(e.message().find(name) != std::string::npos, e.what());
      }
    };
    ladder_options lo;
    lo.tolerances = {};
    refused(lo, "tolerances");
    for (double t : {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      lo.tolerances = {1e-2, t};
      refused(lo, "tolerances[1]");
    }
    lo = {};
    lo.reference_factor = 0;
    refused(lo, "reference_factor");
    lo.reference_factor = 2;
    refused(lo, "reference_factor");
    lo = {};
    lo.absolute_factor = std::numeric_limits<double>::quiet_NaN();
    refused(lo, "absolute_factor");
    lo = {};
    lo.newton_factor = -1;
    refused(lo, "newton_factor");
    lo = {};
    lo.repeats = 0;
    refused(lo, "repeats");
  }

  TEST_CASE("the run statistics print in one call with the values statistic() reports") {
    dof x;
    osc_model m = oscillator(x);
    simulation sim(m, newmark{});
    sim.run({.end = 1.0, .smax = 0.01});
    const std::string s = to_string(sim.statistics());
    std::ostringstream os;
    os << sim.statistics();
    CHECK(os.str() == s);
    auto field = [&](const std::string& key) {  // "KEY=value" at the start or after a space
      const std::string padded = " " + s, pat = " " + key + "=";
      const auto p = padded.find(pat);
      REQUIRE(p != std::string::npos);
      return std::stod(padded.substr(p + pat.size()));
    };
    CHECK(field("NSTEP") == sim.statistic("NSTEP"));
    CHECK(field("NSTEP") == 100);  // 1 s in fixed steps of 0.01
    CHECK(field("NREJ") == sim.statistic("NREJ"));
    CHECK(field("NITTOT") == sim.statistic("NITTOT"));
    CHECK(field("NFACT") == sim.statistic("NFACT"));
    CHECK(field("NITER") == sim.statistic("NITER"));
    CHECK(field("STEP") == doctest::Approx(sim.statistic("STEP")));
    CHECK(field("NEVAL") == static_cast<double>(sim.statistics().evaluations));
    CHECK(field("NERR") == 0);
  }
}
