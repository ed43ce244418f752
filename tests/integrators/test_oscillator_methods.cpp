// Properties of the integration schemes on the undamped harmonic oscillator
// m u'' + k u = 0 (MASS + SPRING to the ground, X0/V0 initial conditions),
// against closed forms:
//  - average-acceleration Newmark (beta 1/4, gamma 1/2): exact discrete solution
//    u_n = u0 cos(n theta), tan(theta/2) = Omega/2, hence the period error
//    Tbar/T - 1 = Omega / (2 atan(Omega/2)) - 1 and no amplitude decay
//    (Hughes, The Finite Element Method, Dover 2000, section 9.3);
//  - PRADIS's Stoermer scheme (Newmark beta 1/2, gamma 1; pradis-methods.md
//    section 4): spectral radius per step 1/sqrt(1 + Omega^2/2) for Omega < 4 and
//    the larger real root beyond (derivation in integrator_test_support.hpp);
//  - convergence orders by step halving: 2 for gamma = 1/2, 1 for gamma > 1/2
//    (Newmark 1959; Hughes section 9.3: second order iff gamma = 1/2).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::tight_newton;

namespace {

using oscillator_model = model<point_mass, linear_spring, initial_displacement, initial_velocity>;

struct trajectory {
  std::vector<double> t, u, v, a;
  run_statistics stats;
};

/// Integrates m u'' + k u = 0 with m = 1, k = w^2, u(0) = u0, v(0) = v0 with a
/// fixed step h (SMAX = h, no step-size control in the kernel) up to t_end,
/// recording every accepted step.
template <class Scheme>
trajectory run_oscillator(Scheme scheme, double w, double h, double t_end, double u0, double v0) {
  oscillator_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {w * w}, x, m.ground());
  if (u0 != 0) m.add<initial_displacement>("x0", {u0}, x);
  if (v0 != 0) m.add<initial_velocity>("v0", {v0}, x);
  simulation sim(m, scheme);
  trajectory tr;
  sim.on_output([&](const auto& s) {
    tr.t.push_back(s.time());
    tr.u.push_back(s.u(x));
    tr.v.push_back(s.v(x));
    tr.a.push_back(s.a(x));
  });
  run_options o;
  o.end = t_end;
  o.smax = h;
  o.smin = 1e-3 * h;
  o.newton = tight_newton(1e-12, 1e-13);
  tr.stats = sim.run(o);
  return tr;
}

/// Energy norm of the state, sqrt(u^2 + (v/w)^2): the amplitude of a free oscillation.
double amplitude(double u, double v, double w) { return std::sqrt(u * u + (v / w) * (v / w)); }

}  // namespace

TEST_CASE("average-acceleration Newmark on the oscillator: exact discrete solution, period error, no decay") {
  const double w = 2.0 * std::numbers::pi;  // T = 1 s
  for (const double omega_h : {0.1, 0.5}) {
    CAPTURE(omega_h);
    const double h = omega_h / w;
    const double periods = 10;
    // An integer number of steps up to 10 periods (plus a little, for the last crossing).
    const double t_end = h * std::ceil((periods + 0.3) / h);
    const auto tr = run_oscillator(newmark{}, w, h, t_end, 1.0, 0.0);
    REQUIRE(tr.t.size() > 10);
    CHECK(tr.stats.rejected_steps == 0);

    // The discrete solution is u_n = cos(n theta), theta = 2 atan(Omega/2): the
    // scheme is the trapezoidal rule on (u, v), whose amplification matrix is the
    // Cayley transform of [[0, 1], [-w^2, 0]] and commutes with it.
    const double theta = 2.0 * std::atan(0.5 * omega_h);
    double max_dev = 0, max_amp_dev = 0, max_exact_dev = 0;
    for (std::size_t n = 0; n < tr.t.size(); ++n) {
      const double phase = static_cast<double>(n) * theta;
      max_dev = std::max(max_dev, std::abs(tr.u[n] - std::cos(phase)));
      max_amp_dev = std::max(max_amp_dev, std::abs(amplitude(tr.u[n], tr.v[n], w) - 1.0));
      // Against the exact solution cos(w t): the error is the accumulated phase
      // error |w t - n theta| (times the unit amplitude), plus roundoff.
      const double phase_error = std::abs(w * tr.t[n] - phase);
      max_exact_dev = std::max(max_exact_dev, std::abs(tr.u[n] - std::cos(w * tr.t[n])) - phase_error);
    }
    // Roundoff: ~1e-16 per step over <= 700 steps.
    CHECK(max_dev < 1e-11);
    // No algorithmic damping: the energy norm is conserved (Cayley transform is
    // orthogonal in the energy norm) to roundoff, 1e-10 relative over 10 periods.
    CHECK(max_amp_dev < 1e-10);
    CHECK(max_exact_dev < 1e-11);

    // Period from the zero crossings of u (symmetric signal: all crossings).
    const auto c = pradis_test::zero_crossings(tr.t, tr.u);
    REQUIRE(c.size() >= 20);
    const double period = pradis_test::period_from_crossings(c, false);
    const double measured = period / 1.0 - 1.0;
    const double predicted = pradis_test::trapezoidal_period_error(omega_h);
    INFO("Newmark 1/4,1/2 Omega = " << omega_h << ": measured Tbar/T - 1 = " << measured
                                       << ", closed form " << predicted);
    // Within 2% of the closed-form error (the crossing interpolation error is
    // O(Omega^4)/(2 pi) per crossing, averaged over 20 crossings).
    CHECK(std::abs(measured - predicted) <= 0.02 * predicted);
    // Leading term Omega^2/12 (benchmarks: Newmark average acceleration).
    CHECK(predicted == doctest::Approx(omega_h * omega_h / 12.0).epsilon(omega_h * omega_h / 10.0));
  }
}

TEST_CASE("Stoermer (Newmark 1/2, 1): spectral radius per step matches the amplification matrix") {
  // Reference values (pradis-methods.md section 4): 0.9975 at Omega = 0.1,
  // 0.8165 at Omega = 1, 0.92 at Omega = 10, to the digits given.
  CHECK(pradis_test::stoermer_amplification(0.1).spectral_radius() == doctest::Approx(0.9975).epsilon(1e-4));
  CHECK(pradis_test::stoermer_amplification(1.0).spectral_radius() == doctest::Approx(0.8165).epsilon(1e-4));
  CHECK(pradis_test::stoermer_amplification(10.0).spectral_radius() == doctest::Approx(0.92).epsilon(1e-3));
  // Not annihilating high frequencies: rho -> 1 as Omega grows (1 - rho ~ 4/Omega^2).
  CHECK(pradis_test::stoermer_amplification(1e3).spectral_radius() > 0.999);

  const double w = 1.0;
  struct case_t {
    double omega_h, table;
    int steps;
  };
  for (const case_t cs : {case_t{0.1, 0.9975, 3000}, case_t{1.0, 0.8165, 60}, case_t{10.0, 0.92, 60}}) {
    CAPTURE(cs.omega_h);
    const double h = cs.omega_h / w;
    const auto tr = run_oscillator(stoermer{}, w, h, h * cs.steps, 1.0, 0.0);
    REQUIRE(tr.u.size() == static_cast<std::size_t>(cs.steps + 1));
    const pradis_test::stoermer_amplification amp(cs.omega_h);
    const double rho = amp.spectral_radius();

    // (a) Fit the two-term recurrence u_{n+1} = t u_n - d u_{n-1} that any
    // one-step linear scheme with a 2x2 amplification matrix obeys (least squares
    // over the whole run): t, d are the measured trace and determinant. The
    // acceleration must not enter (a0 drops out of Newmark 1/2, 1).
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    const std::size_t nfit = std::min<std::size_t>(tr.u.size(), 40);  // before the decay reaches roundoff
    for (std::size_t n = 1; n + 1 < nfit; ++n) {
      const double p = tr.u[n], q = -tr.u[n - 1], y = tr.u[n + 1];
      s11 += p * p;
      s12 += p * q;
      s22 += q * q;
      r1 += p * y;
      r2 += q * y;
    }
    const double det_n = s11 * s22 - s12 * s12;
    const double t_fit = (r1 * s22 - r2 * s12) / det_n, d_fit = (s11 * r2 - s12 * r1) / det_n;
    CHECK(t_fit == doctest::Approx(amp.trace).epsilon(1e-9));
    CHECK(d_fit == doctest::Approx(amp.det).epsilon(1e-9));

    // (b) Amplitude decay over n steps.
    double rho_measured = 0;
    if (cs.omega_h < 4) {
      // Complex eigenvalues: the discrete solution is u_n = C rho^n cos(n phi + psi).
      // Its squared amplitude is read from three consecutive samples alone:
      //     u_n^2 - u_{n-1} u_{n+1} = C^2 rho^(2n) sin^2(phi)
      // (cos(x - phi) cos(x + phi) = cos^2 x - sin^2 phi), so the amplitude ratio
      // over n steps gives rho without assuming the trace or determinant.
      auto amp2 = [&](std::size_t n) { return tr.u[n] * tr.u[n] - tr.u[n - 1] * tr.u[n + 1]; };
      const std::size_t n1 = 1, n2 = tr.u.size() - 2;
      rho_measured = std::pow(amp2(n2) / amp2(n1), 0.5 / static_cast<double>(n2 - n1));
      CHECK(rho_measured == doctest::Approx(rho).epsilon(1e-9));
      // Cross-check with the largest |u| over the first and the last discrete
      // period: the sampled peak misses the envelope by a factor cos(delta),
      // |delta| <= phi/2, at each end, a log error <= phi^2/4 over the steps between.
      const double phi = std::acos(amp.trace / (2.0 * std::sqrt(amp.det)));
      const auto per = static_cast<std::size_t>(std::ceil(2.0 * std::numbers::pi / phi));
      REQUIRE(tr.u.size() > 2 * per);
      double first = 0, last = 0;
      std::size_t i_first = 0, i_last = 0;
      for (std::size_t n = 0; n < per; ++n)
        if (std::abs(tr.u[n]) > first) first = std::abs(tr.u[n]), i_first = n;
      for (std::size_t n = tr.u.size() - per; n < tr.u.size(); ++n)
        if (std::abs(tr.u[n]) > last) last = std::abs(tr.u[n]), i_last = n;
      const double steps = static_cast<double>(i_last - i_first);
      const double rho_peaks = std::pow(last / first, 1.0 / steps);
      CHECK(std::abs(std::log(rho_peaks / rho)) <= (phi * phi / 4.0) / steps + 1e-12);
    } else {
      // Real eigenvalues: the dominant one (-rho) takes over after a few steps
      // (the other is ~0.02 at Omega = 10); ratio of |u| over the last 40 steps.
      const std::size_t n1 = tr.u.size() - 41, n2 = tr.u.size() - 1;
      rho_measured = std::pow(std::abs(tr.u[n2] / tr.u[n1]), 1.0 / 40.0);
      CHECK(rho_measured == doctest::Approx(rho).epsilon(1e-10));
      CHECK(tr.u[n2] * tr.u[n2 - 1] < 0);  // rings with alternating sign
    }
    INFO("Stoermer Omega = " << cs.omega_h << ": rho measured " << rho_measured << ", closed form " << rho
                                << ", table " << cs.table);
    CHECK(rho_measured == doctest::Approx(cs.table).epsilon(cs.omega_h > 5 ? 1e-3 : 1e-4));
  }
}

TEST_CASE("convergence orders by step halving: 2 for average acceleration, 1 for Stoermer and gamma > 1/2") {
  // u'' + 4 u = 0, u(0) = 1, v(0) = 0.5: at t = 1 the phase is generic. The
  // error is measured in the energy norm (so a pure phase error is not hidden at
  // a peak of u). Observed order p = log2(e(h) / e(h/2)).
  const double w = 2.0, t_end = 1.0, u0 = 1.0, v0 = 0.5;
  auto error_at_end = [&](auto scheme, double h) {
    const auto tr = run_oscillator(scheme, w, h, t_end, u0, v0);
    REQUIRE(tr.t.back() == doctest::Approx(t_end).epsilon(1e-14));
    const double ue = u0 * std::cos(w * t_end) + v0 / w * std::sin(w * t_end);
    const double ve = -u0 * w * std::sin(w * t_end) + v0 * std::cos(w * t_end);
    return amplitude(tr.u.back() - ue, tr.v.back() - ve, w);
  };
  auto orders = [&](auto scheme, const std::string& label, double expected) {
    const double h = 0.01;
    const double e1 = error_at_end(scheme, h), e2 = error_at_end(scheme, h / 2), e4 = error_at_end(scheme, h / 4);
    const double p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e4);
    INFO(label << ": errors " << e1 << ", " << e2 << ", " << e4 << "; orders " << p1 << ", " << p2);
    CHECK(std::abs(p1 - expected) <= 0.1);
    CHECK(std::abs(p2 - expected) <= 0.1);
  };
  orders(newmark{}, "Newmark beta 1/4 gamma 1/2", 2.0);
  orders(stoermer{}, "Stoermer (beta 1/2 gamma 1)", 1.0);
  // gamma = 0.6, beta = (gamma + 1/2)^2 / 4 = 0.3025: unconditionally stable, first order.
  orders(newmark(newmark_parameters{0.3025, 0.6}), "Newmark beta 0.3025 gamma 0.6", 1.0);
}
