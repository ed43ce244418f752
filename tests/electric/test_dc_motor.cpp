// DCM, the DC motor: electrical time constant and stall torque with the shaft held,
// no-load speed V/k and the loaded steady state on a free inertia, and bad parameters.
// Motor equations: L i' + R i + k w = V, J w' = k i - T_load (e.g. Hughes & Drury,
// Electric Motors and Drives, ch. 3).

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// Trapezoidal decay y_{n+1} = r y_n, r = (1 - x/2)/(1 + x/2), x = h / tau, against e^{-n x}:
// |r^n - e^{-n x}| <= n |r - e^{-x}| (see tests/electric/test_circuits.cpp).
double decay_bound(double h, double tau, double t) {
  const double x = h / tau, r = (1 - x / 2) / (1 + x / 2);
  return std::round(t / h) * std::abs(r - std::exp(-x)) + 1e-12;
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using dc_motor_model = pradis::model<voltage_dc, dc_motor, point_mass, constant_force, resistor>;
TEST_SUITE("electric/DCM") {
  TEST_CASE("stalled motor: the armature current rises as V/R (1 - exp(-t R/L)) to the stall torque k V / R") {
    // Shaft held (w = 0): L i' + R i = V, i(0) = 0; torque k i.
    const double big_v = 12.0, r = 2.0, l = 0.01, k = 0.05, tau = l / r, h = 1e-4, end = 0.1;
    dc_motor_model md;
    const dof plus = md.add_dof("plus");
    md.add<voltage_dc>("V", {big_v}, plus);
    const auto m = md.add<dc_motor>("M", {r, l, k}, plus, md.ground(), md.ground());
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), i = big_v / r * (1 - std::exp(-t / tau));
      worst = std::max(worst, std::abs(md.work(m)[0] - i) / (big_v / r * decay_bound(h, tau, t)));
    });
    sim.run(fixed_step(end, h));
    CHECK(worst <= 1.0);
    CHECK(md.work(m)[1] == doctest::Approx(k * big_v / r).epsilon(1e-8));  // stall torque k V/R (t = 20 tau)
  }

  TEST_CASE("no-load run-up with L = 0: w = V/k (1 - exp(-t k^2/(R J))), the back-EMF tends to V") {
    // L = 0: i = (V - k w)/R, J w' = k i => w' = (V/k - w) / tau_m, tau_m = R J / k^2.
    const double big_v = 24.0, r = 1.5, k = 0.1, j = 2e-4, tau = r * j / (k * k), h = 1e-3, end = 0.3;
    dc_motor_model md;
    const dof plus = md.add_dof("plus"), shaft = md.add_dof("shaft");
    md.add<voltage_dc>("V", {big_v}, plus);
    const auto m = md.add<dc_motor>("M", {r, 0.0, k}, plus, md.ground(), shaft);
    md.add<point_mass>("J", {j}, shaft);
    CHECK(md.dof_domain(shaft) == domain::mechanical);
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), w = big_v / k * (1 - std::exp(-t / tau));
      worst = std::max(worst, std::abs(s.v(shaft) - w) / (big_v / k * decay_bound(h, tau, t)));
    });
    sim.run(fixed_step(end, h));
    CHECK(worst <= 1.0);
    CHECK(sim.v(shaft) == doctest::Approx(big_v / k).epsilon(1e-4));  // no-load speed V/k (t = 65 tau_m)
    CHECK(md.work(m)[2] == doctest::Approx(big_v).epsilon(1e-4));      // back-EMF k w -> V
  }

  TEST_CASE("loaded motor with inductance settles at w = (V - R T/k)/k with the current T/k") {
    // Steady state of L i' + R i + k w = V, J w' = k i - T: i = T/k, w = (V - R T/k)/k. The slower
    // eigenvalue of L J s^2 + R J s + k^2 = 0 is about -35 1/s: after 1 s the transient is e^{-35}.
    const double big_v = 24.0, r = 1.5, l = 2e-3, k = 0.1, j = 2e-4, load = 0.2;
    dc_motor_model md;
    const dof plus = md.add_dof("plus"), shaft = md.add_dof("shaft");
    md.add<voltage_dc>("V", {big_v}, plus);
    const auto m = md.add<dc_motor>("M", {r, l, k}, plus, md.ground(), shaft);
    md.add<point_mass>("J", {j}, shaft);
    md.add<constant_force>("load", {-load}, shaft);
    simulation sim(md);
    sim.run(fixed_step(1.0, 1e-3));
    CHECK(sim.v(shaft) == doctest::Approx((big_v - r * load / k) / k).epsilon(1e-8));
    CHECK(md.work(m)[0] == doctest::Approx(load / k).epsilon(1e-8));
    CHECK(md.work(m)[1] == doctest::Approx(load).epsilon(1e-8));
  }

  TEST_CASE("bad DCM parameters stop the run with code 100 naming the parameter") {
    struct bad_case {
      dc_motor::parameters p;
      const char* mention;
    };
    const std::array<bad_case, 5> bad{{{{-1.0, 0.0, 1.0}, "armature resistance R"},
                                       {{1.0, -1e-3, 1.0}, "armature inductance L"},
                                       {{0.0, 0.0, 1.0}, "both zero"},
                                       {{1.0, 0.0, 0.0}, "motor constant k"},
                                       {{1.0, std::numeric_limits<double>::infinity(), 1.0}, "armature inductance L"}}};
    for (const auto& b : bad) {
      CAPTURE(b.mention);
      dc_motor_model md;
      const dof plus = md.add_dof(), shaft = md.add_dof();
      md.add<voltage_dc>("V", {1.0}, plus);
      md.add<dc_motor>("M", b.p, plus, md.ground(), shaft);
      md.add<point_mass>("J", {1.0}, shaft);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.01, 0.001)); }), error_code::invalid_parameter, "DCM", "M",
                  b.mention);
    }
  }

  TEST_CASE("a DCM shaft on an electric node is refused, naming both") {
    dc_motor_model md;
    const dof n = md.add_dof("n");
    md.add<resistor>("R", {1.0}, n, md.ground());
    check_error(error_from([&] { md.add<dc_motor>("M", {1.0, 0.0, 1.0}, n, md.ground(), n); }),
                error_code::invalid_model, "DCM", "M", "electric");
  }
}
