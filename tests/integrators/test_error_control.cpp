// Error-controlled step size (run_options::error_control; PRADIS's local error
// estimate and three-branch controller, pradis-methods.md section 4):
//  - tolerance proportionality on the oscillator u'' + w^2 u = 0: with
//    DABSX = DRLTX = tol the achieved global error falls monotonically with tol
//    and, for the second-order schemes, stays within two decades of it;
//    Stoermer (first order, local-error-per-step control) is measured and reported;
//  - a stiff damped mass-spring system (about 1 Hz and 100 kHz) completes in few
//    steps once the fast mode has decayed, with the dissipative schemes;
//  - error rejections happen; SMIN failure names the DOF and the time; CONTROL
//    puts a floor under the step; bad options are rejected naming the option;
//  - the round-off floor of the error test does not excuse a step that fell far below
//    the stage's steps (a pendulum chain under NEWMARK, against HHT on the same chain
//    and the RK4 solution of bench/chain_reference.hpp).

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "../../bench/chain_reference.hpp"
#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "testing/test_support.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using error_control_model = pradis::model<point_mass, linear_spring, linear_damper, initial_displacement,
    initial_velocity, planar_rigid_link, constant_force>;

using pradis_test::rel_newton;

struct result {
  double u = 0, v = 0;
  run_statistics stats;
};

/// u'' + w^2 u = 0, u(0) = 1, v(0) = 0, error control with DABSX = DRLTX = tol.
template <class Scheme>
result oscillator(Scheme scheme, double w, double t_end, double tol) {
  error_control_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {w * w}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  simulation sim(m, scheme);
  result r;
  r.stats = sim.run({.end = t_end,
                     .smax = 0.05,
                     .smin = 1e-12,
                     .newton = rel_newton,
                     .error_control = true,
                     .dabsx = tol,
                     .drltx = tol});
  r.u = sim.u(x);
  r.v = sim.v(x);
  return r;
}

/// Relative error of the state at t_end against cos(w t), in the energy norm.
double state_error(const result& r, double w, double t) {
  const double du = r.u - std::cos(w * t), dv = (r.v + w * std::sin(w * t)) / w;
  return std::sqrt(du * du + dv * dv);
}

template <class Scheme>
std::vector<double> tolerance_sweep(Scheme scheme, const std::string& label, std::vector<long>& steps) {
  const double w = 2 * std::numbers::pi, t_end = 2.0;
  std::vector<double> err;
  for (int e = 2; e <= 8; ++e) {
    const double tol = std::pow(10.0, -e);
    const result r = oscillator(scheme, w, t_end, tol);
    err.push_back(state_error(r, w, t_end));
    steps.push_back(r.stats.steps);
    MESSAGE(label << ": tol " << tol << " -> global error " << err.back() << " (ratio " << err.back() / tol
                  << "), steps " << r.stats.steps << ", error rejections " << r.stats.error_rejections);
  }
  return err;
}

/// Two masses: m1 = 1 on k1 = (2 pi)^2 (1 Hz) with 2 % damping; m2 = 1e-3 on
/// k2 = m2 (2 pi 1e5)^2 to m1 (100 kHz) with 5 % damping. x1(0) = 1, x2(0) = 1.001.
struct stiff_system {
  static constexpr double m1 = 1.0, m2 = 1e-3;
  static constexpr double w1 = 2 * std::numbers::pi, w2 = 2 * std::numbers::pi * 1e5;
  static constexpr double k1 = m1 * w1 * w1, k2 = m2 * w2 * w2;
  static constexpr double c1 = 2 * 0.02 * m1 * w1, c2 = 2 * 0.05 * m2 * w2;
  /// Exact state (x1, x2, v1, v2) at t from the modal decomposition of the first-order system.
  static Eigen::Vector4d exact(double t) {
    Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
    a(0, 2) = a(1, 3) = 1;
    a(2, 0) = -(k1 + k2) / m1, a(2, 1) = k2 / m1, a(2, 2) = -(c1 + c2) / m1, a(2, 3) = c2 / m1;
    a(3, 0) = k2 / m2, a(3, 1) = -k2 / m2, a(3, 2) = c2 / m2, a(3, 3) = -c2 / m2;
    Eigen::EigenSolver<Eigen::Matrix4d> es(a);
    const Eigen::Matrix4cd v = es.eigenvectors();
    const Eigen::Vector4cd x0(1.0, 1.001, 0.0, 0.0);
    Eigen::Vector4cd c = v.partialPivLu().solve(x0);
    for (int i = 0; i < 4; ++i) c(i) *= std::exp(es.eigenvalues()(i) * t);
    return (v * c).real();
  }
};

/// Two stages: the transient of the fast mode (to t_fast) and the rest (to t_end).
struct stiff_result {
  result fast, slow;
  Eigen::Vector4d state;
};

template <class Scheme>
stiff_result stiff_run(Scheme scheme, double tol, double t_fast, double t_end) {
  error_control_model m;
  const dof x1 = m.add_dof("x1"), x2 = m.add_dof("x2");
  m.add<point_mass>("m1", {stiff_system::m1}, x1);
  m.add<point_mass>("m2", {stiff_system::m2}, x2);
  m.add<linear_spring>("k1", {stiff_system::k1}, x1, m.ground());
  m.add<linear_damper>("c1", {stiff_system::c1}, x1, m.ground());
  m.add<linear_spring>("k2", {stiff_system::k2}, x2, x1);
  m.add<linear_damper>("c2", {stiff_system::c2}, x2, x1);
  m.add<initial_displacement>("x10", {1.0}, x1);
  m.add<initial_displacement>("x20", {1.001}, x2);
  simulation sim(m, scheme);
  // DABSI above the round-off of the stiff spring's force, k2 eps |x| ~ 1e-7 N
  // (its flows are tiny once the fast mode has decayed, so DRLTI does not cover it).
  run_options o{.end = t_fast,
                .smax = 0.01,
                .smin = 1e-12,
                .newton = {.dabsu = 1e-12, .drltu = 1e-9, .dabsi = 1e-6, .drlti = 1e-9, .itr = 8},
                .error_control = true,
                .dabsx = tol,
                .drltx = tol};
  stiff_result r;
  r.fast.stats = sim.run(o);
  o.end = t_end;
  r.slow.stats = sim.run(o);
  r.state = Eigen::Vector4d(sim.u(x1), sim.u(x2), sim.v(x1), sim.v(x2));
  return r;
}

template <class F>
void expect_invalid_option(F&& f, const std::string& name, const std::string& range) {
  try {
    f();
    FAIL("no exception; expected invalid_option naming " << name);
  } catch (const pradis::error& e) {
    CHECK(e.code() == error_code::invalid_option);
    INFO("message: " << e.message());
    CHECK(e.message().find(name) != std::string::npos);
    CHECK(e.message().find(range) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("error control: global error proportional to the requested tolerance (second-order schemes)") {
  long rejections = 0;
  auto check_sweep = [&](auto scheme, const std::string& label) {
    std::vector<long> steps;
    const auto err = tolerance_sweep(scheme, label, steps);
    for (std::size_t i = 0; i + 1 < err.size(); ++i) {
      CAPTURE(i);
      CHECK(err[i + 1] < err[i]);      // monotone in the tolerance
      CHECK(steps[i + 1] > steps[i]);  // and paid for with steps
    }
    for (std::size_t i = 0; i < err.size(); ++i) {
      const double tol = std::pow(10.0, -2.0 - static_cast<double>(i));
      CAPTURE(tol);
      CHECK(err[i] <= 100 * tol);  // within two decades of the request
      CHECK(err[i] >= 0.01 * tol);
    }
    // Second order under local error per unit step: error ~ tol, so 6 decades
    // of tol give about 6 decades of error (a first-order slope would give 3).
    const double slope = std::log10(err.front() / err.back()) / 6.0;
    MESSAGE(label << ": slope d log(error) / d log(tol) = " << slope);
    CHECK(slope > 0.8);
    CHECK(slope < 1.25);
  };
  check_sweep(newmark{}, "Newmark average acceleration");
  check_sweep(hht(-0.1), "HHT alpha -0.1");
  check_sweep(hht(-0.3), "HHT alpha -0.3");
  check_sweep(generalized_alpha(0.0), "generalized-alpha rho_inf 0");
  check_sweep(generalized_alpha(0.8), "generalized-alpha rho_inf 0.8");
  (void)rejections;
}

TEST_CASE("error control with Stoermer (first order, local error per step): measured tolerance response") {
  std::vector<long> steps;
  const auto err = tolerance_sweep(stoermer{}, "Stoermer", steps);
  for (std::size_t i = 0; i + 1 < err.size(); ++i) CHECK(err[i + 1] < err[i]);
  // Local error per step ~ h^2 controlled to tol, global error ~ N h^2 ~ h ~ sqrt(tol).
  const double slope = std::log10(err.front() / err.back()) / 6.0;
  MESSAGE("Stoermer: slope d log(error) / d log(tol) = " << slope << " (sqrt(tol) would be 0.5)");
  CHECK(slope > 0.35);
  CHECK(slope < 0.65);
}

TEST_CASE("error control on a stiff damped system (1 Hz and 100 kHz): few steps once the fast mode is damped") {
  // The 100 kHz mode (5 % damping) decays by e^-63 within 2 ms; error control
  // resolves that transient (physically real: thousands of steps of ~1e-8 s), then
  // the 1 Hz mode alone sets the step for the remaining 998 ms.
  const double t_fast = 2e-3, t_end = 1.0, tol = 1e-4;
  const Eigen::Vector4d ref = stiff_system::exact(t_end);
  long rejections = 0;
  auto check_run = [&](auto scheme, const std::string& label, long max_slow_steps, double max_err) {
    const stiff_result r = stiff_run(scheme, tol, t_fast, t_end);
    const double err = (r.state - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    MESSAGE(label << ": transient (0-2 ms) " << r.fast.stats.steps << " steps, " << r.fast.stats.error_rejections
                  << " error rejections; then (2 ms-1 s) " << r.slow.stats.steps << " steps, "
                  << r.slow.stats.error_rejections << " error rejections, " << r.slow.stats.rejected_steps
                  << " rejected; relative error at t = 1: " << err);
    CHECK(r.slow.stats.steps <= max_slow_steps);
    // A handful of Newton failures (step cuts) happen while the step grows from
    // SMIN through the transient (3 to 9 here); none afterwards.
    CHECK(r.fast.stats.rejected_steps - r.fast.stats.error_rejections <= 20);
    CHECK(r.slow.stats.rejected_steps == r.slow.stats.error_rejections);
    CHECK(err < max_err);
    rejections += r.fast.stats.error_rejections + r.slow.stats.error_rejections;
  };
  // Measured (this kernel): Stoermer 474 steps after the transient, generalized-alpha
  // rho_inf 0 608 (average acceleration 716 with 40 rejections, rho_inf 0.8 257).
  check_run(stoermer{}, "Stoermer", 1000, 5e-2);  // first order: error ~ sqrt(tol)
  check_run(generalized_alpha(0.0), "generalized-alpha rho_inf 0", 1000, 5e-3);
  check_run(generalized_alpha(0.8), "generalized-alpha rho_inf 0.8", 1000, 5e-3);
  check_run(newmark{}, "Newmark average acceleration", 1500, 5e-3);
  CHECK(rejections > 0);  // the controller did reject steps
}

TEST_CASE("error control: where the local error vanishes the step jumps from SMIN to SMAX before any rejection") {
  // A free mass at constant velocity has zero acceleration, so the local error estimate is
  // zero at every step. PRADIS's rule then proposes SMAX; max_step_growth (step_control.hpp)
  // bounds the growth only after the run's first error rejection (tested on a contact:
  // tests/spatial/test_sphere_contact.cpp, "CSPHPL: the Hunt-Crossley rebound ...").
  error_control_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<initial_velocity>("v0", {3.0}, x);
  simulation sim(m, newmark{});
  std::vector<double> steps;
  sim.on_step([&](const auto& s) { steps.push_back(s.statistics().last_step); });
  const double smin = 1e-9, smax = 1e-2;
  sim.run({.end = 0.1, .smax = smax, .smin = smin, .newton = rel_newton, .error_control = true, .drltx = 1e-6});
  REQUIRE(steps.size() >= 3);
  CHECK(sim.statistics().error_rejections == 0);
  CHECK(steps[0] == doctest::Approx(smin));
  CHECK(steps[1] == doctest::Approx(smax));
  // Uniform motion: Newmark integrates it exactly.
  CHECK(sim.u(x) == doctest::Approx(0.3).epsilon(1e-12));
}

TEST_CASE("error control: SMIN cannot reach an impossible tolerance -> step_too_small naming the DOF and the time") {
  error_control_model m;
  const dof x = m.add_dof("slider");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  simulation sim(m, newmark{});
  try {
    sim.run({.end = 1.0, .smax = 0.01, .smin = 1e-3, .newton = rel_newton, .error_control = true, .dabsx = 1e-30,
             .drltx = 0.0});
    FAIL("no exception");
  } catch (const pradis::error& e) {
    INFO("message: " << e.message());
    CHECK(e.code() == error_code::step_too_small);
    CHECK(e.message().find("SMIN") != std::string::npos);
    CHECK(e.message().find("'slider'") != std::string::npos);
    CHECK(e.message().find("t = ") != std::string::npos);
    CHECK(e.dof() == x.index);
  }
}

// CONTROL: an impossible tolerance (DABSX = 1e-30) with a floor of 1e-3: every
// step is accepted at the floor, and the step after it is the floor again.
TEST_CASE("error control: CONTROL puts a floor under the step (accepts at the floor instead of failing)") {
  error_control_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  simulation sim(m, newmark{});
  const run_statistics s = sim.run({.end = 0.5, .smax = 0.01, .smin = 1e-6, .newton = rel_newton,
                                    .error_control = true, .dabsx = 1e-30, .drltx = 0.0, .control = 1e-3});
  CHECK(sim.time() == doctest::Approx(0.5));
  CHECK(s.steps >= 490);   // steps of the floor 1e-3 (a few SMIN-sized start steps)
  CHECK(s.steps <= 520);
}

TEST_CASE("error control options: DABSX, DRLTX, CONTROL out of range -> invalid_option naming the option") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto run_with = [](run_options o) {
    error_control_model m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("spring", {1.0}, x, m.ground());
    simulation sim(m, generalized_alpha(0.5));
    o.end = 0.1;
    o.error_control = true;
    sim.run(o);
  };
  run_options o;
  o.dabsx = nan;
  expect_invalid_option([&] { run_with(o); }, "DABSX", ">= 0");
  o.dabsx = -1e-3;
  expect_invalid_option([&] { run_with(o); }, "DABSX", ">= 0");
  o = {};
  o.drltx = nan;
  expect_invalid_option([&] { run_with(o); }, "DRLTX", ">= 0");
  o.drltx = -1e-3;
  expect_invalid_option([&] { run_with(o); }, "DRLTX", ">= 0");
  o = {};
  o.dabsx = 0;
  o.drltx = 0;
  expect_invalid_option([&] { run_with(o); }, "DABSX + DRLTX", "> 0");
  o = {};
  o.control = -1e-3;
  expect_invalid_option([&] { run_with(o); }, "CONTROL", ">= 0");
  o.control = nan;
  expect_invalid_option([&] { run_with(o); }, "CONTROL", ">= 0");
  // Both zero is fine without error control (the tolerances are not used).
  error_control_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {1.0}, x, m.ground());
  simulation sim(m, newmark{});
  CHECK_NOTHROW(sim.run({.end = 0.1, .dabsx = 0, .drltx = 0}));
}

// The round-off floor of the error test (step_control.hpp, roundoff_floor_drop). A chain of ten
// 0.05 kg point masses on 0.1 m LINKX links, hinged at the origin and released horizontally
// (bench/chain_reference.hpp, the work-precision problem "chain"), under NEWMARK at
// DRLTX = DABSX = 1e-4: at t = 0.3576 s the undamped alternation of the link forces keeps the
// estimate above the tolerance at every step, and the step falls from ~1e-3 s to SMIN. Before,
// the floor 4 eps |u| / h passed it there, the step grew back to ~2e-8 s and the run crawled
// through 6.6 million steps (150 s) to a state 8.7e-2 off the reference (the benchmark's error: the
// largest relative error of the link angles and rates). Now it ends with code 141
// naming the alternation, within a thousand steps, and HHT-0.1, which the message recommends,
// runs the same chain at the same tolerance to the RK4 reference's tip.
TEST_CASE("error control: a step far below the stage's steps gets no round-off floor (NEWMARK chain -> code 141)") {
  constexpr int n = 10;
  constexpr double l = 0.1, mass = 0.05, g = 9.81, end = 0.4;
  error_control_model m;
  std::vector<dof> x, y;
  for (int i = 0; i < n; ++i) {
    x.push_back(m.add_dof("x" + std::to_string(i + 1)));
    y.push_back(m.add_dof("y" + std::to_string(i + 1)));
    m.add<point_mass>("mx" + std::to_string(i + 1), {mass}, x.back());
    m.add<point_mass>("my" + std::to_string(i + 1), {mass}, y.back());
    m.add<constant_force>("g" + std::to_string(i + 1), {-mass * g}, y.back());
    const dof ax = i == 0 ? m.ground() : x[x.size() - 2], ay = i == 0 ? m.ground() : y[y.size() - 2];
    m.add<planar_rigid_link>("link" + std::to_string(i + 1), {i * l, 0.0, (i + 1) * l, 0.0}, ax, ay, x.back(),
                             y.back());
  }
  // The work-precision benchmark's options for this point (bench/work_precision/work_precision.cpp).
  const run_options o{.end = end, .smax = end / 20, .smin = 1e-12,
                      .newton = {.dabsu = 1e-7, .drltu = 1e-7, .dabsi = 1e-10, .drlti = 1e-7, .itr = 8},
                      .error_control = true, .dabsx = 1e-4, .drltx = 1e-4};
  {
    simulation sim(m, newmark{});
    std::ostringstream log;
    sim.log().to(log);
    const auto e = pradis_test::error_of([&] { sim.run(o); });
    REQUIRE(e.has_value());
    CHECK(e->code() == error_code::step_too_small);
    CHECK(e->message().find("does not damp their alternation") != std::string::npos);
    CHECK(e->message().find("use HHT or GALPHA") != std::string::npos);
    CHECK(sim.time() == doctest::Approx(0.3576).epsilon(1e-3));
    CHECK(sim.statistics().steps < 1000);
  }
  simulation sim(m, hht{-0.1});
  std::ostringstream log;
  sim.log().to(log);
  sim.run(o);
  CHECK(sim.time() == doctest::Approx(end));
  const Eigen::Vector2d tip = pradis_reference::chain_tip(pradis_reference::chain_reference(n, l, g, end, 40000), l);
  const double dx = n * l + sim.u(x.back()) - tip.x(), dy = sim.u(y.back()) - tip.y();
  MESSAGE("HHT-0.1 at 1e-4: ", sim.statistics().steps, " steps, tip off the reference by ", std::hypot(dx, dy), " m");
  CHECK(std::hypot(dx, dy) < 1e-4);
}
