// D (smooth Shockley diode) and SW (time-switched resistance): operating points
// against independent solutions, the C1 continuation of the diode above Vmax, the
// switch's resistance law and step recommendations, and bad parameters.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// Principal branch of the Lambert W function for x > 0: Newton on f(w) = w + ln w - ln x
// (w e^w = x in logarithmic form, safe for huge x).
double lambert_w(double x) {
  const double lx = std::log(x);
  double w = lx > 1 ? lx - std::log(lx) : 0.5;
  for (int k = 0; k < 100; ++k) {
    const double f = w + std::log(w) - lx, step = f / (1 + 1 / w);
    w -= step;
    if (std::abs(step) < 1e-15 * w) break;
  }
  return w;
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using diode_switch_model = pradis::model<voltage_dc, resistor, diode, time_switch>;
TEST_SUITE("electric/D") {
  TEST_CASE("diode and resistor: the operating point equals the Lambert-W solution") {
    // (V - vd)/R = Is (exp(vd/(n Vt)) - 1) with Gmin = 0 has the closed form (e.g. Banwell & Jayakumar,
    // Electronics Letters 36 (2000) 291): vd = V + Is R - n Vt W(Is R/(n Vt) exp((V + Is R)/(n Vt))).
    // The argument overflows a double, so W is evaluated from its logarithm.
    const double big_v = 5.0, r = 1e3, is = 1e-14, n = 1.2, vt = 0.025852, nvt = n * vt;
    const double ln_arg = std::log(is * r / nvt) + (big_v + is * r) / nvt;
    double w = ln_arg - std::log(ln_arg);  // W from w + ln w = ln_arg
    for (int k = 0; k < 100; ++k) w -= (w + std::log(w) - ln_arg) / (1 + 1 / w);
    const double vd = big_v + is * r - nvt * w;
    CHECK(lambert_w(std::exp(2.0)) == doctest::Approx(1.5571455989976114).epsilon(1e-14));  // W(e^2), tables
    diode_switch_model md;
    const dof in = md.add_dof("in"), anode = md.add_dof("anode");
    md.add<voltage_dc>("V", {big_v}, in);
    md.add<resistor>("R", {r}, in, anode);
    const auto d = md.add<diode>("D", {is, n, vt, 0.9, 0.0}, anode, md.ground());
    simulation sim(md);
    // A purely resistive diode node has no capacitance to slow Newton down: from the linear start
    // (5 V) Newton walks down the exponential by about n Vt per iteration, more than ITR = 5 allows.
    run_options o = fixed_step(1e-3, 1e-4);
    o.newton.itr = 50;
    sim.run(o);
    CHECK(sim.v(anode) == doctest::Approx(vd).epsilon(1e-10));
    CHECK(md.work(d)[0] == doctest::Approx((big_v - vd) / r).epsilon(1e-10));
    CHECK(md.work(d)[1] == doctest::Approx(vd).epsilon(1e-10));
  }

  TEST_CASE("reverse bias: the diode conducts -Is + Gmin vd") {
    diode_switch_model md;
    const dof in = md.add_dof("in"), cathode = md.add_dof("cathode");
    md.add<voltage_dc>("V", {10.0}, in);
    md.add<resistor>("R", {1e3}, in, cathode);
    const auto d = md.add<diode>("D", {1e-12, 1.0, 0.025852, 0.9, 1e-9}, md.ground(), cathode);
    simulation sim(md);
    run_options o = fixed_step(1e-3, 1e-4);
    o.newton.itr = 50;
    sim.run(o);
    // KCL at the cathode: (10 - vc)/R = -i_D with i_D = -Is - Gmin vc (vd = -vc):
    // vc = (10/R - Is) / (1/R + Gmin).
    const double vc = (10.0 / 1e3 - 1e-12) / (1.0 / 1e3 + 1e-9);
    CHECK(sim.v(cathode) == doctest::Approx(vc).epsilon(1e-12));
    CHECK(md.work(d)[0] == doctest::Approx(-1e-12 - 1e-9 * vc).epsilon(1e-9));
  }

  TEST_CASE("above Vmax the current is the tangent at Vmax: continuous with a continuous slope, never overflowing") {
    const diode d({1e-14, 1.0, 0.025852, 0.8, 1e-12});
    double i_lo = 0, g_lo = 0, i_hi = 0, g_hi = 0, i_far = 0, g_far = 0;
    d.characteristic(0.8 - 1e-12, i_lo, g_lo);
    d.characteristic(0.8 + 1e-12, i_hi, g_hi);
    CHECK(i_hi == doctest::Approx(i_lo).epsilon(1e-9));
    CHECK(g_hi == doctest::Approx(g_lo).epsilon(1e-9));
    d.characteristic(1e6, i_far, g_far);
    CHECK(std::isfinite(i_far));
    CHECK(g_far == doctest::Approx(g_hi).epsilon(1e-12));  // linear above Vmax
    const double em = std::exp(0.8 / 0.025852);
    CHECK(i_far == doctest::Approx(1e-14 * (em * (1 + (1e6 - 0.8) / 0.025852) - 1) + 1e-12 * 1e6).epsilon(1e-12));
  }

  TEST_CASE("bad D parameters stop the run with code 100 naming the parameter") {
    struct bad_case {
      diode::parameters p;
      const char* mention;
    };
    const std::array<bad_case, 6> bad{{{{0.0, 1.0, 0.025, 0.8, 0.0}, "saturation current Is"},
                                       {{1e-14, -1.0, 0.025, 0.8, 0.0}, "emission coefficient n"},
                                       {{1e-14, 1.0, 0.0, 0.8, 0.0}, "thermal voltage Vt"},
                                       {{1e-14, 1.0, 0.025, 6.0, 0.0}, "limiting voltage Vmax"},
                                       {{1e-14, 1.0, 0.025, -0.1, 0.0}, "limiting voltage Vmax"},
                                       {{1e-14, 1.0, 0.025, 0.8, -1.0}, "minimum conductance Gmin"}}};
    for (const auto& b : bad) {
      CAPTURE(b.mention);
      diode_switch_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<diode>("D1", b.p, n, md.ground());
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.01, 0.001)); }), error_code::invalid_parameter, "D", "D1",
                  b.mention);
    }
  }
}

TEST_SUITE("electric/SW") {
  TEST_CASE("a switch in a divider: v = V R / (R + R_sw(t)) with R_sw = R1^(1-s) R2^s and s the smoothstep") {
    const double big_v = 10.0, r = 100.0, r1 = 1e6, r2 = 0.1, t1 = 0.1, t2 = 0.3, tau = 0.02;
    // s(t) = S((t - t1)/tau) - S((t - t2)/tau), S(x) = 3x^2 - 2x^3 on [0, 1].
    const auto smooth = [](double x) { return x <= 0 ? 0.0 : (x >= 1 ? 1.0 : 3 * x * x - 2 * x * x * x); };
    const auto rsw = [&](double t) {
      const double s = smooth((t - t1) / tau) - smooth((t - t2) / tau);
      return std::pow(r1, 1 - s) * std::pow(r2, s);
    };
    diode_switch_model md;
    const dof in = md.add_dof("in"), out = md.add_dof("out");
    md.add<voltage_dc>("V", {big_v}, in);
    const auto sw = md.add<time_switch>("S", {r1, r2, t1, t2, tau}, in, out);
    md.add<resistor>("R", {r}, out, md.ground());
    simulation sim(md);
    double worst = 0;
    std::vector<double> times;
    sim.on_step([&](const auto& s) { times.push_back(s.time()); });
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      if (t == 0) return;  // the algebraic node becomes consistent with the first step
      worst = std::max({worst, std::abs(s.v(out) - big_v * r / (r + rsw(t))),
                        std::abs(md.work(sw)[1] - rsw(t)) / rsw(t)});
    });
    sim.run(fixed_step(0.5, 0.05));
    CHECK(worst < 1e-12);
    // The switch recommends steps that land on t1 and t2 and resolve each transition with 10 steps.
    int on_t1 = 0, on_t2 = 0, in_ramp = 0;
    for (double t : times) {
      on_t1 += std::abs(t - t1) < 1e-12;
      on_t2 += std::abs(t - t2) < 1e-12;
      in_ramp += t > t1 && t < t1 + tau;
    }
    CHECK(on_t1 == 1);
    CHECK(on_t2 == 1);
    CHECK(in_ramp >= 9);
  }

  TEST_CASE("bad SW parameters stop the run with code 100 naming the parameter") {
    struct bad_case {
      time_switch::parameters p;
      const char* mention;
    };
    const std::array<bad_case, 5> bad{{{{0.0, 1.0, 0.0, 1.0, 0.1}, "resistance R1"},
                                       {{1.0, -1.0, 0.0, 1.0, 0.1}, "resistance R2"},
                                       {{1.0, 1.0, 0.0, 1.0, 0.0}, "transition time tau"},
                                       {{1.0, 1.0, 0.5, 0.55, 0.1}, "t2 >= t1 + tau"},
                                       {{1.0, 1.0, inf, 1.0, 0.1}, "switching times"}}};
    for (const auto& b : bad) {
      CAPTURE(b.mention);
      diode_switch_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<time_switch>("S1", b.p, n, md.ground());
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.01, 0.001)); }), error_code::invalid_parameter, "SW", "S1",
                  b.mention);
    }
  }
}
