// examples/models/rlc_circuit.prd: a series RLC circuit switched onto a battery, in
// the model language (VDC, R, L, C). With alpha = R/(2L), w0^2 = 1/(LC) and
// wd^2 = w0^2 - alpha^2 > 0 the capacitor voltage and the loop current are
//     v_C(t) = V (1 - exp(-alpha t) (cos wd t + alpha/wd sin wd t)),
//     i(t)   = V / (L wd) exp(-alpha t) sin wd t
// (the step response of the series RLC circuit: Nilsson and Riedel, Electric
// Circuits, 10th ed., 2015, section 8.4); node 2, between R and L, is at V - R i.

#include <cmath>
#include <memory>
#include <numbers>

#include "lang_test_support.hpp"

using namespace pradis;

TEST_SUITE("lang/rlc circuit") {
  TEST_CASE("examples/models/rlc_circuit.prd: capacitor voltage and current of the series RLC step response") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "rlc_circuit.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t vc = lang_test::column(t, "Capacitor voltage"), v2 = lang_test::column(t, "Node 2 voltage"),
                      cur = lang_test::column(t, "Current");
    const double V = 10, R = 10, L = 0.01, C = 1e-5;  // the file's $DATA
    const double alpha = R / (2 * L), wd = std::sqrt(1 / (L * C) - alpha * alpha);
    REQUIRE(t.rows() == 201);  // t = 0 and every 0.05 ms to 10 ms
    double err_v = 0, err_i = 0, err_2 = 0;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double time = t.at(r, 0), e = std::exp(-alpha * time);
      const double v_exact = V * (1 - e * (std::cos(wd * time) + alpha / wd * std::sin(wd * time)));
      const double i_exact = V / (L * wd) * e * std::sin(wd * time);
      err_v = std::max(err_v, std::abs(t.at(r, vc) - v_exact));
      err_i = std::max(err_i, std::abs(t.at(r, cur) - i_exact));
      err_2 = std::max(err_2, std::abs(t.at(r, v2) - (V - R * i_exact)));
    }
    // BDF at DRLTX = DABSX = 1e-7 over three periods: measured 3.7e-5 V and 1.1e-6 A
    // (of 16 V and 0.3 A); the bounds are within 3x and 10x of that.
    CHECK(err_v < 1e-4);
    CHECK(err_i < 1e-5);
    CHECK(err_2 < 1e-4);
    // The overshoot V exp(-alpha pi / wd) = 6.05 V peaks at t = pi / wd = 1.006 ms: the
    // largest output is at the sample nearest to it, 1.0 ms (row 20).
    std::size_t top = 0;
    for (std::size_t r = 1; r < t.rows(); ++r)
      if (t.at(r, vc) > t.at(top, vc)) top = r;
    CHECK(std::abs(t.at(top, 0) - std::numbers::pi / wd) < 2.5e-5);
    CHECK(t.at(top, vc) > V + 6.0);
  }
}
