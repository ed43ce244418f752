// Electric sources: current sources (IDC, ISIN, ITAB), voltage sources to ground that
// prescribe their node (VDC, VSIN, VTAB) and floating voltage sources with the current
// as an internal DOF (VDC2, VSIN2, VTAB2), in circuits with closed-form answers, and
// their bad parameters.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {

// Integral from 0 to t of the table (0, 0), (1, 2), (3, -2), constant -2 after t = 3, by hand:
// 0..1: t^2; 1..3: 1 + 2 (t-1) - (t-1)^2; after 3: 1 - 2 (t - 3) (the area 1 + 4 - 4 = 1 at t = 3).
double table_integral(double t) {
  if (t <= 1) return t * t;
  if (t <= 3) return 1 + 2 * (t - 1) - (t - 1) * (t - 1);
  return 1 - 2 * (t - 3);
}
double table_value(double t) { return t <= 1 ? 2 * t : (t <= 3 ? 2 - 2 * (t - 1) : -2.0); }
const table_wave::parameters table{{0.0, 0.0, 1.0, 2.0, 3.0, -2.0}};

// Runs a one-stage model and returns the error it throws.
template <class M>
std::optional<error> run_error(M& md) {
  simulation sim(md);
  return error_from([&] { sim.run(fixed_step(0.01, 0.001)); });
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using sources_model = pradis::model<current_dc, resistor, current_sine, capacitor, current_table, voltage_table,
    voltage_sine, floating_voltage_dc, floating_voltage_sine, floating_voltage_table, voltage_dc>;
TEST_SUITE("electric/sources") {
  TEST_CASE("IDC into a resistor to ground: v = I R from t = 0 on; W(2) is the voltage across the source") {
    sources_model md;
    const dof n = md.add_dof("n");
    const auto src = md.add<current_dc>("I", {0.25}, n, md.ground());
    md.add<resistor>("R", {40.0}, n, md.ground());
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max({worst, std::abs(s.v(n) - 10.0), std::abs(md.work(src)[1] - 10.0)});
    });
    sim.run(fixed_step(0.1, 0.01));
    CHECK(worst < 1e-12);
    CHECK(md.work(src)[0] == 0.25);
  }

  TEST_CASE("ISIN charging a capacitor: v = (I0 t - A (cos(wt + ph) - cos ph)/w) / C within the trapezoidal bound") {
    // C v' = I(t): v is the integral of I / C; the trapezoidal rule's error on it is at most
    // t h^2 max|I''| / (12 C) = t h^2 A w^2 / (12 C).
    const double c = 1e-3, i0 = 0.01, amp = 0.05, f = 5.0, ph = 30 * deg, w = 2 * std::numbers::pi * f, h = 1e-3;
    sources_model md;
    const dof n = md.add_dof("n");
    md.add<current_sine>("I", {amp, f, 30.0, i0}, n, md.ground());
    md.add<capacitor>("C", {c}, n, md.ground());
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), exact = (i0 * t - amp * (std::cos(w * t + ph) - std::cos(ph)) / w) / c;
      worst = std::max(worst, std::abs(s.v(n) - exact) / (t * h * h * amp * w * w / (12 * c) + 1e-12));
    });
    sim.run(fixed_step(0.5, h));
    CHECK(worst <= 1.0);
  }

  TEST_CASE("ITAB charging a capacitor with steps on the breakpoints: v = integral of the table / C exactly") {
    // A piecewise-linear current is integrated exactly by the trapezoidal rule when every kink is a step end.
    const double c = 0.5;
    sources_model md;
    const dof n = md.add_dof("n");
    const auto src = md.add<current_table>("I", table, n, md.ground());
    md.add<capacitor>("C", {c}, n, md.ground());
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max({worst, std::abs(s.v(n) - table_integral(s.time()) / c),
                        std::abs(md.work(src)[0] - table_value(s.time()))});
    });
    sim.run(fixed_step(4.0, 0.05));
    CHECK(worst < 1e-11);
  }

  TEST_CASE("VTAB prescribes its node: v = table(t), u = its exact integral, W(1) = v / R into a resistor") {
    sources_model md;
    const dof n = md.add_dof("n");
    const auto src = md.add<voltage_table>("V", table, n);
    md.add<resistor>("R", {4.0}, n, md.ground());
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      worst = std::max({worst, std::abs(s.v(n) - table_value(t)), std::abs(s.u(n) - table_integral(t)),
                        std::abs(md.work(src)[0] - table_value(t) / 4.0)});
    });
    sim.run(fixed_step(3.7, 0.013));
    CHECK(worst < 1e-12);
  }

  TEST_CASE("VSIN prescribes v = V0 + A sin(wt + ph) with u its exact integral; a resistor draws v / R") {
    const double amp = 3.0, f = 2.0, v0 = 1.0, ph = 45 * deg, w = 2 * std::numbers::pi * f, r = 2.0;
    sources_model md;
    const dof n = md.add_dof("n");
    const auto src = md.add<voltage_sine>("V", {amp, f, 45.0, v0}, n);
    md.add<resistor>("R", {r}, n, md.ground());
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), v = v0 + amp * std::sin(w * t + ph);
      const double u = v0 * t - amp * (std::cos(w * t + ph) - std::cos(ph)) / w;
      worst = std::max({worst, std::abs(s.v(n) - v), std::abs(s.u(n) - u), std::abs(md.work(src)[0] - v / r)});
    });
    sim.run(fixed_step(1.0, 0.01));
    CHECK(worst < 1e-12);
  }

  TEST_CASE("VDC2 between two free nodes: a voltage divider to ground, current V/(R1+R2) as the internal DOF") {
    // The source's + node a feeds R1 to ground, its - node b is fed through R2 from ground:
    // i = V / (R1 + R2), v_a = i R1, v_b = -i R2. The constraint row of the internal current has a zero
    // diagonal; the sparse LU handles it by static pivoting.
    const double big_v = 9.0, r1 = 100.0, r2 = 200.0, i = big_v / (r1 + r2);
    sources_model md;
    const dof a = md.add_dof("a"), b = md.add_dof("b");
    const auto src = md.add<floating_voltage_dc>("V", {big_v}, a, b);
    md.add<resistor>("R1", {r1}, a, md.ground());
    md.add<resistor>("R2", {r2}, md.ground(), b);
    simulation sim(md);
    sim.run(fixed_step(0.05, 0.01));
    CHECK(sim.v(a) == doctest::Approx(i * r1).epsilon(1e-12));
    CHECK(sim.v(b) == doctest::Approx(-i * r2).epsilon(1e-12));
    CHECK(md.work(src)[0] == doctest::Approx(i).epsilon(1e-12));
    CHECK(md.work(src)[1] == big_v);
  }

  TEST_CASE("VSIN2 stacked on VTAB2 feeding an RC: both source constraints hold and both carry the loop current") {
    // VSIN2 (+ at a, - at b) on top of VTAB2 (+ at b, - at ground): v_b = V_tab(t), v_a - v_b = V_sin(t)
    // exactly (constraint rows); one loop through R and C, so both internal currents equal (v_a - v_c) / R.
    const double r = 10.0, c = 0.01, h = 1e-3;
    sources_model md;
    const dof a = md.add_dof("a"), b = md.add_dof("b"), cn = md.add_dof("c");
    const auto vs = md.add<floating_voltage_sine>("Vs", {1.0, 2.0, 0.0, 0.5}, a, b);
    const auto vt = md.add<floating_voltage_table>("Vt", table, b, md.ground());
    md.add<resistor>("R", {r}, a, cn);
    md.add<capacitor>("C", {c}, cn, md.ground());
    simulation sim(md);
    double worst_constraint = 0, worst_kcl = 0;
    sim.on_output([&](const auto& s) {
      // From t = 0 on: the zero step solves the internal currents (integrators/velocity_constraints.hpp).
      const double t = s.time(), vsin = 0.5 + std::sin(4 * std::numbers::pi * t);
      worst_constraint = std::max({worst_constraint, std::abs(s.v(a) - s.v(b) - vsin),
                                   std::abs(s.v(b) - table_value(t))});
      // One loop: both sources carry the resistor current (v_a - v_c) / R.
      const double ir = (s.v(a) - s.v(cn)) / r;
      worst_kcl = std::max({worst_kcl, std::abs(md.work(vs)[0] - ir), std::abs(md.work(vt)[0] - ir)});
    });
    sim.run(fixed_step(1.0, h));
    CHECK(worst_constraint < 1e-9);
    CHECK(worst_kcl < 1e-9);
  }

  TEST_CASE("a voltage source to ground on the ground is refused with code 90") {
    sources_model md;
    md.add<resistor>("R", {1.0}, md.add_dof(), md.ground());
    md.add<voltage_dc>("V", {1.0}, md.ground());
    check_error(run_error(md), error_code::conflicting_initial, "VDC", "V", "ground");
  }

  TEST_CASE("bad source parameters stop the run with code 100 naming the type, the instance and the parameter") {
    SUBCASE("IDC") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<current_dc>("I", {inf}, n, md.ground());
      check_error(run_error(md), error_code::invalid_parameter, "IDC", "I", "current I0");
    }
    SUBCASE("ISIN") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<current_sine>("I", {1.0, -1.0, 0.0, 0.0}, n, md.ground());
      check_error(run_error(md), error_code::invalid_parameter, "ISIN", "I", "frequency f");
    }
    SUBCASE("ITAB: times not increasing") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<current_table>("I", {{0.0, 1.0, 2.0, 1.0, 2.0, 3.0}}, n, md.ground());
      check_error(run_error(md), error_code::invalid_parameter, "ITAB", "I", "time t3");
    }
    SUBCASE("ITAB: odd count") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<current_table>("I", {{0.0, 1.0, 2.0, 1.0, 3.0}}, n, md.ground());
      check_error(run_error(md), error_code::invalid_parameter, "ITAB", "I", "even number");
    }
    SUBCASE("ITAB: flat list with an odd count is code 101") {
      sources_model md;
      const std::array<dof, 2> d{md.add_dof(), md.ground()};
      const std::array<double, 5> five{0.0, 1.0, 2.0, 1.0, 3.0};
      check_error(flat_add_error<current_table>(md, "I", d, five), error_code::parameter_count, "ITAB", "I",
                  "got 5 parameters");
    }
    SUBCASE("VDC") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<voltage_dc>("V", {-inf}, n);
      check_error(run_error(md), error_code::invalid_parameter, "VDC", "V", "voltage V0");
    }
    SUBCASE("VSIN") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<voltage_sine>("V", {inf, 1.0, 0.0, 0.0}, n);
      check_error(run_error(md), error_code::invalid_parameter, "VSIN", "V", "amplitude");
    }
    SUBCASE("VTAB") {
      sources_model md;
      const dof n = md.add_dof();
      md.add<resistor>("R", {1.0}, n, md.ground());
      md.add<voltage_table>("V", {{1.0, 1.0, 0.5, 1.0}}, n);
      check_error(run_error(md), error_code::invalid_parameter, "VTAB", "V", "time t2");
    }
    SUBCASE("VDC2, VSIN2, VTAB2") {
      sources_model md;
      const dof a = md.add_dof(), b = md.add_dof();
      md.add<resistor>("R", {1.0}, a, b);
      md.add<floating_voltage_dc>("V1", {inf}, a, md.ground());
      check_error(run_error(md), error_code::invalid_parameter, "VDC2", "V1", "voltage V0");
      sources_model m2;
      const dof c = m2.add_dof();
      m2.add<resistor>("R", {1.0}, c, m2.ground());
      m2.add<floating_voltage_sine>("V2", {1.0, inf, 0.0, 0.0}, c, m2.ground());
      check_error(run_error(m2), error_code::invalid_parameter, "VSIN2", "V2", "frequency f");
      sources_model m3;
      const dof e = m3.add_dof();
      m3.add<resistor>("R", {1.0}, e, m3.ground());
      m3.add<floating_voltage_table>("V3", {{0.0, 1.0, 1.0, inf}}, e, m3.ground());
      check_error(run_error(m3), error_code::invalid_parameter, "VTAB2", "V3", "table value 4");
    }
  }
}
