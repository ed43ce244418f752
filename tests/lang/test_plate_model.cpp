// examples/models/plate_strip.prd through the model language: two TRIPL by their
// catalog name, an end moment on a side rotation; the strip bends into the exact
// constant-curvature field w = a x^2 / 2 - nu a y^2 / 2, a = -P / (b D (1 - nu^2))
// (pure bending of a plate strip with free long edges: Timoshenko and
// Woinowsky-Krieger, Theory of Plates and Shells, section 2 (anticlastic
// curvature); Morley's triangle represents it exactly: its patch test,
// tests/spatial/test_plate.cpp).

#include <doctest/doctest.h>

#include <cmath>

#include "lang_test_support.hpp"

using namespace pradis;

TEST_SUITE("lang/plate") {
  TEST_CASE("the plate strip model file bends into the exact anticlastic constant-curvature field") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "plate_strip.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const double e = 2.1e11, nu = 0.3, h = 0.01, l = 1, b = 0.5, p = 10;
    const double d = e * h * h * h / (12 * (1 - nu * nu)), a = -p / (b * d * (1 - nu * nu)), c = -nu * a;
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, 0) == doctest::Approx(1.0));
    const auto near = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::abs(y); };
    CHECK(near(t.at(last, lang_test::column(t, "Deflection 2")), a * l * l / 2));
    CHECK(near(t.at(last, lang_test::column(t, "Deflection 3")), (a * l * l + c * b * b) / 2));
    CHECK(near(t.at(last, lang_test::column(t, "Deflection 4")), c * b * b / 2));
    CHECK(near(t.at(last, lang_test::column(t, "End rotation")), -a * l));  // rotation about +Y = -dw/dx
    CHECK(near(t.at(last, lang_test::column(t, "Moment Mx")), p / b));
    CHECK(std::abs(t.at(last, lang_test::column(t, "Moment My"))) < 1e-9 * p / b);
  }
}
