// The BDF driver under error control on an undamped system with two modes: a slow one
// (about 1 Hz) that carries the motion and a faster one (about 20 Hz) that the start
// excites slightly. Both modal amplitudes sqrt(q^2 + (q' / w)^2) are invariants of the
// exact motion (undamped modal superposition of the generalized eigenproblem
// K phi = w^2 M phi: Clough and Penzien, Dynamics of Structures, sections 11-12). The
// local error control bounds what each step adds to them, not its sign, so over many
// steps a mode's amplitude drifts by the signed sum. BDF1, BDF2 and BDF5 damp an
// undamped oscillation whose period the step resolves, BDF3 and BDF4 amplify it (the
// principal root of the characteristic polynomial, test_bdf.cpp; Hairer and Wanner,
// Solving ODEs II, section V.2); docs/bdf.md, "Undamped modes and the order".

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// The two-mode chain: m1 = 1 on k1 = (2 pi)^2 to the ground, m2 = 1e-3 on k2 = m2 (2 pi 20)^2
/// to m1, undamped; x1(0) = 1, x2(0) = 1 + 1e-5, at rest.
struct two_mode_chain {
  static constexpr double m1 = 1, m2 = 1e-3, x20 = 1 + 1e-5;
  const double k1 = 4 * std::numbers::pi * std::numbers::pi;
  const double k2 = m2 * std::pow(2 * std::numbers::pi * 20, 2);
  double lam[2] = {};    ///< w^2 of the slow and the fast mode
  double shape[2] = {};  ///< the mode shapes phi = (1, shape)

  two_mode_chain() {
    // The roots of det(K - lam M) = m1 m2 lam^2 - (m1 k2 + m2 (k1 + k2)) lam + k1 k2.
    const double b = m1 * k2 + m2 * (k1 + k2), disc = std::sqrt(b * b - 4 * m1 * m2 * k1 * k2);
    lam[0] = 2 * k1 * k2 / (b + disc);
    lam[1] = (b + disc) / (2 * m1 * m2);
    for (int i = 0; i < 2; ++i) shape[i] = (k1 + k2 - lam[i] * m1) / k2;
  }
  /// Modal coordinate q_i = phi_i^T M x / phi_i^T M phi_i.
  double modal(int i, double x1, double x2) const {
    return (m1 * x1 + m2 * shape[i] * x2) / (m1 + m2 * shape[i] * shape[i]);
  }
  /// Modal amplitude sqrt(q^2 + (q' / w)^2) of a state.
  double amplitude(int i, double x1, double x2, double v1, double v2) const {
    return std::hypot(modal(i, x1, x2), modal(i, v1, v2) / std::sqrt(lam[i]));
  }

  struct result {
    double slow = 0;          ///< the slow mode's amplitude at the end / its initial amplitude
    double fast_end = 0;      ///< the fast mode's, at the end
    double fast_largest = 0;  ///< the fast mode's, largest over the accepted steps
    long steps = 0;
  };
  /// Runs 20 s (20 slow periods) under error control, DRLTX = DABSX = 1e-6, at MAXORD k.
  result run(int max_order) const {
    model<point_mass, linear_spring, initial_displacement> m;
    const dof x1 = m.add_dof("x1"), x2 = m.add_dof("x2");
    m.add<point_mass>("m1", {m1}, x1);
    m.add<point_mass>("m2", {m2}, x2);
    m.add<linear_spring>("k1", {k1}, x1, m.ground());
    m.add<linear_spring>("k2", {k2}, x2, x1);
    m.add<initial_displacement>("x10", {1.0}, x1);
    m.add<initial_displacement>("x20", {x20}, x2);
    bdf_options bo;
    bo.max_order = max_order;
    bdf_simulation sim(m, bo);
    const double slow0 = amplitude(0, 1, x20, 0, 0), fast0 = amplitude(1, 1, x20, 0, 0);
    result r;
    sim.on_step([&](const auto& s) {
      r.fast_largest = std::max(r.fast_largest, amplitude(1, s.u(x1), s.u(x2), s.v(x1), s.v(x2)) / fast0);
    });
    run_options o;
    o.end = 20;
    o.smax = 1;
    o.smin = 1e-12;
    o.error_control = true;
    o.drltx = 1e-6;
    o.dabsx = 1e-6;
    r.steps = sim.run(o).steps;
    r.slow = amplitude(0, sim.u(x1), sim.u(x2), sim.v(x1), sim.v(x2)) / slow0;
    r.fast_end = amplitude(1, sim.u(x1), sim.u(x2), sim.v(x1), sim.v(x2)) / fast0;
    return r;
  }
};

}  // namespace

TEST_SUITE("integrators/bdf") {
  TEST_CASE("error control on an undamped two-mode chain: the default MAXORD 5 never lets a mode grow, 3 and 4 do") {
    const two_mode_chain chain;
    // Measured (this file's settings): the fast mode's amplitude ends at 3.8e-10 (BDF1), 0.94
    // (BDF2), 1.63 (BDF3), 1.06 (BDF4) and 0.89 (BDF5, the default) of its initial one.
    for (int k = 1; k <= 5; ++k) {
      CAPTURE(k);
      const two_mode_chain::result r = chain.run(k);
      MESSAGE("MAXORD " << k << ": slow mode " << r.slow << ", fast mode at the end " << r.fast_end << ", largest "
                        << r.fast_largest << ", " << r.steps << " steps");
      if (k == 3 || k == 4) {
        // The documented weakness: the resolved fast mode grows, by much more than the
        // tolerance, while the slow mode stays accurate (below).
        CHECK(r.fast_end > (k == 3 ? 1.3 : 1.02));
      } else {
        // A-stable BDF1 and BDF2, and BDF5 at the steps its error test allows here: the
        // fast mode never rises above its initial amplitude (beyond the tolerance).
        CHECK(r.fast_largest < 1 + 1e-3);
        CHECK(r.fast_end < 1);
      }
      // The slow mode: to the tolerance's order at orders 2..5; BDF1's damping costs it
      // 5 % over 20 periods (161,000 steps).
      if (k >= 2)
        CHECK(std::abs(r.slow - 1) < 1e-4);
      else
        CHECK(r.slow < 1);
    }
  }
}
