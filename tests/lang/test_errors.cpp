// Errors in model files: every kind of mistake gives `file:line:column: error:
// message` naming the offending text, never a crash or a hang.

#include <random>

#include "lang_test_support.hpp"

using lang_test::error_of;
using lang_test::small_model;
using lang_test::small_with;

using lang_test::expect_error;

TEST_SUITE("lang/errors") {
  TEST_CASE("the small model itself is valid") { CHECK(error_of(small_model).empty()); }

  TEST_CASE("unknown names suggest the nearest known name") {
    expect_error(small_with("'MASS (1", "'MAS (1"), "7:9", {"unknown element model 'MAS'", "did you mean 'MASS'?"});
    expect_error(small_with("'SPRING (0 1", "'SPRNIG (0 1"), "8:11", {"'SPRNIG'", "did you mean 'SPRING'?"});
    expect_error(small_with("'SHTERM", "'SHTERN"), "14:9", {"unknown integration program 'SHTERN'", "'SHTERM'"});
    expect_error(small_with("'X (1; 1)", "'XX (1; 1)"), "11:13", {"unknown output program 'XX'", "did you mean 'X'?"});
    expect_error(small_with("$END", "$PRINT\n  P 'DSIP ()\n$END"), "16:6", {"unknown display program 'DSIP'", "'DISP'"});
    expect_error(small_with("$RUN", "$RUNN"), "13:1", {"unknown section $RUNN", "did you mean 'RUN'?"});
    expect_error(small_with("#OUTPUT", "#OUTPT"), "10:1", {"unknown subsection #OUTPT", "'OUTPUT'"});
    // A program used in the wrong section is named as such.
    expect_error(small_with("'MASS (1; Mass)", "'X (1; 1)"), "7:9", {"'X' is an output program"});
    expect_error(small_with("'X (1; 1)", "'MASS (1; 1)"), "11:13", {"'MASS' is an element model"});
  }

  TEST_CASE("wrong number of nodes names EXT") {
    expect_error(small_with("'SPRING (0 1;", "'SPRING (1;"), "8:19", {"'SPRING' needs 2 nodes (EXT = 2), got 1"});
    expect_error(small_with("'MASS (1;", "'MASS (1 2;"), "7:15", {"'MASS' needs 1 node (EXT = 1), got 2"});
  }

  TEST_CASE("a parameter count breaking PAR/VPR reports the rule") {
    expect_error(small_with("(1; Mass)", "(1; Mass, 3)"), "7:18",
           {"'MASS' takes exactly PAR = 1 parameter", "VPR = 0", "got 2 after expanding $DATA lists"});
    expect_error(small_with("Mass = 2", "Mass = 2, 3"), "7:18", {"got 2"});  // a list expands in place
    expect_error(small_with("(1; Mass)", "(1)"), "7:14", {"(nodes; parameters)", "no ';'"});
  }

  TEST_CASE("undefined $DATA names, duplicates and bad definitions") {
    expect_error(small_with("(0 1; Stiffness)", "(0 1; Stifness)"), "8:24",
           {"undefined $DATA name 'Stifness'", "did you mean 'Stiffness'?"});
    expect_error(small_with("Load = 10", "Load = 10\n  Mass = 3"), "5:3", {"'Mass' is already defined at test.prd:2:3"});
    expect_error(small_with("Load = 10", "Load = Weight"), "4:10", {"undefined $DATA name 'Weight'"});
    expect_error(small_with("Load = 10", "Load ="), "4:9", {"expected a value after '='"});
    expect_error(small_with("Load = 10", "Load = 10,"), "5:1", {"expected a value"});
    expect_error(small_with("Load = 10", "Load 10"), "4:10", {"expected a name followed by '='"});
  }

  TEST_CASE("unparsable numbers") {
    expect_error(small_with("Load = 10", "Load = 1.2.3"), "4:10", {"unparsable number '1.2.3'"});
    expect_error(small_with("Load = 10", "Load = 5x"), "4:10", {"unparsable number '5x'"});
    expect_error(small_with("Load = 10", "Load = 1E"), "4:10", {"unparsable number '1E'"});
    expect_error(small_with("Load = 10", "Load = 1E999"), "4:10", {"unparsable number '1E999'"});
    expect_error(small_with("END=0.1", "END=0.1s"), "14:21", {"unparsable number '0.1s'"});
    expect_error(small_with("(1; 1)", "(1.5; 1)"), "11:16", {"a node must be a whole number"});
    expect_error(small_with("(1; 1)", "(1; 4)"), "11:19", {"order of 'X", "got 4"});
  }

  TEST_CASE("missing sections and a truncated file") {
    expect_error("$DATA\n  A = 1\n$END\n", "3:1", {"missing section $FRAGMENT"});
    expect_error("$FRAGMENT\n#OUTPUT\n  P 'X (1; 1)\n$RUN\n  C 'SHTERM (END=1)\n$END\n", "1:1",
           {"$FRAGMENT has no #STRUCTURE subsection"});
    expect_error(small_with("$RUN\n  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n", ""), "13:1", {"missing section $RUN"});
    expect_error(small_with("$END\n", ""), "15:1", {"missing $END", "truncated"});
    // Cut in the middle of a statement: the '(' without ')' is named.
    std::string cut = small_model;
    cut = cut.substr(0, cut.find("Stiffness)"));
    expect_error(cut, "8:18", {"missing ')' for this '('"});
    expect_error(small_with("(0 1; Stiffness)", "(0 1; Stiffness"), "8:18", {"missing ')'", "a new statement starts at 9:8"});
    expect_error(small_with("END=0.1, SMAX=1E-3)", "END=0.1, SMAX=1E-3"), "14:16", {"missing ')'"});
    expect_error("", "1:1", {"missing $END"});
    expect_error("$END", "1:1", {"missing section $FRAGMENT"});
  }

  TEST_CASE("outputs naming a non-existent element, work entry or node") {
    expect_error(small_with("W:Spring(1)", "W:Sprung(1)"), "12:20", {"no element named 'Sprung'", "did you mean 'Spring'?"});
    expect_error(small_with("W:Spring(1)", "W:Spring(2)"), "12:29",
           {"'Spring' (SPRING) has 1 work-vector entry; W:Spring(2) does not exist"});
    expect_error(small_with("W:Spring(1)", "W:Spring(0)"), "12:29", {"whole number >= 1"});
    // Found by the fuzzer (fuzz/regressions/crash-7425a366...): a huge index was cast to int (UB).
    expect_error(small_with("W:Spring(1)", "W:Spring(8.9E69)"), "12:29", {"whole number >= 1"});
    expect_error(small_with("W:Spring(1)", "W:Spring(2.5)"), "12:29", {"whole number >= 1"});
    expect_error(small_with("(1; 1)", "(7; 1)"), "11:16", {"node 7 is not connected to any element"});
    expect_error(small_with("(1; 1)", "(0; 1)"), "11:16", {"node 0 is the ground"});
    expect_error(small_with("(W:Spring(1); 1)", "(W:Spring(1); 2)"), "12:33", {"only order 1"});
    expect_error(small_with("Position 'X", "Spring force 'X"), "12:3",
           {"'Spring force' is already defined at test.prd:11:3"});
  }

  TEST_CASE("integration keys: unimplemented, unknown, duplicated, missing END, bad values") {
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, WEIGHT=0.05"), "14:37",
           {"key WEIGHT of SHTERM is not implemented by pradis yet", "implemented: END OUT SMAX"});
    for (const char* bad : {"OPTIM=5", "OPTIM=-1", "OPTIM=2.5"})
      expect_error(small_with("SMAX=1E-3", std::string("SMAX=1E-3, ") + bad), "14:43",
             {"OPTIM must be a whole number from 0 to 4"});
    expect_error(small_with("SMAX=1E-3", "SMAXX=1E-3"), "14:26", {"unknown key SMAXX of SHTERM", "did you mean 'SMAX'?"});
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, SMAX=2"), "14:37", {"key SMAX is given twice"});
    expect_error(small_with("END=0.1, ", ""), "14:16", {"SHTERM needs END="});
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, BETA=0.3"), "14:37", {"BETA belongs to NEWMARK"});
    expect_error(small_with("'SHTERM (", "'NEWMARK (BETA=0.9, "), "14:17", {"beta", "outside its valid range"});
    expect_error(small_with("SMAX=1E-3", "SMAX=-1"), "14:3", {"SHTERM: SMAX = -1 must be > 0"});
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, ITR=0"), "14:41", {"ITR must be a whole number from 1"});
    expect_error(small_with("SMAX=1E-3", "SMAX=1E-3, IGNORE=2"), "14:44", {"IGNORE must be a whole number from 0 to 1"});
    expect_error(small_with("(END=0.1, SMAX=1E-3)", "(END=0.1, SMAX=1E-3)\n  Again 'SHTERM (END=0.05)"), "15:17",
           {"END = 0.05 must be after the current time 0.1"});
    expect_error(small_with("END=0.1", "END=Mass, Load"), "14:27", {"KEY=value"});
  }

  TEST_CASE("errors the elements report during the run are located at the element") {
    expect_error(small_with("Mass = 2", "Mass = -2"), "7:3",
           {"MASS 'Body'", "mass m = -2", "pradis error 100", "during the stage at test.prd:14:3"});
  }

  TEST_CASE("lexical errors: binary bytes, strings, stray characters") {
    expect_error(std::string("$DATA\n  A = 1\x01\n$END\n"), "2:8",
           {"invalid character (byte 1)", "not look like a text file"});
    expect_error(std::string("\x7f"
                       "ELF\x02\x01\x01\x00\x00",
                       9),
           "1:1", {"invalid character (byte 127)"});
    expect_error("$INCLUDE \"abc\n$END\n", "1:10", {"unterminated string"});
    expect_error("$ DATA\n$END\n", "1:1", {"expected a section keyword after '$'"});
    expect_error("Hello\n$END\n", "1:1", {"expected a section ($DATA, $FRAGMENT, $RUN, ...), found 'Hello'"});
    expect_error("#STRUCTURE\n$END\n", "1:1", {"subsection #STRUCTURE outside $FRAGMENT"});
    expect_error(small_with("Body 'MASS", "Body MASS"), "7:13",
           {"expected \"'\" and a model or program name after 'Body MASS'"});
    expect_error(small_with("Body 'MASS (1; Mass)", "Body 'MASS (1; Mass) extra"), "7:24", {"unexpected 'extra'"});
  }

  TEST_CASE("sections in the wrong place, $REPLACE, $INCLUDE, $SAVE and $RESTORE mistakes") {
    expect_error(small_with("$END", "$DATA\n  B = 1\n$END"), "15:1", {"section $DATA after $RUN"});
    expect_error(small_with("$END", "$REPLACE\n  Mas = 3\n$END"), "16:3",
           {"$REPLACE of an undefined $DATA name 'Mas'", "'Mass'"});
    expect_error(small_with("$END", "$REPLACE\n  Mass = 3, 4\n$RUN\n  C 'SHTERM (END=0.2)\n$END"), "15:1",
           {"$REPLACE changes the number of parameters of 'Body' from 1 to 2"});
    expect_error(small_with("$END", "$INCLUDE \"nowhere.prd\"\n$END"), "15:1",
           {"cannot read the included file 'nowhere.prd'"});
    expect_error(small_with("$END", "$INCLUDE\n$END"), "16:1", {"$INCLUDE needs a file name in double quotes"});
    expect_error(small_with("$RUN", "$SAVE \"x.ckp\"\n$RUN"), "13:1", {"$SAVE before any stage has run"});
    expect_error(small_with("$END", "$SHOW\n$END"), "15:1", {"section $SHOW is not implemented by pradis yet"});
  }

  TEST_CASE("recursive $INCLUDE stops with an error") {
    const auto load = lang_test::memory_loader({{"self.prd", "$INCLUDE \"self.prd\"\n"}});
    const std::string e = error_of("$INCLUDE \"self.prd\"\n$END\n", load);
    CHECK(e.find("nested more than 16 levels deep") != std::string::npos);
  }

  TEST_CASE("every message comes with the offending line and a caret") {
    try {
      lang_test::build(small_with("(0 1; Stiffness)", "(0 1; Stifness)"));
      FAIL("no error");
    } catch (const pradis::lang::lang_error& e) {
      CHECK(e.excerpt() == " 8 |   Spring 'SPRING (0 1; Stifness)\n   |                        ^\n");
      CHECK(e.where().line == 8);
      CHECK(e.where().col == 24);
    }
  }

  TEST_CASE("random bytes and random mutations of a valid model never crash or hang") {
    std::mt19937 rng(2024);
    std::uniform_int_distribution<int> byte(0, 255);
    int errors = 0;
    for (int trial = 0; trial < 300; ++trial) {
      std::string text;
      if (trial < 100) {
        text.resize(static_cast<std::size_t>(byte(rng)));
        for (char& c : text) c = static_cast<char>(byte(rng));
      } else {
        // Mutate the valid model: replace, delete or insert a few characters, mostly printable.
        text = small_model;
        std::uniform_int_distribution<std::size_t> pos(0, text.size() - 1);
        const int edits = 1 + trial % 4;
        static const std::string alphabet = "$#'(),;:=*/\" \n0123456789.-+EeDdWXABCSHTRMNkmz";
        std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
        for (int k = 0; k < edits && !text.empty(); ++k) {
          const std::size_t p = pos(rng) % text.size();
          const int op = byte(rng) % 3;
          if (op == 0)
            text[p] = alphabet[pick(rng)];
          else if (op == 1)
            text.erase(p, 1 + static_cast<std::size_t>(byte(rng) % 8));
          else
            text.insert(p, 1, alphabet[pick(rng)]);
        }
      }
      CAPTURE(text);
      try {
        // Build only: a mutated END or SMAX could make a valid run arbitrarily long.
        (void)lang_test::build(text, lang_test::memory_loader({}));
      } catch (const pradis::lang::lang_error&) {
        ++errors;
      }
    }
    CHECK(errors > 150);
  }
}
