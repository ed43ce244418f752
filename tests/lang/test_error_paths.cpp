// Located error paths of the lexer, parser, model builder and session that no
// other test reaches: each is triggered by a model text and checked for its
// file:line:column and a distinctive part of its message (strings, $DATA
// lists, argument items, sub-structure fragments, #OUTPUT calls, $REPLACE,
// the output directory and checkpoint files).

#include <filesystem>
#include <string>

#include "lang_test_support.hpp"

using lang_test::expect_error;
using lang_test::small_model;
using lang_test::small_with;

namespace {

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
std::string ep_replace(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  REQUIRE_MESSAGE(p != std::string::npos, from);
  text.replace(p, from.size(), to);
  return text;
}

/// The message of the lang_error that building `text` (with `load`) and running
/// it with `settings` throws; empty if none was thrown.
std::string ep_error_of(const std::string& text, const pradis::lang::run_settings& settings,
                        const pradis::lang::file_loader& load = pradis::lang::read_file) {
  try {
    auto s = lang_test::build(text, load);
    s->run(settings);
  } catch (const pradis::lang::lang_error& e) {
    return e.what();
  }
  return {};
}

/// As lang_test::expect_error, with run settings and a loader of its own.
void ep_expect(const std::string& text, const std::string& where, std::initializer_list<std::string> parts,
               const pradis::lang::run_settings& settings = {.write_files = false},
               const pradis::lang::file_loader& load = pradis::lang::read_file, int line = __builtin_LINE()) {
  const std::string e = ep_error_of(text, settings, load);
  CAPTURE(line);
  CAPTURE(e);
  REQUIRE_FALSE(e.empty());
  CHECK(e.rfind("test.prd:" + where + ": error: ", 0) == 0);
  for (const auto& p : parts) CHECK(e.find(p) != std::string::npos);
}

/// A valid model with a sub-structure: fragment OSC (external node 1, a mass on
/// a spring) instantiated once as Left. Line numbers are in the comments.
const char* const ep_osc_model =
    "$FRAGMENT OSC\n"                  // 1
    "#EXTERNAL 1\n"                    // 2
    "#STRUCTURE\n"                     // 3
    "  Mass 'MASS (2; 1)\n"            // 4
    "  Spring 'SPRING (1 2; 100)\n"    // 5
    "$FRAGMENT\n"                      // 6
    "#STRUCTURE\n"                     // 7
    "  Base 'MASS (1; 5)\n"            // 8
    "  Support 'SPRING (0 1; 1000)\n"  // 9
    "  Left 'OSC (1)\n"                // 10
    "$RUN\n"                           // 11
    "  Calc 'SHTERM (END=0.01)\n"      // 12
    "$END\n";

/// ep_osc_model with the first `from` replaced by `to`.
std::string ep_osc_with(const std::string& from, const std::string& to) { return ep_replace(ep_osc_model, from, to); }

/// A chain of `levels` fragments NEST0 .. NEST<levels-1>, each instantiating the
/// next on its external node 1 (the last holds a mass), under a main model that
/// instantiates NEST0. The instance of NEST<k> (k >= 1) is on line 4 k.
std::string ep_nested_chain(int levels) {
  std::string t;
  for (int k = 0; k < levels; ++k) {
    t += "$FRAGMENT NEST" + std::to_string(k) + "\n#EXTERNAL 1\n#STRUCTURE\n";
    t += k + 1 < levels ? "  In 'NEST" + std::to_string(k + 1) + " (1)\n" : std::string("  Mass 'MASS (1; 1)\n");
  }
  t += "$FRAGMENT\n#STRUCTURE\n  Spring 'SPRING (0 1; 100)\n  Top 'NEST0 (1)\n$RUN\n  Calc 'SHTERM (END=0.01)\n$END\n";
  return t;
}

/// A 1 x 1 symmetric Matrix Market file with the entry `x`.
std::string ep_mtx(const std::string& x) { return "%%MatrixMarket matrix coordinate real symmetric\n1 1 1\n1 1 " + x + "\n"; }

/// A planar body MD whose two parameters (m, J) $REPLACE takes from
/// CRAIGBAMPTON of k.mtx and m.mtx (all DOFs on the boundary: K_r = K, M_r = M).
const char* const ep_replace_cb_model =
    "$DATA\n"                                               // 1
    "  Inertia = 1, 0.1\n"                                  // 2
    "$FRAGMENT\n"                                           // 3
    "#STRUCTURE\n"                                          // 4
    "  Disc 'MD (1 2 3; Inertia)\n"                         // 5
    "$REPLACE\n"                                            // 6
    "  Inertia = CRAIGBAMPTON(\"k.mtx\", \"m.mtx\", 0, 1)\n"  // 7
    "$RUN\n"                                                // 8
    "  Calc 'SHTERM (END=0.01)\n"                           // 9
    "$END\n";

}  // namespace

TEST_SUITE("lang/error paths") {
  TEST_CASE("a control character inside a string") {
    expect_error(std::string("$INCLUDE \"ab") + "\x01" + "c\"\n$END\n", "1:13", {"invalid character in a string"});
    expect_error(small_with("$RUN", std::string("$RESTORE \"x") + "\x7f" + "\"\n$RUN"), "13:12",
                 {"invalid character in a string"});
  }

  TEST_CASE("$DATA: a list growing beyond the limit") {
    // L0 = 1, Lk = L(k-1), L(k-1): L16 has 65536 values, L17 would have 131072 > 100000.
    std::string t = "$DATA\n  L0 = 1\n";
    for (int k = 1; k <= 17; ++k)
      t += "  L" + std::to_string(k) + " = L" + std::to_string(k - 1) + ", L" + std::to_string(k - 1) + "\n";
    const std::string model = small_model;
    t += model.substr(model.find("$FRAGMENT"));
    // L17 is on line 19; its second L16 (the one that crosses the limit) at column 14.
    expect_error(t, "19:14", {"the list grows beyond 100000 values"});
  }

  TEST_CASE("KEY=value and W:Name(k) where only numbers and $DATA names are allowed") {
    expect_error(small_with("(1; Mass)", "(1; K=2)"), "7:18",
                 {"only numbers and $DATA names are allowed in an element's parameter list"});
    expect_error(small_with("(1; Mass)", "(1; W:Spring(1))"), "7:18",
                 {"only numbers and $DATA names are allowed in an element's parameter list"});
    // The order of 'X is one number (or $DATA name).
    expect_error(small_with("(1; 1)", "(1; W:Spring(1))"), "11:19",
                 {"the order of 'X (1 displacement, 2 velocity, 3 acceleration) must be a number or a $DATA name"});
    expect_error(small_with("(1; 1)", "(1; ORDER=2)"), "11:19", {"must be a number or a $DATA name"});
  }

  TEST_CASE("argument items: a key that is not a name, a missing work-vector index, a missing value") {
    expect_error(small_with("(1; Mass)", "(1; 5=2)"), "7:18", {"expected a key name before '=', found '5'"});
    expect_error(small_with("W:Spring(1)", "W:Spring()"), "12:29",
                 {"expected the work-vector index k in W:Name(k), found ')'"});
    // A value that is not a word at all.
    expect_error(small_with("Load = 10", "Load = ;"), "4:10", {"expected a number or a name, found ';'"});
    expect_error(small_with("#STRUCTURE", "#EXTERNAL \"one\"\n#STRUCTURE"), "6:11",
                 {"expected a number or a name, found string \"one\""});
    // A word that is neither a number nor a name.
    expect_error(small_with("Load = 10", "Load = -"), "4:10", {"expected a number or a name, found '-'"});
    expect_error(small_with("(0 1; Stiffness)", "(0 1; %k)"), "8:24", {"expected a number or a name, found '%k'"});
  }

  TEST_CASE("sub-structures: duplicate names, labels, nesting, #EXTERNAL") {
    CHECK(lang_test::error_of(ep_osc_model).empty());
    // A second fragment OSC (line 6): reported there.
    expect_error(ep_osc_with("$FRAGMENT\n#STRUCTURE\n",
                             "$FRAGMENT OSC\n#EXTERNAL 1\n#STRUCTURE\n  Mass 'MASS (2; 1)\n$FRAGMENT\n#STRUCTURE\n"),
                 "6:1", {"$FRAGMENT OSC is defined twice"});
    // An instance without a label: at the statement (its "'").
    expect_error(ep_osc_with("  Left 'OSC (1)", "  'OSC (1)"), "10:3",
                 {"an instance of fragment OSC needs a label"});
    // A fragment without #EXTERNAL used as a sub-structure: at the fragment.
    expect_error(ep_osc_with("#EXTERNAL 1\n", ""), "1:1",
                 {"fragment OSC is used as a sub-structure but has no #EXTERNAL nodes"});
    // Parameters after the nodes: at the '('.
    expect_error(ep_osc_with("'OSC (1)", "'OSC (1; 2)"), "10:13",
                 {"a fragment instance takes only its external nodes: 'NAME (nodes)'"});
    // #EXTERNAL mistakes: at #EXTERNAL.
    expect_error(ep_osc_with("#EXTERNAL 1", "#EXTERNAL 0"), "2:1", {"the ground (node 0) cannot be an external node"});
    expect_error(ep_replace(ep_osc_with("#EXTERNAL 1", "#EXTERNAL 1 1"), "'OSC (1)", "'OSC (1 1)"), "2:1",
                 {"node 1 is listed twice in #EXTERNAL"});
  }

  TEST_CASE("sub-structures nested too deep") {
    // 32 levels (NEST0 .. NEST31 below the main model) build.
    CHECK_NOTHROW(lang_test::build(ep_nested_chain(32)));
    // NEST0 .. NEST32: the main model instantiates NEST0, NEST31 (the 32nd level)
    // instantiates NEST32, the 33rd, on line 4 * 32 = 128, at its name (column 7).
    expect_error(ep_nested_chain(33), "128:7", {"fragments nested more than 32 levels deep"});
    // Deeper chains stop at the same instance.
    expect_error(ep_nested_chain(40), "128:7", {"fragments nested more than 32 levels deep"});
  }

  TEST_CASE("an empty #STRUCTURE and #MAP") {
    expect_error("$FRAGMENT\n#STRUCTURE\n#OUTPUT\n  Steps 'NSTEP ()\n$RUN\n  C 'SHTERM (END=1)\n$END\n", "1:1",
                 {"the model has no elements (#STRUCTURE is empty)"});
    expect_error(small_with("#OUTPUT", "#MAP\n#OUTPUT"), "10:1", {"subsection #MAP is not implemented by pradis yet"});
    expect_error(small_with("#OUTPUT", "# MAP:\n#OUTPUT"), "10:1", {"subsection #MAP is not implemented"});
  }

  TEST_CASE("#OUTPUT: wrong arguments of 'X, 'W, 'LQ and the statistics") {
    expect_error(small_with("'X (1; 1)", "'X (1 2; 1)"), "11:15", {"'X needs (node; order) or (W:Element(k); 1)"});
    expect_error(small_with("'X (1; 1)", "'X"), "11:13", {"'X needs (node; order)"});
    expect_error(small_with("'X (1; 1)", "'W (0 0 0; 1)"), "11:16",
                 {"nodes 0 0 0 are the ground, not a spatial rotational node"});
    expect_error(small_with("'X (1; 1)", "'LQ (0 0 0)"), "11:17", {"nodes 0 0 0 are the ground"});
    expect_error(small_with("'X (1; 1)", "'NSTEP (1)"), "11:19", {"'NSTEP takes no arguments: 'NSTEP ()"});
    expect_error(small_with("'X (1; 1)", "'NITER (; )"), "11:19", {"'NITER takes no arguments"});
  }

  TEST_CASE("more outputs than the limit") {
    // 10001 statistics outputs, one a line from line 11: the last (line 10011) is one too many.
    std::string outs;
    for (int k = 1; k <= 10001; ++k) outs += "  Out " + std::to_string(k) + " 'NSTEP ()\n";
    expect_error(small_with("  Position 'X (1; 1)\n  Spring force 'X (W:Spring(1); 1)\n", outs), "10011:3",
                 {"more than 10000 outputs"});
  }

  TEST_CASE("$REPLACE without definitions") {
    expect_error(small_with("$END", "$REPLACE\n$END"), "15:1", {"$REPLACE without any `Name = values` line"});
    expect_error(small_with("$RUN", "$REPLACE:\n\n$RUN"), "13:1", {"$REPLACE without any"});
  }

  TEST_CASE("CRAIGBAMPTON whose reduction overflows; a reduction near the largest double") {
    // K = [[1E308, 1E308], [1E308, 1]] with DOF 1 on the boundary: K_r = K_11 - K_12^2 / K_22
    // overflows to -inf. The reduction refuses it at the call (line 7, column 13), so no
    // non-finite number reaches $REPLACE (whose own check, "$REPLACE gives ... a non-finite
    // parameter", is then a guard that no input reaches).
    const std::string k2 = "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 1E308\n2 1 1E308\n2 2 1\n";
    const std::string m2 = "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1\n2 2 1\n";
    const auto bad = lang_test::memory_loader({{"k.mtx", k2}, {"m.mtx", m2}});
    ep_expect(ep_replace_cb_model, "7:13", {"CRAIGBAMPTON cannot reduce", "not finite"}, {.write_files = false}, bad);
    // With a moderate K the same $REPLACE is accepted and the stage runs (a finite K
    // near the largest double: tests/linalg/test_reduction.cpp).
    const auto good = lang_test::memory_loader({{"k.mtx", ep_mtx("2")}, {"m.mtx", ep_mtx("1")}});
    CHECK(ep_error_of(ep_replace_cb_model, {.write_files = false}, good).empty());
  }

  TEST_CASE("an empty output directory name is refused before anything runs") {
    auto s = lang_test::build(small_model);
    bool thrown = false;
    try {
      s->run({.output_dir = ""});
    } catch (const pradis::lang::lang_error&) {
      FAIL("a lang_error: the output directory is not part of the model file");
    } catch (const pradis::error& e) {
      thrown = true;
      CHECK(e.code() == pradis::error_code::io_error);
      CHECK(e.message() == "the output directory name is empty");
    }
    CHECK(thrown);
    CHECK(s->results().rows() == 0);
    CHECK(s->files().empty());
  }

  TEST_CASE("checkpoints that cannot be written or read") {
    const auto dir = lang_test::scratch_dir("error_paths");
    const pradis::lang::run_settings quiet{.output_dir = dir.string(), .write_files = false};

    // $SAVE into a directory that does not exist: the file cannot be opened.
    const std::string missing = (dir / "missing" / "half.chk").string();
    ep_expect(small_with("$END", "$SAVE \"missing/half.chk\"\n$END"), "15:1",
              {"cannot write the checkpoint '" + missing + "'", "No such file or directory"}, quiet);

    // The SAVE key's checkpoint <stem>.t0.05.chk, where a directory of that name is.
    std::filesystem::create_directories(dir / "model.t0.05.chk");
    ep_expect(small_with("SMAX=1E-3)", "SMAX=1E-3, SAVE=0.05)"), "14:3",
              {"cannot write the checkpoint '" + (dir / "model.t0.05.chk").string() + "'"},
              {.output_dir = dir.string(), .plot = false});
    CHECK(std::filesystem::exists(dir / "model.csv"));  // the rows up to the failure are kept

    // $SAVE to a full device: opening succeeds, the write fails when the file is closed.
    if (std::filesystem::exists("/dev/full")) {
      ep_expect(small_with("$END", "$SAVE \"/dev/full\"\n$END"), "15:1",
                {"cannot write the checkpoint '/dev/full'", "No space left on device"}, quiet);
    } else {
      MESSAGE("no /dev/full: the failed close of a checkpoint is not checked");
    }

    // $RESTORE of a file that does not exist.
    ep_expect(small_with("$RUN", "$RESTORE \"absent.chk\"\n$RUN"), "13:1",
              {"cannot read the checkpoint '" + (dir / "absent.chk").string() + "'", "No such file or directory"},
              quiet);
    std::filesystem::remove_all(dir);
  }
}
