// The zero step's rates of viscous DOFs (integrators/start_newton.hpp, viscous_rates):
// a massless point s between a spring k (to a mass at x) and a damper c (to the ground)
// obeys k (s - x) + c s' = 0, so its velocity is fixed by the state, s' = k (x - s) / c,
// and its rate by the derivative of that equation, s'' = k (x' - s') / c. With x(0) = x0,
// s(0) = 0 and x'(0) = 0: s'(0) = k x0 / c and s''(0) = -k^2 x0 / c^2 (the Maxwell
// element's relaxation, e.g. Findley, Lai and Onaran, Creep and Relaxation of Nonlinear
// Viscoelastic Materials, 1976, ch. 5). Both drivers start from these values.

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
/// A viscous flow without a root: f = 1 + atan(v) / 2 lies in (1 - pi/4, 1 + pi/4) [N].
template <class = void>
struct zsr_no_root_t {
  static constexpr pradis::passport passport{.name = "NOROOT", .ext = 1, .par = 0, .adr = 2, .ign = 3};
  static constexpr element_help help{.title = "viscous flow without a root",
                                     .name = "f = 1 + atan(v) / 2",
                                     .field = "mechanics",
                                     .dofs = "1 - the DOF",
                                     .parameters = "none",
                                     .work = "none",
                                     .special = "none"};
  struct parameters {};
  parameters p;
  explicit zsr_no_root_t(parameters q = {}) : p(q) {}
  static parameters example() { return {}; }
  static zsr_no_root_t from_parameters(std::span<const double>) { return zsr_no_root_t{}; }
  void evaluate(const local_input<zsr_no_root_t>& in, local_output<zsr_no_root_t>& out, element_context&) const {
    out.f(0) = 1 + 0.5 * std::atan(in.v(0));
    if (out.want_jacobian) out.C(0, 0) = 0.5 / (1 + in.v(0) * in.v(0));
  }
};
using zsr_no_root = zsr_no_root_t<>;

/// A linear damper c = 2 that refuses any displacement of its DOF (code 75), so the zero step's
/// difference quotients along the motion meet a refusal.
template <class = void>
struct zsr_fragile_t {
  static constexpr pradis::passport passport{.name = "FRAGILE", .ext = 1, .par = 0, .adr = 2, .ign = 3};
  static constexpr element_help help{.title = "damper that refuses displacement",
                                     .name = "f = 2 v, code 75 if u != 0",
                                     .field = "mechanics",
                                     .dofs = "1 - the DOF",
                                     .parameters = "none",
                                     .work = "none",
                                     .special = "code 75 if u != 0"};
  struct parameters {};
  parameters p;
  explicit zsr_fragile_t(parameters q = {}) : p(q) {}
  static parameters example() { return {}; }
  static zsr_fragile_t from_parameters(std::span<const double>) { return zsr_fragile_t{}; }
  void evaluate(const local_input<zsr_fragile_t>& in, local_output<zsr_fragile_t>& out, element_context& ctx) const {
    if (in.u(0) != 0) ctx.singular("displaced");
    out.f(0) = 2 * in.v(0);
    if (out.want_jacobian) out.C(0, 0) = 2;
  }
};
using zsr_fragile = zsr_fragile_t<>;

/// Runs `md` with the BDF or the one-step driver, `observe` on every output.
template <class M, class F>
void zsr_run(M& md, bool bdf, const run_options& o, F&& observe) {
  if (bdf) {
    bdf_simulation sim(md);
    sim.on_output(observe);
    sim.run(o);
  } else {
    simulation sim(md);
    sim.on_output(observe);
    sim.run(o);
  }
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using zero_step_rates_model = pradis::model<point_mass, linear_spring, linear_damper, initial_displacement, zsr_no_root,
    zsr_fragile, constant_force, resistor, current_sine, current_table>;
TEST_SUITE("integrators/zero step") {
  TEST_CASE("a massless point between a spring and a damper starts with s' = k x0 / c and s'' = -k^2 x0 / c^2") {
    const double k = 40, c = 2, m = 3, x0 = 0.05;
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      zero_step_rates_model md;
      const dof x = md.add_dof("x"), s = md.add_dof("s");
      md.add<point_mass>("mass", {m}, x);
      md.add<linear_spring>("spring", {k}, x, s);
      md.add<linear_damper>("damper", {c}, s, md.ground());
      md.add<initial_displacement>("x0", {x0}, x);
      double vs = 0, as = 0, ax = 0;
      auto at_start = [&](const auto& r) {
        if (r.time() == 0) vs = r.v(s), as = r.a(s), ax = r.a(x);
      };
      const run_options o{.end = 1e-3, .out = 1e-3, .smax = 1e-4};
      zsr_run(md, bdf, o, at_start);
      CHECK(vs == doctest::Approx(k * x0 / c).epsilon(1e-14));
      CHECK(ax == doctest::Approx(-k * x0 / m).epsilon(1e-14));
      CHECK(as == doctest::Approx(-k * k * x0 / (c * c)).epsilon(1e-9));
    }
  }

  TEST_CASE("a viscous DOF whose flow has no root: the zero step warns and the first step fails in Newton") {
    zero_step_rates_model md;
    const dof v = md.add_dof("v");
    md.add<zsr_no_root>("noroot", {}, v);
    simulation sim(md);
    std::ostringstream log;
    sim.log().to(log);
    bool failed = false;
    try {
      sim.run({.end = 1e-3, .smax = 1e-4});
    } catch (const error& e) {
      failed = true;
      CHECK(e.code() == error_code::newton_failure);
      // The flow left is its infimum 1 - pi/4 (v far below zero), not a NaN.
      CHECK(std::string(e.what()).find("largest residual 0.2146") != std::string::npos);
    }
    CHECK(failed);
    CAPTURE(log.str());
    CHECK(log.str().find("warning: the zero step's Newton iterations on the initial derivatives stopped converging") !=
          std::string::npos);
  }

  TEST_CASE("an element that refuses the states next to the start: rates at 0 with a warning, the run goes on") {
    // The damper balances the applied force -1 N: 2 v = -1, v = -0.5 from the first solve; the
    // difference quotients along the motion displace the DOF.
    zero_step_rates_model md;
    const dof v = md.add_dof("v");
    md.add<zsr_fragile>("fragile", {}, v);
    md.add<constant_force>("push", {-1.0}, v);
    simulation sim(md);
    std::ostringstream log;
    sim.log().to(log);
    double v0 = 0, a0 = 1;
    sim.on_output([&](const auto& r) {
      if (r.time() == 0) v0 = r.v(v), a0 = r.a(v);
    });
    // The first step displaces the DOF too: the element's own error ends the run.
    CHECK_THROWS_AS(sim.run({.end = 1e-3, .smax = 1e-4}), error);
    CHECK(v0 == doctest::Approx(-0.5).epsilon(1e-14));
    CHECK(a0 == 0.0);
    CHECK(log.str().find("warning: no consistent rates of the viscous DOFs at the zero step: an element refuses") !=
          std::string::npos);
    CHECK(log.str().find("displaced") != std::string::npos);
  }

  TEST_CASE("explicit time dependence: a current source feeding a resistor starts with v' = R I'(0)") {
    // The node equation v / R - I(t) = 0 holds at all times, so v = R I(t) and v' = R I'(t):
    // the node voltage's rate comes from the source's time dependence alone (no state term).
    // ISIN: I = I0 + A sin(2 pi f t + phi), I'(0) = 2 pi f A cos(phi). ITAB: the ramp (0, 0),
    // (1, 2) from t = 0, I'(0+) = 2 A/s (before t = 0 the table holds its first value, so a
    // central difference would give half of it). The one-sided differences with two
    // Richardson levels are exact on the ramp and within O((2 pi f e)^3) on the sine, where
    // e <= 1e-2 / (20 f) (ISIN's recommended step): 3e-8 relative.
    const double R = 10, A = 0.2, f = 50, phi = 30.0, I0 = 0.1;
    const double pi = 3.14159265358979323846;
    for (const bool bdf : {false, true})
      for (const bool table : {false, true}) {
        CAPTURE(bdf);
        CAPTURE(table);
        zero_step_rates_model md;
        const dof n = md.add_dof("n");
        md.add<resistor>("R", {R}, n, md.ground());
        if (table)
          md.add<current_table>("I", {{0.0, 0.0, 1.0, 2.0}}, n, md.ground());
        else
          md.add<current_sine>("I", {A, f, phi, I0}, n, md.ground());
        double v0 = -1, a0 = 0;
        auto at_start = [&](const auto& r) {
          if (r.time() == 0) v0 = r.v(n), a0 = r.a(n);
        };
        const run_options o{.end = 1e-4, .out = 1e-4, .smax = 1e-5};
        zsr_run(md, bdf, o, at_start);
        if (table) {
          CHECK(v0 == 0.0);
          CHECK(a0 == doctest::Approx(2 * R).epsilon(1e-12));
        } else {
          CHECK(v0 == doctest::Approx(R * (I0 + A * std::sin(phi * pi / 180))).epsilon(1e-14));
          CHECK(a0 == doctest::Approx(R * 2 * pi * f * A * std::cos(phi * pi / 180)).epsilon(3e-8));
        }
      }
  }
}
