// Loss of precision of the displacement on a DOF far stiffer than the step
// (omega h >> 1): the alpha-family update computes u from the velocities, so
// NEWMARK keeps u exact to round-off; HHT and generalized-alpha compute u from
// h^2 a terms that are ~(omega h)^2 |u| and lose it, which the simulation
// reports in the diagnostics log (integrators/precision.hpp).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
using stiff_model = model<point_mass, linear_spring, initial_displacement>;

struct precision_run {
  double max_u = 0;     // largest |u| over the run
  std::string log;      // the diagnostics log
};

// MASS m on SPRING k to the ground, X0 = 1, V0 = 0, fixed steps h up to t = 1.
precision_run run_stiff(double m, double k, double h, const alpha_family& scheme) {
  stiff_model mod;
  const dof x = mod.add_dof("x");
  mod.add<point_mass>("mass", {m}, x);
  mod.add<linear_spring>("spring", {k}, x, mod.ground());
  mod.add<initial_displacement>("x0", {1.0}, x);
  simulation<stiff_model, alpha_family> sim(mod, scheme);
  std::ostringstream log;
  sim.log().to(log);
  precision_run out;
  sim.on_step([&](const auto& s) { out.max_u = std::max(out.max_u, std::abs(s.u(x))); });
  sim.run({.end = 1.0, .smax = h});
  out.log = log.str();
  return out;
}
}  // namespace

TEST_SUITE("integrators/precision") {
  TEST_CASE("NEWMARK keeps |u| <= 1 on MASS 1e-12 / SPRING 1e12 with SMAX 1e-3 (omega h = 1e9)") {
    // Newmark's average acceleration rule conserves the discrete energy
    // k u^2 / 2 + m v^2 / 2 of a linear oscillator exactly (Hughes, The Finite
    // Element Method, Dover 2000, section 9.1.4), so |u| <= sqrt(2 E / k) = 1 with
    // X0 = 1, V0 = 0 for every step size; before u was computed from the
    // velocities, the cancellation of h^2 (a0 + a) / 4 gave |u| up to 17.
    const precision_run r = run_stiff(1e-12, 1e12, 1e-3, alpha_family(newmark{}));
    CHECK(r.max_u <= 1.0 + 1e-12);
    CHECK(r.max_u >= 1.0 - 1e-12);  // u alternates between +1 and -1 at omega h -> infinity
    CHECK(r.log.find("loss of precision") == std::string::npos);
  }

  TEST_CASE("generalized-alpha on the same DOF warns that the displacement is lost in round-off") {
    // rho_inf = 0.5: u is computed from h^2 (1/2 - beta/gamma) a0 with |a0| = k/m |u| =
    // 1e24 |u|, i.e. from terms 1e17 times |u|: u is resolved only to ~eps 1e17.
    const precision_run r = run_stiff(1e-12, 1e12, 1e-3, alpha_family(generalized_alpha{0.5}));
    CHECK(r.log.find("warning: loss of precision: at t = 0.001 ") != std::string::npos);
    CHECK(r.log.find("the displacement of DOF 'x' is resolved only to") != std::string::npos);
    // Written once per stage.
    const auto first = r.log.find("loss of precision");
    CHECK(r.log.find("loss of precision", first + 1) == std::string::npos);
  }

  TEST_CASE("a step that resolves the element's frequency writes no precision warning") {
    // omega = 1, h = 1e-3: every term of the update is of the size of u.
    for (const alpha_family& s : {alpha_family(newmark{}), alpha_family(hht{-0.1}), alpha_family(generalized_alpha{0.5})}) {
      const precision_run r = run_stiff(1.0, 1.0, 1e-3, s);
      CHECK(r.log.find("loss of precision") == std::string::npos);
      CHECK(r.max_u <= 1.0 + 1e-12);  // energy conserved (Newmark) or dissipated
    }
  }
}
