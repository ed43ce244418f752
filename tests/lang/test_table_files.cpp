// FILE("table.csv") in $DATA: a value list read from a two-column table file
// (io::parse_table_csv), used by TSPRING; errors point into the table file
// (file:line:column) or at the FILE call; the example model
// examples/models/tabular_spring.prd settles at the analytic deflection.

#include <cmath>
#include <numbers>

#include "lang_test_support.hpp"

using namespace pradis;
using lang_test::error_of;
using lang_test::memory_loader;

namespace {
// A mass on a TSPRING whose table is FILE("<name>"), released from 0.2 m.
std::string model_with(const std::string& curve) {
  return "$DATA\n"
         "  Curve = " + curve + "\n"
         "$FRAGMENT\n"
         "#STRUCTURE\n"
         "  Body 'MASS (1; 0.5)\n"
         "  Spring 'TSPRING (1 0; 0, 0, Curve)\n"
         "  Start 'X0 (1; 0.2)\n"
         "#OUTPUT\n"
         "  Position 'X (1; 1)\n"
         "$RUN\n"
         "  Calc 'NEWMARK (END=0.25, OUT=1E-3, SMAX=1E-3)\n"
         "$END\n";
}
std::string run_error(const std::string& curve, const std::map<std::string, std::string>& files) {
  return error_of(model_with(curve), memory_loader(files));
}
}  // namespace

TEST_SUITE("lang/table files") {
  TEST_CASE("FILE(\"...\") expands to the table's pairs; a linear table gives the period 2 pi sqrt(m/k)") {
    // Table of f = 200 d (m = 0.5: w = 20 rad/s); linear interpolation of a
    // linear law is exact, so the run is the linear oscillator under the
    // trapezoidal rule (period error (w h)^2 / 12 = 3e-5): the first minimum is
    // at half a period, pi / w, to the output grid h = 1e-3, and its value is
    // -0.2 to 0.2 (1 - cos(w h / 2)) = 1e-5.
    const auto s = lang_test::build(model_with("FILE(\"curve.csv\")"),
                                    memory_loader({{"curve.csv", "d, F\n-0.3, -60\n0, 0\n0.3, 60\n"}}));
    s->run({.write_files = false});
    const auto& t = s->results();
    std::size_t rmin = 0;
    for (std::size_t r = 0; r < t.rows(); ++r)
      if (t.at(r, 1) < t.at(rmin, 1)) rmin = r;
    CHECK(std::abs(t.at(rmin, 0) - std::numbers::pi / 20) <= 0.5e-3 + 1e-5);
    CHECK(t.at(rmin, 1) == doctest::Approx(-0.2).epsilon(1e-4));
  }

  TEST_CASE("FILE may stand among other values and in $REPLACE") {
    // Curve = 0, 0, FILE(...) gives the same 2 + 6 values; mode and damping as numbers before it.
    const std::string text = lang_test::small_with("  Spring 'SPRING (0 1; Stiffness)",
                                                   "  Spring 'TSPRING (0 1; Curve)");
    std::string model = text;
    model.replace(model.find("  Mass = 2"), 10, "  Mass = 2\n  Curve = 1, 0.5, FILE(\"t.csv\")");
    const auto s = lang_test::build(model, memory_loader({{"t.csv", "0 0\n0.1 10\n0.2 20\n"}}));
    CHECK_NOTHROW(s->run({.write_files = false}));
  }

  TEST_CASE("a bad table file is reported at its line and column, naming the FILE call") {
    const std::string e = run_error("FILE(\"c.csv\")", {{"c.csv", "d,F\n0,0\n0.1,abc\n"}});
    CHECK(e.rfind("c.csv:3:5: error: 'abc' is not a finite number (in the table file read by FILE at test.prd:2:11)",
                  0) == 0);
    const std::string cols = run_error("FILE(\"c.csv\")", {{"c.csv", "0 0\n0.1 1 2\n"}});
    CHECK(cols.rfind("c.csv:2:7: error: expected 2 columns (x, y), found 3", 0) == 0);
    const std::string empty = run_error("FILE(\"c.csv\")", {{"c.csv", "# nothing\n"}});
    CHECK(empty.rfind("test.prd:2:16: error: the table file has no data lines", 0) == 0);
  }

  TEST_CASE("FILE mistakes in the model: missing file, no string, no ')', empty name") {
    CHECK(run_error("FILE(\"none.csv\")", {}).rfind("test.prd:2:16: error: cannot read the table file 'none.csv'", 0) ==
          0);
    CHECK(run_error("FILE(curve)", {}).rfind("test.prd:2:16: error: FILE needs a file name in double quotes", 0) == 0);
    CHECK(run_error("FILE(\"c.csv\"", {{"c.csv", "0 0\n1 1\n"}})
              .rfind("test.prd:2:23: error: expected ')' after the file name of FILE", 0) == 0);
    CHECK(run_error("FILE(\"\")", {}).rfind("test.prd:2:16: error: FILE with an empty file name", 0) == 0);
    // A table that is read but bad for the element: code 100 at the element's line.
    const std::string e = run_error("FILE(\"c.csv\")", {{"c.csv", "0 0\n0.3 1\n0.2 2\n"}});
    CHECK(e.find("deformation 3 (0.2) is not above deformation 2 (0.3)") != std::string::npos);
    CHECK(e.rfind("test.prd:6:", 0) == 0);
  }

  TEST_CASE("examples/models/tabular_spring.prd settles at the root of 100 d + 10000 d^3 = 15") {
    auto s = std::make_unique<lang::session>(
        lang::parse_file((lang_test::models_dir() / "tabular_spring.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    // Cardano: d^3 + p d - q = 0, p = 0.01, q = 0.0015.
    const double p = 0.01, q = 0.0015, r = std::sqrt(q * q / 4 + p * p * p / 27);
    const double d = std::cbrt(q / 2 + r) + std::cbrt(q / 2 - r);
    // PCHIP with 30 segments of 10 mm: deflection error below 1e-4 (the h^3
    // convergence measured in tests/elements/test_table_spring.cpp gives 3.1e-5
    // for 32 segments of 9.4 mm on the same law).
    CHECK(std::abs(t.at(t.rows() - 1, 1) - d) < 1e-4);
    CHECK(t.at(t.rows() - 1, 2) == doctest::Approx(15.0).epsilon(1e-6));  // spring force = load at rest
  }
}
