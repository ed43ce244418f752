// examples/models/source_bench.prd: the current sources IDC, ISIN, ITAB and the floating
// voltage sources VDC2, VSIN2, VTAB2, each on a circuit with a closed form (the file's
// comment). Kirchhoff's current law at each node and the elements' laws
// (docs/domains-electric-pneumatic.md) give:
//   - IDC into R1: v1 = I0 R1; ISIN into R2: v2 = R2 I(t) at every instant (resistive nodes);
//   - ITAB into C: v3 = (integral of the piecewise linear pulse) / C. NEWMARK (beta = 1/4,
//     gamma = 1/2) is the trapezoidal rule on v3' = I / C, exact for a linear I on a step, and
//     the fixed steps of 0.1 ms fall on the pulse's kinks (10, 20, 30 ms);
//   - VDC2 across R4 (+ side) and R5 (- side) in series through the ground: i = V / (R4 + R5),
//     v4 = R4 i, v5 = -R5 i; VSIN2 across two equal resistors: v6 = -v7 = V(t) / 2, i = V / (2 R6);
//   - VTAB2 ramp V = 100 t [V] with R8 on its + node and C on its - node: v8 = v9 + V and
//     C v9' = -v8 / R8, so v9' = -(v9 + V) / tau, tau = R8 C = 0.1 s, whose solution from rest is
//     v9 = -100 (t - tau (1 - exp(-t / tau))). The trapezoidal rule's own solution of this linear
//     ODE at the step h follows the recurrence
//       v_{n+1} (1 + h / (2 tau)) = v_n (1 - h / (2 tau)) - h (V_n + V_{n+1}) / (2 tau),
//     which the run must reproduce to round-off; its distance from the exact solution is the
//     rule's global error, O(h^2) (Hughes, The Finite Element Method, section 9.3; bounded below);
//   - VDC2 across an inductor (L = 0.1 H, i0 = 0.2 A): v10 = V from t = 0, i = i0 + V t / L (the inductor
//     law v = L di/dt), linear in t, so the trapezoidal rule is exact; the zero step fixes v10 and
//     the source current (integrators/velocity_constraints.hpp, kind 6).
// The zero step makes the floating sources' currents and the potentials they fix consistent
// (docs/domains-electric-pneumatic.md, "floating source"): every circuit is checked from t = 0.
// Tolerances: every equation is linear and Newton's tests are at 1e-12, so Newton ends with a
// residual at round-off; the states are sums of at most 400 steps of terms of order 10, so
// 1e-11 V (about 400 * 10 * 2 eps) bounds the accumulated round-off of v3 and v9.

#include <cmath>
#include <memory>
#include <numbers>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {
constexpr double srcb_pi = std::numbers::pi;
/// The ITAB pulse's integral from 0 to t [A s]: 0 -> 0.5 A over 10 ms, 0.5 A for 10 ms, -> 0 over 10 ms.
double srcb_pulse_charge(double t) {
  const double a = 0.5, t1 = 0.01;
  if (t <= t1) return a * t * t / (2 * t1);
  if (t <= 2 * t1) return a * t1 / 2 + a * (t - t1);
  if (t <= 3 * t1) {
    const double s = t - 2 * t1;
    return a * t1 / 2 + a * t1 + a * s - a * s * s / (2 * t1);
  }
  return 2 * a * t1;
}
}  // namespace

TEST_SUITE("lang/source bench") {
  TEST_CASE("examples/models/source_bench.prd: current and floating voltage sources against Kirchhoff's laws") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "source_bench.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    auto c = [&](const char* label) { return lang_test::column(t, label); };
    const std::size_t v1 = c("v1"), v2 = c("v2"), v3 = c("v3"), v4 = c("v4"), v5 = c("v5"), v6 = c("v6"), v7 = c("v7"),
                      v8 = c("v8"), v9 = c("v9"), i1 = c("I1"), i2 = c("I2"), i3 = c("I3"), i4 = c("I4"), i6 = c("I6"),
                      i8 = c("I8"), v10 = c("v10"), i10 = c("I10"), il10 = c("IL10");
    REQUIRE(t.rows() == 41);  // t = 0 and every 1 ms to 40 ms
    const double C = 1e-3, tau = 100 * C, h = 1e-4, ramp = 100;
    double e_res = 0, e_cap = 0, e_float = 0, e_disc = 0, e_exact = 0, e_coil = 0;
    double vd = 0;  // the trapezoidal recurrence for v9, advanced in steps of h
    double td = 0;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double time = t.at(r, 0);
      const double isin = 0.1 + 0.2 * std::sin(2 * srcb_pi * 50 * time + srcb_pi / 6);
      e_res = std::max({e_res, std::abs(t.at(r, v1) - 2.0), std::abs(t.at(r, i1) - 0.25),
                        std::abs(t.at(r, v2) - 10 * isin), std::abs(t.at(r, i2) - isin)});
      const double q = srcb_pulse_charge(time);
      e_cap = std::max(e_cap, std::abs(t.at(r, v3) - q / C));
      const double pulse = time <= 0.01 ? 50 * time : time <= 0.02 ? 0.5 : time <= 0.03 ? 0.5 - 50 * (time - 0.02) : 0;
      e_cap = std::max(e_cap, std::abs(t.at(r, i3) - pulse));
      while (td < time - h / 2) {
        const double k = h / (2 * tau);
        vd = (vd * (1 - k) - k * ramp * (td + (td + h))) / (1 + k);
        td += h;
      }
      e_coil = std::max({e_coil, std::abs(t.at(r, v10) - 3.0), std::abs(t.at(r, il10) - (0.2 + 30 * time)),
                         std::abs(t.at(r, i10) - (0.2 + 30 * time))});
      const double vs = 1 + 2 * std::sin(2 * srcb_pi * 50 * time);
      e_float = std::max({e_float, std::abs(t.at(r, v4) - 1.0), std::abs(t.at(r, v5) + 2.0),
                          std::abs(t.at(r, i4) - 0.01), std::abs(t.at(r, v6) - vs / 2),
                          std::abs(t.at(r, v7) + vs / 2), std::abs(t.at(r, i6) - vs / 100),
                          std::abs(t.at(r, v8) - t.at(r, v9) - ramp * time),
                          std::abs(t.at(r, i8) - t.at(r, v8) / 100)});
      e_disc = std::max(e_disc, std::abs(t.at(r, v9) - vd));
      e_exact = std::max(e_exact, std::abs(t.at(r, v9) + ramp * (time - tau * (1 - std::exp(-time / tau)))));
    }
    MESSAGE("resistive nodes ", e_res, " V/A; capacitor under the pulse ", e_cap, "; floating sources ", e_float,
            "; v9 against the trapezoidal recurrence ", e_disc, " V, against the exact solution ", e_exact,
            " V; source across the inductor ", e_coil);
    CHECK(e_res <= 1e-12);
    CHECK(e_cap <= 1e-11);
    CHECK(e_float <= 1e-11);
    CHECK(e_disc <= 1e-11);
    CHECK(e_coil <= 1e-11);
    // The trapezoidal rule's global error on v9' = -(v9 + V) / tau: at most T h^2 / 12 max|v9'''|,
    // v9''' = -(100 / tau^2) exp(-t / tau) in magnitude at most 1e4 V/s^3: 0.04 * 1e-8 / 12 * 1e4 = 3.3e-7 V.
    CHECK(e_exact <= 3.4e-7);
    CHECK(e_exact > 1e-9);  // the run is the discrete solution, not the exact one
    CHECK(t.at(t.rows() - 1, v3) == doctest::Approx(10.0).epsilon(1e-12));
  }
}
