// MASS, SPRING and DAMPER: analytic answers through real simulations, direct
// evaluation of the flows, and the code-101 / code-100 parameter checks.
//
// Accuracy argument used below (average-acceleration Newmark = trapezoidal rule
// on y = (u, v), because a_n satisfies the balance at every step, including
// t = 0 where the kernel solves M a0 = -F):
//  * undamped oscillator: the discrete solution is the exact one with w
//    replaced by wd, tan(wd h/2) = w h/2, so |u_n - u(t_n)| <= A (w - wd) t_n
//    <= A w^3 h^2 t / 12 (Hughes, The Finite Element Method, 9.3);
//  * first-order decay v' = -lambda v: v_n = v0 rho^n, rho = (1 - x)/(1 + x),
//    x = lambda h / 2, and 0 <= exp(-lambda t) - rho^n
//    <= exp(-lambda t) lambda^3 h^2 t / (12 (1 - x^2)) (rho = exp(-2 atanh x),
//    2x <= 2 atanh x <= 2x + 2x^3 / (3 (1 - x^2))).

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
using mass_spring_damper_model = pradis::model<point_mass, linear_spring, initial_displacement, initial_velocity,
    linear_damper>;
TEST_SUITE("elements/MASS") {
  TEST_CASE("a mass on a spring oscillates as u0 cos(wt) + v0/w sin(wt) within the trapezoidal phase error") {
    // Undamped oscillator m u'' + k u = 0: u = u0 cos(wt) + v0/w sin(wt), w = sqrt(k/m).
    const double m = 0.5, w = 2 * std::numbers::pi, k = m * w * w, u0 = 0.1, v0 = 0.3, h = 1e-3, end = 1.0;
    mass_spring_damper_model md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    md.add<linear_spring>("spring", {k}, x, md.ground());
    md.add<initial_displacement>("x0", {u0}, x);
    md.add<initial_velocity>("v0", {v0}, x);
    simulation sim(md);
    const double wd = trapezoidal_frequency(w, h), amp = std::hypot(u0, v0 / w);
    double worst_discrete = 0, worst_exact_ratio = 0, last_t = 0, phase = 0;
    int outputs = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      // Discrete phase: each step of size dt advances it by dt wd(dt) (steps may end shorter at END).
      if (t > last_t) phase += (t - last_t) * trapezoidal_frequency(w, t - last_t);
      last_t = t;
      const double u_exact = u0 * std::cos(w * t) + v0 / w * std::sin(w * t);
      const double u_discrete = u0 * std::cos(phase) + v0 / w * std::sin(phase);
      const double v_discrete = w * (-u0 * std::sin(phase) + v0 / w * std::cos(phase));
      worst_discrete = std::max({worst_discrete, std::abs(s.u(x) - u_discrete), std::abs(s.v(x) - v_discrete) / w});
      // Rigorous bound amp (w - wd(h)) t (steps are at most h and w - wd grows with the step),
      // plus the Newton/round-off floor.
      worst_exact_ratio = std::max(worst_exact_ratio, std::abs(s.u(x) - u_exact) / (amp * (w - wd) * t + 1e-11));
      ++outputs;
    });
    sim.run(fixed_step(end, h));
    CHECK(outputs == 1001);  // t = 0 and every step
    CHECK(sim.time() == doctest::Approx(end).epsilon(1e-15));
    CHECK(worst_discrete < 1e-11);
    CHECK(worst_exact_ratio <= 1.0);
    // The phase bound is sharp: after a full period the error is a sizeable fraction of it.
    const double u_exact_end = u0 * std::cos(w * end) + v0 / w * std::sin(w * end);
    CHECK(std::abs(sim.u(x) - u_exact_end) > 0.1 * amp * (w - wd) * end);
  }

  TEST_CASE("the flow of a mass is m a and its only Jacobian block is dF/da = m") {
    static_assert(!element_traits<point_mass>::has_k && !element_traits<point_mass>::has_c &&
                  element_traits<point_mass>::has_m);
    const point_mass e({2.5});
    local_input<point_mass> in;
    in.u(0) = 7.0;  // displacement and velocity do not matter
    in.v(0) = -4.0;
    in.a(0) = 3.0;
    local_output<point_mass> out;
    element_context ctx("MASS", "body");
    e.evaluate(in, out, ctx);
    CHECK(out.f(0) == 7.5);
    CHECK(out.M(0, 0) == 2.5);
  }

  TEST_CASE("a flat MASS with a wrong parameter count is refused with code 101 naming MASS and the instance") {
    mass_spring_damper_model md;
    const std::array<dof, 1> d{md.add_dof()};
    const std::array<double, 2> two{1.0, 2.0};
    check_error(flat_add_error<point_mass>(md, "body", d, two), error_code::parameter_count, "MASS",
                "body", "got 2 parameters");
    check_error(flat_add_error<point_mass>(md, "empty", d, {}),
                error_code::parameter_count, "MASS", "empty", "got 0 parameters");
    const std::array<double, 1> bad{not_a_number};
    check_error(flat_add_error<point_mass>(md, "nan", d, bad), error_code::invalid_parameter, "MASS",
                "nan", "non-finite");
    CHECK(md.element_count() == 0);
  }

  TEST_CASE("a negative mass stops the run with code 100 naming the instance and the mass") {
    mass_spring_damper_model md;
    const dof x = md.add_dof();
    md.add<point_mass>("body", {-1.0}, x);
    md.add<linear_spring>("spring", {1.0}, x, md.ground());
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "MASS", "body",
                "mass m");
  }

  TEST_CASE("a non-finite mass (NaN or infinity) stops the run with code 100") {
    for (const double bad : {not_a_number, inf}) {
      CAPTURE(bad);
      mass_spring_damper_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {bad}, x);
      md.add<linear_spring>("spring", {1.0}, x, md.ground());
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "MASS", "body",
                  "mass m");
    }
  }
}

TEST_SUITE("elements/SPRING") {
  TEST_CASE("two masses joined by a spring: the centre of mass drifts uniformly and the stretch oscillates at sqrt(k/mu)") {
    // Two-body problem: xc = (m1 u1 + m2 u2)/(m1 + m2) moves at constant speed;
    // r = u2 - u1 obeys mu r'' + k r = 0, mu = m1 m2/(m1 + m2), so
    // r = r0 cos(wt) + r0'/w sin(wt), w = sqrt(k/mu) (any mechanics text, two-body reduction).
    const double m1 = 1.0, m2 = 3.0, k = 12.0, mu = m1 * m2 / (m1 + m2), w = std::sqrt(k / mu);  // w = 4
    const double x10 = 0.05, v20 = 0.4, h = 1e-3, end = 2.0;
    mass_spring_damper_model md;
    const dof d1 = md.add_dof("1"), d2 = md.add_dof("2");
    md.add<point_mass>("m1", {m1}, d1);
    md.add<point_mass>("m2", {m2}, d2);
    const auto spring = md.add<linear_spring>("spring", {k}, d1, d2);
    md.add<initial_displacement>("x0", {x10}, d1);
    md.add<initial_velocity>("v0", {v20}, d2);
    simulation sim(md);
    const double r0 = -x10, rd0 = v20, amp = std::hypot(r0, rd0 / w), wd = trapezoidal_frequency(w, h);
    const double xc0 = m1 * x10 / (m1 + m2), vc = m2 * v20 / (m1 + m2);
    double worst_centre = 0, worst_r_ratio = 0, worst_work = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), u1 = s.u(d1), u2 = s.u(d2);
      // The centre of mass is linear in the DOFs and unforced: exact up to round-off.
      worst_centre = std::max(worst_centre, std::abs((m1 * u1 + m2 * u2) / (m1 + m2) - (xc0 + vc * t)));
      const double r_exact = r0 * std::cos(w * t) + rd0 / w * std::sin(w * t);
      worst_r_ratio = std::max(worst_r_ratio, std::abs(u2 - u1 - r_exact) / (amp * (w - wd) * t + 1e-11));
      // W(1): spring force k (u2 - u1), positive in tension.
      worst_work = std::max(worst_work, std::abs(md.work(spring)[0] - k * (u2 - u1)));
    });
    sim.run(fixed_step(end, h));
    CHECK(worst_centre < 1e-12);
    CHECK(worst_r_ratio <= 1.0);
    CHECK(worst_work < 1e-12);
  }

  TEST_CASE("the flows of a spring are k (u1 - u2) and k (u2 - u1) with stiffness block k [1 -1; -1 1]") {
    const linear_spring e({40.0});
    local_input<linear_spring> in;
    in.u << 0.25, -0.05;
    local_output<linear_spring> out;
    std::array<double, 1> work{};
    element_context ctx("SPRING", "s");
    ctx.work = work;
    e.evaluate(in, out, ctx);
    CHECK(out.f(0) == doctest::Approx(12.0));
    CHECK(out.f(1) == doctest::Approx(-12.0));
    CHECK(work[0] == doctest::Approx(-12.0));  // W(1) = k (u2 - u1) < 0: the ends approach, compression
    CHECK(out.K(0, 0) == 40.0);
    CHECK(out.K(0, 1) == -40.0);
    CHECK(out.K(1, 0) == -40.0);
    CHECK(out.K(1, 1) == 40.0);
  }

  TEST_CASE("a flat SPRING with a wrong parameter count is refused with code 101 naming SPRING and the instance") {
    mass_spring_damper_model md;
    const std::array<dof, 2> d{md.add_dof(), md.ground()};
    const std::array<double, 2> two{1.0, 2.0};
    check_error(flat_add_error<linear_spring>(md, "spring", d, two), error_code::parameter_count,
                "SPRING", "spring", "got 2 parameters");
  }

  TEST_CASE("a negative stiffness stops the run with code 100 naming the instance and the stiffness") {
    mass_spring_damper_model md;
    const dof x = md.add_dof();
    md.add<point_mass>("body", {1.0}, x);
    md.add<linear_spring>("spring", {-5.0}, x, md.ground());
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "SPRING", "spring",
                "stiffness k");
  }

  TEST_CASE("a non-finite stiffness (NaN or infinity) stops the run with code 100") {
    for (const double bad : {not_a_number, inf}) {
      CAPTURE(bad);
      mass_spring_damper_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {1.0}, x);
      md.add<linear_spring>("spring", {bad}, x, md.ground());
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "SPRING",
                  "spring", "stiffness k");
    }
  }
}

TEST_SUITE("elements/DAMPER") {
  TEST_CASE("a mass coasting against a damper slows as v0 exp(-c t / m) and travels v0 m/c (1 - exp(-c t / m))") {
    // m v' + c v = 0: v = v0 exp(-lambda t), u = (v0/lambda)(1 - exp(-lambda t)), lambda = c/m.
    // The trapezoidal rule gives v_n = v0 rho^n and, summing u_n = u_{n-1} + h (v_{n-1} + v_n)/2,
    // u_n = (v0/lambda)(1 - rho^n): the error bound of the header comment applies to both.
    const double m = 2.0, c = 3.0, lambda = c / m, v0 = 1.2, h = 0.01, end = 3.0;
    mass_spring_damper_model md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    const auto damper = md.add<linear_damper>("damper", {c}, x, md.ground());
    md.add<initial_velocity>("v0", {v0}, x);
    simulation sim(md);
    const double xh = lambda * h / 2;
    double worst_discrete = 0, worst_work = 0, last_t = 0, rho_n = 1;
    bool below_exact = true, within_bound = true;
    long n = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), decay = std::exp(-lambda * t), dt = t - last_t;
      rho_n *= (1 - lambda * dt / 2) / (1 + lambda * dt / 2);  // one factor rho per step (dt <= h)
      last_t = t;
      ++n;
      worst_discrete = std::max({worst_discrete, std::abs(s.v(x) - v0 * rho_n), std::abs(s.u(x) - v0 / lambda * (1 - rho_n))});
      // 0 <= exp(-lambda t) - rho^n <= bound (steps of at most h).
      const double bound = decay * std::pow(lambda, 3) * h * h * t / (12 * (1 - xh * xh));
      below_exact = below_exact && s.v(x) <= v0 * decay + 1e-12;
      within_bound = within_bound && s.v(x) >= v0 * (decay - bound) - 1e-12 &&
                     std::abs(s.u(x) - v0 / lambda * (1 - decay)) <= v0 / lambda * bound + 1e-12;
      // W(1): damper force c (v2 - v1) with end 2 on the ground.
      worst_work = std::max(worst_work, std::abs(md.work(damper)[0] + c * s.v(x)));
    });
    sim.run(fixed_step(end, h));
    CHECK(n == 301);  // t = 0 and 300 steps
    CHECK(worst_discrete < 1e-12);
    CHECK(below_exact);
    CHECK(within_bound);
    CHECK(worst_work < 1e-12);
    CHECK(sim.a(x) == doctest::Approx(-lambda * sim.v(x)).epsilon(1e-10));
  }

  TEST_CASE("a damper between two free masses conserves their momentum and damps the relative velocity at rate c/mu") {
    // m1 v1' = c (v2 - v1), m2 v2' = -c (v2 - v1): m1 v1 + m2 v2 is constant and
    // vr = v2 - v1 obeys vr' = -(c/mu) vr, mu = m1 m2/(m1 + m2).
    const double m1 = 1.0, m2 = 3.0, c = 0.6, mu = m1 * m2 / (m1 + m2), lambda = c / mu, v10 = 2.0, h = 0.01;
    mass_spring_damper_model md;
    const dof d1 = md.add_dof("1"), d2 = md.add_dof("2");
    md.add<point_mass>("m1", {m1}, d1);
    md.add<point_mass>("m2", {m2}, d2);
    md.add<linear_damper>("damper", {c}, d1, d2);
    md.add<initial_velocity>("v0", {v10}, d1);
    simulation sim(md);
    const double xh = lambda * h / 2;
    double worst_momentum = 0, worst_relative = 0, last_t = 0, rho_n = 1;
    sim.on_output([&](const auto& s) {
      const double dt = s.time() - last_t;
      rho_n *= (1 - lambda * dt / 2) / (1 + lambda * dt / 2);
      last_t = s.time();
      worst_momentum = std::max(worst_momentum, std::abs(m1 * s.v(d1) + m2 * s.v(d2) - m1 * v10));
      worst_relative = std::max(worst_relative, std::abs(s.v(d2) - s.v(d1) + v10 * rho_n));
    });
    sim.run(fixed_step(4.0, h));
    CHECK(worst_momentum < 1e-12);
    CHECK(worst_relative < 1e-12);
    // Exact answer at t = 4 within the bound of the header comment.
    const double decay = std::exp(-lambda * 4.0);
    CHECK(std::abs(sim.v(d2) - sim.v(d1) + v10 * decay) <= v10 * decay * std::pow(lambda, 3) * h * h * 4.0 / (12 * (1 - xh * xh)) + 1e-12);
  }

  TEST_CASE("a flat DAMPER with a wrong parameter count is refused with code 101 naming DAMPER and the instance") {
    mass_spring_damper_model md;
    const std::array<dof, 2> d{md.add_dof(), md.ground()};
    const std::array<double, 3> three{1.0, 2.0, 3.0};
    check_error(flat_add_error<linear_damper>(md, "damper", d, three), error_code::parameter_count,
                "DAMPER", "damper", "got 3 parameters");
  }

  TEST_CASE("a negative damping coefficient stops the run with code 100 naming the instance and the coefficient") {
    mass_spring_damper_model md;
    const dof x = md.add_dof();
    md.add<point_mass>("body", {1.0}, x);
    md.add<linear_damper>("damper", {-0.5}, x, md.ground());
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "DAMPER", "damper",
                "damping coefficient c");
  }

  TEST_CASE("a non-finite damping coefficient (NaN or infinity) stops the run with code 100") {
    for (const double bad : {not_a_number, inf}) {
      CAPTURE(bad);
      mass_spring_damper_model md;
      const dof x = md.add_dof();
      md.add<point_mass>("body", {1.0}, x);
      md.add<linear_damper>("damper", {bad}, x, md.ground());
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "DAMPER",
                  "damper", "damping coefficient c");
    }
  }
}
