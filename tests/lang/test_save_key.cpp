// The SAVE key of the integration programs: interval checkpoints
// `<stem>.t<time>.chk` at the multiples of SAVE, a restart from one of them
// reproducing the uninterrupted run bit for bit, and bad SAVE values.

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "lang_test_support.hpp"

using namespace pradis;
using lang_test::expect_error;
using lang_test::small_with;

namespace {
using lang_test::scratch_dir;
using lang_test::slurp;
/// The small model (mass 2, spring 100, load 10) with its position, velocity
/// and acceleration as outputs and the stage lines `stages` under $RUN.
std::string model_with(const std::string& before_run, const std::string& stages) {
  std::string text = small_with("$RUN\n  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n", before_run + "$RUN\n" + stages);
  return text.replace(text.find("  Spring force"), 0, "  V 'X (1; 2)\n  A 'X (1; 3)\n");
}
}  // namespace

TEST_SUITE("lang/save") {
  TEST_CASE("SAVE writes <stem>.t<time>.chk at every multiple of SAVE, steps end there, results unchanged in between") {
    const auto dir = scratch_dir("names");
    // One stage from 0 to 0.1 (SAVE = 0.025: checkpoints at 0.025, 0.05, 0.075
    // and at END), then one from 0.1 to 0.13 (SAVE = 0.02: at 0.12 only; 0.14 is
    // after END).
    auto s = lang_test::build(model_with("", "  A 'GALPHA (END=0.1, SMAX=1E-3, OUT=0.004, SAVE=0.025)\n"
                                             "  B 'HHT (END=0.13, SMAX=1E-3, SAVE=0.02)\n"));
    s->run({.output_dir = dir.string(), .stem = "m", .plot = false});
    std::vector<std::string> chk;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".chk") chk.push_back(e.path().filename().string());
    std::sort(chk.begin(), chk.end());
    CHECK(chk == std::vector<std::string>{"m.t0.025.chk", "m.t0.05.chk", "m.t0.075.chk", "m.t0.1.chk", "m.t0.12.chk"});
    // Every checkpoint time is an output row (a step ends there).
    const auto& t = s->results();
    for (double tc : {0.025, 0.05, 3 * 0.025, 0.1, 6 * 0.02}) {
      bool found = false;
      for (std::size_t r = 0; r < t.rows(); ++r) found = found || std::abs(t.at(r, 0) - tc) <= 1e-15;
      CAPTURE(tc);
      CHECK(found);
    }
    // Equilibrium m a + k u = F holds at every row (SAVE changes where steps end, not the equations).
    for (std::size_t r = 0; r < t.rows(); ++r) CHECK(2 * t.at(r, 3) + 100 * t.at(r, 1) == doctest::Approx(10).epsilon(1e-9));
    // Without write_files no checkpoint is written, and the results are the same.
    const auto quiet_dir = scratch_dir("quiet");
    auto q = lang_test::build(model_with("", "  A 'GALPHA (END=0.1, SMAX=1E-3, OUT=0.004, SAVE=0.025)\n"
                                             "  B 'HHT (END=0.13, SMAX=1E-3, SAVE=0.02)\n"));
    q->run({.output_dir = quiet_dir.string(), .write_files = false});
    CHECK(std::filesystem::is_empty(quiet_dir));
    REQUIRE(q->results().rows() == t.rows());
    for (std::size_t r = 0; r < t.rows(); ++r) CHECK(q->results().at(r, 1) == t.at(r, 1));
    std::filesystem::remove_all(dir);
    std::filesystem::remove_all(quiet_dir);
  }

  TEST_CASE("a run restarted from an interval checkpoint reproduces the uninterrupted run bit for bit") {
    // OUT = 0.004 does not divide SAVE = 0.03, and 0.03 k is not exact in binary:
    // the restart must meet the same output and checkpoint times all the same.
    for (const char* program : {"SHTERM", "GALPHA (RHOINF=0.6, ", "HHT (ALPHA=-0.25, ", "NEWMARK (BETA=0.3, GAMMA=0.6, "}) {
      CAPTURE(program);
      std::string head = program;
      const std::string open = head.find('(') == std::string::npos ? head + " (" : head;
      const std::string stage = "  Calc '" + open + "END=0.2, SMAX=1E-3, OUT=0.004, SAVE=0.03)\n";
      const auto dir = scratch_dir("restart");
      auto whole = lang_test::build(model_with("", stage));
      whole->run({.output_dir = dir.string(), .stem = "m", .plot = false});
      REQUIRE(std::filesystem::exists(dir / "m.t0.09.chk"));
      auto again = lang_test::build(model_with("$RESTORE \"m.t0.09.chk\"\n", stage));
      again->run({.output_dir = dir.string(), .stem = "restarted", .plot = false});
      const auto& a = whole->results();
      const auto& b = again->results();
      REQUIRE(b.rows() > 10);
      REQUIRE(a.rows() > b.rows());
      const std::size_t off = a.rows() - b.rows();
      CHECK(a.at(off - 1, 0) == 3 * 0.03);  // the restart continues right after the checkpoint's row
      bool same = true;
      for (std::size_t r = 0; r < b.rows(); ++r)
        for (std::size_t c = 0; c <= b.names().size(); ++c) same = same && b.at(r, c) == a.at(off + r, c);
      CHECK(same);
      // The state vectors at the end, including the scheme's pseudo-acceleration.
      const auto& sa = whole->simulation_ptr()->state();
      const auto& sb = again->simulation_ptr()->state();
      CHECK((sa.u == sb.u));
      CHECK((sa.v == sb.v));
      CHECK((sa.a == sb.a));
      CHECK((sa.p == sb.p));
      CHECK(whole->simulation_ptr()->statistics().steps == again->simulation_ptr()->statistics().steps);
      // The later checkpoints of both runs are the same bytes (the CSV rows as well).
      CHECK(slurp(dir / "m.t0.18.chk") == slurp(dir / "restarted.t0.18.chk"));
      std::filesystem::remove_all(dir);
    }
  }

  TEST_CASE("a checkpoint without the session's scheme record is restored; a damaged record is refused") {
    const auto dir = scratch_dir("record");
    auto first = lang_test::build(model_with("", "  A 'GALPHA (END=0.05, SMAX=1E-3)\n$SAVE \"g.chk\"\n"));
    first->run({.output_dir = dir.string(), .write_files = false});
    const std::string bytes = slurp(dir / "g.chk");
    REQUIRE(bytes.size() > 40);
    CHECK(bytes.substr(bytes.size() - 8) == "PRLANG01");
    {
      // Without the record (as the library's save_checkpoint() writes it): restored, the scheme is not known.
      std::ofstream(dir / "plain.chk", std::ios::binary) << bytes.substr(0, bytes.size() - 40);
      auto s = lang_test::build(model_with("$RESTORE \"plain.chk\"\n", "  B 'GALPHA (END=0.1, SMAX=1E-3)\n"));
      s->run({.output_dir = dir.string(), .write_files = false});
      CHECK(s->simulation_ptr()->time() == 0.1);
    }
    std::string bad = bytes;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    bad.replace(bad.size() - 40, sizeof nan, reinterpret_cast<const char*>(&nan), sizeof nan);
    std::ofstream(dir / "bad.chk", std::ios::binary) << bad;
    const std::string text =
        model_with("$RESTORE \"" + (dir / "bad.chk").string() + "\"\n", "  B 'GALPHA (END=0.1, SMAX=1E-3)\n");
    expect_error(text, "15:1", {"bad.chk': its record of the integration scheme is damaged"});
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("bad SAVE values are located errors naming the key") {
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, SAVE=0"), "14:37",
           {"SAVE = 0 must be a number > 0 (the interval of simulated time between checkpoints)"});
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, SAVE=-0.5"), "14:37", {"SAVE = -0.5 must be a number > 0"});
    {
      std::string pair = small_with("  Load = 10\n", "  Load = 10\n  Pair = 1, 2\n");
      pair.replace(pair.find("SMAX=1E-3"), 9, "SMAX=1E-3, SAVE=Pair");
      expect_error(pair, "15:42", {"SAVE needs one value; 'Pair' is a list of 2"});
    }
    // NaN cannot be written in a model file (no arithmetic, no NaN literal); a
    // syntax tree built by a program can carry it, and is refused the same way.
    {
      auto prog = lang::parse_string(small_with("SMAX=1E-3", "SMAX=1E-3, SAVE=1"), "test.prd");
      bool set = false;
      for (auto& a : prog.actions)
        for (auto& g : a.stage.args)
          for (auto& it : g)
            if (it.text == "SAVE") {
              it.value.front().number = std::numeric_limits<double>::quiet_NaN();
              set = true;
            }
      REQUIRE(set);
      std::string e;
      try {
        lang::session s(std::move(prog));
      } catch (const lang::lang_error& x) {
        e = x.what();
      }
      CHECK(e.rfind("test.prd:14:37: error: SAVE = nan must be a number > 0", 0) == 0);
    }
    // Too many checkpoints for the stage.
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, SAVE=1E-6"), "14:37",
           {"SAVE = 1e-06 would write ", " checkpoints in this stage (from t = 0 to END = 0.1); at most 10000"});
    // Checkpoint times k SAVE out of reach of double precision: a stage far from t = 0.
    expect_error(small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n",
                      "  Far 'SHTERM (END=1E11, SMAX=1E11)\n  Near 'SHTERM (END=1.00000001E11, SMAX=1, SAVE=0.5)\n"),
           "15:44", {"SAVE = 0.5 is too small for END = 1.00000001e+11", "k <= 1e11"});
  }
}
