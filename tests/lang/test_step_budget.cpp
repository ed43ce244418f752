// NSTEPMAX, the step budget of a stage in the model language (run_options::max_steps,
// error 142): the stop at the stage's line with the time reached, the rows computed
// before it kept, the budget counted over the whole stage when SAVE cuts it into
// pieces, and bad values located at the key.

#include <fstream>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;
using lang_test::expect_error;
using lang_test::small_with;

namespace {
/// The small model (mass 2, spring 100, load 10; its stage at line 14) with the stage `stage`.
std::string with_stage(const std::string& stage) {
  return small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n", "  " + stage + "\n");
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
}
