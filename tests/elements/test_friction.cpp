// FRICT, GEAR and BELT: a block on a slope that holds without creep or slides
// with the textbook acceleration, the Coulomb oscillator's linear decay and
// stop (Den Hartog), a gear pair's speed and torque ratio and its backlash, the
// capstan ratio exp(mu theta); Jacobians in every mode; bad parameters.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "element_test_support.hpp"
#include "pradis/elements/mech1d/belt.hpp"
#include "pradis/elements/mech1d/friction.hpp"
#include "pradis/elements/mech1d/gear.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
constexpr double g_n = 9.80665;
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();

// Central-difference check of an element's K and C blocks at a state with a
// given accepted state vector (the mode of FRICT / the slip of BELT).
template <class E, std::size_t S>
void check_jacobian(const E& e, const local_input<E>& at, std::array<double, S> old_state) {
  constexpr int n = element_traits<E>::n;
  std::array<double, S> fresh{};
  std::array<double, 8> work{};
  element_context ctx(E::passport.name, "fd");
  ctx.old_state = old_state;
  ctx.new_state = fresh;
  ctx.work = std::span<double>(work.data(), static_cast<std::size_t>(E::passport.wrk));
  local_output<E> ana;
  e.evaluate(at, ana, ctx);
  const double h = 1e-7;
  for (int j = 0; j < n; ++j)
    for (const bool by_v : {false, true}) {
      local_input<E> p = at, m = at;
      (by_v ? p.v(j) : p.u(j)) += h;
      (by_v ? m.v(j) : m.u(j)) -= h;
      local_output<E> fp, fm;
      e.evaluate(p, fp, ctx);
      e.evaluate(m, fm, ctx);
      for (int i = 0; i < n; ++i) {
        const double num = (fp.f(i) - fm.f(i)) / (2 * h);
        double an = 0;
        if constexpr (element_traits<E>::has_k)
          if (!by_v) an = ana.K(i, j);
        if constexpr (element_traits<E>::has_c)
          if (by_v) an = ana.C(i, j);
        CAPTURE(i);
        CAPTURE(j);
        CAPTURE(by_v);
        CHECK(num == doctest::Approx(an).epsilon(1e-6).scale(1.0));
      }
    }
}

// Runs a one-DOF model of a mass with E on it and returns the error the run throws.
template <class E>
std::optional<error> run_error(typename E::parameters p) {
  model<point_mass, E> md;
  const dof x = md.add_dof("x"), y = md.add_dof("y");
  md.template add<point_mass>("m1", {1.0}, x);
  md.template add<point_mass>("m2", {1.0}, y);
  md.template add<E>("bad", p, x, y);
  simulation sim(md);
  return error_from([&] { sim.run(fixed_step(0.01, 1e-3)); });
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using friction_model = pradis::model<point_mass, friction, constant_force, linear_spring, initial_displacement,
    velocity_source, gear, linear_damper, belt>;
TEST_SUITE("elements/FRICT") {
  TEST_CASE("a block on a slope steeper than its friction angle does not hold, below it holds without creep") {
    // Block of mass m on a slope of angle alpha: the slope component m g sin(alpha)
    // is a constant force along the DOF, the friction forces are mu N with the
    // normal force N = m g cos(alpha) (Meriam & Kraige, Engineering Mechanics:
    // Statics, 6/2: the block holds iff tan(alpha) <= mu_s; sliding, it
    // accelerates at a = g (sin(alpha) - mu_k cos(alpha)), Dynamics, 3/4).
    const double m = 2.0, alpha = 20.0 * std::numbers::pi / 180, h = 1e-3;
    const double P = m * g_n * std::sin(alpha), N = m * g_n * std::cos(alpha);
    SUBCASE("mu = 0.5 > tan(20 deg) = 0.364: held for 20 s at the stick spring's deflection P / ks, no creep") {
      // The stick spring is critically damped and resolved by the step
      // (h sqrt(ks/m) = 0.22): the stuck transient's force peaks near
      // P (1 + e^-2) (critically damped step response), below Fs = 1.37 P.
      const double mu = 0.5, ks = 1e5, cs = 2 * std::sqrt(ks * m);
      friction_model md;
      const dof x = md.add_dof("x");
      md.add<point_mass>("block", {m}, x);
      md.add<constant_force>("slope", {P}, x);
      const auto fr = md.add<friction>("contact", {mu * N, mu * N, 1e-3, 0.0, ks, cs, 1e-6}, md.ground(), x);
      simulation sim(md);
      double worst = 0, late = 0;
      bool always_stuck = true;
      sim.on_output([&](const auto& s) {
        worst = std::max(worst, std::abs(s.u(x)));
        if (s.time() > 1.0) late = std::max(late, std::abs(s.u(x) - P / ks));
        if (s.time() > 0) always_stuck = always_stuck && md.work(fr)[2] == 1.0;
      });
      sim.run(fixed_step(20.0, h));
      // The block starts at rest on the unstretched stick spring (a0 = P / m).
      // The energy E = m v^2 / 2 + ks (u - P/ks)^2 / 2 starts at P^2 / (2 ks) and
      // never grows under the trapezoidal rule with damping (E_{n+1} - E_n =
      // -h cs v_{n+1/2}^2; Hughes 9.3), so 0 <= u <= 2 P / ks; the damped stick
      // spring then rests at P / ks to round-off: no creep over 20000 steps.
      CHECK(always_stuck);
      CHECK(worst <= 2 * P / ks * (1 + 1e-9));
      CHECK(late <= 1e-9 * P / ks);
      CHECK(md.work(fr)[0] == doctest::Approx(P).epsilon(1e-9));  // the friction carries the slope force
    }
    SUBCASE("mu = 0.2 < tan(20 deg): slides with a = g (sin - mu cos) from the first step") {
      const double mu = 0.2, fc = mu * N, A = g_n * (std::sin(alpha) - mu * std::cos(alpha));
      friction_model md;
      const dof x = md.add_dof("x");
      md.add<point_mass>("block", {m}, x);
      md.add<constant_force>("slope", {P}, x);
      const auto fr = md.add<friction>("contact", {fc, fc, 1e-3, 0.0, 1e7, 0.0, 1e-6}, md.ground(), x);
      simulation sim(md);
      // The zero step finds the contact stuck on an unstretched spring, so the
      // initial acceleration is P / m = A + D, D = fc / m; the first step breaks
      // away and from then on the acceleration is A. The trapezoidal rule is
      // exact for constant acceleration, so u_n = A t^2 / 2 + (h D / 2)(t - h / 2)
      // and v_n = A t + h D / 2 (integrate a0 over the first half step).
      const double D = fc / m;
      double worst_u = 0, worst_v = 0;
      bool sliding = true;
      sim.on_output([&](const auto& s) {
        const double t = s.time();
        if (t == 0) return;
        worst_u = std::max(worst_u, std::abs(s.u(x) - (A * t * t / 2 + h * D / 2 * (t - h / 2))));
        worst_v = std::max(worst_v, std::abs(s.v(x) - (A * t + h * D / 2)));
        sliding = sliding && md.work(fr)[2] == 0.0 && md.work(fr)[0] == doctest::Approx(fc).epsilon(1e-14);
      });
      sim.run(fixed_step(2.0, h));
      CHECK(sliding);
      CHECK(worst_u < 1e-10);
      CHECK(worst_v < 1e-10);
      CHECK(sim.u(x) / 2.0 == doctest::Approx(A).epsilon(1e-3));  // u(2) / (2^2 / 2) = A up to the h D term
    }
  }

  TEST_CASE("the Coulomb oscillator loses 2 F / k per half cycle and stops after the analytic count and time") {
    // m x'' + k x + F sign(x') = 0 from rest at x0: each half cycle is a harmonic
    // half-oscillation of period pi sqrt(m/k) about -F/k sign(x'), so the
    // amplitude falls by 2 F / k per half cycle, x_j = (-1)^j (|x0| - 2 j F / k);
    // the mass stops at the first turning point with |x_j| <= F / k (the static
    // friction F holds the spring force k |x_j|), i.e. after
    // n = ceil((|x0| - F/k) / (2 F/k)) half cycles, at t = n pi sqrt(m/k)
    // (Den Hartog, Mechanical Vibrations, 4th ed., 8.2).
    const double m = 1.0, k = 100.0, F = 1.0, x0 = 0.095, ks = 1e8;
    const double w = std::sqrt(k / m), fk = F / k;
    const int n = static_cast<int>(std::ceil((x0 - fk) / (2 * fk)));
    REQUIRE(n == 5);
    struct run_result {
      std::vector<double> x, t;  // turning points: v changes sign at the end of a sliding step
      double end_u = 0;
      bool end_stuck = false;
    };
    const auto run = [&](double h) {
      friction_model md;
      const dof x = md.add_dof("x");
      md.add<point_mass>("mass", {m}, x);
      md.add<linear_spring>("spring", {k}, x, md.ground());
      const auto fr =
          md.add<friction>("contact", {F, F, 1e-3, 0.0, ks, 2 * std::sqrt(ks * m), 1e-6}, md.ground(), x);
      md.add<initial_displacement>("x0", {x0}, x);
      simulation sim(md);
      run_result r;
      double prev_v = 0;
      bool prev_sliding = false;
      sim.on_output([&](const auto& s) {
        const double v = s.v(x);
        if (prev_sliding && prev_v * v <= 0) {
          r.x.push_back(s.u(x));
          r.t.push_back(s.time());
        }
        prev_v = v;
        prev_sliding = md.work(fr)[2] == 0.0;
      });
      sim.run({.end = 2.0, .smax = h, .newton = tight_newton});
      r.end_u = sim.u(x);
      r.end_stuck = md.work(fr)[2] == 1.0;
      return r;
    };
    const double h = 1e-4;
    const run_result coarse = run(h), fine = run(h / 2);
    // n turning points, the last one the final rest.
    REQUIRE(coarse.x.size() == static_cast<std::size_t>(n));
    REQUIRE(fine.x.size() == static_cast<std::size_t>(n));
    for (int j = 1; j <= n; ++j) {
      const auto i = static_cast<std::size_t>(j - 1);
      const double exact_x = (j % 2 ? -1.0 : 1.0) * (x0 - 2 * j * fk), exact_t = j * std::numbers::pi / w;
      CAPTURE(j);
      // STEPMD ends a step where the velocity reaches zero; the discrete half
      // cycle keeps the amplitude of the harmonic motion (trapezoidal rule:
      // Cayley transform, Hughes 9.3), so the turning points are sharp.
      CHECK(std::abs(coarse.x[i] - exact_x) < 1e-7);
      CHECK(std::abs(fine.x[i] - exact_x) < 1e-7);
      // The time is first-order accurate: at each turn the friction force jumps
      // by 2F while the trapezoidal step after it still averages the old
      // acceleration, a velocity kick of about h F / m; it shifts the next half
      // cycle by about h (F/k) / A_j (A_j its amplitude). Halving h halves it.
      const double ec = coarse.t[i] - exact_t, ef = fine.t[i] - exact_t;
      double bound = 0;
      for (int q = 1; q <= j; ++q) bound += 2 * h * fk / (x0 - (2 * q - 1) * fk);
      CHECK(std::abs(ec) < bound);
      CHECK(ec / ef == doctest::Approx(2.0).epsilon(0.25));
    }
    MESSAGE("Coulomb oscillator, stop time error at h = 1e-4 and 5e-5: ", coarse.t.back() - n * std::numbers::pi / w,
            " ", fine.t.back() - n * std::numbers::pi / w, " s; stop position error: ",
            coarse.x.back() - (n % 2 ? -1.0 : 1.0) * (x0 - 2 * n * fk), " m");
    const double rest = (n % 2 ? -1.0 : 1.0) * (x0 - 2 * n * fk);
    CHECK(std::abs(rest) <= fk);
    CHECK(coarse.end_stuck);
    CHECK(std::abs(coarse.end_u - rest) < 1e-7);
  }

  TEST_CASE("sliding at a constant speed, the friction force follows the Stribeck curve plus viscous friction") {
    // F(v) = sign(v) (Fc + (Fs - Fc) exp(-(v/vs)^2)) + b v (Armstrong-Helouvry,
    // Dupont & Canudas de Wit, Automatica 30 (1994) 1083, the Stribeck model);
    // the drive's reaction is the friction force.
    const double fs = 10.0, fc = 7.0, vs = 0.2, b = 0.5;
    for (const double v : {-0.5, -0.1, 0.05, 0.2, 1.0}) {
      CAPTURE(v);
      friction_model md;
      const dof x = md.add_dof("x");
      const auto drive = md.add<velocity_source>("drive", {0.0, 0.0, 0.0, v}, x);
      const auto fr = md.add<friction>("contact", {fs, fc, vs, b, 1e6, 0.0, 1e-6}, md.ground(), x);
      simulation sim(md);
      sim.run(fixed_step(0.1, 1e-3));
      const double expected = (v > 0 ? 1 : -1) * (fc + (fs - fc) * std::exp(-(v / vs) * (v / vs))) + b * v;
      CHECK(md.work(fr)[0] == doctest::Approx(expected).epsilon(1e-12));
      CHECK(md.work(fr)[1] == doctest::Approx(v).epsilon(1e-12));
      CHECK(md.work(drive)[0] == doctest::Approx(expected).epsilon(1e-9));
    }
  }

  TEST_CASE("the FRICT Jacobian is exact in the stuck, breakaway and sliding modes") {
    const friction e({10.0, 7.0, 0.2, 0.5, 1e4, 3.0, 1e-3});
    local_input<friction> in;
    in.u << 0.1, 0.1002;
    in.v << 0.0, 0.05;
    SUBCASE("stuck, anchored at d = 0: |ks d + cs v| = 2.15 < Fs") { check_jacobian(e, in, std::array{1.0, 0.0, 0.0}); }
    SUBCASE("stuck, anchored at d = -1e-3 (stick force 12.15 > Fs, moving): breaks away") {
      check_jacobian(e, in, std::array{1.0, 0.0, -1e-3});
    }
    SUBCASE("sliding in + at v = 0.05, in the Stribeck range") {
      check_jacobian(e, in, std::array{2.0, 1.0, 0.0});
      in.v(1) = -0.3;  // reversed within the step: the law keeps s = +1
      check_jacobian(e, in, std::array{2.0, 1.0, 0.0});
    }
  }

  TEST_CASE("FRICT: stuck -> sliding, sliding -> stuck and the STEPMD recommendation, one evaluation at a time") {
    const friction e({10.0, 7.0, 0.2, 0.5, 1e4, 3.0, 1e-3});
    std::array<double, 3> old{}, next{}, work{};
    element_context ctx("FRICT", "f");
    ctx.old_state = old;
    ctx.new_state = next;
    ctx.work = work;
    local_input<friction> in;
    local_output<friction> out;
    // Zero state, at rest: stuck where it is, no force.
    in.u << 0.0, 0.3;
    e.evaluate(in, out, ctx);
    CHECK(next == std::array{1.0, 0.0, 0.3});
    CHECK(out.f(1) == 0.0);
    // Stuck at 0.3, pulled 5e-4 further (stick force 5): holds.
    old = next;
    in.u(1) = 0.3005;
    in.v(1) = 1e-4;
    e.evaluate(in, out, ctx);
    CHECK(out.f(1) == doctest::Approx(1e4 * 5e-4 + 3.0 * 1e-4).epsilon(1e-12));
    CHECK(work[2] == 1.0);
    // Pulled 2e-3 (stick force 20 > Fs = 10) and moving: slides with Fs at v -> 0.
    in.u(1) = 0.302;
    e.evaluate(in, out, ctx);
    CHECK(next[0] == 2.0);
    CHECK(next[1] == 1.0);
    CHECK(out.f(1) == doctest::Approx(7.0 + 3.0 * std::exp(-0.25e-6) + 0.5e-4).epsilon(1e-12));
    // The same stick force while moving back does not break away (s v < 0).
    in.v(1) = -1e-4;
    e.evaluate(in, out, ctx);
    CHECK(work[2] == 1.0);
    // Sliding in +, decelerating at 2: recommends the step v / |a| that reaches v = 0.
    old = {2.0, 1.0, 0.0};
    in.v(1) = 0.04;
    in.a(1) = -2.0;
    ctx.recommended_step = std::numeric_limits<double>::infinity();
    e.evaluate(in, out, ctx);
    CHECK(ctx.recommended_step == doctest::Approx(0.02).epsilon(1e-14));
    CHECK(next[0] == 2.0);
    // Below the threshold: stuck from the next step, anchored at this d.
    in.v(1) = 5e-4;
    e.evaluate(in, out, ctx);
    CHECK(next == std::array{1.0, 0.0, 0.302});
    CHECK(work[2] == 0.0);  // this step still slid
  }

  TEST_CASE("bad FRICT parameters are refused with code 100 naming the parameter") {
    const friction::parameters ok{10.0, 8.0, 0.1, 0.0, 1e6, 0.0, 1e-6};
    CHECK_FALSE(run_error<friction>(ok).has_value());
    auto with = [&](auto change) {
      friction::parameters p = ok;
      change(p);
      return run_error<friction>(p);
    };
    const auto code = error_code::invalid_parameter;
    check_error(with([](auto& p) { p.fs = -1; }), code, "FRICT", "bad", "static friction force Fs = -1");
    check_error(with([](auto& p) { p.fc = -1; }), code, "FRICT", "bad", "kinetic friction force Fc = -1");
    check_error(with([](auto& p) { p.fc = 11; }), code, "FRICT", "bad",
                "Fc = 11 must not exceed the static friction force Fs = 10");
    check_error(with([](auto& p) { p.vs = 0; }), code, "FRICT", "bad", "Stribeck velocity vs = 0 must be finite and > 0");
    check_error(with([](auto& p) { p.b = -0.5; }), code, "FRICT", "bad", "viscous friction coefficient b = -0.5");
    check_error(with([](auto& p) { p.ks = 0; }), code, "FRICT", "bad", "stick stiffness ks = 0");
    check_error(with([](auto& p) { p.cs = -1; }), code, "FRICT", "bad", "stick damping cs = -1");
    check_error(with([](auto& p) { p.vth = 0; }), code, "FRICT", "bad", "stick velocity threshold vth = 0");
    check_error(with([](auto& p) { p.fs = nan_value; }), code, "FRICT", "bad", "static friction force Fs = nan");
  }
}

TEST_SUITE("elements/GEAR") {
  TEST_CASE("a stiff gear pair turns shaft 2 at r times the speed of shaft 1 and needs r times its torque") {
    // Ideal gear pair: w2 = r w1 and, power-consistent, T1 = r T2 (Shigley's
    // Mechanical Engineering Design, 13-7: the same tangential tooth force on
    // both pitch circles). Shaft 1 turns at w1 (VSRC), shaft 2 carries an inertia
    // and a load torque TL; after the mesh transient (damped at zeta = 0.5 with
    // the time constant 1 / (zeta w) = 2 ms, run 100 ms) shaft 2 turns at r w1,
    // the mesh torque balances the load and the drive supplies r TL.
    for (const double r : {-2.0, 0.5}) {
      CAPTURE(r);
      const double w1 = 3.0, J2 = 0.01, k = 1e4, TL = 4.0, c = std::sqrt(k * J2);  // zeta = 0.5 about shaft 2
      friction_model md;
      const dof a = md.add_dof("shaft1"), b = md.add_dof("shaft2");
      const auto drive = md.add<velocity_source>("drive", {0.0, 0.0, 0.0, w1}, a);
      md.add<point_mass>("J2", {J2}, b);
      const auto mesh = md.add<gear>("mesh", {r, 0.0, k, c}, a, b);
      md.add<constant_force>("load", {-TL}, b);
      simulation sim(md);
      sim.run(fixed_step(0.1, 1e-4));
      CHECK(sim.v(b) == doctest::Approx(r * w1).epsilon(1e-9));
      CHECK(md.work(mesh)[0] == doctest::Approx(-TL).epsilon(1e-9));
      // The drive's reaction (the torque it applies to shaft 1) is r TL.
      CHECK(md.work(drive)[0] == doctest::Approx(r * TL).epsilon(1e-9));
      // The power balance of the mesh: torque 1 times w1 + torque 2 times w2 = 0 in steady state.
      CHECK(md.work(drive)[0] * w1 + (-TL) * sim.v(b) == doctest::Approx(0.0).scale(1.0).epsilon(1e-8));
    }
  }

  TEST_CASE("inside the backlash the driven gear is free: no torque until the gap closes at t = b / (|r| w1)") {
    // Shaft 1 turns at w1 from the centred gap g = 0, shaft 2 rests: the gap
    // g = phi2 - r phi1 = -r w1 t reaches the backlash b at t_c = b / (|r| w1).
    // Before, the torque is exactly zero and shaft 2 does not move at all.
    const double r = 2.0, w1 = 1.0, b = 0.0205, J2 = 0.01, k = 1e4, c = 2 * std::sqrt(k * J2), cl = 0.05, h = 1e-4;
    const double tc = b / (std::abs(r) * w1);
    friction_model md;
    const dof a = md.add_dof("shaft1"), s2 = md.add_dof("shaft2");
    md.add<linear_damper>("load", {cl}, s2, md.ground());  // a viscous load: no torque at rest
    md.add<velocity_source>("drive", {0.0, 0.0, 0.0, w1}, a);
    md.add<point_mass>("J2", {J2}, s2);
    const auto mesh = md.add<gear>("mesh", {r, b, k, c}, a, s2);
    simulation sim(md);
    double first_contact = -1;
    bool free_before = true;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), torque = md.work(mesh)[0];
      if (t < tc) free_before = free_before && torque == 0.0 && s.u(s2) == 0.0 && s.v(s2) == 0.0;
      if (first_contact < 0 && torque != 0.0) first_contact = t;
    });
    sim.run(fixed_step(0.2, h));
    CHECK(free_before);
    // The first step end past t_c (steps of h; rounding of t: 1e-12).
    CHECK(first_contact >= tc - 1e-12);
    CHECK(first_contact < tc + h + 1e-12);
    CHECK(md.work(mesh)[2] == -1.0);  // shaft 1 drives shaft 2 on the negative flank
    // Afterwards the critically damped mesh (c = 2 sqrt(k J2), decay 1 ms) drives
    // shaft 2 at r w1 against the load torque cl r w1, on the flank g = -b - cl r w1 / k.
    CHECK(sim.v(s2) == doctest::Approx(r * w1).epsilon(1e-9));
    CHECK(md.work(mesh)[0] == doctest::Approx(-cl * r * w1).epsilon(1e-9));
    CHECK(md.work(mesh)[1] == doctest::Approx(-b - cl * r * w1 / k).epsilon(1e-9));
  }

  TEST_CASE("the GEAR Jacobian is exact in contact on both flanks and zero in the gap") {
    const gear e({-2.5, 0.05, 1e4, 5.0});
    local_input<gear> in;
    in.v << 0.3, -0.2;
    for (const double phi2 : {0.3, -0.04, -0.3}) {
      in.u << 0.02, phi2;
      check_jacobian(e, in, std::array<double, 0>{});  // g = 0.35 (contact), 0.01 (gap), -0.25 (contact)
    }
  }

  TEST_CASE("bad GEAR parameters are refused with code 100 naming the parameter") {
    CHECK_FALSE(run_error<gear>({2.0, 0.01, 1e3, 1.0}).has_value());
    const auto code = error_code::invalid_parameter;
    check_error(run_error<gear>({0.0, 0.01, 1e3, 1.0}), code, "GEAR", "bad", "ratio r = 0 must be finite and nonzero");
    check_error(run_error<gear>({nan_value, 0.01, 1e3, 1.0}), code, "GEAR", "bad", "ratio r = nan");
    check_error(run_error<gear>({2.0, -0.01, 1e3, 1.0}), code, "GEAR", "bad", "backlash b = -0.01");
    check_error(run_error<gear>({2.0, 0.01, -1e3, 1.0}), code, "GEAR", "bad", "mesh stiffness k = -1000");
    check_error(run_error<gear>({2.0, 0.01, 1e3, -1.0}), code, "GEAR", "bad", "mesh damping c = -1");
  }
}

TEST_SUITE("elements/BELT") {
  // A load m1 g hangs on end 1 of a rope over a fixed drum (mu, theta); a holding
  // force P and a small mass m2 are on end 2. Capstan equation (Euler 1762,
  // Eytelwein; e.g. Meriam & Kraige, Statics, 6/9): the rope holds while
  // T1 / T2 <= exp(mu theta) and slips with T1 = exp(mu theta) T2.
  constexpr double mu = 0.3, theta = std::numbers::pi, k = 1e5, m1 = 10.0, m2 = 1.0;

  TEST_CASE("the rope holds just below the capstan ratio and slips just above it with T1 / T2 = exp(mu theta)") {
    const double E = std::exp(mu * theta), W = m1 * g_n;
    for (const double factor : {0.99, 1.01, -0.99, -1.01}) {
      CAPTURE(factor);
      // factor > 0: P = W / (factor E), the load side is the tight side.
      // factor < 0: P = |factor| E W, the holding side is the tight side.
      const double P = factor > 0 ? W / (factor * E) : -factor * E * W;
      const bool slips = std::abs(factor) > 1;
      // Rigid-rope acceleration of the load downwards (u1 up, u2 down):
      // (W - m1 a) = E (P + m2 a) when end 1 is tight, E (W - m1 a) = P + m2 a when end 2 is.
      const double a = !slips ? 0.0 : (factor > 0 ? (W - E * P) / (m1 + E * m2) : (W * E - P) / (E * m1 + m2));
      const double T1 = W - m1 * a, T2 = P + m2 * a;
      friction_model md;
      const dof e1 = md.add_dof("end1"), e2 = md.add_dof("end2");
      md.add<point_mass>("load", {m1}, e1);
      md.add<constant_force>("weight", {W}, e1);
      md.add<point_mass>("hand", {m2}, e2);
      md.add<constant_force>("hold", {P}, e2);
      const auto rope = md.add<belt>("rope", {mu, theta, k}, e1, e2);
      // Start stretched as the steady motion needs (no slip yet, s = 0): the
      // exact solution is then u1 = T1/k + a t^2 / 2, u2 = T2/k - a t^2 / 2,
      // s = a t^2 / 2, constant tensions; the trapezoidal rule is exact for it.
      md.add<initial_displacement>("u1", {T1 / k}, e1);
      md.add<initial_displacement>("u2", {T2 / k}, e2);
      simulation sim(md);
      double worst = 0, worst_ratio = 0;
      sim.on_output([&](const auto& s) {
        const double t = s.time();
        worst = std::max({worst, std::abs(s.u(e1) - (T1 / k + a * t * t / 2)),
                          std::abs(s.u(e2) - (T2 / k - a * t * t / 2))});
        if (slips && t > 0) {
          const double ratio = factor > 0 ? md.work(rope)[0] / md.work(rope)[1] : md.work(rope)[1] / md.work(rope)[0];
          worst_ratio = std::max(worst_ratio, std::abs(ratio / E - 1));
          CHECK(md.work(rope)[3] == (factor > 0 ? 1.0 : -1.0));
        }
      });
      sim.run(fixed_step(1.0, 1e-3));
      CHECK(worst < 1e-9);
      CHECK(worst_ratio < 1e-12);
      if (!slips) {
        CHECK(md.work(rope)[2] == 0.0);  // no slip at all
        CHECK(md.work(rope)[3] == 0.0);
      } else {
        CHECK(md.work(rope)[2] == doctest::Approx(a / 2).epsilon(1e-9));  // s = a t^2 / 2 at t = 1
      }
    }
  }

  TEST_CASE("the BELT Jacobian is exact while holding and slipping both ways") {
    const belt e({mu, theta, 2e3});
    local_input<belt> in;
    for (const auto& u : {std::array{0.1, 0.08}, std::array{0.3, 0.01}, std::array{0.01, 0.3}}) {
      in.u << u[0], u[1];
      check_jacobian(e, in, std::array{0.002});
    }
  }

  TEST_CASE("bad BELT parameters are refused with code 100 naming the parameter") {
    CHECK_FALSE(run_error<belt>({0.3, 3.0, 1e3}).has_value());
    const auto code = error_code::invalid_parameter;
    check_error(run_error<belt>({-0.3, 3.0, 1e3}), code, "BELT", "bad", "friction coefficient mu = -0.3");
    check_error(run_error<belt>({0.3, -3.0, 1e3}), code, "BELT", "bad", "wrap angle theta = -3");
    check_error(run_error<belt>({1e3, 1e3, 1e3}), code, "BELT", "bad", "exp(mu theta) overflows");
    check_error(run_error<belt>({0.3, 3.0, 0.0}), code, "BELT", "bad", "belt stiffness k = 0");
  }
}
