// R, C and L in circuits with closed-form answers: RC charging, RL current rise,
// LC oscillation and the series RLC step response. On an electric DOF v is the node
// voltage, u its time integral (flux linkage) and a its derivative; the default
// scheme is the trapezoidal rule (Newmark beta = 1/4, gamma = 1/2).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// Trapezoidal rule on y' = -y / tau: y_{n+1} = r y_n with r = (1 - x/2) / (1 + x/2),
// x = h / tau. Against the exact factor e^{-x}: r^n - e^{-n x} = (r - e^{-x}) sum_k
// r^k e^{-(n-1-k) x}, each term of the sum at most 1, so |r^n - e^{-nx}| <= n |r - e^{-x}|.
double trapezoidal_decay_bound(double h, double tau, double t) {
  const double x = h / tau, r = (1 - x / 2) / (1 + x / 2);
  return std::round(t / h) * std::abs(r - std::exp(-x)) + 1e-12;
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using circuits_model = pradis::model<voltage_dc, resistor, capacitor, inductor, initial_velocity>;
TEST_SUITE("electric/circuits") {
  TEST_CASE("RC charging: the capacitor voltage is V (1 - exp(-t/RC)) and its current V/R exp(-t/RC)") {
    // KCL at the capacitor node: C v' + (v - V)/R = 0, v(0) = 0 => v = V (1 - e^{-t/RC}).
    const double big_v = 10.0, r = 1e3, c = 1e-6, tau = r * c, h = 2e-5, end = 5e-3;
    circuits_model md;
    const dof in = md.add_dof("in"), out = md.add_dof("out");
    const auto src = md.add<voltage_dc>("V", {big_v}, in);
    md.add<resistor>("R", {r}, in, out);
    const auto cap = md.add<capacitor>("C", {c}, out, md.ground());
    CHECK(md.dof_domain(out) == domain::electric);
    simulation sim(md);
    double worst_v = 0, worst_i = 0, worst_src = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), e = std::exp(-t / tau);
      const double bound = trapezoidal_decay_bound(h, tau, t);
      worst_v = std::max(worst_v, std::abs(s.v(out) - big_v * (1 - e)) / (big_v * bound));
      worst_i = std::max(worst_i, std::abs(md.work(cap)[0] - big_v / r * e) / (big_v / r * bound));
      // The source delivers the resistor current (v_in - v_out) / R (W(1), the reaction).
      worst_src = std::max(worst_src, std::abs(md.work(src)[0] - (big_v - s.v(out)) / r));
    });
    sim.run(fixed_step(end, h));
    CHECK(worst_v <= 1.0);
    CHECK(worst_i <= 1.0);
    CHECK(worst_src < 1e-12);
    CHECK(sim.v(out) == doctest::Approx(big_v * (1 - std::exp(-end / tau))).epsilon(1e-5));
    CHECK(sim.u(in) == doctest::Approx(big_v * end).epsilon(1e-14));  // flux linkage of the source node: V t
  }

  TEST_CASE("RL current rise: i = V/R (1 - exp(-t R/L)) and the inductor node starts at V") {
    // Mesh equation L i' + R i = V, i(0) = 0. The flux linkage of the node between R and L
    // obeys u' = v = V - R u / L, so the trapezoidal bound of the decay applies with tau = L/R.
    const double big_v = 5.0, r = 10.0, l = 0.1, tau = l / r, h = 2e-4, end = 0.05;
    circuits_model md;
    const dof in = md.add_dof("in"), mid = md.add_dof("mid");
    md.add<voltage_dc>("V", {big_v}, in);
    md.add<resistor>("R", {r}, in, mid);
    const auto ind = md.add<inductor>("L", {l, 0.0}, mid, md.ground());
    simulation sim(md);
    double worst = 0;
    int outputs = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      if (outputs++ == 0) CHECK(s.v(mid) == doctest::Approx(big_v));  // consistent start: no current, no drop on R
      const double i = big_v / r * (1 - std::exp(-t / tau));
      worst = std::max(worst, std::abs(md.work(ind)[0] - i) / (big_v / r * trapezoidal_decay_bound(h, tau, t)));
    });
    sim.run(fixed_step(end, h));
    CHECK(worst <= 1.0);
    CHECK(md.work(ind)[0] == doctest::Approx(big_v / r * (1 - std::exp(-end / tau))).epsilon(1e-4));
  }

  TEST_CASE("LC oscillation: the voltage of a charged LC tank oscillates with the period 2 pi sqrt(LC)") {
    // C v' + i = 0, L i' = v => v'' + v / (LC) = 0: v = V0 cos(w t), w = 1/sqrt(LC). In the nodal form
    // it is the undamped oscillator u'' + w^2 u = 0 in the flux linkage u; the trapezoidal rule keeps
    // its amplitude and shifts its frequency to wd, tan(wd h/2) = w h/2 (trapezoidal_frequency), with
    // 0 <= w - wd <= w^3 h^2 / 12.
    const double l = 2e-3, c = 5e-6, v0 = 3.0, w = 1 / std::sqrt(l * c), h = 2e-6, end = 4e-3;
    const double wd = trapezoidal_frequency(w, h);
    circuits_model md;
    const dof n = md.add_dof("tank");
    md.add<capacitor>("C", {c}, n, md.ground());
    md.add<inductor>("L", {l, 0.0}, n, md.ground());
    md.add<initial_velocity>("V0", {v0}, n);
    simulation sim(md);
    double worst = 0, prev_t = 0, prev_v = v0;
    std::vector<double> up_crossings;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), v = s.v(n);
      worst = std::max(worst, std::abs(v - v0 * std::cos(wd * t)));
      if (prev_v < 0 && v >= 0) up_crossings.push_back(prev_t + (t - prev_t) * (-prev_v) / (v - prev_v));
      prev_t = t;
      prev_v = v;
    });
    sim.run(fixed_step(end, h));
    CHECK(worst < 1e-9 * v0 * end / h);
    REQUIRE(up_crossings.size() >= 4);
    // Period from the first and last upward zero crossings; linear interpolation of a sine near its
    // zero errs by O((w h)^2 h), far below the frequency shift of the scheme.
    const double measured = (up_crossings.back() - up_crossings.front()) / static_cast<double>(up_crossings.size() - 1);
    const double exact = 2 * std::numbers::pi * std::sqrt(l * c);
    CHECK(std::abs(measured - 2 * std::numbers::pi / wd) < 1e-3 * exact * (w * h) * (w * h));
    CHECK(std::abs(measured - exact) <= exact * (w * h) * (w * h) / 12 * 1.01);
  }

  TEST_CASE("series RLC step response: vc = V [1 - e^{-alpha t} (cos wd t + alpha/wd sin wd t)], second order") {
    // L C vc'' + R C vc' + vc = V, vc(0) = vc'(0) = 0, underdamped: alpha = R/(2L), wd = sqrt(1/(LC) - alpha^2)
    // (any circuits text, e.g. Nilsson & Riedel, Electric Circuits, 8.3). The trapezoidal rule is second
    // order: halving the step divides the largest error by about 4.
    const double big_v = 1.0, r = 20.0, l = 0.01, c = 1e-5, alpha = r / (2 * l);
    const double wd = std::sqrt(1 / (l * c) - alpha * alpha), end = 0.01;
    const auto run = [&](double h) {
      circuits_model md;
      const dof n1 = md.add_dof("n1"), n2 = md.add_dof("n2"), n3 = md.add_dof("n3");
      md.add<voltage_dc>("V", {big_v}, n1);
      md.add<resistor>("R", {r}, n1, n2);
      md.add<inductor>("L", {l, 0.0}, n2, n3);
      md.add<capacitor>("C", {c}, n3, md.ground());
      simulation sim(md);
      double worst = 0;
      sim.on_output([&](const auto& s) {
        const double t = s.time();
        const double vc = big_v * (1 - std::exp(-alpha * t) * (std::cos(wd * t) + alpha / wd * std::sin(wd * t)));
        worst = std::max(worst, std::abs(s.v(n3) - vc));
      });
      sim.run(fixed_step(end, h));
      return worst;
    };
    const double coarse = run(2e-5), fine = run(1e-5);
    CHECK(fine < 1e-3 * big_v);
    CHECK(coarse / fine == doctest::Approx(4.0).epsilon(0.05));
  }
}
