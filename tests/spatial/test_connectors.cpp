// The spatial connecting elements SD3 (translational spring-damper between body
// points), RSD3 (rotational spring-damper), SPH3 and REV3 (penalty joints) in
// scenes with exact solutions or invariants: the damped oscillation of a body
// hanging on SD3 (m z'' + c z' + k z = -m g), conservation of energy, momentum and
// angular momentum of two free bodies joined by an undamped SD3 at offset points
// (Newton-Euler), and the bad parameters (code 100 with element and instance).

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <tuple>

#include "../elements/element_test_support.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;
using pradis_spatial_tests::seconds_since;
using pradis_spatial_tests::tight_newton;

namespace {
using pradis_spatial_tests::pi;
using pradis_spatial_tests::g;
/// Body parameters: mass m, principal inertias (jx, jy, jz), centre of mass at the reference point.
using pradis_spatial_tests::body;
/// Seconds since t0.
}  // namespace

/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using connectors_model = pradis::model<rigid_body, spatial_spring_damper, spatial_force, initial_rotation,
    initial_velocity, rotational_spring_damper>;
TEST_SUITE("spatial/connectors") {
  TEST_CASE("SD3: a body hanging on a spring-damper from a fixed point follows m z'' + c z' + k z = -m g exactly") {
    // Body (m = 2) with its reference point at the origin, attached at the body point
    // r = (0, 0, 0.5) to the ground point (0, 0, 1.5): L0 = 1, the spring starts unstressed and
    // the line of action passes through the centre of mass (no moment). Gravity is F3.
    // Exact: z(t) = -delta [1 - e^(-sigma t) (cos wd t + sigma / wd sin wd t)], delta = m g / k,
    // sigma = c / (2 m), wd = sqrt(k / m - sigma^2) (the damped linear oscillator).
    const auto t0 = std::chrono::steady_clock::now();
    const double mass = 2.0, k = 800.0, c = 8.0, h = 1e-3;
    connectors_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", body(mass, 0.3, 0.4, 0.5), x[0], x[1], x[2], r);
    const auto sd = m.add<spatial_spring_damper>(
        "spring", {0, 0, 1.5, 0, 0, 0, 0, 0, 0, 0, 0, 0.5, k, 1.0, c}, G, G, G, G, G, G, x[0], x[1], x[2], r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    simulation sim(m);
    const double delta = mass * g / k, sigma = c / (2 * mass), wd = std::sqrt(k / mass - sigma * sigma);
    // Trapezoidal rule: the frequency error is about wn^3 h^2 / 12 per unit time (Hughes 9.3).
    double worst = 0, worst_rot = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      const double z = -delta * (1 - std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t)));
      worst = std::max(worst, std::abs(s.u(x[2]) - z));
      worst_rot = std::max({worst_rot, std::abs(s.u(x[0])), std::abs(s.u(x[1])), node_angular_velocity(s, r).norm()});
    });
    sim.run({.end = 2.0, .out = 0.01, .smax = h, .newton = tight_newton});
    const double wn = std::sqrt(k / mass);
    MESSAGE("SD3 hanging body: max |z - z_exact| = ", worst, " m (delta = ", delta, " m), bound wn^3 h^2 t delta / 12 = ",
            wn * wn * wn * h * h * 2.0 * delta / 12, "; lateral/rotation ", worst_rot, "; ", seconds_since(t0), " s");
    CHECK(worst < wn * wn * wn * h * h * 2.0 * delta / 12);
    CHECK(worst_rot < 1e-12);
    // Static elongation: the work vector at the end (the oscillation has decayed by e^-4).
    const auto w = m.work(sd);
    CHECK(w[0] - 1.0 == doctest::Approx(delta).epsilon(0.02));
    CHECK(w[2] == doctest::Approx(mass * g).epsilon(0.02));
  }

  TEST_CASE("SD3: two free bodies joined at offset points conserve energy, momentum and angular momentum") {
    // Undamped SD3 between body points off the centres of mass: the spring force is internal,
    // so the total momentum and angular momentum about the origin are exactly conserved
    // (Newton-Euler), the energy T + k (L - L0)^2 / 2 too. The trapezoidal rule keeps the
    // momentum to the Newton tolerance, the energy and the angular momentum to O(h^2) (as for
    // the free body in test_spatial_elements.cpp): their drifts must fall ~4x when h halves.
    const auto t0 = std::chrono::steady_clock::now();
    const double k = 200.0, l0 = 0.8;
    struct drift {
      double e0 = 0, emax = 0, dp = 0, dh = 0;
    };
    auto run = [&](double h) {
    connectors_model m;
    const auto xa = m.add_dofs(3, "xa");
    const auto xb = m.add_dofs(3, "xb");
    const rotation_node ra = m.add_rotation_node("ra"), rb = m.add_rotation_node("rb");
    const vec3 ia(0.3, 0.5, 0.7), ib(0.6, 0.4, 0.2);
    const double ma = 1.5, mb = 2.5;
    const auto ba = m.add<rigid_body>("a", body(ma, ia.x(), ia.y(), ia.z()), xa[0], xa[1], xa[2], ra);
    const auto bb = m.add<rigid_body>("b", body(mb, ib.x(), ib.y(), ib.z()), xb[0], xb[1], xb[2], rb);
    const vec3 xa0(0, 0, 0), xb0(1.2, 0.3, -0.2);
    const auto sd = m.add<spatial_spring_damper>(
        "spring", {xa0.x(), xa0.y(), xa0.z(), 0.2, -0.1, 0.3, xb0.x(), xb0.y(), xb0.z(), -0.25, 0.15, 0.1, k, l0, 0.0},
        xa[0], xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
    m.add<initial_rotation>("wa", {1, 0, 0, 0, 1.0, -0.5, 2.0}, ra);
    m.add<initial_rotation>("wb", {0, 1, 0, 20, -1.5, 0.7, 0.3}, rb);
    m.add<initial_velocity>("va", {0.4}, xa[1]);
    m.add<initial_velocity>("vb", {-0.3}, xb[2]);
    simulation sim(m);
    auto invariants = [&](const auto& s, vec3& p, vec3& lmom, double& e) {
      const vec3 va(s.v(xa[0]), s.v(xa[1]), s.v(xa[2])), vb(s.v(xb[0]), s.v(xb[1]), s.v(xb[2]));
      const vec3 pa = xa0 + vec3(s.u(xa[0]), s.u(xa[1]), s.u(xa[2]));
      const vec3 pb = xb0 + vec3(s.u(xb[0]), s.u(xb[1]), s.u(xb[2]));
      const auto wa = m.work(ba), wb = m.work(bb), wsd = m.work(sd);
      p = ma * va + mb * vb;
      lmom = vec3(wa[1], wa[2], wa[3]) + vec3(wb[1], wb[2], wb[3]) + ma * pa.cross(va) + mb * pb.cross(vb);
      e = wa[0] + wb[0] + 0.5 * k * (wsd[0] - l0) * (wsd[0] - l0);
    };
    vec3 p0, h0;
    double e0 = 0, dp = 0, dh = 0, emax = 0;
    bool first = true;
    sim.on_output([&](const auto& s) {
      vec3 p, hh;
      double e;
      invariants(s, p, hh, e);
      if (first) {
        p0 = p, h0 = hh, e0 = e, first = false;
        return;
      }
      emax = std::max(emax, std::abs(e - e0) / e0);
      dp = std::max(dp, (p - p0).norm());
      dh = std::max(dh, (hh - h0).norm());
    });
    sim.run({.end = 1.0, .out = 0.01, .smax = h, .newton = tight_newton});
    return drift{e0, emax, dp, dh};
    };
    const drift coarse = run(2e-3), fine = run(1e-3);
    MESSAGE("SD3 two bodies, h = 1e-3: energy rel. drift ", fine.emax, " (E0 = ", fine.e0, " J), momentum ", fine.dp,
            ", angular momentum ", fine.dh, "; at h = 2e-3: ", coarse.emax, ", ", coarse.dp, ", ", coarse.dh, "; ",
            seconds_since(t0), " s");
    CHECK(fine.e0 > 1.0);
    CHECK(fine.emax < 1e-4);
    CHECK(fine.dp < 1e-10);
    CHECK(fine.dh < 1e-4);
    CHECK(coarse.emax / fine.emax == doctest::Approx(4.0).epsilon(0.15));
    CHECK(coarse.dh / fine.dh == doctest::Approx(4.0).epsilon(0.15));
  }

  TEST_CASE("RSD3: a body on a torsional spring-damper to the ground oscillates at sqrt(k/J - sigma^2) about a principal axis") {
    // Body with principal inertias (0.4, 0.6, J = 0.25) turning about its Z axis, RSD3 to the
    // fully fixed node, started at rest orientation with w0 about Z: J theta'' + c theta' + k theta = 0,
    // theta(t) = (w0 / wd) e^(-sigma t) sin(wd t), sigma = c / (2 J), wd = sqrt(k / J - sigma^2).
    const auto t0 = std::chrono::steady_clock::now();
    const double jz = 0.25, k = 40.0, c = 0.5, w0 = 2.0, h = 1e-3;
    connectors_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", body(1, 0.4, 0.6, jz), x[0], x[1], x[2], r);
    const auto rs = m.add<rotational_spring_damper>("torsion", {k, c}, G, G, G, r);
    m.add<initial_rotation>("start", {0, 0, 1, 0, 0, 0, w0}, r);
    simulation sim(m);
    const double sigma = c / (2 * jz), wd = std::sqrt(k / jz - sigma * sigma), wn = std::sqrt(k / jz);
    double worst = 0, off_axis = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), theta = w0 / wd * std::exp(-sigma * t) * std::sin(wd * t);
      const quaternion q = node_quaternion(s, r);
      worst = std::max(worst, to_axis_angle(relative_rotation(q, from_axis_angle(vec3::UnitZ(), theta))).angle);
      off_axis = std::max({off_axis, std::abs(q(0)), std::abs(q(1))});
    });
    const double end = 2.0;
    sim.run({.end = end, .out = 0.01, .smax = h, .newton = tight_newton});
    // Trapezoidal phase error wn^3 h^2 t / 12 times the amplitude w0 / wn.
    const double bound = wn * wn * wn * h * h * end / 12 * (w0 / wn);
    MESSAGE("RSD3 torsional oscillator: max angle error ", worst, " rad (amplitude ", w0 / wd, " rad), bound ", bound,
            "; off-axis ", off_axis, "; ", seconds_since(t0), " s");
    CHECK(worst < bound);
    CHECK(off_axis < 1e-12);
    const auto w = m.work(rs);
    const double theta_end = w0 / wd * std::exp(-sigma * end) * std::sin(wd * end);
    CHECK(w[0] == doctest::Approx(std::abs(theta_end)).epsilon(1e-3));
  }

  TEST_CASE("RSD3: two free bodies joined by an undamped rotational spring conserve angular momentum and energy") {
    // The spring's moments on a and b are equal and opposite (internal), so the total angular
    // momentum and the energy T + k phi^2 / 2 are invariants; the trapezoidal rule keeps both
    // to O(h^2): their drifts must fall ~4x when h halves. Relative angles reach 0.7 rad: the
    // finite-rotation formula, not a small-angle one.
    const auto t0 = std::chrono::steady_clock::now();
    const double k = 5.0;
    struct drift {
      double emax = 0, dh = 0, phimax = 0;
    };
    auto run = [&](double h) {
    connectors_model m;
    const auto xa = m.add_dofs(3, "xa");
    const auto xb = m.add_dofs(3, "xb");
    const rotation_node ra = m.add_rotation_node("ra"), rb = m.add_rotation_node("rb");
    const auto ba = m.add<rigid_body>("a", body(1, 0.3, 0.5, 0.7), xa[0], xa[1], xa[2], ra);
    const auto bb = m.add<rigid_body>("b", body(1, 0.6, 0.4, 0.2), xb[0], xb[1], xb[2], rb);
    const auto rs = m.add<rotational_spring_damper>("spring", {k, 0.0}, ra, rb);
    m.add<initial_rotation>("wa", {1, 0, 0, 0, 1.0, -0.5, 2.0}, ra);
    m.add<initial_rotation>("wb", {0, 1, 0, 20, -1.5, 0.7, 0.3}, rb);
    simulation sim(m);
    vec3 h0;
    double e0 = 0, emax = 0, dh = 0, phimax = 0;
    bool first = true;
    sim.on_output([&](const auto&) {
      const auto wa = m.work(ba), wb = m.work(bb), ws = m.work(rs);
      const vec3 hh = vec3(wa[1], wa[2], wa[3]) + vec3(wb[1], wb[2], wb[3]);
      const double e = wa[0] + wb[0] + 0.5 * k * ws[0] * ws[0];
      phimax = std::max(phimax, ws[0]);
      if (first) {
        h0 = hh, e0 = e, first = false;
        return;
      }
      emax = std::max(emax, std::abs(e - e0) / e0);
      dh = std::max(dh, (hh - h0).norm());
    });
    sim.run({.end = 1.5, .out = 0.01, .smax = h, .newton = tight_newton});
    return drift{emax, dh, phimax};
    };
    const drift coarse = run(2e-3), fine = run(1e-3);
    MESSAGE("RSD3 two bodies, h = 1e-3: energy rel. drift ", fine.emax, ", angular momentum ", fine.dh,
            ", max relative angle ", fine.phimax, " rad; at h = 2e-3: ", coarse.emax, ", ", coarse.dh, "; ",
            seconds_since(t0), " s");
    CHECK(fine.phimax > 0.5);
    CHECK(fine.emax < 1e-5);
    CHECK(fine.dh < 1e-5);
    CHECK(coarse.emax / fine.emax == doctest::Approx(4.0).epsilon(0.15));
    CHECK(coarse.dh / fine.dh == doctest::Approx(4.0).epsilon(0.15));
  }

  TEST_CASE("SD3 with a negative stiffness, length or damping stops the run with code 100 in its name") {
    struct bad {
      double k, l0, c;
      const char* mention;
    };
    for (const bad b : {bad{-1.0, 1.0, 0.0, "k < 0"}, bad{1.0, -0.5, 0.0, "L0 < 0"}, bad{1.0, 1.0, -2.0, "c < 0"}}) {
      connectors_model m;
      const auto x = m.add_dofs(3, "x");
      const rotation_node r = m.add_rotation_node("r");
      const dof G = m.ground();
      m.add<rigid_body>("body", body(1, 1, 1, 1), x[0], x[1], x[2], r);
      m.add<spatial_spring_damper>("sd", {0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, b.k, b.l0, b.c}, G, G, G, G, G, G, x[0],
                                   x[1], x[2], r);
      simulation sim(m);
      check_error(error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); }), error_code::invalid_parameter, "SD3", "sd",
                  b.mention);
    }
    // The flat path checks the parameter count (code 101).
    library_model lm;
    const auto d = lm.add_dofs(12, "d");
    const std::array<double, 3> few{1, 2, 3};
    const auto e = error_from([&] { lm.add_by_name("SD3", "short", d, few); });
    REQUIRE(e.has_value());
    CHECK(e->number() == static_cast<int>(error_code::parameter_count));
    CHECK(e->instance() == "short");
  }

  TEST_CASE("RSD3 with a negative stiffness or damping stops the run with code 100 in its name") {
    for (const auto& [k, c, mention] : {std::tuple{-1.0, 0.0, "k < 0"}, std::tuple{1.0, -1.0, "c < 0"}}) {
      connectors_model m;
      const auto x = m.add_dofs(3, "x");
      const rotation_node r = m.add_rotation_node("r");
      const dof G = m.ground();
      m.add<rigid_body>("body", body(1, 1, 1, 1), x[0], x[1], x[2], r);
      m.add<rotational_spring_damper>("rsd", {k, c}, G, G, G, r);
      simulation sim(m);
      check_error(error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); }), error_code::invalid_parameter, "RSD3",
                  "rsd", mention);
    }
  }
}
