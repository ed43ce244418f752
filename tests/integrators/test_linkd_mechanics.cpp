// LINKD in whole models, the tests the PRADIS element developer's manual asks
// for (section 3.6.9: "the static deformation of the spring by a force along its
// axis; the spring pendulum with different initial angular positions; the simple
// pendulum"), each with an analytic answer:
//  - static elongation P/k and axial force W(3) = P (Hooke);
//  - spring pendulum: vertical mode 2 pi sqrt(m/k), swing mode 2 pi sqrt(L/g)
//    with L the static length (linearisation about the hanging equilibrium);
//  - simple pendulum (stiff link): T = 4 K(k^2) / w, k = sin(theta0/2),
//    w = sqrt(g/L); at 90 deg, L = 1, g = 9.81: T = 2.367841947576237 s
//    (IFToMM multibody benchmark A01, simple pendulum);
//  - the manual's own model of section 3.6.9 (two MD bodies, LINKD, force):
//    the centre of mass moves as F t^2 / (2 (m1 + m2)).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::tight_newton;

namespace {
constexpr double g = 9.81;
}

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using linkd_mechanics_model = pradis::model<planar_inertia, planar_link, constant_force, linear_damper, point_mass,
    initial_displacement>;
TEST_CASE("LINKD static deflection under an axial force: elongation P/k, W(3) = P") {
  // Point A grounded, point B on an MD body (m = 2, J = 0.1, the manual's body 2),
  // k = 5e3 and P = 1e3 (manual 3.6.9 data), a critically damped DAMPER (c = 2
  // sqrt(k m)) from B's x and y DOFs to the ground so that the motion settles.
  // The static solution is a fixed point of the scheme; after t = 3 the
  // transient (decay rate >= sqrt(k/m) = 50 1/s) is below 1e-60.
  using M = linkd_mechanics_model;
  const double k = 5e3, P = 1e3, mass = 2.0, c = 2.0 * std::sqrt(k * mass);
  struct geometry {
    double xa, ya, xb, yb;
  };
  // Horizontal, and inclined at 45 deg (A and B at the manual's centres of gravity (1,1) and (2,2)).
  for (const geometry geo : {geometry{0, 0, 1, 0}, geometry{1, 1, 2, 2}}) {
    CAPTURE(geo.xb);
    M m;
    const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y"), br = m.add_dof("B.rot");
    m.add<planar_inertia>("body", {mass, 0.1}, bx, by, br);
    const auto link = m.add<planar_link>("link", {geo.xa, geo.ya, geo.xb, geo.yb, k}, m.ground(), m.ground(), bx, by);
    const double l0 = std::hypot(geo.xb - geo.xa, geo.yb - geo.ya);
    const double ex = (geo.xb - geo.xa) / l0, ey = (geo.yb - geo.ya) / l0;
    // Force P along the link axis, pulling B away from A (components on x and y).
    if (std::abs(ex) > 0) m.add<constant_force>("Fx", {P * ex}, bx);
    if (std::abs(ey) > 0) m.add<constant_force>("Fy", {P * ey}, by);
    m.add<linear_damper>("damper x", {c}, bx, m.ground());
    m.add<linear_damper>("damper y", {c}, by, m.ground());
    simulation sim(m, stoermer{});
    run_options o;
    o.end = 3.0;
    o.smax = 0.005;
    o.newton = tight_newton(1e-9, 1e-12);
    sim.run(o);
    const double elongation = P / k;  // 0.2 m
    // Newton leaves a residual <= DABSI + DRLTI sum|F| ~ 1e-9 N: displacement error ~ 1e-9 / k.
    CHECK(sim.u(bx) == doctest::Approx(elongation * ex).epsilon(1e-10));
    CHECK(sim.u(by) == doctest::Approx(elongation * ey).epsilon(1e-10));
    CHECK(std::abs(sim.u(br)) < 1e-14);  // nothing acts on the rotation
    const auto w = m.work(link);
    CHECK(w[0] == doctest::Approx(l0).epsilon(1e-15));               // W(1) = L0
    CHECK(w[1] == doctest::Approx(l0 + elongation).epsilon(1e-10));  // W(2) = current length
    CHECK(w[2] == doctest::Approx(P).epsilon(1e-9));                 // W(3) = axial force, tension > 0
    CHECK(std::abs(sim.v(bx)) < 1e-10);
  }
}

TEST_CASE("LINKD spring pendulum: vertical period 2 pi sqrt(m/k), swing period 2 pi sqrt(L/g)") {
  // A grounded at (0, 0); B carries a point mass m (MASS on its x and y DOFs),
  // gravity as F = -m g on y. Static length L = L0 + m g / k = 1 m.
  using M = linkd_mechanics_model;
  const double mass = 1.0, k = 100.0;  // vertical w = 10 rad/s; swing w = 3.13 rad/s (ratio 3.19, far from 2:1)
  const double l = 1.0, l0 = l - mass * g / k;
  const double h = 1e-3;
  auto run = [&](double theta0, double extra_stretch, double t_end, std::vector<double>& t, std::vector<double>& x,
                 std::vector<double>& r) {
    M m;
    const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
    m.add<point_mass>("mx", {mass}, bx);
    m.add<point_mass>("my", {mass}, by);
    const double s = std::sin(theta0), c = std::cos(theta0);
    // The link is defined at its natural length L0 along the initial direction; X0
    // moves B out to the static length L (plus an extra stretch) along the link.
    m.add<planar_link>("link", {0.0, 0.0, l0 * s, -l0 * c, k}, m.ground(), m.ground(), bx, by);
    m.add<constant_force>("gravity", {-mass * g}, by);
    const double d = l - l0 + extra_stretch;
    if (std::abs(d * s) > 0) m.add<initial_displacement>("x0", {d * s}, bx);
    m.add<initial_displacement>("y0", {-d * c}, by);
    simulation sim(m, newmark{});
    sim.on_output([&](const auto& q) {
      t.push_back(q.time());
      const double px = l0 * s + q.u(bx), py = -l0 * c + q.u(by);
      x.push_back(px);
      r.push_back(std::hypot(px, py));
    });
    run_options o;
    o.end = t_end;
    o.smax = h;
    o.newton = tight_newton(1e-10, 1e-12);
    sim.run(o);
  };

  SUBCASE("vertical mode") {
    // Purely vertical motion (x stays 0 exactly): a linear oscillator about the
    // static length, exact period 2 pi sqrt(m/k) for any amplitude below m g / k.
    // Average-acceleration Newmark lengthens it by Omega/(2 atan(Omega/2)) - 1 exactly.
    std::vector<double> t, x, r;
    const double t_exact = 2.0 * std::numbers::pi * std::sqrt(mass / k);
    run(0.0, 0.02, 10.3 * t_exact, t, x, r);
    std::vector<double> dr(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) dr[i] = r[i] - l;
    double xmax = 0;
    for (double xi : x) xmax = std::max(xmax, std::abs(xi));
    REQUIRE(xmax == 0.0);  // symmetric: no horizontal force ever arises
    const auto cr = pradis_test::zero_crossings(t, dr);
    REQUIRE(cr.size() >= 20);
    const double period = pradis_test::period_from_crossings(cr, false);
    const double omega_h = std::sqrt(k / mass) * h;
    const double predicted = pradis_test::trapezoidal_period_error(omega_h);  // 8.3e-6
    INFO("vertical period " << period << ", exact " << t_exact << ", rel. error " << period / t_exact - 1
                            << ", Newmark prediction " << predicted);
    // Linear problem: the measured error is the closed form within the crossing
    // interpolation error (~1e-10 relative here).
    CHECK(std::abs(period / t_exact - 1.0 - predicted) <= 0.01 * predicted);
  }

  SUBCASE("swing mode, small amplitude") {
    // theta0 = 0.01 rad, released at rest at the static length. Second-order
    // Lindstedt-Poincare expansion (derived for this test) in (rho = r - L, theta):
    //     rho'' + w_v^2 rho = (L + rho) theta'^2 - g (1 - cos theta),
    //     theta'' + w_s^2 theta = w_s^2 theta^3 / 6 + w_s^2 theta rho / L - 2 rho' theta' / L.
    // With theta = theta0 cos(tau), tau = w t, the forced radial response is
    //     rho = A0 + A2 cos(2 tau),  A0 = g theta0^2 / (4 w_v^2),
    //     A2 = -(3/4) g theta0^2 / (w_v^2 - 4 w_s^2)
    // (plus a free oscillation at w_v from the start at rho = 0, not resonant with
    // the swing), and removing the secular terms gives
    //     T / T_lin - 1 = theta0^2 (1/16 + e/8 + (9/16) e / (1 - 4 e)),  e = (w_s / w_v)^2:
    // the rigid pendulum's theta0^2/16 plus the elastic coupling (0.103 theta0^2 here).
    // Average-acceleration Newmark adds (w_s h)^2 / 12.
    const double theta0 = 0.01;
    std::vector<double> t, x, r;
    const double t_lin = 2.0 * std::numbers::pi * std::sqrt(l / g);
    run(theta0, 0.0, 5.3 * t_lin, t, x, r);
    const auto cr = pradis_test::zero_crossings(t, x);
    REQUIRE(cr.size() >= 10);
    const double period = pradis_test::period_from_crossings(cr, false);
    const double ws2 = g / l, wv2 = k / mass, e = ws2 / wv2;
    const double amplitude_term = theta0 * theta0 * (1.0 / 16.0 + e / 8.0 + (9.0 / 16.0) * e / (1.0 - 4.0 * e));
    const double disc = ws2 * h * h / 12.0;
    const double err = period / t_lin - 1.0;
    INFO("swing period " << period << ", linearised " << t_lin << ", rel. error " << err << ", predicted "
                         << amplitude_term << " + " << disc);
    // Linearised period: correct to O(theta0^2).
    CHECK(std::abs(err) <= theta0 * theta0 / 4.0 + disc);
    // The expansion: the next terms are O(theta0^4) = 1e-8 (relative 6e-4 of the
    // prediction) and O(theta0^2 (w h)^2); allow 1% of the prediction.
    CHECK(std::abs(err - (amplitude_term + disc)) <= 0.01 * (amplitude_term + disc));
    // Radial motion: |rho| <= |A0| + |A2| + |A0 + A2| (forced response plus the
    // free oscillation started at rho = 0), 2.4e-5 m here, up to O(theta0^2) relative.
    const double a0 = g * theta0 * theta0 / (4.0 * wv2), a2 = -0.75 * g * theta0 * theta0 / (wv2 - 4.0 * ws2);
    const double rbound = std::abs(a0) + std::abs(a2) + std::abs(a0 + a2);
    double rmax = 0;
    for (double ri : r) rmax = std::max(rmax, std::abs(ri - l));
    INFO("max |r - L| = " << rmax << ", bound " << rbound);
    CHECK(rmax <= 1.01 * rbound);
    CHECK(rmax >= 0.9 * rbound);
  }
}

TEST_CASE("LINKD as a stiff simple pendulum: period against 4 K(k^2)/w") {
  // Elliptic integral: AGM against the library's comp_ellint_1 (modulus k).
  CHECK(pradis_test::elliptic_k(0.5) == doctest::Approx(std::comp_ellint_1(std::sqrt(0.5))).epsilon(1e-15));
  CHECK(pradis_test::elliptic_k(0.0) == doctest::Approx(std::numbers::pi / 2).epsilon(1e-16));
  // IFToMM A01: 4 K(1/2) / sqrt(9.81).
  CHECK(pradis_test::pendulum_period(std::numbers::pi / 2, g, 1.0) ==
        doctest::Approx(2.367841947576237).epsilon(1e-15));

  // m = 1 (MASS on B's x and y), L = 1, A grounded at (0, 0), k = 1e8 (axial
  // frequency 1e4 rad/s), average-acceleration Newmark, h = 1e-3, released at rest.
  using M = linkd_mechanics_model;
  const double mass = 1.0, l = 1.0, k = 1e8, h = 1e-3;
  const double w = std::sqrt(g / l);
  auto measure = [&](double theta0, double step, double periods) {
    M m;
    const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
    m.add<point_mass>("mx", {mass}, bx);
    m.add<point_mass>("my", {mass}, by);
    const double x0 = l * std::sin(theta0), y0 = -l * std::cos(theta0);
    m.add<planar_link>("rod", {0.0, 0.0, x0, y0, k}, m.ground(), m.ground(), bx, by);
    m.add<constant_force>("gravity", {-mass * g}, by);
    simulation sim(m, newmark{});
    std::vector<double> t, x;
    sim.on_output([&](const auto& q) {
      t.push_back(q.time());
      x.push_back(x0 + q.u(bx));
    });
    run_options o;
    o.end = periods * pradis_test::pendulum_period(theta0, g, l);
    o.smax = step;
    // Flow roundoff is about k eps L = 2e-8 N: DABSI 1e-6 N (1e-14 m of stretch).
    o.newton = tight_newton(1e-6, 1e-10);
    const auto st = sim.run(o);
    CHECK(st.rejected_steps == 0);
    const auto cr = pradis_test::zero_crossings(t, x);
    REQUIRE(cr.size() >= 4);
    return pradis_test::period_from_crossings(cr, false);
  };

  // Error model (relative period error) e(h) = C h^2 + s + O(h^4, 1/k^2):
  //  - discretisation C h^2: second order (trapezoidal rule); for small swings
  //    C h^2 = (w h)^2 / 12 (Hughes, FEM, section 9.3);
  //  - link stiffness s: eliminating the stiff radial coordinate (its slaved
  //    stretch d = m (L theta'^2 + g cos theta) / k) adds
  //    m^2 (L theta'^2 + g cos theta)^2 / (2k) to the Lagrangian; first-order
  //    perturbation of the period (derived for this test) gives
  //        s = (m g / (k L)) (7.5 <cos theta> - 6.5 cos theta0) / 2,
  //    <.> the time average over the rigid motion: 0.505 m g/(k L) at 5 deg and
  //    1.714 m g/(k L) at 90 deg, i.e. 5.0e-8 and 1.7e-7 for k = 1e8;
  //  - zero crossings: cubic interpolation, < 1e-10.
  // Two runs (h, h/2) separate the terms: Richardson (4 e(h/2) - e(h)) / 3 = s.
  auto check_pendulum = [&](double theta0, double periods) {
    const double exact = pradis_test::pendulum_period(theta0, g, l);
    const double e1 = measure(theta0, h, periods) / exact - 1.0;
    const double e2 = measure(theta0, h / 2, periods) / exact - 1.0;
    const double s = pradis_test::stiff_pendulum_period_shift(theta0) * mass * g / (k * l);
    const double richardson = (4.0 * e2 - e1) / 3.0;
    const double order = std::log2((e1 - s) / (e2 - s));
    INFO("theta0 = " << theta0 * 180 / std::numbers::pi << " deg: rel. errors " << e1 << " (h), " << e2
                     << " (h/2); Richardson " << richardson << ", stiffness term " << s << "; order " << order);
    // Extrapolated period: exact up to the stiffness term; left over are O(h^4)
    // ~ e(h)^2 = 1e-11 and O((m g / k L)^2) = 1e-14. Tolerance 2e-9 (1% of s at 90 deg).
    CHECK(std::abs(richardson - s) <= 2e-9);
    CHECK(std::abs(order - 2.0) <= 0.1);
    CHECK(e1 > 0);  // the trapezoidal rule lengthens periods
    return e1 - s;
  };
  SUBCASE("5 degrees") {
    const double theta0 = 5.0 * std::numbers::pi / 180.0;
    const double disc = check_pendulum(theta0, 2.3);
    // The discretisation part is the small-swing (w h)^2 / 12 up to a relative
    // O(theta0^2) = O(0.008) amplitude correction (not derived here: only its size is checked).
    const double linear = (w * h) * (w * h) / 12.0;
    CHECK(disc == doctest::Approx(linear).epsilon(0.05));
  }
  SUBCASE("90 degrees (IFToMM A01)") {
    const double theta0 = std::numbers::pi / 2.0;
    CHECK(pradis_test::pendulum_period(theta0, g, l) == doctest::Approx(2.367841947576237).epsilon(1e-15));
    check_pendulum(theta0, 2.3);
  }
}

TEST_CASE("the manual's section 3.6.9 model: two MD bodies, LINKD, force; centre of mass exact") {
  // Body 1 'MD (1 2 3; 1, 0.1) at (1, 1); body 2 'MD (4 5 6; 2, 0.1) at (2, 2);
  // LINKD (1 2 4 5; 1, 1, 2, 2, 5E3); F (5; 1E3); SHTERM (END = 1).
  // Internal forces cancel, so the total momentum obeys P_n = P_{n-1} + h F
  // exactly under Stoermer (v_n = v_{n-1} + h a_n, sum m a_n = F once Newton has
  // converged), and x_n = x_{n-1} + h (v_{n-1} + v_n)/2 integrates the linear
  // centre-of-mass velocity exactly: y_cm(t) = F t^2 / (2 (m1 + m2)), x_cm fixed.
  using M = linkd_mechanics_model;
  M m;
  const auto d = m.add_dofs(6, "dof");
  m.add<planar_inertia>("Body 1", {1.0, 0.1}, d[0], d[1], d[2]);
  m.add<planar_inertia>("Body 2", {2.0, 0.1}, d[3], d[4], d[5]);
  const auto link = m.add<planar_link>("Connection", {1.0, 1.0, 2.0, 2.0, 5e3}, d[0], d[1], d[3], d[4]);
  m.add<constant_force>("Force", {1e3}, d[4]);
  simulation sim(m, stoermer{});
  run_options o;
  o.end = 1.0;
  o.newton = tight_newton(1e-8, 1e-10);
  sim.run(o);
  const double mt = 3.0, t = 1.0;
  const double ycm = (1.0 * sim.u(d[1]) + 2.0 * sim.u(d[4])) / mt;
  const double xcm = (1.0 * sim.u(d[0]) + 2.0 * sim.u(d[3])) / mt;
  // Newton residual per DOF <= 1e-8 N (+ relative part) per step: momentum error
  // <= 100 steps * h * 1e-8 N, negligible against 1e-9 relative.
  CHECK(ycm == doctest::Approx(1e3 * t * t / (2.0 * mt)).epsilon(1e-9));
  CHECK(std::abs(xcm) < 1e-9);
  CHECK(std::abs(sim.u(d[2])) < 1e-14);
  CHECK(std::abs(sim.u(d[5])) < 1e-14);
  // W(2) is the current length of the link, W(3) = k (L - L0).
  const double lx = (2.0 + sim.u(d[3])) - (1.0 + sim.u(d[0])), ly = (2.0 + sim.u(d[4])) - (1.0 + sim.u(d[1]));
  const auto w = m.work(link);
  CHECK(w[1] == doctest::Approx(std::hypot(lx, ly)).epsilon(1e-14));
  CHECK(w[2] == doctest::Approx(5e3 * (std::hypot(lx, ly) - std::sqrt(2.0))).epsilon(1e-9));
}
