// CAM and its periodic cubic spline: the spline reproduces a harmonic lift to
// its O(h^4) / O(h^2) interpolation error and is C2 across the period; the
// follower of a cam at constant speed stays on the profile with the contact
// force F0 + k_s s + m s'' w^2 below the lift-off speed and lifts off above it;
// exact Jacobian at random states; bad parameters are code 100 / 101.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include "element_test_support.hpp"
#include "pradis/elements/mech1d/cam.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
constexpr double pi = std::numbers::pi;
/// The harmonic lift s = h (1 - cos theta) / 2 sampled at n + 1 points over one turn.
std::vector<double> harmonic_table(double h, int n) {
  std::vector<double> t;
  for (int i = 0; i <= n; ++i) {
    const double th = 2 * pi * i / n;
    t.insert(t.end(), {th, i == n ? 0.0 : 0.5 * h * (1 - std::cos(th))});
  }
  return t;
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using cam_model = pradis::model<cam, point_mass, linear_spring, constant_force, velocity_source, initial_displacement>;
TEST_SUITE("elements/CAM") {
  TEST_CASE("the periodic spline reproduces a harmonic lift with errors falling as h^4 (value) and h^2 (curvature)") {
    // Cubic spline interpolation error: |y - s| <= (5/384) h^4 max|y''''|,
    // |y'' - s''| = O(h^2) (de Boor, A Practical Guide to Splines, IV (17)).
    const double h = 0.008;
    double prev_v = 0, prev_c = 0;
    for (int n : {24, 48, 96}) {
      CAPTURE(n);
      const auto tab = harmonic_table(h, n);
      const periodic_spline s(tab);
      REQUIRE(s.problem("angle", "lift").empty());
      double ev = 0, ec = 0;
      for (int i = 0; i < 1000; ++i) {
        const double th = -3 * pi + 7 * pi * i / 1000.0;  // also outside the period
        const auto q = s.at(th);
        ev = std::max(ev, std::abs(q.value - 0.5 * h * (1 - std::cos(th))));
        ec = std::max(ec, std::abs(q.curvature - 0.5 * h * std::cos(th)));
        CHECK(std::abs(q.slope - 0.5 * h * std::sin(th)) < 1e-3 * h);
      }
      const double step = 2 * pi / n;
      CHECK(ev <= 5.0 / 384 * std::pow(step, 4) * 0.5 * h * 1.01);
      if (prev_v > 0) {
        CHECK(prev_v / ev > 14);  // h^4: 16 per halving
        CHECK(prev_c / ec > 3.5);  // h^2: 4 per halving
      }
      prev_v = ev;
      prev_c = ec;
      // C2 across the period's end.
      const auto a = s.at(2 * pi - 1e-9), b = s.at(1e-9);
      CHECK(std::abs(a.curvature - b.curvature) < 1e-6 * h);
    }
  }

  TEST_CASE("a follower stays on the cam below the lift-off speed sqrt(2 (F0 + k_s h) / (m h)) and lifts off above it") {
    // Harmonic lift s = h (1 - cos theta)/2 at constant speed w: a follower on the
    // profile needs the contact force F = F0 + k_s s + m s'' w^2,
    // s'' = (h/2) cos theta; it is least at theta = pi, F0 + k_s h - m h w^2 / 2,
    // which is zero at w_c = sqrt(2 (F0 + k_s h) / (m h)) (Norton, Cam Design and
    // Manufacturing Handbook, 2009, ch. 10: follower jump).
    const double m = 0.5, ks = 2000, f0 = 50, h = 0.008, k = 1e7, c = 2000;
    const double wc = std::sqrt(2 * (f0 + ks * h) / (m * h));
    for (double ratio : {0.98, 1.02}) {
      CAPTURE(ratio);
      const double w = ratio * wc, turn = 2 * pi / w;
      cam_model md;
      const dof th = md.add_dof("theta"), y = md.add_dof("y");
      md.add<velocity_source>("drive", {0.0, 0.0, 0.0, w}, th);
      const auto cm = md.add<cam>("cam", {k, c, harmonic_table(h, 72)}, th, y);
      md.add<point_mass>("follower", {m}, y);
      md.add<linear_spring>("spring", {ks}, md.ground(), y);
      md.add<constant_force>("preload", {-f0}, y);
      md.add<initial_displacement>("y0", {-f0 / k}, y);
      simulation<decltype(md), alpha_family> sim(md, alpha_family(hht{-0.1}));
      double fmin = 1e300, worst = 0;
      sim.on_output([&](const auto& s) {
        if (s.time() < turn) return;  // the start transient dies out in the first turn
        const double f = md.work(cm)[0], q = s.u(th);
        fmin = std::min(fmin, f);
        if (ratio < 1) worst = std::max(worst, std::abs(f - (f0 + ks * 0.5 * h * (1 - std::cos(q)) +
                                                             m * 0.5 * h * std::cos(q) * w * w)));
      });
      sim.run(fixed_step(3 * turn, turn / 2000));
      if (ratio < 1) {
        CHECK(fmin > 0);
        // F0 + k_s h - m h w^2 / 2 = 2.6 N at 0.98 w_c; the contact's compliance
        // and the spline's curvature error (72 points) stay below 0.3 % of the preload.
        // Measured: 0.097 N worst, and the least force 2.52 N against 2.61 N.
        CHECK(worst < 0.15);
        CHECK(fmin == doctest::Approx(f0 + ks * h - m * h * w * w / 2).epsilon(0.05));
      } else {
        CHECK(fmin == 0);  // lifted off
      }
    }
  }

  TEST_CASE("the CAM Jacobian is exact at random states in and out of contact") {
    testing::jacobian_checker<cam> chk{cam(cam::example())};
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    int in_contact = 0, checked = 0;
    for (int trial = 0; trial < 300; ++trial) {
      local_input<cam> in;
      in.u(0) = 4 * uni(rng);
      in.u(1) = 0.005 + 0.004 * uni(rng);
      in.v(0) = 50 * uni(rng);
      in.v(1) = 0.2 * uni(rng);
      if (!chk.element().admissible(in)) continue;
      ++checked;
      if (chk.flows(in).norm() > 0) ++in_contact;
      if (!jacobian_passes(chk.check(in))) break;
    }
    CHECK(in_contact > 50);
    CHECK(checked - in_contact > 50);
  }

  TEST_CASE("bad CAM parameters stop the run with code 100 naming the element, the instance and the problem") {
    struct bad {
      cam::parameters q;
      const char* mention;
    };
    const auto good = harmonic_table(0.008, 12);
    auto broken = [&](std::size_t at, double value) {
      auto t = good;
      t[at] = value;
      return t;
    };
    const std::vector<bad> cases{
        {{0.0, 1.0, good}, "contact stiffness k"},
        {{1e6, -1.0, good}, "contact damping c"},
        {{1e6, 1.0, broken(2, 5.0)}, "is not above angle 2 (5)"},
        {{1e6, 1.0, broken(25, 0.001)}, "must equal the first"},
        {{1e6, 1.0, {0.0, 0.0, 1.0, 0.0, 2.0, 0.0}}, "at least 4 points"},
        {{1e6, 1.0, broken(7, std::nan(""))}, "point 4 is not finite"},
    };
    for (const auto& b : cases) {
      CAPTURE(b.mention);
      cam_model md;
      const dof th = md.add_dof("theta"), y = md.add_dof("y");
      md.add<cam>("cam", b.q, th, y);
      md.add<point_mass>("follower", {1.0}, y);
      md.add<point_mass>("rotor", {1.0}, th);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.01, 1e-3)); }), error_code::invalid_parameter, "CAM", "cam",
                  b.mention);
    }
    // An odd flat count is code 101.
    cam_model md;
    const dof th = md.add_dof("theta"), y = md.add_dof("y");
    const std::vector<dof> dofs{th, y};
    std::vector<double> flat{1e6, 1.0};
    flat.insert(flat.end(), good.begin(), good.end());
    flat.push_back(1.0);
    const auto e = flat_add_error<cam>(md, "cam", dofs, flat);
    REQUIRE(e.has_value());
    CHECK(e->number() == static_cast<int>(error_code::parameter_count));
  }
}
