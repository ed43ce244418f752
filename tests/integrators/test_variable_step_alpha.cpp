// HHT and generalized-alpha under error control (variable steps) on a linear
// oscillator: both are dissipative schemes (spectral radius <= 1 at fixed steps),
// so the energy must not grow, and its loss must fall with the tolerance. Without
// the shift of the pseudo-acceleration on a step change
// (pseudo_acceleration_shift, newmark.hpp; Arnold and Bruels, Multibody System
// Dynamics 18 (2007) 185-202), generalized-alpha rho_inf = 0.8 gained energy
// linearly in time (+2.7e-5 of E0 after 100 periods at DRLTX = 1e-4).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
using osc_model = model<point_mass, linear_spring, initial_displacement>;

// m = 1, k = (2 pi)^2 (period 1), X0 = 1: relative energy change after `periods`.
double energy_change(const alpha_family& scheme, double drltx, double periods) {
  osc_model m;
  const dof x = m.add_dof("x");
  const double k = 4 * std::numbers::pi * std::numbers::pi;
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {k}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  simulation<osc_model, alpha_family> sim(m, scheme);
  sim.run({.end = periods, .smax = 0.1, .error_control = true, .drltx = drltx});
  const double e = 0.5 * sim.v(x) * sim.v(x) + 0.5 * k * sim.u(x) * sim.u(x);
  return e / (0.5 * k) - 1;
}
}  // namespace

TEST_SUITE("integrators/variable-step alpha") {
  TEST_CASE("HHT and generalized-alpha under error control lose energy, less at tighter tolerances") {
    for (const alpha_family& s : {alpha_family(hht{-0.1}), alpha_family(generalized_alpha{0.8}),
                                  alpha_family(generalized_alpha{0.5})}) {
      CAPTURE(s.label());
      const double loose = energy_change(s, 1e-4, 20), tight = energy_change(s, 1e-5, 20);
      CAPTURE(loose);
      CAPTURE(tight);
      CHECK(loose < 0);
      CHECK(tight < 0);
      CHECK(loose > -1e-3);
      // Dissipation per unit time ~ h^3 and h ~ DRLTX^(1/2): a factor 10 of
      // tolerance is about 30 in energy; require at least 10.
      CHECK(std::abs(tight) * 10 < std::abs(loose));
    }
  }

  TEST_CASE("NEWMARK under error control keeps the oscillator's energy to round-off") {
    // The trapezoidal rule conserves the discrete energy of a linear oscillator at
    // every step size (Hughes, The Finite Element Method, 2000, section 9.1.4),
    // so also under variable steps.
    CHECK(std::abs(energy_change(alpha_family(newmark{}), 1e-4, 20)) < 1e-12);
  }
}
