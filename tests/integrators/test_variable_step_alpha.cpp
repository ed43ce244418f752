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
#include <span>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// A one-sided wall at u = 0 with stiffness k that asks for steps of h_c while in
/// contact (STEPMD) and nothing outside: after the contact the step jumps back to
/// SMAX at once.
struct stepping_wall {
  static constexpr pradis::passport passport{.name = "WALLT", .ext = 1, .par = 2, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "one-sided wall with a contact step",
                                             .name = "Wall for the step-jump test",
                                             .field = "mechanics",
                                             .dofs = "1 - position [m]",
                                             .parameters = "1 - stiffness k [N/m]\n2 - step in contact [s]",
                                             .work = "",
                                             .special = "STEPMD while in contact"};
  struct parameters {
    double k = 0, h = 0;
  };
  parameters p;
  explicit stepping_wall(parameters q) : p(q) {}
  static stepping_wall from_parameters(std::span<const double> v) { return stepping_wall({v[0], v[1]}); }
  void evaluate(const local_input<stepping_wall>& in, local_output<stepping_wall>& out, element_context& ctx) const {
    const bool touching = in.u(0) < 0;
    out.f(0) = touching ? p.k * in.u(0) : 0.0;
    if (touching) ctx.recommend_step(p.h);
    if (out.want_jacobian) out.K(0, 0) = touching ? p.k : 0.0;
  }
};

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using variable_step_alpha_model = pradis::model<point_mass, linear_spring, initial_displacement, initial_velocity,
    stepping_wall>;

// m = 1, k = (2 pi)^2 (period 1), X0 = 1: relative energy change after `periods`.
double energy_change(const alpha_family& scheme, double drltx, double periods) {
  variable_step_alpha_model m;
  const dof x = m.add_dof("x");
  const double k = 4 * std::numbers::pi * std::numbers::pi;
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {k}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  simulation<variable_step_alpha_model, alpha_family> sim(m, scheme);
  sim.run({.end = periods, .smax = 0.1, .error_control = true, .drltx = drltx});
  const double e = 0.5 * sim.v(x) * sim.v(x) + 0.5 * k * sim.u(x) * sim.u(x);
  return e / (0.5 * k) - 1;
}

static_assert(check_element<stepping_wall>());
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

  TEST_CASE("after a contact the step jumps 5000x and the free flight keeps its velocity (shift capped)") {
    // A unit mass at 1 m/s hits a wall (k = 1e8) that asks for steps of 2e-7 s while
    // in contact; afterwards no force acts, so the velocity must stay what it was
    // when the contact ended (momentum balance). The first free step is 5000 times
    // the last contact step. The variable-step shift of the pseudo-acceleration,
    // uncapped, extrapolated the contact's last acceleration change over that step:
    // HHT alpha = -0.05 then flew on at 2.78 m/s after leaving at 0.993 m/s. The
    // shift now extrapolates over at most one previous step; what remains is the
    // scheme's memory of the last contact step (p_n carries alpha_f a_n for one
    // step), a velocity change of about h (1 - gamma) alpha_f |a_exit|.
    for (const alpha_family& s : {alpha_family(hht{-0.05}), alpha_family(hht{-0.3}),
                                  alpha_family(generalized_alpha{0.8})}) {
      CAPTURE(s.label());
      variable_step_alpha_model m;
      const dof x = m.add_dof("x");
      m.add<point_mass>("mass", {1.0}, x);
      m.add<initial_displacement>("x0", {1e-3}, x);
      m.add<initial_velocity>("v0", {-1.0}, x);
      m.add<stepping_wall>("wall", {1e8, 2e-7}, x);
      simulation<decltype(m), alpha_family> sim(m, s);
      double v_exit = 0, h_exit = 0, h_after = 0;
      bool left = false, in_contact = false;
      sim.on_step([&](const auto& r) {
        if (r.u(x) < 0) in_contact = true;
        if (in_contact && !left && r.u(x) > 0) {
          left = true;
          v_exit = r.v(x);
          h_exit = r.statistic("STEP");
        } else if (left && h_after == 0) {
          h_after = r.statistic("STEP");
        }
      });
      (void)sim.run({.end = 0.05, .smax = 1e-3});
      REQUIRE(left);
      CAPTURE(v_exit);
      CAPTURE(sim.v(x));
      CHECK(h_after > 4000 * h_exit);            // the step did jump
      CHECK(v_exit > 0.85);                       // an elastic rebound (HHT dissipates a little in the contact)
      CHECK(std::abs(sim.v(x) - v_exit) < 1e-3);  // and the free flight keeps it
    }
  }
}
