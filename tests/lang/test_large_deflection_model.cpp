// examples/models/large_deflection.prd: BEAM3C in the model language. A cantilever of two BEAM3C (eight condensed
// corotational segments in all) under a dead tip load ramped to P L^2 / (E I) = 3 against the elastica
// (tests/testing/elastica.hpp, checked there against Bisshopp and Drucker, Q. Appl. Math. 3 (1945) 272).

#include <cmath>
#include <memory>

#include "lang_test_support.hpp"
#include "testing/elastica.hpp"

using namespace pradis;

TEST_SUITE("lang/large deflection") {
  TEST_CASE("examples/models/large_deflection.prd: the tip of two BEAM3C follows the elastica at P L^2 / EI = 3") {
    auto s =
        std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "large_deflection.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t x = lang_test::column(t, "Tip X"), y = lang_test::column(t, "Tip Y"),
                      its = lang_test::column(t, "Condensation iterations");
    const std::size_t last = t.rows() - 1;
    REQUIRE(t.at(last, 0) == doctest::Approx(1.0));
    const auto ref = pradis_test::elastica_tip(3.0);
    const double tip_x = 1 + t.at(last, x), tip_y = t.at(last, y);
    const double err = std::hypot(tip_x - ref[0], tip_y - ref[1]);
    MESSAGE("tip (", tip_x, ", ", tip_y, "), elastica (", ref[0], ", ", ref[1], "), distance ", err,
            "; condensation iterations in the last call ", t.at(last, its));
    // Eight segments: the discretisation error of tests/elements/test_condensed_beam.cpp (9.0e-4 L at N = 8), which
    // falls as 1/N^2.
    CHECK(err < 1.5e-3);
    CHECK(t.at(last, its) >= 1);
    CHECK(t.at(last, its) <= 30);
  }
}
