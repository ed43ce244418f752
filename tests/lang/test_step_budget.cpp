// NSTEPMAX, the step budget of a stage in the model language (run_options::max_steps,
// error 142): the stop at the stage's line with the time reached, the rows computed
// before it kept, the budget counted over the whole stage when SAVE cuts it into
// pieces, and bad values located at the key. The drivers' warnings (among them the
// crawl warning, integrators/step_watch.hpp) reach the session's report lines.

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "lang_test_support.hpp"

using namespace pradis;
using lang_test::expect_error;
using lang_test::small_with;

namespace {
/// The small model (mass 2, spring 100, load 10; its stage at line 14) with the stage `stage`.
std::string with_stage(const std::string& stage) {
  return small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n", "  " + stage + "\n");
}

/// An example model (examples/models/`file`) with each pair's first text replaced by its
/// second (each must occur), run without files: the run's error text (empty if none) and
/// its report lines.
struct mutant_run {
  std::string error, log;
  std::unique_ptr<lang::session> session;
};
mutant_run run_mutant(const std::string& file, const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string text = lang_test::slurp(lang_test::models_dir() / file);
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
  }
  std::ostringstream log;
  mutant_run r;
  r.session = lang_test::build(text);
  try {
    r.session->run({.write_files = false, .log = &log});
  } catch (const lang::lang_error& x) {
    r.error = x.what();
  }
  r.log = log.str();
  return r;
}
}  // namespace

TEST_SUITE("lang/step_budget") {
  TEST_CASE("NSTEPMAX: the stage stops with error 142 at its line after that many steps; the rows are kept") {
    const auto dir = lang_test::scratch_dir("budget");
    auto s = lang_test::build(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, NSTEPMAX=20)"));
    std::string e;
    try {
      s->run({.output_dir = dir.string(), .stem = "m", .plot = false});
    } catch (const lang::lang_error& x) {
      e = x.what();
    }
    CAPTURE(e);
    CHECK(e.rfind("test.prd:14:", 0) == 0);
    CHECK(e.find("the stage used up its NSTEPMAX = 20 accepted steps at t = 0.02, before END = 0.1") !=
          std::string::npos);
    CHECK(e.find("(pradis error 142, step budget used up)") != std::string::npos);
    // The zero step's row and one row per step (OUT = 0), in the session and in the CSV.
    const io::table& t = s->results();
    REQUIRE(t.rows() == 21);
    CHECK(t.at(20, 0) == doctest::Approx(0.02).epsilon(1e-12));
    std::ifstream csv(dir / "m.csv");
    REQUIRE(csv.good());
    int lines = 0;
    for (std::string line; std::getline(csv, line);) ++lines;
    CHECK(lines == 22);  // the header and 21 rows
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("NSTEPMAX counts the stage's steps across the pieces SAVE cuts it into") {
    // SMAX = 1e-3 and SAVE = 0.005: pieces of 5 steps. A budget of 12 runs out inside the
    // third piece, one of 10 exactly at the end of the second.
    std::string e = lang_test::error_of(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, SAVE=0.005, NSTEPMAX=12)"));
    CAPTURE(e);
    CHECK(e.find("test.prd:14:") == 0);
    CHECK(e.find("NSTEPMAX = 12 accepted steps at t = 0.012, before END = 0.1") != std::string::npos);
    e = lang_test::error_of(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, SAVE=0.005, NSTEPMAX=10)"));
    CHECK(e.find("NSTEPMAX = 10 accepted steps at t = 0.01, before END = 0.1") != std::string::npos);
    // The warning that the stage needs more steps than its NSTEPMAX comes once, for the stage, not per piece.
    std::ostringstream log;
    auto p = lang_test::build(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, SAVE=0.005, NSTEPMAX=12)"));
    CHECK_THROWS_AS(p->run({.write_files = false, .log = &log}), lang::lang_error);
    const std::string l = log.str();
    CAPTURE(l);
    const auto w = l.find("warning: the stage needs at least 100 steps to END = 0.1 (from t = 0 in steps of at most "
                          "SMAX = 0.001), more than its NSTEPMAX = 12");
    CHECK(w != std::string::npos);
    CHECK(l.find("needs at least", l.find("needs at least") + 1) == std::string::npos);  // once
    // A budget the stage does not use up changes nothing.
    auto a = lang_test::run(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, SAVE=0.005, NSTEPMAX=100)"));
    auto b = lang_test::run(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, SAVE=0.005)"));
    REQUIRE(a->results().rows() == b->results().rows());
    CHECK(a->results().rows() == 101);
    for (std::size_t r = 0; r < a->results().rows(); ++r) CHECK(a->results().at(r, 1) == b->results().at(r, 1));
  }

  TEST_CASE("NSTEPMAX under BDF and under error control") {
    std::string e = lang_test::error_of(with_stage("Calc 'BDF (END=0.1, SMAX=1E-3, DRLTX=1E-6, NSTEPMAX=7)"));
    CAPTURE(e);
    CHECK(e.find("test.prd:14:") == 0);
    CHECK(e.find("NSTEPMAX = 7 accepted steps at t = ") != std::string::npos);
    CHECK(e.find("(pradis error 142, step budget used up)") != std::string::npos);
    e = lang_test::error_of(with_stage("Calc 'HHT (END=0.1, SMAX=1E-3, DRLTX=1E-6, NSTEPMAX=7)"));
    CHECK(e.find("NSTEPMAX = 7 accepted steps at t = ") != std::string::npos);
  }

  TEST_CASE("NSTEPMAX that is not a whole number from 0 to 2e9 is an error at its value") {
    for (const char* bad : {"-1", "2.5", "3E9"}) {
      CAPTURE(bad);
      expect_error(with_stage(std::string("Calc 'SHTERM (END=0.1, SMAX=1E-3, NSTEPMAX=") + bad + ")"), "14:46",
                   {"NSTEPMAX must be a whole number from 0 to 2000000000, got"});
    }
  }

  TEST_CASE("the drivers' warnings reach the session's report lines; a run's error is reported once, located") {
    // Error control at DRLTX = 0.1 on the mass on a spring: SMAX decides the steps
    // (integrators/precision.hpp, smax_warning_text).
    std::ostringstream log;
    auto s = lang_test::build(with_stage("Calc 'NEWMARK (END=0.1, SMAX=1E-3, DRLTX=0.1)"));
    s->run({.write_files = false, .log = &log});
    CAPTURE(log.str());
    CHECK(log.str().find("warning: error control: ") != std::string::npos);
    CHECK(log.str().find(" steps were SMAX = 0.001: the local error stayed below") != std::string::npos);
    CHECK(log.str().find("stage 1 'Calc' NEWMARK: t = 0 .. 0.1") != std::string::npos);
    // A note names the stage's program (examples/models/source_bench.prd: a source's current is
    // a multiplier, and NEWMARK does not damp it).
    std::ostringstream log3;
    auto b = lang_test::build(lang_test::slurp(lang_test::models_dir() / "source_bench.prd"));
    b->run({.write_files = false, .log = &log3});
    CHECK(log3.str().find("note: the model has constraint equations (Lagrange multipliers, e.g. LINKX, SPH3X, VDC2) "
                          "and NEWMARK has no numerical damping") != std::string::npos);
    // The budget's error is the session's located error, not also a line of the log.
    std::ostringstream log2;
    auto f = lang_test::build(with_stage("Calc 'SHTERM (END=0.1, SMAX=1E-3, NSTEPMAX=20)"));
    CHECK_THROWS_AS(f->run({.write_files = false, .log = &log2}), lang::lang_error);
    CHECK(log2.str().find("pradis error") == std::string::npos);
    // The stage needs at least 100 steps of SMAX and its NSTEPMAX is 20: the warning at its start says so.
    CHECK(log2.str().find("warning: the stage needs at least 100 steps to END = 0.1 (from t = 0 in steps of at most "
                          "SMAX = 0.001), more than its NSTEPMAX = 20: it will end with code 142 before END") !=
          std::string::npos);
  }

  TEST_CASE("a run that crawls: the warning names it, NSTEPMAX ends it (two_bodies.prd with body 2 on DOFs 1 5 6)") {
    // The fuzz find: body 2's MD on DOFs (1, 5, 6) instead of (4, 5, 6) leaves DOF 4 massless,
    // held only by the LINKD link, whose force on it vanishes where the link has its free
    // length. At t = 0.14 s SHTERM's steps fall from SMAX = 1e-4 s to below 1e-7 s; without
    // a budget it reached t = 0.26 s of its 1 s stage after 120 s.
    const mutant_run r =
        run_mutant("two_bodies.prd", {{"'MD (4 5 6;", "'MD (1 5 6;"}, {"DRLTI=1E-8)", "DRLTI=1E-8, NSTEPMAX=40000)"}});
    const std::string& e = r.error;
    CAPTURE(e);
    CAPTURE(r.log);
    CHECK(e.find("the stage used up its NSTEPMAX = 40000 accepted steps at t = 0.14") != std::string::npos);
    CHECK(e.find("(pradis error 142, step budget used up)") != std::string::npos);
    const std::string& l = r.log;
    const std::string head =
        "warning: the run crawls: the last 10000 accepted steps were on average below 0.001 of the stage's largest "
        "step 0.0001 (now h = ";
    const auto w = l.find(head);
    REQUIRE(w != std::string::npos);
    const double h = std::stod(l.substr(w + head.size()));
    CHECK(h < 1e-7);
    CHECK(l.find("failed steps (Newton, singular situations) cut the step: ", w) != std::string::npos);
    // The rows up to the stop are kept (OUT = 0.005: the last one at t = 0.145).
    const io::table& t = r.session->results();
    REQUIRE(t.rows() >= 2);
    CHECK(t.at(t.rows() - 1, 0) == doctest::Approx(0.145).epsilon(1e-12));
  }

  TEST_CASE("a run held at SMIN by a source of 1e30 Hz: the warning names the step and its cause") {
    // The fuzz find: eccentric_shaker.prd with its guide's XSRC at f = 1e30 Hz (parameters
    // 0, 1e30, 0, -2). The source recommends T / 20 = 5e-32 s, NEWMARK takes SMIN = 1e-11 s
    // from the start, and so the stage's largest step is SMIN too; before the floor
    // criterion of step_watch, 6 million steps passed without a line.
    const mutant_run r = run_mutant("eccentric_shaker.prd", {{"Guide = 0, 0, 0, 0", "Guide = 0, 1e30, 0, -2"},
                                                             {"ITR=20,", "ITR=20, NSTEPMAX=10500,"}});
    const std::string& e = r.error;
    CAPTURE(e);
    CAPTURE(r.log);
    CHECK(e.find("the stage used up its NSTEPMAX = 10500 accepted steps at t = 1.05e-07") != std::string::npos);
    const std::string& l = r.log;
    CHECK(l.find("warning: the run crawls: the last 10000 accepted steps were held at SMIN = 1e-11 (on average "
                 "below twice it; SMAX = 0.001) (now h = 1e-11 at t = 1e-07; at this step the stage needs about "
                 "3.9999999e+11 more steps to END = 4); an element's recommended step (STEPMD) 5e-32 sets the step") !=
          std::string::npos);
  }

  TEST_CASE("a crawl under error control from failed steps: the warning names them (spring_pendulum.prd, no Mass X)") {
    // The fuzz find: spring_pendulum.prd without its line 'Mass X'. DOF 1 is then massless,
    // held only by the LINKD link; NEWMARK under error control has its steps cut by Newton
    // failures and crawls from t = 0.17 s on. The error test limits no step there, so the
    // warning names the failed steps (it used to name no cause).
    const mutant_run r = run_mutant("spring_pendulum.prd", {{"    Mass X 'MASS (1; Mass)\n", ""},
                                                            {"GAMMA=0.5,", "GAMMA=0.5, NSTEPMAX=30000,"}});
    const std::string& e = r.error;
    CAPTURE(e);
    CAPTURE(r.log);
    CHECK(e.find("the stage used up its NSTEPMAX = 30000 accepted steps at t = 0.1") != std::string::npos);
    const std::string& l = r.log;
    const auto w = l.find("warning: the run crawls: the last 10000 accepted steps were on average below 0.001 of the "
                          "stage's largest step 0.001 (now h = ");
    REQUIRE(w != std::string::npos);
    CHECK(l.find("failed steps (Newton, singular situations) cut the step: ", w) != std::string::npos);
    CHECK(l.find("NEWMARK has no numerical damping") != std::string::npos);
  }
}
