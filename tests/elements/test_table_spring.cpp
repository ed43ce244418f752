// TSPRING and its tabular_law: a mass on a table that samples a linear law
// oscillates exactly like a linear spring; PCHIP tables of a cubic hardening law
// give the static deflection to the interpolation error, which falls as h^3 with
// table refinement; the Jacobian is the exact slope; every bad table is refused
// with code 100 (or 101 for a flat count) naming the element, instance and entry.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "element_test_support.hpp"
#include "pradis/elements/mech1d/table_spring.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// Table of f(d) = k d + k3 d^3 at n + 1 equally spaced points on [a, b].
std::vector<double> cubic_table(double k, double k3, double a, double b, int n) {
  std::vector<double> t;
  for (int i = 0; i <= n; ++i) {
    const double d = a + (b - a) * i / n;
    t.push_back(d);
    t.push_back(k * d + k3 * d * d * d);
  }
  return t;
}
// The real root of k d + k3 d^3 = F (k, k3 > 0): Cardano's formula for
// d^3 + p d - q = 0 with p = k / k3 > 0, q = F / k3 (one real root).
double cubic_root(double k, double k3, double F) {
  const double p = k / k3, q = F / k3, s = std::sqrt(q * q / 4 + p * p * p / 27);
  return std::cbrt(q / 2 + s) + std::cbrt(q / 2 - s);
}
// Force and dF/du2 of a TSPRING from ground (DOF 1 at 0) to a DOF at d.
std::array<double, 2> force_slope(const table_spring& e, double d) {
  local_input<table_spring> in;
  in.u(1) = d;
  local_output<table_spring> out;
  out.want_jacobian = true;
  element_context ctx("TSPRING", "t");
  std::array<double, 2> w{};
  ctx.work = w;
  e.evaluate(in, out, ctx);
  return {out.f(1), out.K(1, 1)};
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using table_spring_model = pradis::model<point_mass, table_spring, initial_displacement, constant_force>;
TEST_SUITE("elements/TSPRING") {
  TEST_CASE("a mass on a piecewise-linear table of k d oscillates with the period 2 pi sqrt(m/k)") {
    // The linear interpolation (and the end-slope extrapolation) of a linear law
    // is the law itself, so the run is the undamped oscillator m u'' + k u = 0
    // under the trapezoidal rule: u_n = A cos(wd t_n + phi) with
    // tan(wd h/2) = w h/2 (Hughes, The Finite Element Method, 9.3). The amplitude
    // (0.2) runs over 6 breakpoints and beyond the table's ends (+-0.15).
    const double m = 0.5, k = 200.0, w = std::sqrt(k / m), u0 = 0.2, h = 1e-3, end = 2.0;
    std::vector<double> table;
    for (int i = -3; i <= 3; ++i) table.insert(table.end(), {0.05 * i, k * 0.05 * i});
    table_spring_model md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    md.add<table_spring>("spring", {0.0, 0.0, table}, md.ground(), x);
    md.add<initial_displacement>("x0", {u0}, x);
    simulation sim(md);
    const double wd = trapezoidal_frequency(w, h);
    double worst = 0, prev_t = 0, prev_u = u0;
    std::vector<double> down;  // downward zero crossings, linearly interpolated
    sim.on_output([&](const auto& s) {
      const double t = s.time(), u = s.u(x);
      worst = std::max(worst, std::abs(u - u0 * std::cos(wd * t)));
      if (prev_u > 0 && u <= 0) down.push_back(prev_t + (t - prev_t) * prev_u / (prev_u - u));
      prev_t = t;
      prev_u = u;
    });
    sim.run(fixed_step(end, h));
    CHECK(worst < 1e-9);  // the discrete solution of the linear oscillator
    REQUIRE(down.size() >= 4);
    const double period = (down.back() - down.front()) / static_cast<double>(down.size() - 1);
    const double T = 2 * std::numbers::pi * std::sqrt(m / k);
    // Scheme error: T_d / T - 1 = w / wd - 1 <= (w h)^2 / 12 / (1 - (w h)^2 / 12).
    const double wh2 = w * w * h * h;
    CHECK(std::abs(period / T - 1) <= wh2 / 12 / (1 - wh2 / 12) + 1e-9);
    CHECK(period == doctest::Approx(2 * std::numbers::pi / wd).epsilon(1e-7));
    CHECK(std::abs(period / T - 1) > 0.5 * wh2 / 12);  // the phase error is there and of the predicted size
  }

  TEST_CASE("a PCHIP table of k d + k3 d^3 gives the static deflection to an h^3 interpolation error") {
    // Static deflection under a load F: k d + k3 d^3 = F (Cardano). The PCHIP
    // node slopes (weighted harmonic means) are O(h^2)-accurate on smooth
    // monotone data, so the interpolant is O(h^3) (Fritsch & Carlson 1980;
    // Fritsch & Butland 1984), and so is the deflection error |df| / f'.
    const double k = 100.0, k3 = 1e4;
    std::vector<double> errors;
    for (const int n : {16, 32, 64, 128}) {
      const table_spring e({1.0, 0.0, cubic_table(k, k3, 0.0, 0.3, n)});
      double worst = 0;
      for (int j = 1; j <= 1000; ++j) {
        const double F = 0.08 * j;  // 0.08 ... 80 N: deflections 0.0008 ... 0.17 m
        double d = 0;
        for (int it = 0; it < 50; ++it) {  // Newton with the element's force and Jacobian
          const auto [f, s] = force_slope(e, d);
          const double dd = (f - F) / s;
          d -= dd;
          if (std::abs(dd) < 1e-15) break;
        }
        CHECK(force_slope(e, d)[0] == doctest::Approx(F).epsilon(1e-12));
        worst = std::max(worst, std::abs(d - cubic_root(k, k3, F)));
      }
      errors.push_back(worst);
    }
    MESSAGE("PCHIP deflection errors, 16/32/64/128 segments: ", errors[0], " ", errors[1], " ", errors[2], " ",
            errors[3]);
    for (std::size_t i = 1; i < errors.size(); ++i) {
      const double order = std::log2(errors[i - 1] / errors[i]);
      CAPTURE(order);
      CHECK(order > 2.7);
    }
    CHECK(errors[3] < 1e-6);
  }

  TEST_CASE("a damped mass under a constant load settles at the PCHIP deflection of the cubic law") {
    // m u'' + c u' + f(u) = F with f the PCHIP table of k d + k3 d^3: the rest
    // state is f(u) = F; with 128 segments on [0, 0.3] the deflection error of
    // the table is below 1e-6 (previous test), so u -> cubic_root(F) within that.
    const double m = 1.0, k = 100.0, k3 = 1e4, c = 40.0, F = 15.0;
    table_spring_model md;
    const dof x = md.add_dof("x");
    md.add<point_mass>("body", {m}, x);
    md.add<table_spring>("spring", {1.0, c, cubic_table(k, k3, 0.0, 0.3, 128)}, md.ground(), x);
    md.add<constant_force>("load", {F}, x);
    simulation sim(md);
    sim.run(fixed_step(6.0, 0.01));
    CHECK(std::abs(sim.u(x) - cubic_root(k, k3, F)) < 1e-6);
    CHECK(std::abs(sim.v(x)) < 1e-8);
  }

  TEST_CASE("the stiffness in the Jacobian is the segment slope (linear) and the exact PCHIP derivative") {
    const table_spring lin({0.0, 3.0, {0.0, 0.0, 0.1, 5.0, 0.3, 6.0}});
    // Mid-segment and at a breakpoint (the segment to the right): slopes 50 and 5 N/m.
    CHECK(force_slope(lin, 0.05)[1] == doctest::Approx(50.0).epsilon(1e-14));
    CHECK(force_slope(lin, 0.05)[0] == doctest::Approx(2.5).epsilon(1e-14));
    CHECK(force_slope(lin, 0.1)[1] == doctest::Approx(5.0).epsilon(1e-14));
    CHECK(force_slope(lin, 0.1)[0] == doctest::Approx(5.0).epsilon(1e-14));
    // Extrapolation with the end slopes: below 0 slope 50, above 0.3 slope 5.
    CHECK(force_slope(lin, -0.2)[0] == doctest::Approx(-10.0).epsilon(1e-14));
    CHECK(force_slope(lin, 0.5)[0] == doctest::Approx(7.0).epsilon(1e-14));
    CHECK(force_slope(lin, 0.5)[1] == doctest::Approx(5.0).epsilon(1e-14));
    // PCHIP node slopes by the formulas (Moler, Numerical Computing with MATLAB,
    // 3.4): x = 0, 1, 2, 3, y = 0, 1, 1, 2: secants 1, 0, 1, interior slopes 0
    // (a flat secant), end slopes ((2 h0 + h1) d0 - h0 d1) / (h0 + h1) = 1.5.
    const tabular_law pc(std::vector<double>{0, 0, 1, 1, 2, 1, 3, 2}, interpolation::monotone_cubic);
    CHECK(pc.node_slope(0) == 1.5);
    CHECK(pc.node_slope(1) == 0.0);
    CHECK(pc.node_slope(2) == 0.0);
    CHECK(pc.node_slope(3) == 1.5);
    // It interpolates, stays within [1, 1] on the flat segment (no overshoot) and has these slopes at the nodes.
    for (int i = 0; i < 4; ++i) CHECK(pc.at(i).value == std::vector<double>{0, 1, 1, 2}[static_cast<std::size_t>(i)]);
    for (double xv = 1.0; xv <= 2.0; xv += 0.125) CHECK(pc.at(xv).value == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(pc.at(0.0).slope == 1.5);
    CHECK(pc.at(3.0).slope == 1.5);
    CHECK(pc.at(4.0).value == 3.5);  // extrapolation with the end node slope
    // Unequal spacing: weighted harmonic mean, h0 = 1, h1 = 2, secants 1 and 2:
    // w1 = 2 h1 + h0 = 5, w2 = h1 + 2 h0 = 4, slope 9 / (5/1 + 4/2) = 9/7.
    const tabular_law un(std::vector<double>{0, 0, 1, 1, 3, 5}, interpolation::monotone_cubic);
    CHECK(un.node_slope(1) == doctest::Approx(9.0 / 7.0).epsilon(1e-15));
    // The Jacobian of both kinds against central differences at many states
    // (off the breakpoints) and the damping block C = c [1 -1; -1 1].
    for (const double kind : {0.0, 1.0}) {
      CAPTURE(kind);
      testing::jacobian_checker<table_spring> chk(
          table_spring({kind, 4.0, {-0.4, -3.0, -0.1, -0.5, 0.0, 0.0, 0.2, 0.3, 0.5, 4.0}}), 12);
      int checked = 0;
      for (int i = 0; i < 97; ++i) {
        local_input<table_spring> in;
        in.u(0) = 0.01 * i - 0.3;
        in.u(1) = -0.007 * i + 0.2;
        in.v(0) = 0.1 * i;
        in.v(1) = -1.0;
        if (!chk.element().admissible(in)) continue;
        const auto r = chk.check(in);
        CHECK(r.ok);
        ++checked;
      }
      CHECK(checked > 90);
    }
  }

  TEST_CASE("bad tables are refused with code 100 naming TSPRING, the instance and the entry") {
    const auto run_error = [](table_spring::parameters p) {
      table_spring_model md;
      const dof x = md.add_dof("x");
      md.add<point_mass>("body", {1.0}, x);
      md.add<table_spring>("curve", std::move(p), md.ground(), x);
      simulation sim(md);
      return error_from([&] { sim.run(fixed_step(0.1, 0.01)); });
    };
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    check_error(run_error({0, 0, {0.0, 0.0, 0.1, 1.0, 0.2}}), error_code::invalid_parameter, "TSPRING", "curve",
                "an even number of values), got 5 values");
    check_error(run_error({0, 0, {0.0, 0.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "at least 2 points (4 values), got 1");
    check_error(run_error({0, 0, {}}), error_code::invalid_parameter, "TSPRING", "curve", "got 0");
    check_error(run_error({0, 0, {0.0, 0.0, 0.3, 1.0, 0.2, 2.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "deformation 3 (0.2) is not above deformation 2 (0.3)");
    check_error(run_error({1, 0, {0.0, 0.0, 0.1, 1.0, 0.1, 2.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "deformation 3 (0.1) is not above deformation 2 (0.1)");
    check_error(run_error({0, 0, {0.0, 0.0, 0.1, nan}}), error_code::invalid_parameter, "TSPRING", "curve",
                "table value 4 (force 2) is not finite");
    check_error(run_error({0, 0, {-inf, 0.0, 0.1, 1.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "table value 1 (deformation 1) is not finite");
    check_error(run_error({2, 0, {0.0, 0.0, 0.1, 1.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "interpolation = 2 must be 0 (piecewise linear) or 1 (monotone cubic)");
    check_error(run_error({0.5, 0, {0.0, 0.0, 0.1, 1.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "interpolation = 0.5");
    check_error(run_error({0, -1, {0.0, 0.0, 0.1, 1.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "damping coefficient c = -1 must be finite and >= 0");
    check_error(run_error({0, inf, {0.0, 0.0, 0.1, 1.0}}), error_code::invalid_parameter, "TSPRING", "curve",
                "damping coefficient c = inf");
    // A valid table runs.
    CHECK_FALSE(run_error({1, 0, {0.0, 0.0, 0.1, 1.0}}).has_value());
  }

  TEST_CASE("a flat TSPRING with an odd count or fewer than 2 points is refused with code 101") {
    table_spring_model md;
    const std::array<dof, 2> d{md.add_dof(), md.add_dof()};
    const std::array<double, 7> odd{0, 0, 0.0, 0.0, 0.1, 1.0, 0.2};
    check_error(flat_add_error<table_spring>(md, "odd", d, odd), error_code::parameter_count, "TSPRING", "odd",
                "got 7 parameters");
    const std::array<double, 4> one_point{0, 0, 0.0, 0.0};
    check_error(flat_add_error<table_spring>(md, "short", d, one_point), error_code::parameter_count, "TSPRING",
                "short", "got 4 parameters");
    const std::array<double, 6> nan_entry{0, 0, 0.0, std::numeric_limits<double>::quiet_NaN(), 0.1, 1.0};
    check_error(flat_add_error<table_spring>(md, "nan", d, nan_entry), error_code::invalid_parameter, "TSPRING", "nan",
                "non-finite");
    CHECK(md.element_count() == 0);
    const std::array<double, 8> ok{1, 2.5, 0.0, 0.0, 0.1, 1.0, 0.3, 1.5};
    md.add_flat<table_spring>("ok", d, ok);
    CHECK(md.element_count() == 1);
  }
}
