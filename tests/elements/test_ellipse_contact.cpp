// ELLPL: an ellipse on a planar body against a polyline. Resting penetration
// m g / k (linear) and (m g / k)^(2/3) (Hertz); no creep on a slope under static
// friction and the analytic sliding acceleration below it; a sliding disc reaches
// rolling at 2/3 of its speed; the Hunt-Crossley rebound speed against the exact
// relation of the model; a drop and rebound that keeps its energy without
// damping; tunnelling is code 75; exact Jacobians in the stick and slip modes;
// bad parameters are code 100/101.

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include "element_test_support.hpp"
#include "pradis/elements/planar/ellipse_contact.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
constexpr double g0 = 9.81;
using contact_model = model<planar_inertia, ellipse_contact, constant_force, initial_velocity>;

/// A body of mass m and inertia j with an ellipse (a along X at angle 0, b) at
/// (x0, y0), gravity g0 along -Y, and the contact `q` (its centre fields are set
/// here). rotation = false fixes the rotation (the DOF is ground).
struct contact_scene {
  contact_model md;
  dof x, y, r;
  element_ref<ellipse_contact> contact;
  contact_scene(double m, double j, ellipse_contact::parameters q, bool rotation = true, double gravity = g0) {
    x = md.add_dof("x");
    y = md.add_dof("y");
    r = rotation ? md.add_dof("phi") : md.ground();
    md.add<planar_inertia>("body", {m, j}, x, y, r);
    if (gravity != 0) md.add<constant_force>("weight", {-m * gravity}, y);
    contact = md.add<ellipse_contact>("contact", std::move(q), x, y, r);
  }
};

/// Contact parameters: ellipse at (x0, y0), semi-axes a, b, law k, e, d, friction
/// mu_s, mu_k, k_t, c_t, polyline.
ellipse_contact::parameters law(double x0, double y0, double a, double b, double k, double e, double d, double mus,
                                double muk, double kt, double ct, std::vector<double> line) {
  return {x0, y0, 0.0, a, b, k, e, d, mus, muk, kt, ct, std::move(line)};
}
}  // namespace

TEST_SUITE("elements/ELLPL") {
  TEST_CASE("a disc at rest on a floor settles at the penetration m g / k (linear) and (m g / k)^(2/3) (Hertz)") {
    // Static equilibrium of the normal law N = k delta^e = m g.
    const double m = 2.0, r = 0.1;
    for (double e : {1.0, 1.5}) {
      CAPTURE(e);
      const double k = e == 1 ? 1e5 : 1e7;
      const double delta = std::pow(m * g0 / k, 1 / e);
      // Released 1 mm above the floor; the damping d settles it (c = k d delta^e).
      contact_scene s(m, 0.5 * m * r * r, law(0.0, r + 1e-3, r, r, k, e, 20.0, 0.0, 0.0, 0.0, 0.0, {-1, 0, 1, 0}));
      simulation<contact_model, alpha_family> sim(s.md, alpha_family(hht{-0.1}));
      sim.run(fixed_step(3.0, 1e-4));
      const auto w = s.md.work(s.contact);
      CHECK(w[4] == doctest::Approx(delta).epsilon(1e-7));
      CHECK(w[5] == doctest::Approx(m * g0).epsilon(1e-7));
      CHECK(w[1] == doctest::Approx(m * g0).epsilon(1e-7));
      CHECK(w[3] == 1);
      CHECK(sim.u(s.y) == doctest::Approx(-1e-3 - delta).epsilon(1e-7));
    }
  }

  TEST_CASE("an ellipse standing on its long axis rests at the depth a - m g / k below its centre") {
    // The support of an ellipse at angle pi/2 in the direction -Y is a.
    const double m = 1.0, a = 0.3, b = 0.1, k = 1e5;
    auto q = law(0.0, a, a, b, k, 1.0, 20.0, 0.0, 0.0, 0.0, 0.0, {-1, 0, 1, 0});
    q.angle = std::numbers::pi / 2;
    contact_scene s(m, 0.01, q, false);
    simulation<contact_model, alpha_family> sim(s.md, alpha_family(hht{-0.1}));
    sim.run(fixed_step(3.0, 1e-4));
    CHECK(sim.u(s.y) == doctest::Approx(-m * g0 / k).epsilon(1e-7));
    CHECK(std::abs(sim.u(s.x)) < 1e-12);
  }

  TEST_CASE("on a 20 degree slope a block does not creep at mu_s above tan(angle) and slides with g (sin - mu cos) below") {
    // A disc with its rotation fixed is a block; static friction holds it while
    // m g sin(a) <= mu_s m g cos(a), with the stick spring stretched by
    // m g sin(a) / k_t, and it must not move further (no creep). Below that it
    // slides with the acceleration g (sin a - mu_k cos a).
    const double m = 2.0, r = 0.1, k = 1e6, kt = 1e6, ct = 2 * std::sqrt(kt * m), al = 20 * std::numbers::pi / 180;
    const double ca = std::cos(al), sa = std::sin(al), d0 = m * g0 * ca / k;
    const std::vector<double> slope{0.0, 0.0, 10 * ca, -10 * sa};
    const double x0 = 1.0 * ca + (r - d0) * sa, y0 = -1.0 * sa + (r - d0) * ca;
    auto along = [&](double dx, double dy) { return dx * ca - dy * sa; };
    SUBCASE("mu_s = 0.5 > tan(20 deg) = 0.364: it sticks") {
      contact_scene s(m, 0.01, law(x0, y0, r, r, k, 1.0, 1e-2, 0.5, 0.4, kt, ct, slope), false);
      simulation<contact_model, alpha_family> sim(s.md, alpha_family(hht{-0.1}));
      sim.run(fixed_step(1.0, 1e-3));
      const double s1 = along(sim.u(s.x), sim.u(s.y));
      CHECK(s1 == doctest::Approx(m * g0 * sa / kt).epsilon(1e-6));
      sim.run(fixed_step(6.0, 1e-3));
      const double s6 = along(sim.u(s.x), sim.u(s.y));
      CHECK(std::abs(s6 - s1) < 1e-12);
      const auto w = s.md.work(s.contact);
      CHECK(w[7] == double(ellipse_contact::stick));
      CHECK(w[6] == doctest::Approx(-m * g0 * sa).epsilon(1e-9));
      CHECK(w[5] == doctest::Approx(m * g0 * ca).epsilon(1e-9));
    }
    SUBCASE("mu = 0.2 < tan(20 deg): it slides with g (sin a - mu cos a)") {
      const double mu = 0.2, acc = g0 * (sa - mu * ca);
      contact_scene s(m, 0.01, law(x0, y0, r, r, k, 1.0, 1e-2, mu, mu, kt, ct, slope), false);
      simulation<contact_model, alpha_family> sim(s.md, alpha_family(hht{-0.1}));
      sim.run(fixed_step(0.5, 1e-3));
      const double v1 = along(sim.v(s.x), sim.v(s.y));
      sim.run(fixed_step(1.0, 1e-3));
      const double v2 = along(sim.v(s.x), sim.v(s.y));
      CHECK((v2 - v1) / 0.5 == doctest::Approx(acc).epsilon(1e-6));
      const auto w = s.md.work(s.contact);
      CHECK(w[7] == double(ellipse_contact::slip_forward));
      CHECK(w[6] == doctest::Approx(-mu * m * g0 * ca).epsilon(1e-9));
    }
  }

  TEST_CASE("a disc thrown sliding without spin rolls at 2/3 of its speed from t = v0 / (3 mu g) on") {
    // Friction acts at the contact point, so the angular momentum about it,
    // m v R + J w, is kept: v_roll = m v0 R / (m R + J / R) = 2 v0 / 3 for a
    // uniform disc (J = m R^2 / 2), reached when v0 - mu g t = 2 v0/3 + ... i.e.
    // at t = v0 / (3 mu g) (Routh, Dynamics of a System of Rigid Bodies, I, 1905).
    const double m = 1.0, r = 0.1, j = 0.5 * m * r * r, k = 1e6, kt = 1e6, mu = 0.3, v0 = 2.0;
    // Critical stick damping for the contact point's effective mass m/3.
    const double ct = 2 * std::sqrt(kt * m / 3), d0 = m * g0 / k, t_roll = v0 / (3 * mu * g0);
    contact_scene s(m, j, law(0.0, r - d0, r, r, k, 1.0, 1e-2, mu, mu, kt, ct, {-1.0, 0.0, 20.0, 0.0}));
    s.md.add<initial_velocity>("v0", {v0}, s.x);
    simulation<contact_model, alpha_family> sim(s.md, alpha_family(hht{-0.1}));
    double t_stick = -1;
    sim.on_output([&](const auto& st) {
      if (t_stick < 0 && s.md.work(s.contact)[7] == double(ellipse_contact::stick)) t_stick = st.time();
    });
    sim.run(fixed_step(1.0, 1e-4));
    CHECK(std::abs(t_stick - t_roll) < 3e-4);
    CHECK(sim.v(s.x) == doctest::Approx(2 * v0 / 3).epsilon(1e-5));
    CHECK(sim.v(s.r) * r == doctest::Approx(-2 * v0 / 3).epsilon(1e-5));
    sim.run(fixed_step(2.0, 1e-4));
    CHECK(sim.v(s.x) == doctest::Approx(2 * v0 / 3).epsilon(1e-5));
    CHECK(s.md.work(s.contact)[7] == double(ellipse_contact::stick));
  }

  TEST_CASE("a Hunt-Crossley impact rebounds with the speed of the model's exact relation; undamped it keeps v0") {
    // N = k delta^e (1 + d delta'): along the impact m v dv / (1 + d v) = -k delta^e
    // d delta with v = delta', and the right side integrates to zero over the
    // closed path delta: 0 -> max -> 0, so the rebound speed ve solves
    // x - ln(1 + x) = -y - ln(1 - y), x = d v0, y = d ve, whatever k, e and m
    // (Hunt and Crossley, J. Appl. Mech. 42 (1975) 440; the integral as in
    // Gonthier et al., Multibody Syst. Dyn. 11 (2004) 209). Without damping
    // ve = v0 (the energy is kept).
    const double m = 1.0, r = 0.1, k = 1e7, v0 = 1.0;
    for (double d : {0.0, 0.2, 0.6}) {
      CAPTURE(d);
      double ve = v0;
      if (d > 0) {  // bisection on y in (0, x): f(y) = y + ln(1 - y) + x - ln(1 + x) falls from x - ln(1+x) > 0
        const double x = d * v0, c = x - std::log1p(x);
        double lo = 0, hi = x;
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (lo + hi);
          (mid + std::log1p(-mid) + c > 0 ? lo : hi) = mid;
        }
        ve = 0.5 * (lo + hi) / d;
      }
      contact_scene s(m, 0.5 * m * r * r, law(0.0, r + 1e-3, r, r, k, 1.5, d, 0.0, 0.0, 0.0, 0.0, {-1, 0, 1, 0}),
                      true, 0.0);
      s.md.add<initial_velocity>("v0", {-v0}, s.y);
      simulation sim(s.md);
      sim.run(fixed_step(0.02, 1e-5));
      CHECK(s.md.work(s.contact)[3] == 0);
      CHECK(sim.v(s.y) == doctest::Approx(ve).epsilon(2e-5));
      CHECK(std::abs(sim.v(s.x)) < 1e-12);
    }
  }

  TEST_CASE("STEPMD: under large steps the contact is entered within the resolution; with IGNORE it is code 75") {
    // A ball 5 cm above a Hertz floor, falling at 10 m/s, with SMAX = 0.05 s: the
    // element limits the step while approaching to max(gap / 2, min(a, b)/1000) / v,
    // so the run resolves the impact (error control) and rebounds at 10 m/s. With
    // IGNORE the first step would carry it 0.5 m, through the floor: code 75, and
    // the step cuts reach the contact again; at SMIN = SMAX it is reported.
    const double m = 1.0, r = 0.1, k = 1e8, v0 = 10.0;
    auto scene = [&] {
      auto s = std::make_unique<contact_scene>(
          m, 0.5 * m * r * r, law(0.0, r + 0.05, r, r, k, 1.5, 0.0, 0.0, 0.0, 0.0, 0.0, {-1, 0, 1, 0}), true, 0.0);
      s->md.add<initial_velocity>("v0", {-v0}, s->y);
      return s;
    };
    run_options o{.end = 0.1, .smax = 0.05, .error_control = true, .drltx = 1e-6};
    {
      auto s = scene();
      simulation sim(s->md);
      sim.run(o);
      CHECK(sim.v(s->y) == doctest::Approx(v0).epsilon(1e-3));
      // Contact at t = 0.005 s, lasting Hertz's t_c = 2.9432 delta_max / v0 with
      // delta_max = (5 m v0^2 / (4 k))^(2/5) (Johnson, Contact Mechanics, 1985, 11.4).
      const double dmax = std::pow(5 * m * v0 * v0 / (4 * k), 0.4), tc = 2.9432 * dmax / v0;
      CHECK(sim.u(s->y) == doctest::Approx(-0.05 + v0 * (0.1 - 0.005 - tc)).epsilon(1e-5));
      // STEPMD brings the ball to the floor in halving steps: 2 step cuts in 1127
      // steps (measured; with IGNORE the same run needs 1168 steps and 24 cuts, each
      // leap through the floor being code 75; 146259 steps and 669063 cuts before the
      // step's growth was bounded after a rejection, max_step_growth).
      MESSAGE("steps ", sim.statistics().steps, ", step cuts ", sim.statistics().rejected_steps);
      CHECK(sim.statistics().rejected_steps <= 5);
      CHECK(sim.statistics().steps < 2000);
    }
    {
      auto s = scene();
      simulation sim(s->md);
      run_options fixed{.end = 0.1, .smax = 0.05, .smin = 0.05, .ignore = true};
      check_error(error_from([&] { sim.run(fixed); }), error_code::singular_situation, "ELLPL", "contact",
                  "passed behind polyline segment 1");
    }
  }

  TEST_CASE("the Jacobian is exact in contact with every mode: free, stick (rotated anchor) and slip both ways") {
    // Central differences of the flows (PRADIS element manual, 3.6.8) at random
    // states of a tilted ellipse on a two-segment floor, with the old state of
    // segment 1 set to each mode.
    const auto q = ellipse_contact::example();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int mode : {0, 1, 2, 3}) {
      CAPTURE(mode);
      testing::jacobian_checker<ellipse_contact> chk(ellipse_contact{q}, 18);
      const auto old = chk.old_state();
      REQUIRE(old.size() == 8);
      old[0] = mode;
      old[1] = 0.05;   // stuck material point in body axes
      old[2] = -0.19;
      old[3] = 1.2;    // anchor along segment 1
      int in_contact = 0;
      for (int trial = 0; trial < 200; ++trial) {
        local_input<ellipse_contact> in;
        for (int k = 0; k < 3; ++k) {
          in.u(k) = 0.01 * uni(rng);
          in.v(k) = 2 * uni(rng);
        }
        if (!chk.element().admissible(in)) continue;
        const auto f = chk.flows(in);
        if (f.norm() == 0) continue;
        ++in_contact;
        if (!jacobian_passes(chk.check(in))) break;
      }
      CHECK(in_contact > 100);
    }
  }

  TEST_CASE("bad parameters stop the run with code 100 naming ELLPL, the instance and the parameter") {
    struct bad {
      ellipse_contact::parameters q;
      const char* mention;
    };
    auto base = [] { return law(0.0, 0.1, 0.1, 0.1, 1e5, 1.0, 0.0, 0.5, 0.4, 1e5, 10.0, {-1, 0, 1, 0}); };
    std::vector<bad> cases;
    auto with = [&](auto change, const char* mention) {
      auto q = base();
      change(q);
      cases.push_back({q, mention});
    };
    with([](auto& q) { q.a = 0; }, "semi-axes");
    with([](auto& q) { q.b = -1; }, "semi-axes");
    with([](auto& q) { q.k = 0; }, "contact stiffness k");
    with([](auto& q) { q.exponent = 0.5; }, "exponent e");
    with([](auto& q) { q.damping = -1; }, "damping factor d");
    with([](auto& q) { q.mu_s = -0.1; }, "static friction coefficient mu_s");
    with([](auto& q) { q.mu_k = 0.6; }, "kinetic friction coefficient mu_k");
    with([](auto& q) { q.mu_k = -0.1; }, "kinetic friction coefficient mu_k");
    with([](auto& q) { q.k_t = 0; }, "stick stiffness k_t");
    with([](auto& q) { q.c_t = -1; }, "stick damping c_t");
    with([](auto& q) { q.x0 = std::nan(""); }, "parameter 1 is not finite");
    with([](auto& q) { q.polyline[3] = INFINITY; }, "polyline coordinate 4");
    with([](auto& q) { q.polyline = {0, 0, 0, 0, 1, 0}; }, "polyline points 1 and 2 coincide");
    with([](auto& q) { q.polyline = {0, 0, 1}; }, "pairs of coordinates");
    for (const auto& c : cases) {
      CAPTURE(c.mention);
      contact_scene s(1.0, 0.01, c.q);
      simulation sim(s.md);
      check_error(error_from([&] { sim.run(fixed_step(0.01, 1e-3)); }), error_code::invalid_parameter, "ELLPL",
                  "contact", c.mention);
    }
  }

  TEST_CASE("a flat ELLPL with an odd parameter count is code 101") {
    contact_model md;
    const dof x = md.add_dof("x"), y = md.add_dof("y"), r = md.add_dof("r");
    const std::vector<dof> dofs{x, y, r};
    const std::vector<double> flat{0, 0.1, 0, 0.1, 0.1, 1e5, 1, 0, 0, 0, 0, 0, -1, 0, 1, 0, 2};
    const auto e = flat_add_error<ellipse_contact>(md, "contact", dofs, flat);
    REQUIRE(e.has_value());
    CHECK(e->number() == static_cast<int>(error_code::parameter_count));
    CHECK(e->element_type() == "ELLPL");
  }
}

