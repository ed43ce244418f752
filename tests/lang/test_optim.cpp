// The OPTIM key of the integration programs: the ordering level of the sparse
// elimination per stage (pradis-methods.md section 6; docs/sparse.md). Every
// level solves the same equations, so the results agree to round-off; the
// level actually used is checked through the solver's permutation. Bad OPTIM
// values are tested with the other key errors in test_errors.cpp.

#include <cmath>
#include <string>

#include "lang_test_support.hpp"
#include "pradis/pradis.hpp"

using namespace pradis;

namespace {

/// A chain of 8 masses on springs, the first pulled by a force; stages `stages`.
std::string chain(const std::string& stages) {
  std::string s =
      "$FRAGMENT\n"
      "#STRUCTURE\n"
      "  Pull 'F (1; 5)\n";
  for (int i = 1; i <= 8; ++i) {
    const std::string n = std::to_string(i), prev = std::to_string(i - 1);
    s += "  Body" + n + " 'MASS (" + n + "; 1)\n";
    s += "  Spring" + n + " 'SPRING (" + prev + " " + n + "; " + std::to_string(100 * i) + ")\n";
    s += "  Damper" + n + " 'DAMPER (" + prev + " " + n + "; 0.5)\n";
  }
  s += "#OUTPUT\n  First 'X (1; 1)\n  Last 'X (8; 1)\n$RUN\n" + stages + "$END\n";
  return s;
}

}  // namespace

TEST_SUITE("lang/optim") {
  TEST_CASE("OPTIM=0..4 selects the ordering level; all levels give the same motion to round-off") {
    auto ref = lang_test::run(chain("  Calc 'NEWMARK (END=0.5, SMAX=1E-3, OUT=0.05)\n"));
    // Without OPTIM the level is chosen by size (8 DOFs: level 1).
    CHECK(ref->simulation_ptr()->solver().ordering().level == -1);
    CHECK(ref->simulation_ptr()->solver().ordering().effective_level(8) == linalg::automatic_level(8));
    for (int level = 0; level <= 4; ++level) {
      CAPTURE(level);
      auto s = lang_test::run(chain("  Calc 'NEWMARK (END=0.5, SMAX=1E-3, OUT=0.05, OPTIM=" + std::to_string(level) +
                                    ")\n"));
      const auto& sim = *s->simulation_ptr();
      CHECK(sim.solver().ordering().level == level);
      // The solver's pivot order is the one of that level's policy on the model's pattern.
      CHECK(sim.solver().permutation() == linalg::ordering_for_level(level)(sim.get_assembler().pattern()));
      REQUIRE(s->results().rows() == ref->results().rows());
      for (std::size_t r = 0; r < ref->results().rows(); ++r)
        for (std::size_t c = 1; c <= 2; ++c)
          CHECK(std::abs(s->results().at(r, c) - ref->results().at(r, c)) <=
                1e-12 * (1.0 + std::abs(ref->results().at(r, c))));
    }
  }

  TEST_CASE("OPTIM holds for its stage only: a later stage without it returns to the choice by size") {
    auto s = lang_test::run(chain("  One 'NEWMARK (END=0.1, SMAX=1E-3, OPTIM=4)\n"
                                  "  Two 'SHTERM (END=0.2, SMAX=1E-3)\n"));
    const auto& sim = *s->simulation_ptr();
    CHECK(sim.solver().ordering().level == -1);
    CHECK(sim.solver().permutation() == linalg::automatic_ordering{}(sim.get_assembler().pattern()));
    CHECK(sim.time() == 0.2);
  }
}
