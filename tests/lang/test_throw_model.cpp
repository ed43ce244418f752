// examples/models/crank_throw.prd and crank_throw_rod.prd: the super-elements THROW and THROWP in the model
// language. Invariant (docs/super-elements.md): a super-element kept without condensation is the same set of
// nodal equations as its parts written out, so the file with its THROW (THROWP) line replaced by the eight
// BEAM3/BEAMI3 lines of the same throw (inner nodes as user DOFs, as in examples/models/crankshaft.prd; THROWP's
// external pin middle is the node 41..46 of both) moves the same to round-off.

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {

std::string throw_file(const std::string& name = "crank_throw.prd") {
  return lang_test::slurp(lang_test::models_dir() / name);
}

/// The text with the line starting with `from` (up to its end) replaced by `to`.
std::string replace_line(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  REQUIRE_MESSAGE(p != std::string::npos, from);
  s.replace(p, s.find('\n', p) - p, to);
  return s;
}

const char* const expanded_lines[8] = {
    "    Front web 'BEAM3 (0 0 0 0 0 0 31 32 33 34 35 36; Steel, Web section, Front web geometry)",
    "    Front web mass 'BEAMI3 (0 0 0 0 0 0 31 32 33 34 35 36; Density, Web mass section, Front web geometry)",
    "    Pin front 'BEAM3 (31 32 33 34 35 36 41 42 43 44 45 46; Steel, Pin section, Pin front geometry)",
    "    Pin front mass 'BEAMI3 (31 32 33 34 35 36 41 42 43 44 45 46; Density, Pin mass section, Pin front geometry)",
    "    Pin rear 'BEAM3 (41 42 43 44 45 46 51 52 53 54 55 56; Steel, Pin section, Pin rear geometry)",
    "    Pin rear mass 'BEAMI3 (41 42 43 44 45 46 51 52 53 54 55 56; Density, Pin mass section, Pin rear geometry)",
    "    Rear web 'BEAM3 (51 52 53 54 55 56 61 62 63 64 65 66; Steel, Web section, Rear web geometry)",
    "    Rear web mass 'BEAMI3 (51 52 53 54 55 56 61 62 63 64 65 66; Density, Web mass section, Rear web geometry)"};

/// The model file `name` with its THROW (THROWP) written out as its parts, in part order or reversed.
std::string expanded(const std::string& name, bool reversed) {
  std::string lines;
  for (int i = 0; i < 8; ++i) lines += std::string(expanded_lines[reversed ? 7 - i : i]) + (i < 7 ? "\n" : "");
  std::string s = replace_line(throw_file(name), "    Throw 'THROW", lines);
  return replace_line(s, "    Front web energy", "    Front web energy 'X (W:Front web(3); 1)");
}

/// Largest difference between two results tables, per output relative to the largest magnitude of that output
/// in `b`, over every output and row.
double max_difference(const io::table& a, const io::table& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.names() == b.names());
  double d = 0;
  for (std::size_t c = 1; c <= a.names().size(); ++c) {
    double m = 0, dc = 0;
    for (std::size_t r = 0; r < a.rows(); ++r) {
      m = std::max(m, std::abs(b.at(r, c)));
      dc = std::max(dc, std::abs(a.at(r, c) - b.at(r, c)));
    }
    REQUIRE(m > 0);
    d = std::max(d, dc / m);
  }
  return d;
}

}  // namespace

TEST_SUITE("lang/throw") {
  TEST_CASE("examples/models/crank_throw.prd and crank_throw_rod.prd: THROW and THROWP (with a connecting rod on "
            "its pin middle) move as their eight parts written out, to round-off") {
    for (const std::string name : {"crank_throw.prd", "crank_throw_rod.prd"}) {
      CAPTURE(name);
      auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / name).string()));
      s->run({.write_files = false});
      const auto fwd = lang_test::run(expanded(name, false));
      const auto rev = lang_test::run(expanded(name, true));
      const io::table& t = s->results();
      REQUIRE(t.rows() == 21);
      const double d_throw = max_difference(t, fwd->results()), d_rev = max_difference(rev->results(), fwd->results());
      INFO("relative difference to the expanded file ", d_throw, ", reversed - expanded ", d_rev);
      MESSAGE(name, ": relative difference to the expanded file ", d_throw, ", reversed - expanded ", d_rev);
      // Only the summation order and the DOF numbering (hence the sparse ordering) differ: round-off. The floor
      // is what the expanded file with its lines reversed (nothing else changed) shows; the super-element must
      // stay within twice that floor, each output's difference relative to that output's largest magnitude over
      // the run (tests/elements/test_composite.cpp explains the magnitudes).
      CHECK(d_throw <= 2 * std::max(d_rev, 1e-15));
      CHECK(d_throw <= 1e-10);
      // The front web's strain energy, from the super-element's work vector and from the BEAM3's.
      const std::size_t e = lang_test::column(t, "Front web energy");
      CHECK(t.at(t.rows() - 1, e) > 0);
      if (name == "crank_throw_rod.prd") {
        // The rod acts on P: its tension, from SD3's work vector, is not zero.
        const std::size_t r = lang_test::column(t, "Rod tension");
        double tmax = 0;
        for (std::size_t i = 0; i < t.rows(); ++i) tmax = std::max(tmax, std::abs(t.at(i, r)));
        MESSAGE("largest rod tension ", tmax, " N");
        CHECK(tmax > 100);
      }
    }
  }

  TEST_CASE("THROW in a model file: a wrong parameter count is located, a bad part parameter is 100 naming the part") {
    const std::string text = throw_file();
    const std::string short_list = replace_line(text, "    Throw 'THROW",
                                                "    Throw 'THROW (0 0 0 0 0 0 61 62 63 64 65 66; Steel, Web section, "
                                                "Front web geometry)");
    const std::string e101 = lang_test::error_of(short_list);
    INFO(e101);
    // The language checks the count against the passport before placing the element.
    CHECK(e101.find("test.prd:26:") != std::string::npos);
    CHECK(e101.find("'THROW' takes exactly PAR = 116 parameters") != std::string::npos);
    CHECK(e101.find("got 15") != std::string::npos);
    const std::string bad =
        replace_line(text, "    Pin section =", "    Pin section = 0.00159043, -2.01289E-07, 2.01289E-07, 4.02578E-07");
    const std::string e100 = lang_test::error_of(bad);
    INFO(e100);
    CHECK(e100.find("100") != std::string::npos);
    CHECK(e100.find("THROW 'Throw'") != std::string::npos);
    CHECK(e100.find("part 3 'BEAM3' (pin front), parameters 30..44 of THROW: "
                    "second moments of area Iy = -2.01289e-07") != std::string::npos);
  }
}
