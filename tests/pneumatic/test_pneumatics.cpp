// Pneumatic elements (gauge pressure v, mass flow): isothermal chamber filled by a
// constant mass flow, ISO 6358 orifice flows at prescribed pressures, polytropic
// compression by a driven piston (p V^n = const), the double-acting cylinder,
// finite-difference Jacobians at realistic states, and bad parameters.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;
namespace pn = pradis::elements::pneumatic;

namespace {
// Newton tolerances for pneumatic nodes: the DOF scale (1e5 Pa, 1e-5 kg/s) multiplies them.
constexpr newton_options tight_pneumatic{.dabsu = 1e-14, .drltu = 0, .dabsi = 1e-9, .drlti = 0};
run_options pneumatic_step(double end, double h) { return {.end = end, .smax = h, .newton = tight_pneumatic}; }

// ISO 6358-1 mass flow through a component at upstream/downstream absolute pressures p1 > p2,
// written as in the standard (not through the element's y): q = C rho0 p1 sqrt(T0/T1) for
// p2/p1 <= b, else q = C rho0 p1 sqrt(T0/T1) sqrt(1 - ((p2/p1 - b)/(1 - b))^2).
double iso6358(double c, double b, double t1, double p1, double p2) {
  const double choked = c * pn::anr_density * p1 * std::sqrt(pn::anr_temperature / t1), r = p2 / p1;
  return r <= b ? choked : choked * std::sqrt(1 - std::pow((r - b) / (1 - b), 2));
}

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using pneumatics_model = pradis::model<gas_piston_chamber, displacement_source, gas_chamber, pneumatic_flow_source,
    pneumatic_cylinder, pneumatic_pressure_source, pneumatic_orifice>;
// Largest relative deviation of the chamber pressure from p0 (V0/V)^n along a run with the piston
// driven by XSRC x(t) = -X sin(2 pi t) over a quarter period (the volume V0 + A x halves for X A = V0/2).
double compression_error(double n, double h) {
  const double area = 1e-3, v0 = 1e-4, amp = 0.05, p0 = 2e5, big_p0 = pn::atmosphere + p0;
  pneumatics_model md;
  const dof gas = md.add_dof("gas"), x = md.add_dof("x");
  const auto ch = md.add<gas_piston_chamber>("chamber", {area, v0, n, p0, 293.15}, gas, x);
  md.add<displacement_source>("drive", {-amp, 1.0, 0.0, 0.0}, x);
  simulation sim(md);
  double worst = 0;
  sim.on_output([&](const auto& s) {
    const double vol = v0 + area * s.u(x), exact = big_p0 * std::pow(v0 / vol, n);
    worst = std::max(worst, std::abs(pn::atmosphere + s.v(gas) - exact) / exact);
    CHECK(md.work(ch)[4] == doctest::Approx(vol).epsilon(1e-14));
    CHECK(md.work(ch)[5] == doctest::Approx(area * s.v(gas)).epsilon(1e-14));
  });
  sim.run(pneumatic_step(0.25, h));
  return worst;
}
}  // namespace

TEST_SUITE("pneumatic/chambers") {
  TEST_CASE("an isothermal chamber filled by a constant mass flow: P = P0 + R T q t / V, m = m0 + q t") {
    // m' = q and P V = m R T with T fixed: P(t) = P0 + R T q t / V. The chamber is linear in v for
    // n = 1 and the forcing is constant, so the trapezoidal rule is exact.
    const double vol = 2e-3, q = 1e-3, t = 293.15, p0 = 5e4, big_p0 = pn::atmosphere + p0;
    pneumatics_model md;
    const dof node = md.add_dof("tank");
    const auto ch = md.add<gas_chamber>("tank", {vol, 1.0, p0, t}, node);
    md.add<pneumatic_flow_source>("fill", {q}, node, md.ground());
    CHECK(md.dof_domain(node) == domain::pneumatic);
    simulation sim(md);
    double worst_p = 0, worst_m = 0;
    const double m0 = big_p0 * vol / (pn::air_gas_constant * t);
    sim.on_output([&](const auto& s) {
      const double exact = big_p0 + pn::air_gas_constant * t * q * s.time() / vol;
      worst_p = std::max(worst_p, std::abs(pn::atmosphere + s.v(node) - exact) / exact);
      worst_m = std::max(worst_m, std::abs(md.work(ch)[2] - (m0 + q * s.time())) / m0);
      CHECK(md.work(ch)[3] == doctest::Approx(t).epsilon(1e-12));  // isothermal
    });
    sim.run(pneumatic_step(2.0, 0.01));
    CHECK(worst_p < 1e-12);
    CHECK(worst_m < 1e-12);
  }

  TEST_CASE("adiabatic compression by a driven piston follows P V^1.4 = const, second order in the step") {
    // A closed chamber keeps its mass: rho(P) V = rho0 V0 with rho = rho0 (P/P0)^(1/n) gives
    // P = P0 (V0/V)^n (Poisson's law for n = kappa = 1.4). The nodal form integrates the mass balance
    // m' = 0 with the trapezoidal rule: the pressure converges with order 2.
    const double coarse = compression_error(1.4, 2e-3), fine = compression_error(1.4, 1e-3);
    CHECK(fine < 1e-5);
    CHECK(coarse / fine == doctest::Approx(4.0).epsilon(0.1));
  }

  TEST_CASE("isothermal compression by a driven piston follows Boyle's law P V = const") {
    const double coarse = compression_error(1.0, 2e-3), fine = compression_error(1.0, 1e-3);
    CHECK(fine < 1e-5);
    CHECK(coarse / fine == doctest::Approx(4.0).epsilon(0.1));
  }

  TEST_CASE("a double-acting cylinder with closed chambers: Boyle in both and the rod force A1 pA - A2 pB") {
    // Rod driven by XSRC x = X sin(2 pi t): VA = VA0 + A1 x, VB = VB0 - A2 x; closed isothermal chambers:
    // PA VA = P0 VA0, PB VB = P0 VB0. The drive supplies the rod force: its reaction W(1) is the
    // sum of the other flows on the rod, -(A1 vA - A2 vB).
    const double a1 = 2e-3, a2 = 1.5e-3, va0 = 2e-4, vb0 = 1.5e-4, p0 = 3e5, big_p0 = pn::atmosphere + p0;
    pneumatics_model md;
    const dof ca = md.add_dof("A"), cb = md.add_dof("B"), x = md.add_dof("rod");
    const auto cyl = md.add<pneumatic_cylinder>("cyl", {a1, a2, va0, vb0, 1.0, p0, 293.15}, ca, cb, x);
    const auto drive = md.add<displacement_source>("drive", {0.04, 1.0, 0.0, 0.0}, x);
    simulation sim(md);
    double worst = 0, worst_force = 0;
    sim.on_output([&](const auto& s) {
      const double va = va0 + a1 * s.u(x), vb = vb0 - a2 * s.u(x);
      worst = std::max({worst, std::abs(pn::atmosphere + s.v(ca) - big_p0 * va0 / va) / big_p0,
                        std::abs(pn::atmosphere + s.v(cb) - big_p0 * vb0 / vb) / big_p0});
      const double force = a1 * s.v(ca) - a2 * s.v(cb);
      worst_force = std::max({worst_force, std::abs(md.work(cyl)[0] - force), std::abs(md.work(drive)[0] + force)});
    });
    sim.run(pneumatic_step(1.0, 1e-3));
    CHECK(worst < 1e-4);
    CHECK(worst_force < 1e-6);
  }
}

TEST_SUITE("pneumatic/PNORF") {
  TEST_CASE("ISO 6358: the flow from a prescribed supply to the atmosphere equals the standard's formula") {
    // Upstream node held by PNSRC, downstream the ground (the atmosphere): the source's reaction W(1) is
    // the orifice's mass flow. Choked (P2/P1 <= b) and subsonic cases.
    const double c = 2e-8, b = 0.3, t1 = 300.0;
    for (const double supply : {6e5, 2e5, 2e4}) {
      CAPTURE(supply);
      pneumatics_model md;
      const dof up = md.add_dof("supply"), tank = md.add_dof("tank");
      const auto src = md.add<pneumatic_pressure_source>("P", {supply}, up);
      const auto orf = md.add<pneumatic_orifice>("valve", {c, b, t1, 0.999}, up, md.ground());
      // A second, unconnected chamber keeps one unknown in the system.
      md.add<gas_chamber>("idle", {1e-3, 1.0, 0.0, 293.15}, tank);
      simulation sim(md);
      sim.run(pneumatic_step(0.01, 1e-3));
      const double expected = iso6358(c, b, t1, pn::atmosphere + supply, pn::atmosphere);
      CHECK(md.work(orf)[0] == doctest::Approx(expected).epsilon(1e-13));
      CHECK(md.work(src)[0] == doctest::Approx(expected).epsilon(1e-13));
    }
    CHECK(iso6358(c, b, t1, pn::atmosphere + 6e5, pn::atmosphere) ==
          doctest::Approx(c * 1.185 * (pn::atmosphere + 6e5) * std::sqrt(293.15 / 300.0)).epsilon(1e-15));
  }

  TEST_CASE("near dp = 0 the flow is the C1 laminar cubic: continuous at b_lam, linear slope at 0, odd") {
    const pneumatic_orifice o({1e-8, 0.4, 293.15, 0.999});
    const double k = 1e-8 * pn::anr_density, big_p = pn::atmosphere;
    // Just above and below the laminar threshold: value equals the ISO formula there.
    const double g_lam = big_p / 0.999 - big_p;  // gauge upstream with P2/P1 = 0.999 exactly
    double q_lo = 0, q_hi = 0, d1_lo = 0, d1_hi = 0, d2 = 0;
    o.flow(g_lam * (1 - 1e-9), 0.0, q_lo, d1_lo, d2);
    o.flow(g_lam * (1 + 1e-9), 0.0, q_hi, d1_hi, d2);
    CHECK(q_hi == doctest::Approx(iso6358(1e-8, 0.4, 293.15, big_p + g_lam, big_p)).epsilon(1e-7));
    CHECK(q_lo == doctest::Approx(q_hi).epsilon(1e-7));
    CHECK(d1_lo == doctest::Approx(d1_hi).epsilon(1e-6));
    // At dp = 0: no flow, finite slope k a / (1 - b) with a = (3 s/yl - d)/2.
    double q0 = 1, dq1 = 0, dq2 = 0;
    o.flow(1e5, 1e5, q0, dq1, dq2);
    const double yl = 0.001 / 0.6, s = std::sqrt(yl * (2 - yl)), d = (1 - yl) / s;
    CHECK(q0 == 0.0);
    CHECK(dq1 == doctest::Approx(k * 0.5 * (3 * s / yl - d) / 0.6).epsilon(1e-12));
    CHECK(dq2 == doctest::Approx(-dq1).epsilon(1e-12));
    // Reverse flow is the mirror image.
    double qf = 0, qr = 0, x1 = 0, x2 = 0;
    o.flow(3e5, 1e5, qf, x1, x2);
    o.flow(1e5, 3e5, qr, x1, x2);
    CHECK(qr == doctest::Approx(-qf).epsilon(1e-15));
  }

  TEST_CASE("the orifice Jacobian matches finite differences in the choked, subsonic, laminar and reverse ranges") {
    // Realistic sizes (flows ~1e-3 kg/s): the checker's absolute floor is scaled down, the step is 0.05 Pa.
    testing::jacobian_checker<pneumatic_orifice> chk(pneumatic_orifice({2e-8, 0.3, 300.0, 0.999}), 4,
                                                     {.rel_step = 0, .abs_step = 0.05, .tolerance = 1e-6,
                                                      .zero_floor = 1e-16});
    for (const auto& gauges : std::array<std::pair<double, double>, 5>{
             {{6e5, 0.0}, {3e4, 1e4}, {1e4 + 20, 1e4}, {1e4, 1e4 + 37}, {0.0, 5e5}}}) {
      const double g1 = gauges.first, g2 = gauges.second;  // not a structured binding: CAPTURE's lambda takes them
      CAPTURE(g1);
      CAPTURE(g2);
      local_input<pneumatic_orifice> in;
      in.v << g1, g2;
      const auto r = chk.check(in);
      CHECK(r.ok);
    }
  }

  TEST_CASE("chamber Jacobians match finite differences at realistic sizes") {
    const testing::jacobian_check_options o{.rel_step = 1e-6, .abs_step = 1e-6, .tolerance = 1e-6, .zero_floor = 1e-20};
    testing::jacobian_checker<gas_chamber> c1(gas_chamber({1e-3, 1.4, 2e5, 293.15}), 4, o);
    local_input<gas_chamber> i1;
    i1.v << 3e5;
    i1.a << 2e6;
    CHECK(c1.check(i1).ok);
    testing::jacobian_checker<gas_piston_chamber> c2(gas_piston_chamber({1e-3, 1e-4, 1.4, 2e5, 293.15}), 5,
                                                     {.rel_step = 1e-4, .abs_step = 1e-6, .tolerance = 1e-5,
                                                      .zero_floor = 1e-20});
    local_input<gas_piston_chamber> i2;
    i2.u << 0.0, 0.03;
    i2.v << 3e5, -0.5;
    i2.a << 2e6, 4.0;
    CHECK(c2.check(i2).ok);
    testing::jacobian_checker<pneumatic_cylinder> c3(
        pneumatic_cylinder({2e-3, 1.5e-3, 2e-4, 1.5e-4, 1.4, 2e5, 293.15}), 7,
        {.rel_step = 1e-4, .abs_step = 1e-6, .tolerance = 1e-5, .zero_floor = 1e-20});
    local_input<pneumatic_cylinder> i3;
    i3.u << 0.0, 0.0, 0.02;
    i3.v << 4e5, 1e5, 0.3;
    i3.a << -1e6, 3e6, 2.0;
    CHECK(c3.check(i3).ok);
  }
}

TEST_SUITE("pneumatic/bad input") {
  template <class E>
  void expect_bad(typename E::parameters p, const char* type, const char* mention) {
    model<E, point_mass> md;
    std::array<dof, element_traits<E>::ext> d{};
    for (auto& x : d) x = md.add_dof();
    std::apply([&](auto... x) { md.template add<E>("bad", p, x...); }, d);
    md.template add<point_mass>("unknown", {1.0}, md.add_dof());  // keeps one unknown in the system
    simulation sim(md);
    check_error(error_from([&] { sim.run(pneumatic_step(0.01, 1e-3)); }), error_code::invalid_parameter, type,
                "bad", mention);
  }

  TEST_CASE("bad pneumatic parameters stop the run with code 100 naming the parameter") {
    expect_bad<gas_chamber>({0.0, 1.0, 0.0, 293.15}, "PNVOL", "volume V");
    expect_bad<gas_chamber>({1e-3, 0.5, 0.0, 293.15}, "PNVOL", "polytropic exponent n");
    expect_bad<gas_chamber>({1e-3, 1.0, -2e5, 293.15}, "PNVOL", "initial gauge pressure p0");
    expect_bad<gas_chamber>({1e-3, 1.0, 0.0, -1.0}, "PNVOL", "initial temperature T0");
    expect_bad<gas_piston_chamber>({-1e-3, 1e-4, 1.0, 0.0, 293.15}, "PNCHP", "piston area A");
    expect_bad<gas_piston_chamber>({1e-3, 0.0, 1.0, 0.0, 293.15}, "PNCHP", "volume V0");
    expect_bad<pneumatic_cylinder>({1e-3, 0.0, 1e-4, 1e-4, 1.0, 0.0, 293.15}, "PNCYL", "annulus area A2");
    expect_bad<pneumatic_cylinder>({1e-3, 1e-3, 1e-4, inf, 1.0, 0.0, 293.15}, "PNCYL", "volume VB0");
    expect_bad<pneumatic_cylinder>({1e-3, 1e-3, 1e-4, 1e-4, 3.0, 0.0, 293.15}, "PNCYL", "polytropic exponent n");
    expect_bad<pneumatic_orifice>({0.0, 0.3, 293.15, 0.999}, "PNORF", "sonic conductance C");
    expect_bad<pneumatic_orifice>({1e-8, 1.0, 293.15, 0.999}, "PNORF", "critical pressure ratio b");
    expect_bad<pneumatic_orifice>({1e-8, 0.3, 0.0, 0.999}, "PNORF", "upstream temperature T");
    expect_bad<pneumatic_orifice>({1e-8, 0.3, 293.15, 0.2}, "PNORF", "laminar pressure ratio b_lam");
    expect_bad<pneumatic_pressure_source>({inf}, "PNSRC", "gauge pressure p");
    expect_bad<pneumatic_flow_source>({-inf}, "PNQ", "mass flow q");
  }

  TEST_CASE("a chamber whose volume vanishes under a driven piston is a singular situation (code 75)") {
    pneumatics_model md;
    const dof gas = md.add_dof("gas"), x = md.add_dof("x");
    md.add<gas_piston_chamber>("ch", {1e-3, 1e-4, 1.0, 0.0, 293.15}, gas, x);
    md.add<displacement_source>("drive", {-0.2, 1.0, 0.0, 0.0}, x);  // x reaches -0.1 m (V = 0) at t = 1/12
    simulation sim(md);
    // As V nears zero, Newton's pressure iterate leaves the admissible range first: the
    // code-75 message is that the absolute pressure is not positive.
    check_error(error_from([&] { sim.run(pneumatic_step(0.25, 1e-3)); }), error_code::singular_situation, "PNCHP",
                "ch", "not positive");
  }

  TEST_CASE("two chambers with different initial pressures on one node are refused with code 90") {
    pneumatics_model md;
    const dof n = md.add_dof("n");
    md.add<gas_chamber>("a", {1e-3, 1.0, 1e5, 293.15}, n);
    md.add<gas_chamber>("b", {1e-3, 1.0, 2e5, 293.15}, n);
    simulation sim(md);
    check_error(error_from([&] { sim.run(pneumatic_step(0.01, 1e-3)); }), error_code::conflicting_initial, "PNVOL",
                "b", "conflicts");
  }
}
