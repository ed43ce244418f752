// The PI-control example's own element PICTRL and node kind (examples/pi_control): the
// element's Jacobian by finite differences and its flows by their formula, its bad
// gains (code 100); the controlled oscillator under Newmark and BDF against the exact
// solution exp(A t) z(0) (pi_exact.hpp), with the steady state h -> F0 / Ki of integral
// action (final value of the linear system: x' = 0 and h' = x = 0 give Ki h = F0).

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <tuple>
#include <type_traits>

#include "../elements/element_test_support.hpp"
#include "pi_control/pi_scene.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;
using pradis_examples::integral_node;
using pradis_examples::pi_controller;
using pradis_examples::pi_plant;

static_assert(std::is_same_v<pradis_examples::pi_model::node_kinds,
                             type_list<spatial::rotation_node_kind, integral_node>>);

TEST_SUITE("examples/pi_control") {
  TEST_CASE("PICTRL: finite-difference Jacobian and the flows Kp x + Ki h on x, none on h") {
    const pi_controller e({300, 1000});
    testing::jacobian_checker<pi_controller> chk(e);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int trial = 0; trial < 20; ++trial) {
      local_input<pi_controller> in;
      in.u << 0.05 * uni(rng), 0.02 * uni(rng);
      in.v << uni(rng), uni(rng);
      const auto r = chk.check(in);
      std::ostringstream os;
      r.print(os);
      CHECK_MESSAGE(r.ok, os.str());
    }
    local_input<pi_controller> in;
    in.u << 0.02, -0.01;
    local_output<pi_controller> out;
    std::array<double, 1> work{};
    element_context ctx("PICTRL", "controller");
    ctx.work = work;
    e.evaluate(in, out, ctx);
    CHECK(out.f(0) == doctest::Approx(300 * 0.02 - 1000 * 0.01));
    CHECK(out.f(1) == 0.0);
    CHECK(work[0] == doctest::Approx(-(300 * 0.02 - 1000 * 0.01)));
  }

  TEST_CASE("PICTRL with a negative or non-finite gain stops with code 100") {
    for (const auto& [kp, ki, mention] : {std::tuple{-1.0, 10.0, "Kp = -1"}, std::tuple{1.0, -2.0, "Ki = -2"},
                                          std::tuple{pradis_test::not_a_number, 1.0, "Kp = nan"},
                                          std::tuple{1.0, pradis_test::inf, "Ki = inf"}}) {
      pi_plant p;
      p.kp = kp;
      p.ki = ki;
      pradis_examples::pi_scene s(p);
      simulation sim(s.m);
      check_error(error_from([&] { sim.run({.end = 0.01, .smax = 1e-3}); }), error_code::invalid_parameter, "PICTRL",
                  "controller", mention);
    }
  }

  TEST_CASE("the controlled oscillator follows exp(A t) z(0) and settles at x = 0, h = F0 / Ki") {
    const pi_plant p;
    const double xs = p.f0 / (p.k + p.kp), hs = xs * 3.0;  // scales of x and h over 3 s
    for (int driver = 0; driver < 2; ++driver) {
      pradis_examples::pi_scene s(p);
      const dof x = s.x, h = s.h;
      double worst = 0;
      auto track = [&](const auto& st) {
        const Eigen::Vector4d z = pradis_examples::pi_exact(p, st.time());
        worst = std::max({worst, std::abs(st.u(x) - z(0)) / xs, std::abs(st.u(h) - z(2)) / hs});
      };
      double x_end = 0, h_end = 0;
      if (driver == 0) {
        simulation sim(s.m);
        sim.on_output(track);
        sim.run({.end = 3.0, .out = 0.01, .smax = 1e-3});
        x_end = sim.u(x), h_end = sim.u(h);
        MESSAGE("PI oscillator, Newmark h = 1e-3: worst relative error ", worst);
        // Trapezoidal phase error w^3 h^2 t / 12 on the oscillating mode (w = 19.5 rad/s): 1.2e-4 rad at
        // t = 0.2 s, where its amplitude peaks (measured 6.6e-5 of the scales).
        CHECK(worst < 2e-4);
      } else {
        bdf_simulation sim(s.m);
        sim.on_output(track);
        sim.run({.end = 3.0, .out = 0.01, .smax = 0.1, .error_control = true, .dabsx = 1e-8, .drltx = 1e-8});
        x_end = sim.u(x), h_end = sim.u(h);
        MESSAGE("PI oscillator, BDF DRLTX 1e-8: worst relative error ", worst);
        CHECK(worst < 1e-5);  // measured 7.0e-7
      }
      // Near the steady state at 3 s: the slowest mode (s = -2.63 1/s) has decayed to 4e-4 of its start.
      CHECK(std::abs(x_end) < 2e-5);
      CHECK(h_end == doctest::Approx(p.f0 / p.ki).epsilon(1e-3));
    }
  }
}
