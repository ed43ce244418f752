// examples/models/coulomb_oscillator.prd through the model language: FRICT by
// its catalog name with the work-vector outputs; the mass stops where and when
// the Coulomb oscillator's analytic solution says (Den Hartog, Mechanical
// Vibrations, 8.2; tests/elements/test_friction.cpp checks every turning point).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "lang_test_support.hpp"

using namespace pradis;

TEST_SUITE("lang/friction") {
  TEST_CASE("the Coulomb oscillator model file stops at x = 0.005 m after 5 half cycles, t = pi / 2") {
    auto s = std::make_unique<lang::session>(
        lang::parse_file((lang_test::models_dir() / "coulomb_oscillator.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    std::size_t pos = 0, stuck = 0;
    for (std::size_t c = 0; c < t.names().size(); ++c) {
      if (t.names()[c] == "Position") pos = c + 1;
      if (t.names()[c] == "Stuck") stuck = c + 1;
    }
    REQUIRE(pos > 0);
    REQUIRE(stuck > 0);
    // x_5 = -(x0 - 5 * 2 F / k) = 0.005 m, reached at t = 5 pi sqrt(m/k) = pi / 2
    // (first-order in the step: within 1e-3 s at h = 1e-4, the test of FRICT).
    const double t_stop = 5 * std::numbers::pi / 10;
    int last_half = 0, after = 0;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double time = t.at(r, 0), x = t.at(r, pos);
      CAPTURE(time);
      if (time > 1.3 && time < t_stop - 1e-3) {  // the last half cycle, from x_4 = 0.015 down to x_5
        CHECK(x > 0.005);
        CHECK(x < 0.015 + 1e-7);
        CHECK(t.at(r, stuck) == 0.0);
        ++last_half;
      } else if (time > t_stop + 1e-3) {  // at rest at x_5
        CHECK(std::abs(x - 0.005) < 1e-7);
        CHECK(t.at(r, stuck) == 1.0);
        ++after;
      }
    }
    CHECK(last_half > 20);
    CHECK(after > 20);
    CHECK(t.at(t.rows() - 1, 0) == doctest::Approx(2.0));
  }
}

TEST_SUITE("lang/friction") {
  TEST_CASE("the gear backlash model file: no torque until t = b / (|r| w1), then shaft 2 at r w1") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "gear_backlash.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    std::size_t speed = 0, torque = 0, gap = 0;
    for (std::size_t c = 0; c < t.names().size(); ++c) {
      if (t.names()[c] == "Shaft 2 speed") speed = c + 1;
      if (t.names()[c] == "Mesh torque") torque = c + 1;
      if (t.names()[c] == "Gap") gap = c + 1;
    }
    REQUIRE(speed > 0);
    REQUIRE(torque > 0);
    REQUIRE(gap > 0);
    const double r = -2, w1 = 1, b = 0.0205, k = 1e4, cl = 0.05, tc = b / (std::abs(r) * w1);
    int free_rows = 0;
    for (std::size_t i = 0; i < t.rows() && t.at(i, 0) < tc; ++i, ++free_rows) {
      CAPTURE(t.at(i, 0));
      CHECK(t.at(i, torque) == 0.0);
      CHECK(t.at(i, speed) == 0.0);
      CHECK(t.at(i, gap) == doctest::Approx(-r * w1 * t.at(i, 0)).epsilon(1e-12));  // g = -r phi1 = -r w1 t
    }
    CHECK(free_rows == 11);  // t = 0, 0.001, ..., 0.010
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, speed) == doctest::Approx(r * w1).epsilon(1e-9));
    CHECK(t.at(last, torque) == doctest::Approx(-cl * r * w1).epsilon(1e-9));
    CHECK(t.at(last, gap) == doctest::Approx(b - cl * r * w1 / k).epsilon(1e-9));
  }
}

TEST_SUITE("lang/friction") {
  TEST_CASE("the capstan model file slips with T1 / T2 = exp(mu theta) at the rigid-rope acceleration") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "capstan.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    std::size_t u1 = 0, t1 = 0, t2 = 0, slip = 0;
    for (std::size_t c = 0; c < t.names().size(); ++c) {
      if (t.names()[c] == "Load position") u1 = c + 1;
      if (t.names()[c] == "Tension 1") t1 = c + 1;
      if (t.names()[c] == "Tension 2") t2 = c + 1;
      if (t.names()[c] == "Slip") slip = c + 1;
    }
    REQUIRE(u1 * t1 * t2 * slip > 0);
    // The capstan equation (Euler, Eytelwein; Meriam & Kraige, Statics, 6/9):
    // T1 = E T2 while slipping; the data of the file: a = (W - E P) / (m1 + E m2).
    const double E = std::exp(0.3 * std::numbers::pi), W = 98.0665, P = 37.834360325167765;
    const double a = (W - E * P) / (10.0 + E * 1.0), T1 = W - 10.0 * a;
    for (std::size_t r = 1; r < t.rows(); ++r) {
      const double time = t.at(r, 0);
      CAPTURE(time);
      CHECK(t.at(r, t1) / t.at(r, t2) == doctest::Approx(E).epsilon(1e-12));
      // The trapezoidal rule is exact for the constant acceleration (as in the BELT test of test_friction.cpp).
      CHECK(std::abs(t.at(r, u1) - (T1 / 1e5 + a * time * time / 2)) < 1e-9);
      CHECK(std::abs(t.at(r, slip) - a * time * time / 2) < 1e-9);
    }
  }
}
