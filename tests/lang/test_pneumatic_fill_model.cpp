// examples/models/pneumatic_fill.prd: a tank filled from a pressure supply through an
// ISO 6358 orifice (PNSRC, PNORF, PNVOL) in the model language. While the orifice is
// choked (P_tank <= b P_supply, absolute) its mass flow is C rho0 P_supply (ISO 6358-1:2013,
// section 3, with T = T0), constant, and the isothermal tank's mass balance
// V P' / (R T) = q makes the tank pressure rise linearly: p(t) = R T q t / V. Over the
// whole run the air the tank gained equals the integral of the orifice's flow.

#include <cmath>
#include <memory>

#include "lang_test_support.hpp"

using namespace pradis;

TEST_SUITE("lang/pneumatic fill") {
  TEST_CASE("examples/models/pneumatic_fill.prd: linear rise while choked, mass balance over the run") {
    auto s =
        std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "pneumatic_fill.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t p = lang_test::column(t, "Tank pressure"), q = lang_test::column(t, "Mass flow"),
                      ratio = lang_test::column(t, "Pressure ratio"), mass = lang_test::column(t, "Air mass");
    const double supply = 5e5 + 101325, C = 1e-8, b = 0.3, T = 293.15, V = 1e-3;  // the file's $DATA
    const double rho0 = 1.185, R = 287.05;                                     // ISO 6358 ANR density, air
    const double q_choked = C * rho0 * supply, rate = R * T * q_choked / V;
    const double t_choked = (b * supply - 101325) / rate;  // 0.132 s
    REQUIRE(t.rows() == 121);                               // t = 0 and every 5 ms to 0.6 s
    std::size_t choked_rows = 0;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double time = t.at(r, 0);
      if (time > t_choked - 0.005) break;
      ++choked_rows;
      // DRLTX = DABSX = 1e-8 on pressures up to 8e4 Pa: within 1e-3 Pa (measured 4e-11 Pa,
      // a linear solution is exact for every BDF order up to round-off).
      CHECK(std::abs(t.at(r, p) - rate * time) < 1e-3);
      if (r > 0) CHECK(t.at(r, q) == doctest::Approx(q_choked).epsilon(1e-12));
      if (r > 0) CHECK(t.at(r, ratio) <= b);
    }
    CHECK(choked_rows == 26);  // 0 .. 0.125 s
    // After the choked phase the flow falls and the tank stays below the supply.
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, q) < 0.8 * q_choked);
    CHECK(t.at(last, p) < supply - 101325);
    for (std::size_t r = choked_rows + 1; r <= last; ++r) CHECK(t.at(r, q) <= t.at(r - 1, q) + 1e-15);
    // Mass balance: m(0.6) - m(0) against Simpson's rule over the 120 sampled flows
    // (measured 3.3e-8 relative; the rule's own error on 5 ms samples of the smooth
    // flow is of that order).
    const double h = t.at(1, 0) - t.at(0, 0);
    double simpson = t.at(0, q) + t.at(last, q);
    for (std::size_t r = 1; r < last; ++r) simpson += (r % 2 == 1 ? 4.0 : 2.0) * t.at(r, q);
    simpson *= h / 3;
    const double gained = t.at(last, mass) - t.at(0, mass);
    CHECK(std::abs(simpson - gained) < 1e-6 * gained);
  }
}
