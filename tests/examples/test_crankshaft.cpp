// The crankshaft example's own element GASF (examples/crankshaft/crankshaft_model.hpp):
// its Jacobian by finite differences, the force of its formula at and off top dead
// centre and during the switch-on, its bad parameters (code 100); and the static
// load of the belt on the two main bearings of the crankshaft at rest (statics of a
// shaft on two supports with an overhung load).

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <type_traits>
#include <vector>

#include "../elements/element_test_support.hpp"
#include "crankshaft/crankshaft_model.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

TEST_SUITE("examples/crankshaft") {
  TEST_CASE("GASF: finite-difference Jacobian, F = -p A exp(-(u/s_w)^2), the switch-on (1 - cos(pi t/t_in))/2") {
    const crankshaft::gas_force e(crankshaft::gas_force::example());
    testing::jacobian_checker<crankshaft::gas_force> chk(e);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
      local_input<crankshaft::gas_force> in;
      in.u(0) = 0.03 * uni(rng);
      in.t = 0.1 + 0.1 * uni(rng);
      const auto r = chk.check(in);
      std::ostringstream os;
      r.print(os);
      CHECK_MESSAGE(r.ok, os.str());
    }
    // The formula: p = 5e6, A = 5e-3, s_w = 0.01, t_in = 0.1 (example()).
    auto force = [&](double u, double t) {
      local_input<crankshaft::gas_force> in;
      in.u(0) = u;
      in.t = t;
      local_output<crankshaft::gas_force> out;
      std::array<double, 1> work{};
      element_context ctx("GASF", "gas");
      ctx.work = work;
      e.evaluate(in, out, ctx);
      CHECK(out.f(0) == -work[0]);
      return work[0];
    };
    CHECK(force(0, 0.2) == doctest::Approx(-5e6 * 5e-3));
    CHECK(force(-0.01, 0.2) == doctest::Approx(-5e6 * 5e-3 * std::exp(-1.0)));
    CHECK(force(0, 0.05) == doctest::Approx(-5e6 * 5e-3 * 0.5));
    CHECK(force(0, 0.0) == 0.0);
  }

  TEST_CASE("GASF with a negative pressure, a zero area or width, or a non-finite value stops with code 100") {
    struct bad {
      crankshaft::gas_force::parameters p;
      const char* mention;
    };
    for (const bad b : {bad{{-1, 1e-3, 0.01, 0}, "p_peak"}, bad{{1e6, 0, 0.01, 0}, "A = 0"},
                        bad{{1e6, 1e-3, 0, 0}, "s_w = 0"}, bad{{1e6, 1e-3, 0.01, -1}, "t_in"},
                        bad{{std::nan(""), 1e-3, 0.01, 0}, "must be finite"}}) {
      model<crankshaft::gas_force, elements::point_mass> m;
      const dof x = m.add_dof("x");
      m.add<elements::point_mass>("m", {1.0}, x);
      m.add<crankshaft::gas_force>("gas", b.p, x);
      simulation sim(m);
      check_error(error_from([&] { sim.run({.end = 0.01, .smax = 1e-3}); }), error_code::invalid_parameter, "GASF", "gas",
                  b.mention);
    }
  }

  // Both shafts: the eight BEAM3 + BEAMI3, and one Craig-Bampton body reduced from them
  // (crankshaft::cb_model_type; Guyan condensation keeps the static stiffness at the boundary exactly).
  TEST_CASE_TEMPLATE("crankshaft at rest: the belt pull loads the main bearings as a shaft on two supports, gaps = R / k",
                     Model, crankshaft::model_type, crankshaft::cb_model_type) {
    // No drive speed, no gas: the belt force F on the pulley (X = 0), bearings at X = 0.05
    // and 0.15 (span L = 0.10, overhang a = 0.05): R1 = F (a + L) / L = 1.5 F, R2 = -F a / L =
    // -0.5 F (statics). The bearing gaps are R / k_bearing once the damped motion has settled.
    crankshaft::parameters P;
    P.w_end = 0;
    P.p_peak = 0;
    Model m;
    const auto h = crankshaft::build(m, P);
    if constexpr (std::is_same_v<Model, crankshaft::cb_model_type>) CHECK(m.dof_count() < 60);  // 5 nodes, 6 modes
    // Generalized-alpha with rho_inf = 0 annihilates the undamped high-frequency bending
    // modes that the sudden load excites, so the statics are reached in a few steps.
    simulation<Model, generalized_alpha> sim(m, generalized_alpha(0.0));
    sim.run({.end = 0.05, .smax = 1e-3});
    const auto w1 = m.work(h.bearing1), w2 = m.work(h.bearing2);
    const double g1 = w1[0], g2 = w2[0];
    MESSAGE("forces on the journals: (", w1[1], ", ", w1[2], ", ", w1[3], ") and (", w2[1], ", ", w2[2], ", ", w2[3],
            "); gaps ", g1, " m and ", g2, " m; statics 1.5 F = ", 1.5 * P.belt_force, ", -0.5 F = ",
            -0.5 * P.belt_force);
    CHECK(std::abs(w1[3] / (1.5 * P.belt_force) - 1) < 1e-3);
    CHECK(std::abs(w2[3] / (-0.5 * P.belt_force) - 1) < 1e-3);
    CHECK(std::abs(g1 / (1.5 * P.belt_force / P.k_bearing) - 1) < 1e-3);
    CHECK(std::abs(g2 / (0.5 * P.belt_force / P.k_bearing) - 1) < 1e-3);
  }
}

// The shaft as one Craig-Bampton body (FLEX3 on the pulley, bearing, crank-pin and flywheel
// nodes, 6 fixed-interface modes of the inner nodes; crankshaft::cb_model_type) against the
// eight BEAM3 + BEAMI3 it is reduced from: in the run-up, the same bearing runout to a small
// fraction of its peak (the reduction drops the inner nodes' higher modes; the body turns
// with one frame where each BEAM3 has its own).
TEST_SUITE("examples/crankshaft") {
  TEST_CASE("crankshaft run-up, first 30 ms: the Craig-Bampton shaft's bearing runout follows the BEAM3 shaft's") {
    const auto beams = crankshaft::bearing_runouts<crankshaft::model_type>(0.03),
               cb = crankshaft::bearing_runouts<crankshaft::cb_model_type>(0.03);
    REQUIRE(beams.size() == cb.size());
    REQUIRE(beams.size() > 250);
    double peak = 0, diff = 0;
    for (std::size_t k = 0; k < beams.size(); ++k)
      for (std::size_t j = 0; j < 2; ++j) {
        peak = std::max(peak, beams[k][j]);
        diff = std::max(diff, std::abs(beams[k][j] - cb[k][j]));
      }
    MESSAGE("peak runout ", peak * 1e6, " um; largest difference Craig-Bampton - BEAM3 ", diff * 1e6, " um (", diff / peak,
            " of the peak)");
    CHECK(peak > 10e-6);
    CHECK(diff < 1e-3 * peak);
  }
}

// The crankshaft with the BDF driver under error control (examples/crankshaft --bdf; docs/bdf.md,
// "Stiff, excited modes: the crankshaft").
TEST_SUITE("examples/crankshaft") {
  TEST_CASE("scale_angular_dofs sets the nominal potential of the angular DOFs and of no other") {
    crankshaft::model_type m;
    const auto h = crankshaft::build(m, crankshaft::parameters{});
    crankshaft::scale_angular_dofs(m, h, 100.0);
    for (const dof d : {h.r[0].q1, h.r[4].q3, h.r[8].q4, h.rod_r.q2, h.phi, h.cam})
      CHECK(m.scale(d).potential == 100.0);
    for (const dof d : {h.x[1][1], h.rod_x[0], h.py}) CHECK(m.scale(d).potential == 1.0);
    CHECK(m.scale(h.r[0].q1).flow == 1.0);  // the nominal flow is kept
  }

  TEST_CASE("crankshaft run-up, first 30 ms: BDF under error control gives the bearing runout of fine fixed steps") {
    // Reference: the default one-step scheme at fixed steps of 0.025 ms (a quarter of the
    // example's). BDF at DRLTX = DABSX = 1e-4 with the angular DOFs at 100 rad/s. Measured:
    // final runout of bearing 1 1.3751e-5 m against 1.3674e-5, peak runouts 2.2240e-5 and
    // 2.1593e-5 against 2.2320e-5 and 2.1949e-5 (at most 1.6 % of the peak apart), in about
    // 560 steps against 1200.
    struct result {
      double end1 = 0, peak1 = 0, peak2 = 0;
      long steps = 0;
    };
    auto run = [](bool bdf) {
      crankshaft::model_type m;
      const auto h = crankshaft::build(m, crankshaft::parameters{});
      result r;
      auto observe = [&](const auto& s) {
        auto runout = [&](int i) {
          const auto& x = h.x[static_cast<std::size_t>(i)];
          return std::hypot(s.u(x[1]), s.u(x[2]));
        };
        r.peak1 = std::max(r.peak1, runout(1));
        r.peak2 = std::max(r.peak2, runout(7));
        r.end1 = runout(1);
      };
      if (bdf) {
        crankshaft::scale_angular_dofs(m, h, 100.0);
        bdf_simulation sim(m);
        sim.on_output(observe);
        run_options o;
        o.end = 0.03;
        o.smax = 1e-3;
        o.smin = 1e-12;
        o.error_control = true;
        o.drltx = 1e-4;
        o.dabsx = 1e-4;
        r.steps = sim.run(o).steps;
      } else {
        simulation sim(m);
        sim.on_output(observe);
        r.steps = sim.run({.end = 0.03, .out = 0, .smax = 2.5e-5}).steps;
      }
      return r;
    };
    const result ref = run(false), b = run(true);
    MESSAGE("BDF: " << b.steps << " steps, runout at 30 ms " << b.end1 << ", peaks " << b.peak1 << ", " << b.peak2
                    << "; fixed steps: " << ref.steps << ", " << ref.end1 << ", " << ref.peak1 << ", " << ref.peak2);
    const double scale = ref.peak1;
    CHECK(std::abs(b.end1 - ref.end1) < 0.025 * scale);
    CHECK(std::abs(b.peak1 - ref.peak1) < 0.025 * scale);
    CHECK(std::abs(b.peak2 - ref.peak2) < 0.025 * scale);
    CHECK(b.steps < ref.steps);
  }
}
