// LINKX: the exact rigid planar link (a constraint with its axial force as a
// Lagrange multiplier). Checked against closed forms (the pendulum released from
// the horizontal) and against an independent solution of a 10-link chain in joint
// coordinates; the length of every link stays at its initial value to round-off.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "../../bench/chain_reference.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
using link_model = model<point_mass, planar_rigid_link, planar_link, constant_force>;
constexpr double g = 9.81;

newton_options tight() { return {.dabsu = 1e-10, .drltu = 1e-10, .dabsi = 1e-9, .drlti = 1e-12, .itr = 10}; }

using pradis_reference::chain_reference;
using pradis_reference::chain_state;
}  // namespace

TEST_SUITE("elements/LINKX rigid link") {
  TEST_CASE("pendulum released from the horizontal: at the bottom v = sqrt(2 g L) and N = 3 m g") {
    // Mass m = 2 on a link of L = 1.5 from the pivot at the origin. A quarter of the
    // period from 90 degrees is sqrt(L/g) K(sin 45 deg), K(1/sqrt 2) =
    // 1.8540746773013719 (Abramowitz and Stegun, table 17.1); there the mass is at
    // the bottom with speed sqrt(2 g L) (energy) and the link pulls 3 m g.
    const double m = 2.0, l = 1.5, quarter = std::sqrt(l / g) * 1.8540746773013719;
    for (const alpha_family& scheme : {alpha_family(newmark{}), alpha_family(hht{-0.1})}) {
      CAPTURE(scheme.label());
      const bool undamped = scheme.label() == "NEWMARK";
      double n_last = 0;
      link_model mod;
      const dof x = mod.add_dof("x"), y = mod.add_dof("y");
      mod.add<point_mass>("mx", {m}, x);
      mod.add<point_mass>("my", {m}, y);
      const auto rod = mod.add<planar_rigid_link>("rod", {0.0, 0.0, l, 0.0}, mod.ground(), mod.ground(), x, y);
      mod.add<constant_force>("weight", {-m * g}, y);
      simulation<link_model, alpha_family> sim(mod, scheme);
      double gap = 0, n_before = 0;
      sim.on_step([&](const auto&) {
        gap = std::max(gap, std::abs(mod.work(rod)[1] - l));
        n_before = n_last;
        n_last = mod.work(rod)[2];
      });
      run_options o{.end = quarter, .smax = quarter / 4000};
      o.newton = tight();
      sim.run(o);
      CHECK(std::abs(l + sim.u(x)) < 2e-6);  // x = 0
      CHECK(std::abs(sim.u(y) + l) < 1e-9);  // y = -L (on the circle)
      CHECK(std::abs(std::hypot(sim.v(x), sim.v(y)) - std::sqrt(2 * g * l)) < 2e-5);
      // Under NEWMARK (no numerical damping) the multiplier of an index-3
      // constraint alternates from step to step (here +-5e-4 relative; a known
      // property of the trapezoidal rule on position constraints); the mean of two
      // steps is accurate. HHT damps the alternation out.
      const double n_end = undamped ? 0.5 * (n_last + n_before) : n_last;
      CHECK(std::abs(n_end - 3 * m * g) < 1e-5 * 3 * m * g);
      if (undamped) CHECK(std::abs(n_last - n_before) > 1e-4 * 3 * m * g);
      CHECK(gap < 1e-13);
    }
  }

  // The chain of chain_reference built in pradis, with exact links (k = 0) or
  // LINKD penalty links of stiffness k; returns the tip's distance from the
  // reference at t_end and the largest |L - L0| of the exact links over the run.
  struct chain_result {
    double tip_error = 0, gap = 0;
  };
  chain_result run_chain(double k, double h) {
    const int n = 10;
    const double l = 0.1, m = 0.05, t_end = 0.4;
    // Independent reference (bench/chain_reference.hpp): RK4 in the link angles, h = 5e-5.
    static const chain_state ref = chain_reference(n, l, g, t_end, 8000);
    link_model mod;
    std::vector<dof> x(n), y(n);
    std::vector<element_ref<planar_rigid_link>> links;
    for (int i = 0; i < n; ++i) {
      const auto si = static_cast<std::size_t>(i);
      x[si] = mod.add_dof("x" + std::to_string(i + 1));
      y[si] = mod.add_dof("y" + std::to_string(i + 1));
      mod.add<point_mass>("mx" + std::to_string(i + 1), {m}, x[si]);
      mod.add<point_mass>("my" + std::to_string(i + 1), {m}, y[si]);
      mod.add<constant_force>("w" + std::to_string(i + 1), {-m * g}, y[si]);
      const dof ax = i == 0 ? mod.ground() : x[si - 1], ay = i == 0 ? mod.ground() : y[si - 1];
      const std::string name = "link" + std::to_string(i + 1);
      if (k > 0)
        mod.add<planar_link>(name, {i * l, 0.0, (i + 1) * l, 0.0, k}, ax, ay, x[si], y[si]);
      else
        links.push_back(mod.add<planar_rigid_link>(name, {i * l, 0.0, (i + 1) * l, 0.0}, ax, ay, x[si], y[si]));
    }
    simulation<link_model, alpha_family> sim(mod, alpha_family(hht{-0.05}));
    chain_result out;
    sim.on_step([&](const auto&) {
      for (const auto& r : links) out.gap = std::max(out.gap, std::abs(mod.work(r)[1] - l));
    });
    run_options o{.end = t_end, .smax = h};
    o.newton = tight();
    sim.run(o);
    double tx = 0, ty = 0;
    for (int j = 0; j < n; ++j) {
      tx += l * std::cos(ref.th(j));
      ty += l * std::sin(ref.th(j));
    }
    out.tip_error = std::hypot(n * l + sim.u(x[n - 1]) - tx, sim.u(y[n - 1]) - ty);
    return out;
  }

  TEST_CASE("a 10-link chain agrees with an independent joint-coordinate solution, second order in h") {
    // Measured: tip error 5.2e-7, 1.3e-7, 3.3e-8, 8.2e-9 at h = 2e-4 ... 2.5e-5.
    const chain_result coarse = run_chain(0, 2e-4), fine = run_chain(0, 1e-4);
    CAPTURE(coarse.tip_error);
    CAPTURE(fine.tip_error);
    CHECK(fine.tip_error < 1e-6);
    const double order = std::log2(coarse.tip_error / fine.tip_error);
    CHECK(order > 1.9);
    CHECK(order < 2.1);
    CHECK(fine.gap < 1e-13);  // the link lengths stay L0 to round-off (index-3: no drift)
  }

  TEST_CASE("the same chain on penalty links (LINKD): the tip error scales as 1/k") {
    // The constraint is met to O(force / k), and the trajectory error follows:
    // measured 9.5e-3, 9.5e-4, 9.5e-5 at k = 1e4, 1e5, 1e6 (h = 2.5e-5).
    const double e5 = run_chain(1e5, 1e-4).tip_error, e6 = run_chain(1e6, 1e-4).tip_error;
    CAPTURE(e5);
    CAPTURE(e6);
    CHECK(e5 / e6 > 9.5);
    CHECK(e5 / e6 < 10.5);
    CHECK(e6 > 50 * run_chain(0, 1e-4).tip_error);  // the exact link is far closer
  }

  TEST_CASE("the log notes that NEWMARK leaves multipliers undamped; HHT writes no such note") {
    for (const alpha_family& scheme : {alpha_family(newmark{}), alpha_family(hht{-0.1})}) {
      link_model mod;
      const dof x = mod.add_dof("x"), y = mod.add_dof("y");
      mod.add<point_mass>("mx", {1.0}, x);
      mod.add<point_mass>("my", {1.0}, y);
      mod.add<planar_rigid_link>("rod", {0.0, 0.0, 1.0, 0.0}, mod.ground(), mod.ground(), x, y);
      mod.add<constant_force>("weight", {-g}, y);
      simulation<link_model, alpha_family> sim(mod, scheme);
      std::ostringstream log;
      sim.log().to(log);
      sim.run({.end = 0.01, .smax = 1e-3});
      const bool noted = log.str().find("note: the model has constraint equations") != std::string::npos;
      CHECK(noted == (scheme.label() == "NEWMARK"));
    }
  }

  TEST_CASE("bad parameters: coincident points and non-finite coordinates are code 100") {
    for (const planar_rigid_link::parameters& bad :
         {planar_rigid_link::parameters{1.0, 2.0, 1.0, 2.0}, planar_rigid_link::parameters{0.0, 0.0, NAN, 1.0}}) {
      link_model mod;
      const dof x = mod.add_dof("x"), y = mod.add_dof("y");
      mod.add<point_mass>("mx", {1.0}, x);
      mod.add<point_mass>("my", {1.0}, y);
      mod.add<planar_rigid_link>("rod", bad, mod.ground(), mod.ground(), x, y);
      simulation sim(mod, newmark{});
      try {
        sim.run({.end = 0.01, .smax = 0.001});
        FAIL("must throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::invalid_parameter);
        CHECK(e.element_type() == "LINKX");
        CHECK(e.instance() == "rod");
      }
    }
  }
}
