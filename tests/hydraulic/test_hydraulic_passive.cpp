// Hydraulic volume, orifices, line segment, pump and motor (docs/domains.md): analytic
// answers through real simulations. Pressure is the velocity-level unknown v, so the
// default (average-acceleration Newmark) scheme is the trapezoidal rule on p:
//  * linear first-order decay p' = -lambda p: p_n = p0 rho^n, rho = (1 - x) / (1 + x),
//    x = lambda h / 2, and 0 <= exp(-lambda t) - rho^n <= exp(-lambda t) lambda^3 h^2 t / (12 (1 - x^2))
//    (see tests/elements/test_mass_spring_damper.cpp for the derivation);
//  * undamped LC oscillator: discrete frequency wd, tan(wd h / 2) = w h / 2 (Hughes, The
//    Finite Element Method, 9.3), as for a mass on a spring.

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
using hydraulic_passive_model = pradis::model<hydraulic_volume, constant_force, laminar_orifice, initial_velocity,
    turbulent_orifice, velocity_source, hydraulic_line, hydraulic_pump, hydraulic_motor, point_mass>;
TEST_SUITE("hydraulic/HVOL") {
  TEST_CASE("a volume fed by a constant flow builds up pressure p = B q t / V") {
    // Volume balance (V / B) dp/dt = q (Merritt, Hydraulic Control Systems, 1967, eq. 3-37 with
    // no outflow): p = B q t / V. Linear in t, so the trapezoidal rule reproduces it exactly.
    const double v = 1e-3, q = 1e-5, h = 1e-3, end = 0.05;
    hydraulic_passive_model md;
    const dof p = md.add_dof("p");
    md.add<hydraulic_volume>("vol", {.volume = v, .bulk_modulus = oil_b}, p);
    md.add<constant_force>("inflow", {q}, p);  // a flow source: q into the node
    CHECK(md.dof_domain(p) == domain::hydraulic);
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) { worst = std::max(worst, std::abs(s.v(p) - oil_b * q * s.time() / v)); });
    sim.run(fixed_step(end, h));
    CHECK(sim.v(p) == doctest::Approx(oil_b * q * end / v).epsilon(1e-12));
    CHECK(worst < 1e-6);  // Pa, on pressures up to 7.5e5 Pa
    CHECK(md.work("vol")[0] == doctest::Approx(v / oil_b).epsilon(1e-15));
    CHECK(md.work("vol")[1] == doctest::Approx(oil_b).epsilon(1e-15));
  }

  TEST_CASE("with entrained air the charged volume follows the polytropic mixture law") {
    // Liquid (1 - alpha) V compressed linearly and air alpha V polytropically (pa + p) V_air^n =
    // const: the volume taken in at gauge pressure p is
    //   W(p) = V [(1 - alpha) p / B + alpha (1 - (pa / (pa + p))^(1/n))],
    // and a constant inflow q gives W(p(t)) = q t (volume conservation). The trapezoidal rule on
    // C(p) p' = q is second order: the error quarters when h halves.
    const double v = 1e-3, alpha = 0.01, pa = 1e5, n = 1.4, q = 2e-5, end = 0.05;
    auto charged = [&](double pr) {
      return v * ((1 - alpha) * pr / oil_b + alpha * (1 - std::pow(pa / (pa + pr), 1 / n)));
    };
    auto error_at = [&](double h) {
      hydraulic_passive_model md;
      const dof p = md.add_dof("p");
      md.add<hydraulic_volume>("vol", {v, oil_b, alpha, pa, n}, p);
      md.add<constant_force>("inflow", {q}, p);
      simulation sim(md);
      sim.run(fixed_step(end, h));
      // Capacitance in the work vector: C(p) = -dW/dp checked against the formula.
      const double pr = sim.v(p);
      const double c = v * ((1 - alpha) / oil_b + alpha / (n * pa) * std::pow(pa / (pa + pr), 1 + 1 / n));
      CHECK(md.work("vol")[0] == doctest::Approx(c).epsilon(1e-12));
      return std::abs(charged(pr) - q * end) / (q * end);
    };
    const double e1 = error_at(1e-3), e2 = error_at(5e-4);
    CHECK(e1 < 1e-3);
    CHECK(e2 < e1);
    CHECK(e1 / e2 == doctest::Approx(4.0).epsilon(0.1));
  }

  TEST_CASE("a volume discharging through a laminar orifice decays with the time constant V R / B") {
    // (V / B) p' = -p / R: p = p0 exp(-t B / (V R)).
    const double v = 2e-4, r = 1e10, p0 = 1e7, h = 2e-4, end = 0.1;
    const double lambda = oil_b / (v * r), x = lambda * h / 2, rho = (1 - x) / (1 + x);
    hydraulic_passive_model md;
    const dof p = md.add_dof("p");
    md.add<hydraulic_volume>("vol", {.volume = v, .bulk_modulus = oil_b}, p);
    md.add<laminar_orifice>("orifice", {r}, p, md.ground());
    md.add<initial_velocity>("p0", {p0}, p);
    simulation sim(md);
    double worst_discrete = 0, worst_ratio = 0;
    long k = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      worst_discrete = std::max(worst_discrete, std::abs(s.v(p) - p0 * std::pow(rho, static_cast<double>(k))) / p0);
      const double bound = std::exp(-lambda * t) * std::pow(lambda, 3) * h * h * t / (12 * (1 - x * x));
      worst_ratio = std::max(worst_ratio, std::abs(s.v(p) / p0 - std::exp(-lambda * t)) / (bound + 1e-12));
      ++k;
    });
    sim.run(fixed_step(end, h));
    CHECK(k == 501);
    CHECK(worst_discrete < 1e-11);
    CHECK(worst_ratio <= 1.0);
    CHECK(md.work("orifice")[0] == doctest::Approx(sim.v(p) / r).epsilon(1e-12));
  }
}

TEST_SUITE("hydraulic/HORT") {
  TEST_CASE("a turbulent orifice at a prescribed pressure passes q = Cd A sqrt(2 dp / rho)") {
    // Bernoulli with a discharge coefficient (Merritt 1967, eq. 2-20). The pressure is prescribed
    // by a velocity source (VSRC: a prescribed potential); its reaction is the flow it supplies.
    const double cd = 0.62, area = 2e-6, dp = 50e5, dpt = 1e3;
    hydraulic_passive_model md;
    const dof p = md.add_dof("p");
    md.add<turbulent_orifice>("orifice", {cd, area, oil_rho, dpt}, p, md.ground());
    md.add<velocity_source>("supply", {.offset = dp}, p);
    simulation sim(md);
    sim.run(fixed_step(0.01, 1e-3));
    const double q_sqrt = cd * area * std::sqrt(2 * dp / oil_rho);
    const double q_reg = cd * area * std::sqrt(2 / oil_rho) * reg_root(dp, dpt);
    CHECK(md.work("orifice")[0] == doctest::Approx(q_reg).epsilon(1e-14));
    // Deviation from the square-root law below dpt^2 / (4 dp^2) = 1e-11 (docs/domains.md).
    CHECK(std::abs(md.work("orifice")[0] / q_sqrt - 1) <= dpt * dpt / (4 * dp * dp));
    CHECK(std::abs(md.work("supply")[0]) == doctest::Approx(q_reg).epsilon(1e-12));
  }

  TEST_CASE("the regularised orifice law: odd, finite slope at dp = 0, monotone, root law far out") {
    const double cd = 0.7, area = 1e-5, dpt = 2e3, k = cd * area * std::sqrt(2 / oil_rho);
    const turbulent_orifice e({cd, area, oil_rho, dpt});
    element_context ctx("HORT", "o");
    std::vector<double> w(1);
    ctx.work = w;
    auto flow = [&](double p1, double p2, double& g) {
      local_input<turbulent_orifice> in;
      in.v << p1, p2;
      local_output<turbulent_orifice> out;
      e.evaluate(in, out, ctx);
      g = out.C(0, 0);
      CHECK(out.f(1) == -out.f(0));
      return out.f(0);
    };
    double g0 = 0, g1 = 0, g2 = 0;
    CHECK(flow(0, 0, g0) == 0.0);
    CHECK(g0 == doctest::Approx(k / std::sqrt(dpt)).epsilon(1e-14));  // r'(0) = 1 / sqrt(dpt)
    CHECK(flow(3e3, 0, g1) == doctest::Approx(-flow(0, 3e3, g2)).epsilon(1e-15));
    double last = -1, gl = 0;
    for (double dp = -1e6; dp <= 1e6; dp += 1e4) {
      const double q = flow(dp, 0, gl);
      CHECK(q > last);
      CHECK(gl > 0);
      last = q;
    }
    CHECK(flow(1e7, 0, gl) == doctest::Approx(k * std::sqrt(1e7)).epsilon(1e-8));
  }
}

TEST_SUITE("hydraulic/HLINE") {
  TEST_CASE("a line closed at one end oscillates with omega = 1 / sqrt(L C / 2)") {
    // End 1 on the tank, end 2 closed with an initial pressure p0: the inertance L = rho l / A
    // and the end capacitance C / 2 = A l / (2 B) form an LC oscillator, p2'' + p2 / (L C/2) = 0
    // (the resistance R = 128 mu l / (pi d^4) with mu = 1e-6 Pa s damps it with zeta = 5e-7,
    // which shifts the frequency by zeta^2 / 2, below 1e-12).
    const double l = 5, d = 0.01, mu = 1e-6, p0 = 1e5, h = 1e-4;
    const double area = std::numbers::pi * d * d / 4, inert = oil_rho * l / area, cap = area * l / oil_b;
    const double w = 1 / std::sqrt(inert * cap / 2), wd = trapezoidal_frequency(w, h);
    const double period = 2 * std::numbers::pi / w;
    hydraulic_passive_model md;
    const dof p = md.add_dof("p");
    md.add<hydraulic_line>("line", {l, d, oil_b, oil_rho, mu}, md.ground(), p);
    md.add<initial_velocity>("p0", {p0}, p);
    simulation sim(md);
    std::vector<double> crossings;
    double t_prev = 0, p_prev = p0;
    sim.on_output([&](const auto& s) {
      const double pn = s.v(p);
      if (s.time() > 0 && pn * p_prev < 0) crossings.push_back(t_prev + (s.time() - t_prev) * p_prev / (p_prev - pn));
      t_prev = s.time();
      p_prev = pn;
    });
    sim.run(fixed_step(10.2 * period, h));
    REQUIRE(crossings.size() >= 20);
    // Mean half period between the first and the last crossing; linear interpolation of a
    // crossing errs by O(h^3 w^3 p0) because p'' = -w^2 p vanishes there.
    const double half = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    CHECK(half == doctest::Approx(std::numbers::pi / wd).epsilon(1e-7));
    CHECK(std::abs(std::numbers::pi / half - w) <= w * w * w * h * h / 12);
    CHECK(md.work("line")[1] == doctest::Approx(cap).epsilon(1e-14));
    CHECK(md.work("line")[2] == doctest::Approx(inert).epsilon(1e-14));
  }

  TEST_CASE("in steady flow the line's pressure drop is the Hagen-Poiseuille R q") {
    // A prescribed pressure p1 at end 1, end 2 to the tank through a laminar orifice R2: in
    // steady state q = p1 / (R + R2), p2 = R2 q (the inertance carries no pressure drop).
    const double l = 2, d = 0.008, mu = 0.03, p1 = 20e5, r2 = 5e10;
    const double r = 128 * mu * l / (std::numbers::pi * std::pow(d, 4));
    hydraulic_passive_model md;
    const dof a = md.add_dof("a"), b = md.add_dof("b");
    md.add<hydraulic_line>("line", {l, d, oil_b, oil_rho, mu}, a, b);
    md.add<laminar_orifice>("load", {r2}, b, md.ground());
    md.add<velocity_source>("supply", {.offset = p1}, a);
    simulation sim(md);
    sim.run(fixed_step(0.5, 1e-3));
    const double q = p1 / (r + r2);
    CHECK(md.work("line")[0] == doctest::Approx(q).epsilon(1e-9));
    CHECK(sim.v(b) == doctest::Approx(r2 * q).epsilon(1e-9));
    CHECK(md.work("line")[3] == doctest::Approx(r).epsilon(1e-14));
  }
}

TEST_SUITE("hydraulic/HPUMP") {
  TEST_CASE("a pump against a turbulent orifice settles at the pressure where the orifice passes D w") {
    // Steady state: D w = k r(p), k = Cd A sqrt(2 / rho), r(p) = p / (p^2 + dpt^2)^(1/4). With
    // Q = D w: k^4 p^4 = Q^4 (p^2 + dpt^2), a quadratic in p^2:
    //   p^2 = (Q^4 + sqrt(Q^8 + 4 k^4 Q^4 dpt^2)) / (2 k^4).
    // The approach is exponential with tau = C / (dq/dp) = 0.3 ms; the run lasts 70 tau.
    const double disp = 1e-5 / (2 * std::numbers::pi), w = 150, cd = 0.7, area = 1e-5, dpt = 1e3;
    const double k = cd * area * std::sqrt(2 / oil_rho), qq = disp * w;
    const double k4 = std::pow(k, 4), q4 = std::pow(qq, 4);
    const double p_exact = std::sqrt((q4 + std::sqrt(q4 * q4 + 4 * k4 * q4 * dpt * dpt)) / (2 * k4));
    hydraulic_passive_model md;
    const dof shaft = md.add_dof("shaft"), p = md.add_dof("p");
    md.add<hydraulic_pump>("pump", {disp, 0, 0}, md.ground(), p, shaft);
    md.add<hydraulic_volume>("vol", {.volume = 1e-4, .bulk_modulus = oil_b}, p);
    md.add<turbulent_orifice>("orifice", {cd, area, oil_rho, dpt}, p, md.ground());
    md.add<velocity_source>("motor", {.offset = w}, shaft);
    CHECK(md.dof_domain(shaft) == domain::mechanical);
    simulation sim(md);
    sim.run(fixed_step(0.02, 1e-4));
    CHECK(sim.v(p) == doctest::Approx(p_exact).epsilon(1e-9));
    CHECK(md.work("pump")[0] == doctest::Approx(qq).epsilon(1e-9));
    // The shaft torque D (p2 - p1): the drive supplies it (its reaction).
    CHECK(md.work("pump")[1] == doctest::Approx(disp * p_exact).epsilon(1e-9));
    CHECK(md.work("motor")[0] == doctest::Approx(disp * p_exact).epsilon(1e-9));
  }

  TEST_CASE("leakage and friction: delivered flow D w - Gl dp, torque D dp + cf w; the losses are dissipated") {
    const double d = 2e-6, gl = 1e-12, cf = 0.01, w = 100, p1 = 1e5, p2 = 80e5;
    const hydraulic_pump e({d, gl, cf});
    element_context ctx("HPUMP", "pump");
    std::vector<double> wk(2);
    ctx.work = wk;
    local_input<hydraulic_pump> in;
    in.v << p1, p2, w;
    local_output<hydraulic_pump> out;
    e.evaluate(in, out, ctx);
    CHECK(-out.f(1) == doctest::Approx(d * w - gl * (p2 - p1)).epsilon(1e-15));
    CHECK(out.f(2) == doctest::Approx(d * (p2 - p1) + cf * w).epsilon(1e-15));
    // Power balance: f . v = Gl dp^2 + cf w^2 (Merritt 1967, section 3.4: pump losses).
    CHECK(out.f.dot(in.v) == doctest::Approx(gl * (p2 - p1) * (p2 - p1) + cf * w * w).epsilon(1e-9));
  }
}

TEST_SUITE("hydraulic/HMOTOR") {
  TEST_CASE("a motor at a prescribed pressure accelerates an inertia to w = D p / cf with tau = J / cf") {
    // J w' = D p - cf w: w = (D p / cf) (1 - exp(-t cf / J)); trapezoidal: w_n = w_ss (1 - rho^n).
    const double d = 5e-6, cf = 0.02, j = 0.01, pr = 50e5, gl = 1e-12, h = 1e-3, end = 2;
    const double w_ss = d * pr / cf, lambda = cf / j, x = lambda * h / 2, rho = (1 - x) / (1 + x);
    hydraulic_passive_model md;
    const dof shaft = md.add_dof("shaft"), p = md.add_dof("p");
    md.add<hydraulic_motor>("motor", {d, gl, cf}, p, md.ground(), shaft);
    md.add<point_mass>("rotor", {j}, shaft);
    md.add<velocity_source>("supply", {.offset = pr}, p);
    simulation sim(md);
    double worst = 0;
    long k = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max(worst, std::abs(s.v(shaft) - w_ss * (1 - std::pow(rho, static_cast<double>(k)))) / w_ss);
      ++k;
    });
    sim.run(fixed_step(end, h));
    CHECK(worst < 1e-10);
    // The supply delivers D w + Gl p.
    CHECK(std::abs(md.work("supply")[0]) == doctest::Approx(d * sim.v(shaft) + gl * pr).epsilon(1e-9));
  }
}
