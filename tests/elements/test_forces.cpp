// F and FSIN: constant and harmonic force sources. Analytic answers through
// real simulations, the step recommendation of FSIN, and the code-101 /
// code-100 parameter checks.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using forces_model = pradis::model<point_mass, constant_force, linear_spring, linear_damper, sine_force>;
TEST_SUITE("elements/F") {
  TEST_CASE_TEMPLATE("a constant force accelerates a free mass from rest as u = P t^2 / (2 m), exactly for Newmark and Stoermer",
                     Scheme, pradis::newmark, pradis::stoermer) {
    // m u'' = P: u = P t^2 / (2 m), v = P t / m. Every Newmark-family scheme integrates a
    // constant acceleration exactly (its update is exact for quadratic u), so only round-off
    // and the Newton tolerance remain.
    using M = forces_model;
    const double m = 2.0, p = 3.0, h = 0.01, end = 2.0;
    M md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    md.add<constant_force>("push", {p}, x);
    simulation<M, Scheme> sim(md, Scheme{});
    double worst = 0;
    int outputs = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      worst = std::max({worst, std::abs(s.u(x) - p * t * t / (2 * m)), std::abs(s.v(x) - p * t / m),
                        std::abs(s.a(x) - p / m)});
      ++outputs;
    });
    sim.run(fixed_step(end, h));
    CHECK(outputs == 201);
    CHECK(worst < 1e-11);
    CHECK(sim.u(x) == doctest::Approx(p * end * end / (2 * m)).epsilon(1e-12));
  }

  TEST_CASE("a constant force on a damped mass-spring settles at the static deflection P/k, carried by the spring") {
    // m u'' + c u' + k u = P, critically damped (c = 2 sqrt(k m)): u = P/k [1 - (1 + wt) exp(-wt)],
    // w = sqrt(k/m) (any vibrations text). At t = 5, w = 10 the transient is 51 exp(-50) ~ 1e-20 of P/k;
    // the trapezoidal transient decays per step by (1 - wh/2)/(1 + wh/2) ~ exp(-wh), as fast.
    const double m = 1.0, k = 100.0, c = 2 * std::sqrt(k * m), p = 5.0;
    forces_model md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    const auto spring = md.add<linear_spring>("spring", {k}, x, md.ground());
    md.add<linear_damper>("damper", {c}, x, md.ground());
    md.add<constant_force>("load", {p}, x);
    simulation sim(md);
    sim.run(fixed_step(5.0, 0.01));
    CHECK(sim.u(x) == doctest::Approx(p / k).epsilon(1e-10));
    CHECK(std::abs(sim.v(x)) < 1e-10);
    // Spring force k (u2 - u1) with end 2 on the ground: the spring pushes back with -P.
    CHECK(md.work(spring)[0] == doctest::Approx(-p).epsilon(1e-10));
  }

  TEST_CASE("the flow of F is -P: the force the system applies to the source") {
    const constant_force e({4.0});
    local_input<constant_force> in;
    in.u(0) = 1.0;
    in.v(0) = 2.0;
    in.a(0) = 3.0;
    local_output<constant_force> out;
    element_context ctx("F", "load");
    e.evaluate(in, out, ctx);
    CHECK(out.f(0) == -4.0);
    CHECK(out.K(0, 0) == 0.0);
  }

  TEST_CASE("a flat F with a wrong parameter count is refused with code 101 naming F and the instance") {
    forces_model md;
    const std::array<dof, 1> d{md.add_dof()};
    const std::array<double, 2> two{1.0, 2.0};
    check_error(flat_add_error<constant_force>(md, "load", d, two), error_code::parameter_count, "F", "load",
                "got 2 parameters");
    const std::array<double, 1> bad{inf};
    check_error(flat_add_error<constant_force>(md, "inf", d, bad), error_code::invalid_parameter, "F", "inf",
                "non-finite");
  }

  TEST_CASE("a non-finite force stops the run with code 100 naming the instance and the force") {
    for (const double bad : {not_a_number, inf, -inf}) {
      CAPTURE(bad);
      forces_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {1.0}, x);
      md.add<constant_force>("load", {bad}, x);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "F", "load",
                  "force P");
    }
  }
}

TEST_SUITE("elements/FSIN") {
  TEST_CASE("an undamped oscillator driven by FSIN from rest follows the particular plus homogeneous solution") {
    // m u'' + k u = P0 + A sin(W t + ph), u(0) = u'(0) = 0, w = sqrt(k/m) != W:
    //   u = P0/k + Ap sin(W t + ph) + C1 cos(w t) + C2 sin(w t),  Ap = A / (k - m W^2),
    //   C1 = -P0/k - Ap sin(ph),  C2 = -Ap W cos(ph) / w            (undetermined coefficients).
    // Error bound of the trapezoidal rule on y = (u, u') in the norm |y| = sqrt(u^2 + u'^2/w^2),
    // in which both the exact flow and the Cayley step are isometries: the Peano form of the local
    // error, y(t+h) - y(t) - h/2 (y'(t) + y'(t+h)) = -1/2 int_0^h s (h - s) y'''(t+s) ds, is at most
    // h^3/12 sup|y'''| per step, hence |u_n - u(t_n)| <= t h^2/12 sup|y'''| with
    // sup|y'''| <= w^3 sqrt(C1^2 + C2^2) + |Ap| W^3 max(1, W/w).
    const double m = 1.0, w = 2 * std::numbers::pi, k = m * w * w;
    const double amp = 2.0, freq = 1.5, big_w = 2 * std::numbers::pi * freq, phase_deg = 30.0, p0 = 0.5;
    const double ph = phase_deg * std::numbers::pi / 180, h = 1e-3, end = 2.0;
    const double ap = amp / (k - m * big_w * big_w), c1 = -p0 / k - ap * std::sin(ph), c2 = -ap * big_w * std::cos(ph) / w;
    const double third = w * w * w * std::hypot(c1, c2) + std::abs(ap) * std::pow(big_w, 3) * std::max(1.0, big_w / w);
    forces_model md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    md.add<linear_spring>("spring", {k}, x, md.ground());
    const auto force = md.add<sine_force>("drive", {amp, freq, phase_deg, p0}, x);
    simulation sim(md);
    double worst_ratio = 0, worst_work = 0, worst_error = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      const double u = p0 / k + ap * std::sin(big_w * t + ph) + c1 * std::cos(w * t) + c2 * std::sin(w * t);
      worst_ratio = std::max(worst_ratio, std::abs(s.u(x) - u) / (t * h * h / 12 * third + 1e-11));
      worst_error = std::max(worst_error, std::abs(s.u(x) - u));
      // W(1): the current force P(t).
      worst_work = std::max(worst_work, std::abs(md.work(force)[0] - (p0 + amp * std::sin(big_w * t + ph))));
    });
    sim.run(fixed_step(end, h));
    CHECK(sim.statistics().steps == 2000);  // 1/(20 f) = 0.033 > h: the recommendation does not interfere
    CHECK(worst_ratio <= 1.0);
    CHECK(worst_error > 1e-7);  // the comparison is not vacuous: the scheme's error is visible
    CHECK(worst_work < 1e-12);
  }

  TEST_CASE("FSIN bounds every step after the first by its recommendation 1/(20 f), unless IGNORE is set") {
    const double freq = 1.0, smax = 0.1;
    for (const bool ignore : {false, true}) {
      CAPTURE(ignore);
      forces_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {1.0}, x);
      md.add<linear_spring>("spring", {1.0}, x, md.ground());
      md.add<sine_force>("drive", {1.0, freq, 0.0, 0.0}, x);
      simulation sim(md);
      std::vector<double> times;
      sim.on_output([&](const auto& s) { times.push_back(s.time()); });
      run_options opt = fixed_step(2.0, smax);
      opt.ignore = ignore;
      sim.run(opt);
      REQUIRE(times.size() >= 3);
      double largest_later = 0;
      for (std::size_t i = 2; i < times.size(); ++i) largest_later = std::max(largest_later, times[i] - times[i - 1]);
      if (ignore)
        CHECK(largest_later == doctest::Approx(smax));
      else
        CHECK(largest_later <= 1.0 / (20 * freq) * (1 + 1e-12));
    }
  }

  TEST_CASE("FSIN's step recommendation made at the zero step bounds the first step too") {
    // The kernel documents "the smallest recommendation of a step bounds the next step"; the
    // zero step evaluates every element (FSIN recommends 1/(20 f) there), so the first step
    // must not exceed it either.
    const double freq = 1.0;
    forces_model md;
    const dof x = md.add_dof();
    md.add<point_mass>("body", {1.0}, x);
    md.add<linear_spring>("spring", {1.0}, x, md.ground());
    md.add<sine_force>("drive", {1.0, freq, 0.0, 0.0}, x);
    simulation sim(md);
    std::vector<double> times;
    sim.on_output([&](const auto& s) { times.push_back(s.time()); });
    sim.run(fixed_step(1.0, 0.1));
    REQUIRE(times.size() >= 2);
    CHECK(times[1] - times[0] <= 1.0 / (20 * freq) * (1 + 1e-12));
  }

  TEST_CASE("a flat FSIN with a wrong parameter count is refused with code 101 naming FSIN and the instance") {
    forces_model md;
    const std::array<dof, 1> d{md.add_dof()};
    const std::array<double, 3> three{1.0, 2.0, 3.0};
    check_error(flat_add_error<sine_force>(md, "drive", d, three), error_code::parameter_count, "FSIN", "drive",
                "got 3 parameters");
  }

  TEST_CASE("a negative or non-finite frequency stops the run with code 100 naming the instance and the frequency") {
    for (const double bad : {-1.0, not_a_number, inf}) {
      CAPTURE(bad);
      forces_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {1.0}, x);
      md.add<sine_force>("drive", {1.0, bad, 0.0, 0.0}, x);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "FSIN",
                  "drive", "frequency f");
    }
  }

  TEST_CASE("a non-finite amplitude, phase or constant part stops the run with code 100") {
    const std::array<sine_force::parameters, 3> bad{{{inf, 1.0, 0.0, 0.0}, {1.0, 1.0, not_a_number, 0.0},
                                                     {1.0, 1.0, 0.0, -inf}}};
    for (const auto& p : bad) {
      forces_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {1.0}, x);
      md.add<sine_force>("drive", p, x);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "FSIN",
                  "drive", "must be finite");
    }
  }
}
