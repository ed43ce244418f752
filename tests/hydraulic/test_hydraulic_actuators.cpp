// Hydraulic cylinder, valves and accumulator (docs/domains.md): analytic answers through
// real simulations. Pressures are the velocity-level unknowns; velocity sources (VSRC)
// prescribe pressures ("a prescribed potential") and kinematic sources drive spools.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "../elements/element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using hydraulic_actuators_model = pradis::model<hydraulic_cylinder, point_mass, velocity_source, initial_velocity,
    valve_43, turbulent_orifice, hydraulic_volume, displacement_source, laminar_orifice, valve_22, linear_spring,
    linear_damper, hydraulic_pump, relief_valve, check_valve, accumulator, constant_force>;
TEST_SUITE("hydraulic/HCYL") {
  TEST_CASE("a constant chamber pressure accelerates a mass with the force A p: x = A p t^2 / (2 m)") {
    // m x'' = AA pA (pB = 0 on the tank): constant acceleration, reproduced exactly by the
    // trapezoidal rule. The supply delivers AA x' (pA is constant: no compression flow).
    const double aa = 2e-3, ab = 1e-3, pa = 10e5, m = 1000, h = 1e-3, end = 0.5;
    hydraulic_actuators_model md;
    const dof pa_dof = md.add_dof("pA"), x = md.add_dof("x");
    md.add<hydraulic_cylinder>("cyl", {aa, ab, 1.0, 0.1, 1e-4, 1e-4, oil_b, 1e8, 1e4, 1e-3}, pa_dof, md.ground(), x);
    md.add<point_mass>("load", {m}, x);
    md.add<velocity_source>("supply", {.offset = pa}, pa_dof);
    simulation sim(md);
    sim.run(fixed_step(end, h));
    CHECK(sim.u(x) == doctest::Approx(aa * pa * end * end / (2 * m)).epsilon(1e-10));
    CHECK(md.work("cyl")[1] == doctest::Approx(aa * pa).epsilon(1e-12));  // force A p
    CHECK(md.work("cyl")[0] == doctest::Approx(0.1 + sim.u(x)).epsilon(1e-12));
    CHECK(md.work("cyl")[2] == doctest::Approx(1e-4 + aa * (0.1 + sim.u(x))).epsilon(1e-12));
    CHECK(std::abs(md.work("supply")[0]) == doctest::Approx(aa * sim.v(x)).epsilon(1e-9));
  }

  TEST_CASE("a closed chamber is a hydraulic spring k = B A^2 / V: a mass on it oscillates with sqrt(k / m)") {
    // Merritt (1967), section 5.2 (hydraulic spring). The exact chamber law p = -B ln(V(x) / V)
    // adds a quadratic force term; its frequency shift (Landau-Lifshitz, Mechanics, section 28)
    // is (5/48) eps^2 with eps = A X / V = 1e-5 here: below 1e-11.
    const double aa = 2e-3, s0 = 0.1, va0 = 1e-4, m = 200, h = 1e-4;
    const double va = va0 + aa * s0, k = oil_b * aa * aa / va, w = std::sqrt(k / m);
    const double amp = 1e-5 * va / aa, v0 = amp * w, wd = trapezoidal_frequency(w, h);
    hydraulic_actuators_model md;
    const dof pa = md.add_dof("pA"), x = md.add_dof("x");
    md.add<hydraulic_cylinder>("cyl", {aa, 1e-3, 1.0, s0, va0, 1e-4, oil_b, 0, 0, 1e-3}, pa, md.ground(), x);
    md.add<point_mass>("load", {m}, x);
    md.add<initial_velocity>("v0", {v0}, x);
    simulation sim(md);
    std::vector<double> crossings;
    double t_prev = 0, u_prev = 0;
    double p_max = 0;
    sim.on_output([&](const auto& s) {
      const double un = s.u(x);
      if (s.time() > 0 && un * u_prev < 0) crossings.push_back(t_prev + (s.time() - t_prev) * u_prev / (u_prev - un));
      t_prev = s.time();
      u_prev = un;
      p_max = std::max(p_max, std::abs(s.v(pa)));
    });
    sim.run(fixed_step(10.3 * 2 * std::numbers::pi / w, h));
    REQUIRE(crossings.size() >= 20);
    const double half = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    CHECK(half == doctest::Approx(std::numbers::pi / wd).epsilon(1e-7));
    CHECK(std::abs(std::numbers::pi / half - w) <= w * w * w * h * h / 12);
    // Pressure amplitude k X / A.
    CHECK(p_max == doctest::Approx(k * amp / aa).epsilon(1e-3));
  }

  TEST_CASE("pushed against the end stop the piston settles at the penetration A p / ke") {
    // Documented contact: beyond the engagement width w the stop force is ke * penetration, so
    // the static balance AA pA = ke (s - stroke) gives s = stroke + AA pA / ke.
    const double aa = 2e-3, pa = 50e5, ke = 1e8, stroke = 0.2;
    hydraulic_actuators_model md;
    const dof pa_dof = md.add_dof("pA"), x = md.add_dof("x");
    md.add<hydraulic_cylinder>("cyl", {aa, 1e-3, stroke, 0.19, 1e-4, 1e-4, oil_b, ke, 1e5, 1e-5}, pa_dof,
                               md.ground(), x);
    md.add<point_mass>("load", {10.0}, x);
    md.add<velocity_source>("supply", {.offset = pa}, pa_dof);
    simulation sim(md);
    sim.run(fixed_step(0.5, 1e-4));
    CHECK(md.work("cyl")[0] == doctest::Approx(stroke + aa * pa / ke).epsilon(1e-9));
    CHECK(md.work("cyl")[4] == doctest::Approx(-aa * pa).epsilon(1e-6));  // stop force balances A p
    CHECK(std::abs(sim.v(x)) < 1e-9);
  }
}

TEST_SUITE("hydraulic/HV43") {
  TEST_CASE("a fully open 4/3 valve with a matched load orifice splits the supply pressure in thirds") {
    // P -> A, load A -> B, B -> T: three equal regularised orifices in series carry the same flow,
    // so (monotone law) each drops ps / 3: pA = 2 ps / 3, pB = ps / 3, q = k r(ps / 3). The port
    // lines have small volumes (time constant below 0.1 ms); the run lasts 50 ms.
    const double cd = 0.7, amax = 1e-5, dpt = 1e3, xmax = 1e-3, ps = 90e5;
    const double k = cd * amax * std::sqrt(2 / oil_rho);
    for (const double side : {1.0, -1.0}) {
      CAPTURE(side);
      hydraulic_actuators_model md;
      const dof p = md.add_dof("P"), a = md.add_dof("A"), b = md.add_dof("B"), x = md.add_dof("spool");
      md.add<hydraulic_volume>("line A", {.volume = 1e-5, .bulk_modulus = oil_b}, a);
      md.add<hydraulic_volume>("line B", {.volume = 1e-5, .bulk_modulus = oil_b}, b);
      md.add<valve_43>("valve", {cd, amax, oil_rho, dpt, xmax, 0.0}, p, md.ground(), a, b, x);
      md.add<turbulent_orifice>("load", {cd, amax, oil_rho, dpt}, a, b);
      md.add<velocity_source>("supply", {.offset = ps}, p);
      md.add<displacement_source>("command", {.offset = 1.5 * side * xmax}, x);
      simulation sim(md);
      sim.run(fixed_step(0.05, 1e-4));
      const double hi = 2 * ps / 3, lo = ps / 3;
      CHECK(sim.v(side > 0 ? a : b) == doctest::Approx(hi).epsilon(1e-9));
      CHECK(sim.v(side > 0 ? b : a) == doctest::Approx(lo).epsilon(1e-9));
      CHECK(md.work("load")[0] == doctest::Approx(side * k * reg_root(lo, dpt)).epsilon(1e-9));
      CHECK(md.work("valve")[4] == doctest::Approx(1.5 * side).epsilon(1e-15));
    }
  }

  TEST_CASE("a centred 4/3 valve leaks equally to both sides: pA = pB = ps / 2 and no load flow") {
    // At x = 0 all four paths have the leakage area Al: P-A-T and P-B-T are equal dividers.
    const double cd = 0.7, amax = 1e-5, dpt = 1e3, ps = 90e5, al = 1e-8;
    hydraulic_actuators_model md;
    const dof p = md.add_dof("P"), a = md.add_dof("A"), b = md.add_dof("B");
    md.add<hydraulic_volume>("line A", {.volume = 1e-7, .bulk_modulus = oil_b}, a);
    md.add<hydraulic_volume>("line B", {.volume = 1e-7, .bulk_modulus = oil_b}, b);
    md.add<valve_43>("valve", {cd, amax, oil_rho, dpt, 1e-3, al}, p, md.ground(), a, b, md.ground());
    md.add<laminar_orifice>("load", {1e9}, a, b);
    md.add<velocity_source>("supply", {.offset = ps}, p);
    simulation sim(md);
    sim.run(fixed_step(0.05, 1e-4));
    CHECK(sim.v(a) == doctest::Approx(ps / 2).epsilon(1e-9));
    CHECK(sim.v(b) == doctest::Approx(ps / 2).epsilon(1e-9));
    const double leak = cd * al * std::sqrt(2 / oil_rho) * reg_root(ps / 2, dpt);
    CHECK(std::abs(md.work("supply")[0]) == doctest::Approx(2 * leak).epsilon(1e-9));
  }
}

TEST_SUITE("hydraulic/HV22") {
  TEST_CASE("a 2/2 valve passes Cd (Al + Amax c(x / xmax)) sqrt(2/rho) r(dp): half open at x = xmax / 2") {
    const double cd = 0.7, amax = 4e-6, dpt = 1e3, xmax = 2e-3, al = 1e-9, dp = 30e5;
    const double alpha = cd * std::sqrt(2 / oil_rho);
    for (const double frac : {-0.5, 0.5, 2.0}) {
      CAPTURE(frac);
      hydraulic_actuators_model md;
      const dof p = md.add_dof("p"), x = md.add_dof("spool");
      md.add<valve_22>("valve", {cd, amax, oil_rho, dpt, xmax, al}, p, md.ground(), x);
      md.add<velocity_source>("supply", {.offset = dp}, p);
      md.add<displacement_source>("command", {.offset = frac * xmax}, x);
      simulation sim(md);
      sim.run(fixed_step(0.01, 1e-3));
      const double y = frac < 0 ? 0.0 : (frac > 1 ? 1.0 : frac);  // outside the rounded corners
      CHECK(md.work("valve")[1] == doctest::Approx(y).epsilon(1e-15));
      CHECK(md.work("valve")[0] == doctest::Approx(alpha * (al + amax * y) * reg_root(dp, dpt)).epsilon(1e-12));
    }
  }
}

TEST_SUITE("hydraulic/spool lag") {
  TEST_CASE("a spool behind SPRING k and DAMPER k tau follows a command step as a first-order lag") {
    // docs/domains.md: k (xc - x) = k tau x', so x = xc (1 - exp(-t / tau)); trapezoidal rule:
    // x_n = xc (1 - rho^n), rho = (1 - h / (2 tau)) / (1 + h / (2 tau)). The valve opening
    // follows as c(x / xmax) with c linear (slope 1 / 0.96) between 4 % and 96 % of the stroke.
    const double xmax = 1e-3, xc = 0.5e-3, k = 1e3, tau = 0.01, h = 1e-3;
    const double x = h / (2 * tau), rho = (1 - x) / (1 + x);
    hydraulic_actuators_model md;
    const dof p = md.add_dof("p"), spool = md.add_dof("spool"), cmd = md.add_dof("command");
    md.add<valve_22>("valve", {0.7, 1e-5, oil_rho, 1e3, xmax, 0.0}, p, md.ground(), spool);
    md.add<linear_spring>("lag spring", {k}, cmd, spool);
    md.add<linear_damper>("lag damper", {k * tau}, spool, md.ground());
    md.add<displacement_source>("command", {.offset = xc}, cmd);
    md.add<velocity_source>("supply", {.offset = 10e5}, p);
    simulation sim(md);
    double worst = 0;
    long n = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max(worst, std::abs(s.u(spool) - xc * (1 - std::pow(rho, static_cast<double>(n)))) / xc);
      ++n;
    });
    sim.run(fixed_step(0.1, h));
    CHECK(n == 101);
    CHECK(worst < 1e-10);
    CHECK(md.work("valve")[1] == doctest::Approx(0.5 + (sim.u(spool) / xmax - 0.5) / 0.96).epsilon(1e-12));
  }
}

TEST_SUITE("hydraulic/HRELIEF") {
  TEST_CASE("a pump feeding a relief valve settles where the valve passes the pump flow") {
    // Steady state: D w = q(p) of the documented characteristic (monotone in p), found here by
    // bisection; it must lie between the cracking and the full-opening pressure.
    const double disp = 1e-5 / (2 * std::numbers::pi), w = 150, qq = disp * w;
    const relief_valve::parameters rp{0.7, 2e-5, oil_rho, 1e3, 100e5, 10e5, 0.0};
    const double alpha = rp.cd * std::sqrt(2 / oil_rho);
    auto q_of = [&](double pr) {
      const double s = (pr - rp.crack) / rp.band;
      // c(s) of docs/domains.md with w = 0.02: (ramp(s - w) - ramp(s - 1 + w)) / (1 - 2 w).
      auto ramp = [](double z) { return z <= -0.02 ? 0.0 : (z >= 0.02 ? z : (z + 0.02) * (z + 0.02) / 0.08); };
      const double y = (ramp(s - 0.02) - ramp(s - 0.98)) / 0.96;
      return alpha * (rp.leakage_area + rp.max_area * y) * reg_root(pr, rp.transition);
    };
    double lo = 0, hi = rp.crack + rp.band;
    for (int i = 0; i < 200; ++i) ((q_of(0.5 * (lo + hi)) < qq) ? lo : hi) = 0.5 * (lo + hi);
    const double p_exact = 0.5 * (lo + hi);
    hydraulic_actuators_model md;
    const dof shaft = md.add_dof("shaft"), p = md.add_dof("p");
    md.add<hydraulic_pump>("pump", {disp, 0, 0}, md.ground(), p, shaft);
    md.add<hydraulic_volume>("vol", {.volume = 1e-4, .bulk_modulus = oil_b}, p);
    md.add<relief_valve>("relief", rp, p, md.ground());
    md.add<velocity_source>("drive", {.offset = w}, shaft);
    simulation sim(md);
    sim.run(fixed_step(0.3, 1e-4));
    CHECK(p_exact > rp.crack);
    CHECK(p_exact < rp.crack + rp.band);
    CHECK(sim.v(p) == doctest::Approx(p_exact).epsilon(1e-9));
    CHECK(md.work("relief")[0] == doctest::Approx(qq).epsilon(1e-9));
  }
}

TEST_SUITE("hydraulic/HCHECK") {
  TEST_CASE("a check valve passes the full-area flow forward and only the leakage in reverse") {
    const check_valve::parameters cp{0.7, 1e-5, oil_rho, 1e3, 0.5e5, 1e5, 1e-9};
    const double alpha = cp.cd * std::sqrt(2 / oil_rho);
    for (const double dp : {10e5, -10e5}) {
      CAPTURE(dp);
      hydraulic_actuators_model md;
      const dof p = md.add_dof("p");
      md.add<check_valve>("check", cp, p, md.ground());
      md.add<velocity_source>("supply", {.offset = dp}, p);
      simulation sim(md);
      sim.run(fixed_step(0.01, 1e-3));
      const double area = dp > 0 ? cp.leakage_area + cp.max_area : cp.leakage_area;
      CHECK(md.work("check")[0] == doctest::Approx(alpha * area * reg_root(dp, cp.transition)).epsilon(1e-12));
      CHECK(md.work("check")[1] == (dp > 0 ? 1.0 : 0.0));
    }
  }
}

TEST_SUITE("hydraulic/HACC") {
  TEST_CASE("an accumulator charged by a constant flow follows the polytropic gas law") {
    // Stored volume W(p) = V0 (1 - (p0 / (pa + p))^(1/n)) + Vd p / B above the pre-charge, so a
    // constant inflow gives W(p(t)) - W(p(0)) = q t; the gas obeys (pa + p) Vgas^n = p0 V0^n.
    // Trapezoidal rule on C(p) p' = q: second order, the error quarters when h halves.
    const double v0 = 1e-3, p0 = 20e5, n = 1.4, pa = 1e5, vd = 1e-5, q = 1e-4, end = 4.0, pi0 = 30e5;
    auto stored = [&](double pr) { return v0 * (1 - std::pow(p0 / (pa + pr), 1 / n)) + vd * pr / oil_b; };
    auto error_at = [&](double h) {
      hydraulic_actuators_model md;
      const dof p = md.add_dof("p");
      md.add<accumulator>("acc", {v0, p0, n, pa, vd, oil_b}, p);
      md.add<constant_force>("inflow", {q}, p);
      md.add<initial_velocity>("p0", {pi0}, p);
      simulation sim(md);
      sim.run(fixed_step(end, h));
      const double pr = sim.v(p);
      const double vgas = v0 - (md.work("acc")[0] - vd * pr / oil_b);
      CHECK((pa + pr) * std::pow(vgas, n) == doctest::Approx(p0 * std::pow(v0, n)).epsilon(1e-12));
      CHECK(md.work("acc")[1] == doctest::Approx(pa + pr).epsilon(1e-15));
      return std::abs(stored(pr) - stored(pi0) - q * end) / (q * end);
    };
    const double e1 = error_at(0.02), e2 = error_at(0.01);
    CHECK(e1 < 1e-3);
    CHECK(e1 / e2 == doctest::Approx(4.0).epsilon(0.1));
  }
}
