// XSRC and VSRC: kinematic sources. They prescribe u, v, a of their DOF and
// write in W(1) the force they apply to it (the reaction), which equals the sum
// of the flows of the other elements on the DOF.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using sources_model = pradis::model<linear_spring, displacement_source, point_mass, velocity_source>;
TEST_SUITE("elements/XSRC") {
  TEST_CASE("a spring divider driven by XSRC follows k2/(k1+k2) u_src and the reaction W(1) is k2 (u_src - u1)") {
    // Massless DOF 1 between a spring k1 to the ground and a spring k2 to the driven DOF 2:
    // balance k1 u1 + k2 (u1 - u2) = 0 gives u1 = k2/(k1+k2) u2 at every instant, and the source
    // applies k2 (u2 - u1) = k1 k2/(k1+k2) u2 to DOF 2 (springs in series).
    const double k1 = 30.0, k2 = 10.0, amp = 0.2, freq = 2.0, phase_deg = 30.0, u0 = 0.05;
    const double big_w = 2 * std::numbers::pi * freq;
    sources_model md;
    const dof d1 = md.add_dof("free"), d2 = md.add_dof("driven");
    md.add<linear_spring>("k1", {k1}, d1, md.ground());
    md.add<linear_spring>("k2", {k2}, d1, d2);
    const auto src = md.add<displacement_source>("src", {amp, freq, phase_deg, u0}, d2);
    simulation sim(md);
    double worst_kinematics = 0, worst_free = 0, worst_reaction = 0;
    int outputs = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), x = big_w * t + phase_deg * deg;
      const double u = u0 + amp * std::sin(x), v = amp * big_w * std::cos(x), a = -amp * big_w * big_w * std::sin(x);
      worst_kinematics = std::max({worst_kinematics, std::abs(s.u(d2) - u), std::abs(s.v(d2) - v) / big_w,
                                   std::abs(s.a(d2) - a) / (big_w * big_w)});
      // The reaction is the spring force on DOF 2 at every output, t = 0 included.
      worst_reaction = std::max(worst_reaction, std::abs(md.work(src)[0] - k2 * (s.u(d2) - s.u(d1))));
      // The balance of the massless DOF 1 holds from the first step on; at t = 0 it still has its
      // initial value 0 (the zero step only makes the accelerations of DOFs with inertia consistent).
      if (t > 0) {
        worst_free = std::max(worst_free, std::abs(s.u(d1) - k2 / (k1 + k2) * u));
        worst_reaction = std::max(worst_reaction, std::abs(md.work(src)[0] - k1 * k2 / (k1 + k2) * u));
      }
      ++outputs;
    });
    sim.run(fixed_step(1.0, 0.01));
    CHECK(outputs == 101);
    CHECK(worst_kinematics < 1e-14);
    CHECK(worst_free < 1e-12);
    CHECK(worst_reaction < 1e-10);
    CHECK(md.work("src")[0] == md.work(src)[0]);  // W(1) is also readable by instance name
    CHECK(sim.residual(d2) == doctest::Approx(md.work(src)[0]));
  }

  TEST_CASE("a mass carried by XSRC needs the reaction W(1) = m a_src(t)") {
    // Newton's second law for the carried mass: the source applies m u''(t), u''(t) = -A W^2 sin(W t + ph).
    const double m = 3.0, amp = 0.1, freq = 2.0, phase_deg = 45.0, u0 = 0.3, big_w = 2 * std::numbers::pi * freq;
    sources_model md;
    const dof d = md.add_dof("carried");
    md.add<point_mass>("body", {m}, d);
    const auto src = md.add<displacement_source>("src", {amp, freq, phase_deg, u0}, d);
    simulation sim(md);
    double worst = 0;
    int outputs = 0;
    sim.on_output([&](const auto& s) {
      const double a = -amp * big_w * big_w * std::sin(big_w * s.time() + phase_deg * deg);
      worst = std::max(worst, std::abs(md.work(src)[0] - m * a));
      ++outputs;
    });
    sim.run(fixed_step(0.5, 0.01));
    CHECK(outputs == 51);  // t = 0 included: W(1) is set at the zero step too
    CHECK(worst < 1e-12);
  }

  TEST_CASE("XSRC on the ground is refused with code 90 naming the source") {
    sources_model md;
    const dof d = md.add_dof();
    md.add<point_mass>("body", {1.0}, d);
    md.add<displacement_source>("src", {0.1, 1.0, 0.0, 0.0}, md.ground());
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::conflicting_initial, "XSRC", "src",
                "ground");
  }

  TEST_CASE("a flat XSRC with a wrong parameter count is refused with code 101 naming XSRC and the instance") {
    sources_model md;
    const std::array<dof, 1> d{md.add_dof()};
    const std::array<double, 3> three{1.0, 2.0, 3.0};
    check_error(flat_add_error<displacement_source>(md, "src", d, three), error_code::parameter_count, "XSRC", "src",
                "got 3 parameters");
  }

  TEST_CASE("a negative or non-finite XSRC frequency stops the run with code 100 naming the instance") {
    for (const double bad : {-2.0, not_a_number, inf}) {
      CAPTURE(bad);
      sources_model md;
      const dof d = md.add_dof();
      md.add<point_mass>("body", {1.0}, d);
      md.add<displacement_source>("src", {0.1, bad, 0.0, 0.0}, d);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "XSRC", "src",
                  "frequency f");
    }
  }

  TEST_CASE("a non-finite XSRC amplitude, phase or constant part stops the run with code 100") {
    const std::array<displacement_source::parameters, 3> bad{
        {{inf, 1.0, 0.0, 0.0}, {0.1, 1.0, not_a_number, 0.0}, {0.1, 1.0, 0.0, -inf}}};
    for (const auto& p : bad) {
      sources_model md;
      const dof d = md.add_dof();
      md.add<point_mass>("body", {1.0}, d);
      md.add<displacement_source>("src", p, d);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "XSRC", "src",
                  "must be finite");
    }
  }
}

TEST_SUITE("elements/VSRC") {
  TEST_CASE("VSRC drives its DOF along the exact integral of its velocity and a mass on it needs W(1) = m a") {
    // v = V0 + A sin(W t + ph), u(0) = 0  =>  u = V0 t - A (cos(W t + ph) - cos ph) / W,  a = A W cos(W t + ph).
    const double m = 3.0, amp = 0.2, freq = 1.0, phase_deg = 60.0, v0 = 0.3, big_w = 2 * std::numbers::pi * freq;
    const double ph = phase_deg * deg;
    sources_model md;
    const dof d = md.add_dof("driven");
    md.add<point_mass>("body", {m}, d);
    const auto src = md.add<velocity_source>("src", {amp, freq, phase_deg, v0}, d);
    simulation sim(md);
    double worst_kinematics = 0, worst_reaction = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), x = big_w * t + ph;
      const double u = v0 * t - amp * (std::cos(x) - std::cos(ph)) / big_w;
      worst_kinematics = std::max({worst_kinematics, std::abs(s.u(d) - u), std::abs(s.v(d) - (v0 + amp * std::sin(x))),
                                   std::abs(s.a(d) - amp * big_w * std::cos(x)) / big_w});
      worst_reaction = std::max(worst_reaction, std::abs(md.work(src)[0] - m * amp * big_w * std::cos(x)));
    });
    sim.run(fixed_step(1.5, 0.01));
    CHECK(worst_kinematics < 1e-14);
    CHECK(worst_reaction < 1e-12);
  }

  TEST_CASE("VSRC with zero frequency moves its DOF at the constant speed V0 + A sin(phase)") {
    const double amp = 0.2, phase_deg = 30.0, v0 = 0.3, speed = v0 + amp * std::sin(phase_deg * deg);
    sources_model md;
    const dof d = md.add_dof();
    md.add<point_mass>("body", {1.0}, d);
    md.add<velocity_source>("src", {amp, 0.0, phase_deg, v0}, d);
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max({worst, std::abs(s.u(d) - speed * s.time()), std::abs(s.v(d) - speed), std::abs(s.a(d))});
    });
    sim.run(fixed_step(1.0, 0.05));
    CHECK(worst < 1e-14);
    CHECK(sim.u(d) == doctest::Approx(0.4));
  }

  TEST_CASE("a mass towed through a spring by a constant-speed VSRC lags as V t - (V/w) sin(wt) and pulls back k (V/w) sin(wt)") {
    // m u1'' + k (u1 - V t) = 0, u1(0) = u1'(0) = 0: u1 = V t - (V/w) sin(wt), w = sqrt(k/m);
    // the source applies k (u2 - u1) = k (V/w) sin(wt). The forcing is linear in t, so the
    // trapezoidal error bound is that of the free oscillation of amplitude V/w: t h^2/12 w^3 (V/w)
    // (Peano bound in the norm sqrt(u^2 + u'^2/w^2), see test_forces.cpp).
    const double m = 2.0, k = 50.0, w = std::sqrt(k / m), speed = 0.8, h = 1e-3, end = 2.0;
    sources_model md;
    const dof d1 = md.add_dof("towed"), d2 = md.add_dof("hook");
    md.add<point_mass>("body", {m}, d1);
    md.add<linear_spring>("rope", {k}, d1, d2);
    const auto src = md.add<velocity_source>("tow", {0.0, 0.0, 0.0, speed}, d2);
    simulation sim(md);
    double worst_ratio = 0, worst_reaction = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      const double bound = t * h * h / 12 * w * w * speed + 1e-11;
      worst_ratio = std::max(worst_ratio, std::abs(s.u(d1) - (speed * t - speed / w * std::sin(w * t))) / bound);
      // The reaction is k (u2 - u1) of the simulated state (exact balance), within k times the bound of the exact one.
      worst_reaction = std::max(worst_reaction, std::abs(md.work(src)[0] - k * (s.u(d2) - s.u(d1))));
      worst_ratio = std::max(worst_ratio, std::abs(md.work(src)[0] - k * speed / w * std::sin(w * t)) / (k * bound));
    });
    sim.run(fixed_step(end, h));
    CHECK(worst_ratio <= 1.0);
    CHECK(worst_reaction < 1e-10);
  }

  TEST_CASE("VSRC on the ground is refused with code 90 naming the source") {
    sources_model md;
    md.add<point_mass>("body", {1.0}, md.add_dof());
    md.add<velocity_source>("src", {0.0, 0.0, 0.0, 1.0}, md.ground());
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::conflicting_initial, "VSRC", "src",
                "ground");
  }

  TEST_CASE("a flat VSRC with a wrong parameter count is refused with code 101 naming VSRC and the instance") {
    sources_model md;
    const std::array<dof, 1> d{md.add_dof()};
    const std::array<double, 5> five{1.0, 2.0, 3.0, 4.0, 5.0};
    check_error(flat_add_error<velocity_source>(md, "src", d, five), error_code::parameter_count, "VSRC", "src",
                "got 5 parameters");
  }

  TEST_CASE("a negative VSRC frequency or a non-finite VSRC parameter stops the run with code 100") {
    struct bad_case {
      velocity_source::parameters p;
      const char* mention;
    };
    const std::array<bad_case, 4> bad{{{{0.1, -1.0, 0.0, 0.0}, "frequency f"},
                                       {{0.1, inf, 0.0, 0.0}, "frequency f"},
                                       {{not_a_number, 1.0, 0.0, 0.0}, "must be finite"},
                                       {{0.1, 1.0, 0.0, inf}, "must be finite"}}};
    for (const auto& b : bad) {
      const std::string mention = b.mention;
      CAPTURE(mention);
      sources_model md;
      const dof d = md.add_dof();
      md.add<point_mass>("body", {1.0}, d);
      md.add<velocity_source>("src", b.p, d);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "VSRC", "src",
                  b.mention);
    }
  }
}
