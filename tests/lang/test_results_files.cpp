// The results files of a run are never lost or silently truncated: rows are
// streamed to <stem>.csv.part and renamed at the end (also after a failed or
// interrupted run), every write is checked (a full disk is an error), the output
// directory is checked before the first stage, OUT cannot ask for a billion
// rows, and two displays cannot write the same file.

#include <algorithm>
#include <cmath>
#include <csignal>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;
using lang_test::scratch_dir;
using lang_test::slurp;
using lang_test::small_model;
using lang_test::small_with;

namespace {
/// Number of lines of a text.
std::size_t lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }
}  // namespace

TEST_SUITE("lang/results files") {
  TEST_CASE("the rows computed before a failing stage are kept in <stem>.csv") {
    const auto dir = scratch_dir("later_failure");
    // Stage 2 fails when it starts (SMIN > SMAX), after stage 1 produced its rows.
    const std::string text =
        small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n",
                   "  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n  Broken 'SHTERM (END=0.2, SMAX=1E-3, SMIN=1)\n");
    auto s = lang_test::build(text);
    CHECK_THROWS_AS(s->run({.output_dir = dir.string(), .stem = "m"}), lang::lang_error);
    REQUIRE(s->stages().size() == 1);
    const std::string csv = slurp(dir / "m.csv");
    // Fixed steps of SMAX = 1e-3 with OUT = 0: a row at t = 0 and after each of the 100 steps.
    CHECK(s->results().rows() == 101);
    CHECK(lines(csv) == 1 + 101);
    CHECK(csv.rfind("t,Position,Spring force\n0,", 0) == 0);
    CHECK_FALSE(std::filesystem::exists(dir / "m.csv.part"));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a complete run writes the same rows as the in-memory table") {
    const auto dir = scratch_dir("complete");
    auto s = lang_test::build(small_model);
    s->run({.output_dir = dir.string(), .stem = "m"});
    const std::string csv = slurp(dir / "m.csv");
    CHECK(lines(csv) == 1 + s->results().rows());
    // The last row: the time and the values written with 17 significant digits
    // read back bit for bit.
    const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
    const std::size_t r = s->results().rows() - 1;
    CHECK(std::stod(last) == s->results().at(r, 0));
    CHECK(std::stod(last.substr(last.find(',') + 1)) == s->results().at(r, 1));
    CHECK_FALSE(std::filesystem::exists(dir / "m.csv.part"));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("an interrupted run (run_settings::stop, set by SIGINT) keeps the rows so far") {
    const auto dir = scratch_dir("interrupt");
    volatile std::sig_atomic_t stop = SIGINT;  // as the signal handler of `pradis run` sets it
    auto s = lang_test::build(small_model);
    try {
      s->run({.output_dir = dir.string(), .stem = "m", .stop = &stop});
      FAIL("the run was not interrupted");
    } catch (const lang::interrupted& e) {
      CHECK(e.time() == 0.0);  // stopped at the first check, after the row at t = 0
    }
    // The header and the one row at t = 0 (the spring's force W(1) = -k u is -0 there).
    const std::string csv = slurp(dir / "m.csv");
    CHECK(lines(csv) == 2);
    CHECK(csv.rfind("t,Position,Spring force\n0,0,", 0) == 0);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a full disk is an error naming the file and the reason, and leaves no truncated file") {
    // The temporary file of the results is a link to /dev/full, where every
    // write fails with ENOSPC (Linux); the failure shows when the buffer is flushed.
    if (!std::filesystem::exists("/dev/full")) {
      MESSAGE("no /dev/full on this system: the disk-full case is checked on Linux only");
      return;
    }
    const auto dir = scratch_dir("full");
    std::filesystem::create_symlink("/dev/full", dir / "m.csv.part");
    auto s = lang_test::build(small_model);
    try {
      s->run({.output_dir = dir.string(), .stem = "m"});
      FAIL("a write to /dev/full succeeded");
    } catch (const pradis::error& e) {
      CHECK(e.code() == error_code::io_error);
      CHECK(e.message().find("m.csv") != std::string::npos);
      CHECK(e.message().find(std::strerror(ENOSPC)) != std::string::npos);
    }
    CHECK_FALSE(std::filesystem::exists(dir / "m.csv"));
    CHECK_FALSE(std::filesystem::exists(std::filesystem::symlink_status(dir / "m.csv.part")));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("an unusable output directory is reported before the first stage") {
    const auto dir = scratch_dir("not_a_dir");
    {
      std::ofstream f(dir / "file");
      f << "x";
    }
    auto s = lang_test::build(small_model);
    try {
      s->run({.output_dir = (dir / "file").string(), .stem = "m"});
      FAIL("a regular file was accepted as the output directory");
    } catch (const pradis::error& e) {
      CHECK(e.code() == error_code::io_error);
      CHECK(e.message().find("cannot use the output directory") != std::string::npos);
    }
    CHECK(s->stages().empty());
    CHECK_THROWS_AS(s->run({.output_dir = "", .stem = "m"}), pradis::error);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("OUT far below the step cannot ask for more than max_rows rows") {
    // END = 0.1, OUT = 1e-12: 1e11 rows (each step would be cut to OUT).
    const std::string e = lang_test::error_of(small_with("END=0.1, SMAX=1E-3", "END=0.1, SMAX=1E-3, OUT=1E-12"));
    CHECK(e.rfind("test.prd:14:37: error: OUT = 1e-12 would write 1e+11 output rows", 0) == 0);
    CHECK(e.find("at most 10000000 rows") != std::string::npos);
    // A sensible OUT runs: 0.1 / 0.01 = 10 rows after the one at t = 0.
    auto s = lang_test::run(small_with("END=0.1, SMAX=1E-3", "END=0.1, SMAX=1E-3, OUT=0.01"));
    CHECK(s->results().rows() == 11);
  }

  TEST_CASE("with OUT = 0 (a row every step) the run stops at max_rows, keeping the rows written") {
    // SMAX = 1e-3 and END = 0.1 with OUT = 0: 101 rows; the run stops at the 20th.
    const auto dir = scratch_dir("max_rows");
    auto s = lang_test::build(small_with("END=0.1, SMAX=1E-3", "END=0.1, SMAX=1E-3, OUT=0"));
    try {
      s->run({.output_dir = dir.string(), .stem = "m", .plot = false, .max_rows = 20});
      FAIL("must throw");
    } catch (const lang::lang_error& e) {
      CHECK(std::string(e.what()).find("the run has produced 20 output rows, the most pradis writes") !=
            std::string::npos);
    }
    CHECK(s->results().rows() == 20);
    CHECK(lines(slurp(dir / "m.csv")) == 1 + 20);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("run_settings::max_rows below 1 or not finite is refused") {
    for (double bad : {0.0, -5.0, std::nan(""), HUGE_VAL}) {
      auto s = lang_test::build(small_model);
      CHECK_THROWS_WITH_AS(s->run({.write_files = false, .max_rows = bad}), doctest::Contains("max_rows"),
                           pradis::error);
    }
  }

  TEST_CASE("two displays that would write the same file are an error at the second") {
    const std::string same_file = small_with("$END", "$PRINT\n  a b 'TABL ()\n  a_b 'TABL ()\n$END");
    const std::string e = lang_test::error_of(same_file);
    CHECK(e.rfind("test.prd:17:3: error: this display would write the same files as the display at test.prd:16:3",
                  0) == 0);
    // Case: a file system may not tell them apart.
    const std::string by_case = small_with("$END", "$PRINT\n  Plot 'TABL ()\n  plot 'TABL ()\n$END");
    CHECK(lang_test::error_of(by_case).find("same files") != std::string::npos);
    // A label equal to the name of an unlabelled display (the second display is DISP2).
    CHECK(lang_test::error_of(small_with("$END", "$PRINT\n  'TABL ()\n  'DISP ()\n  DISP2 'TABL ()\n$END"))
              .find("same files as the display at test.prd:17:3") != std::string::npos);
    // Distinct names are fine.
    CHECK(lang_test::error_of(small_with("$END", "$PRINT\n  a b 'TABL ()\n  'DISP ()\n$END")).empty());
  }

  TEST_CASE("'DISP asks the application for a plot after its CSV is written (the library runs no plotter)") {
    const auto dir = scratch_dir("plot_request");
    auto s = lang_test::build(small_with("$END", "$PRINT\n  Graph 'DISP (Position)\n$END"));
    s->run({.output_dir = dir.string(), .stem = "m"});
    REQUIRE(s->plots().size() == 1);
    const auto& p = s->plots().front();
    CHECK(p.names == std::vector<std::string>{"Position"});
    CHECK(p.csv == (dir / "m.Graph.csv").string());
    CHECK(p.png == (dir / "m.Graph.png").string());
    CHECK(std::filesystem::exists(p.csv));
    auto quiet = lang_test::build(small_with("$END", "$PRINT\n  Graph 'DISP (Position)\n$END"));
    quiet->run({.output_dir = dir.string(), .stem = "m", .plot = false});
    CHECK(quiet->plots().empty());
    std::filesystem::remove_all(dir);
  }
}
