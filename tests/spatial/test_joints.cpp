// The penalty joint SPH3 against exact solutions: a compound pendulum (BODY3 on a
// spherical joint to the ground) swings with the exact period
// 4 sqrt(I_pivot / (m g d)) K(sin(theta0 / 2)) and opens the joint by m g / k; and
// the heavy symmetric top (Lagrange top: BODY3 spinning on SPH3 at its tip under
// gravity, F3) against the nutation bounds and the mean precession rate from the
// cubic f(u) of Goldstein, Classical Mechanics (3rd ed., 2002), section 5.7.
// The penalty hinge REV3: a compound pendulum on a hinge (same exact period; the motion
// stays in the plane normal to the axis), free rotation about the hinge under a constant
// torque (theta = M t^2 / (2 J)) while a perpendicular torque M is resisted by M / kr.

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "../elements/element_test_support.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;
using pradis_spatial_tests::seconds_since;
using pradis_spatial_tests::tight_newton;

namespace {
using pradis_spatial_tests::pi;
using pradis_spatial_tests::g;

/// Exact period of a compound pendulum released at rest from theta0 about a rigid pivot
/// (axis): T = 4 sqrt(I_pivot / (m g d)) K(sin(theta0 / 2)), I_pivot = J + m d^2, K the
/// complete elliptic integral of the first kind (Landau-Lifshitz, Mechanics, section 11).
double compound_pendulum_period(double i_pivot, double mass, double d, double theta0) {
  return 4 * std::sqrt(i_pivot / (mass * g * d)) * std::comp_ellint_1(std::sin(theta0 / 2));
}

/// Downward zero crossings of a swing angle a(t) sampled at the outputs, and the mean
/// period between them (linear interpolation between samples).
struct downward_crossings {
  std::vector<double> times;  ///< crossing times [s]
  double prev_t = 0;          ///< previous sample time [s]
  double prev_a;              ///< previous sample angle [rad]
  /// Starting at angle a0 at t = 0.
  explicit downward_crossings(double a0) : prev_a(a0) {}
  void add(double t, double a) {
    if (prev_a > 0 && a <= 0) times.push_back(prev_t + (t - prev_t) * prev_a / (prev_a - a));
    prev_t = t, prev_a = a;
  }
  double period() const {
    REQUIRE(times.size() >= 2);
    return (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  }
};

/// Result of one compound-pendulum run.
struct pendulum_result {
  double period = 0;    ///< mean period from downward zero crossings [s]
  double gap_ratio = 0; ///< mean joint gap over the second half times k / (m g)
};

/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using joints_model = pradis::model<rigid_body, spherical_joint, spatial_force, initial_rotation, initial_displacement,
    revolute_joint, spatial_torque>;
/// Compound pendulum: body (m, Jxx) with its centre of mass a distance d below a fixed
/// pivot, on SPH3 with stiffness k, started at rest at angle theta0 about X.
pendulum_result compound_pendulum(double k, double theta0, double end, double h) {
  const double mass = 1.0, jxx = 0.02, d = 0.5;
  joints_model m;
  const auto x = m.add_dofs(3, "x");
  const rotation_node r = m.add_rotation_node("r");
  const dof G = m.ground();
  m.add<rigid_body>("body", {mass, jxx, jxx, 0.01, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
  const auto joint = m.add<spherical_joint>(
      "pivot", {{0, 0, 0, 0, 0, 0, 0, 0, -d, 0, 0, d}, k, 0.4 * std::sqrt(k * mass)}, G, G, G, G, G, G, x[0], x[1],
      x[2], r);
  m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
  m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, r);
  // The joint closed at the start: x = (0, d sin theta0, d (1 - cos theta0)).
  m.add<initial_displacement>("y0", {d * std::sin(theta0)}, x[1]);
  m.add<initial_displacement>("z0", {d * (1 - std::cos(theta0))}, x[2]);
  simulation sim(m);
  downward_crossings crossings(theta0);
  double gap_sum = 0;
  int gap_n = 0;
  sim.on_output([&](const auto& s) {
    const quaternion q = node_quaternion(s, r);
    const double t = s.time();
    crossings.add(t, 2 * std::atan2(q(0), q(3)));
    if (t > end / 2) {
      gap_sum += m.work(joint)[0];
      ++gap_n;
    }
  });
  sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
  pendulum_result res;
  res.period = crossings.period();
  res.gap_ratio = gap_sum / gap_n * k / (mass * g);
  return res;
}
}  // namespace

TEST_SUITE("spatial/joints") {
  TEST_CASE("SPH3: a compound pendulum swings with the exact period; the joint gap is m g / k") {
    // Exact period of a compound pendulum of amplitude theta0 (a rigid pivot):
    // T = 4 sqrt(I_pivot / (m g d)) K(sin(theta0 / 2)), I_pivot = Jxx + m d^2 (complete elliptic
    // integral of the first kind; Landau-Lifshitz, Mechanics, section 11). The penalty joint moves
    // the pivot by the gap m g / k, which changes T by O(gap / d): the error must fall with k.
    const auto t0 = std::chrono::steady_clock::now();
    const double theta0 = 3 * pi / 180, h = 1e-3;
    const double ip = 0.02 + 0.25, exact = compound_pendulum_period(ip, 1.0, 0.5, theta0);
    const double small = 2 * pi * std::sqrt(ip / (g * 0.5));
    const pendulum_result soft = compound_pendulum(1e5, theta0, 3.2, h);
    const pendulum_result stiff = compound_pendulum(1e6, theta0, 3.2, h);
    const double es = std::abs(soft.period / exact - 1), ek = std::abs(stiff.period / exact - 1);
    MESSAGE("SPH3 pendulum: exact T = ", exact, " s (small-amplitude 2 pi sqrt(I/(m g d)) = ", small,
            " s); k = 1e5: T = ", soft.period, " (rel. error ", es, "), gap k/(m g) = ", soft.gap_ratio,
            "; k = 1e6: T = ", stiff.period, " (rel. error ", ek, "), gap k/(m g) = ", stiff.gap_ratio, "; ",
            seconds_since(t0), " s");
    CHECK(es < 2e-4);
    CHECK(ek < 5e-5);
    CHECK(ek < es / 5);  // the compliance error scales like 1 / k (measured: 8.6x for 10x k)
    // The gap is the transmitted force over k: m g (1 + O(theta0^2)) / k.
    CHECK(soft.gap_ratio == doctest::Approx(1.0).epsilon(0.01));
    CHECK(stiff.gap_ratio == doctest::Approx(1.0).epsilon(0.01));
  }

  TEST_CASE("heavy symmetric top on SPH3: nutation bounds and mean precession of the Lagrange top") {
    // Goldstein, Classical Mechanics, 3rd ed., section 5.7: with u = cos(theta) (theta the
    // polar angle of the symmetry axis from the upward vertical),
    //   u'^2 = f(u) = (1 - u^2)(alpha - beta u) - (b - a u)^2,
    //   a = I3 w3 / I1, beta = 2 m g l / I1, phi' = (b - a u) / (1 - u^2),
    // I1 the transverse inertia about the pivot, I3 the axial one, l the pivot-CM distance.
    // Released at theta0 with spin w3 only (phi' = theta' = 0): b = a u0, alpha = beta u0, and
    // f(u) = beta (u0 - u)(u - u1)(u2 - u) with u1, u2 the roots of beta u^2 - a^2 u + a^2 u0 - beta.
    // theta moves between theta0 and acos(u1) (the cusp case); over a nutation period T,
    //   T / 2 = int_0^pi dchi / sqrt(beta (u2 - u)),  Dphi / 2 = int_0^pi phi'(u) dchi / sqrt(beta (u2 - u)),
    // with u = (u0 + u1) / 2 + (u0 - u1) / 2 cos chi (smooth periodic integrands: trapezoidal sums).
    const auto t0 = std::chrono::steady_clock::now();
    const double mass = 1.0, l = 0.1, j1 = 0.01, j3 = 0.02, w3 = 30.0, theta0 = 30 * pi / 180, k = 1e6, h = 1e-3;
    const double i1 = j1 + mass * l * l, a = j3 * w3 / i1, beta = 2 * mass * g * l / i1, u0 = std::cos(theta0);
    const double disc = std::sqrt(a * a * a * a - 4 * beta * (a * a * u0 - beta));
    const double u1 = (a * a - disc) / (2 * beta), u2 = (a * a + disc) / (2 * beta);
    double half_t = 0, half_phi = 0;
    const int nq = 2000;
    for (int i = 0; i < nq; ++i) {
      const double chi = (i + 0.5) * pi / nq, u = 0.5 * (u0 + u1) + 0.5 * (u0 - u1) * std::cos(chi);
      const double dt = pi / nq / std::sqrt(beta * (u2 - u));
      half_t += dt;
      half_phi += a * (u0 - u) / (1 - u * u) * dt;
    }
    const double period = 2 * half_t, mean_rate = half_phi / half_t, theta1 = std::acos(u1);
    const int periods = 3;  // CI length: 3 nutation periods (about 0.70 s)

    joints_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("top", {mass, j1, j1, j3, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const vec3 axis0(0, -std::sin(theta0), std::cos(theta0));  // body Z after the tilt about X
    m.add<spherical_joint>("tip",
                           {{0, 0, 0, 0, 0, 0, l * axis0.x(), l * axis0.y(), l * axis0.z(), 0, 0, -l}, k,
                            0.4 * std::sqrt(k * mass)},
                           G, G, G, G, G, G, x[0], x[1], x[2], r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, w3 * axis0.x(), w3 * axis0.y(), w3 * axis0.z()}, r);
    simulation sim(m);
    double th_min = pi, th_max = 0, phi = 0, prev = std::atan2(axis0.y(), axis0.x());
    sim.on_output([&](const auto& s) {
      const vec3 ax = node_rotation(s, r).col(2);
      const double th = std::acos(ax.z()), az = std::atan2(ax.y(), ax.x());
      th_min = std::min(th_min, th);
      th_max = std::max(th_max, th);
      phi += std::remainder(az - prev, 2 * pi);
      prev = az;
    });
    sim.run({.end = periods * period, .out = h, .smax = h, .newton = tight_newton});
    const double rate = phi / (periods * period), amp = theta1 - theta0;
    MESSAGE("heavy top: theta in [", th_min * 180 / pi, ", ", th_max * 180 / pi, "] deg vs exact [",
            theta0 * 180 / pi, ", ", theta1 * 180 / pi, "]; mean precession ", rate, " rad/s vs exact ", mean_rate,
            " (fast-top approximation m g l / (I3 w3) = ", mass * g * l / (j3 * w3), "); nutation period ", period,
            " s; ", seconds_since(t0), " s");
    // Tolerances: 1 % of the nutation amplitude for the bounds (sampling at h, the O(m g / k)
    // compliance of the joint and the trapezoidal phase error (w h)^2 / 12 are all smaller),
    // 0.5 % for the mean precession rate.
    CHECK(std::abs(th_min - theta0) < 0.01 * amp);
    CHECK(std::abs(th_max - theta1) < 0.01 * amp);
    CHECK(rate == doctest::Approx(mean_rate).epsilon(5e-3));
  }

  TEST_CASE("SPH3 with k <= 0 or c < 0 stops the run with code 100 in its name") {
    for (const auto& [k, c, mention] : {std::tuple{0.0, 0.0, "k <= 0"}, std::tuple{1.0, -1.0, "c < 0"}}) {
      joints_model m;
      const auto x = m.add_dofs(3, "x");
      const rotation_node r = m.add_rotation_node("r");
      const dof G = m.ground();
      m.add<rigid_body>("body", {1, 1, 1, 1, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
      m.add<spherical_joint>("ball", {{}, k, c}, G, G, G, G, G, G, x[0], x[1], x[2], r);
      simulation sim(m);
      check_error(error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); }), error_code::invalid_parameter, "SPH3",
                  "ball", mention);
    }
  }

  TEST_CASE("REV3: a hinge pendulum swings with the exact period and stays in the plane normal to the axis") {
    // A compound pendulum on a rigid hinge about X through the pivot obeys I_O theta'' = -m g d sin(theta)
    // exactly (I_O = Jxx + m d^2 about the hinge line, d the distance of the centre of mass from it): the
    // period is the compound-pendulum period of Landau-Lifshitz, Mechanics, section 11 (see
    // compound_pendulum_period). To load the rotational coupling out of the plane, the pivot is offset
    // by 0.1 m along the axis from the centre of mass and the body has a product of inertia Jxy: a rigid
    // hinge carries the resulting moments about Y and Z, the penalty hinge turns by O(moment / kr).
    const auto t0 = std::chrono::steady_clock::now();
    const double mass = 1.0, jxx = 0.02, d = 0.5, off = 0.1, theta0 = 60 * pi / 180, k = 1e6, kr = 1e5, h = 1e-3;
    const double ip = jxx + mass * d * d, exact = compound_pendulum_period(ip, mass, d, theta0);
    joints_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {mass, jxx, 0.015, 0.01, 0.004, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const auto hinge = m.add<revolute_joint>(
        "hinge",
        {{0, 0, 0, 0, 0, 0, -off, 0, -d, off, 0, d}, 1, 0, 0, 1, 0, 0, k, 0.4 * std::sqrt(k * mass), kr,
         0.4 * std::sqrt(kr * ip)},
        G, G, G, G, G, G, x[0], x[1], x[2], r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, r);
    // The joint closed at the start: x = (0, d sin theta0, d (1 - cos theta0)).
    m.add<initial_displacement>("y0", {d * std::sin(theta0)}, x[1]);
    m.add<initial_displacement>("z0", {d * (1 - std::cos(theta0))}, x[2]);
    simulation sim(m);
    downward_crossings crossings(theta0);
    double max_x = 0, max_tilt = 0, max_phi = 0;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, r);
      crossings.add(s.time(), std::atan2(rot(2, 1), rot(1, 1)));  // angle of the body's Y axis about X
      max_x = std::max(max_x, std::abs(s.u(x[0])));                // out-of-plane displacement
      max_tilt = std::max(max_tilt, std::abs(rot(0, 1)) + std::abs(rot(0, 2)));  // body axes out of the plane
      max_phi = std::max(max_phi, m.work(hinge)[4]);               // misalignment angle of the axes
    });
    sim.run({.end = 1.3 * exact, .out = h, .smax = h, .newton = tight_newton});
    const double period = crossings.period(), err = std::abs(period / exact - 1);
    MESSAGE("REV3 pendulum (60 deg): exact T = ", exact, " s, T = ", period, " (rel. error ", err,
            "); max |x| = ", max_x, " m (m g / k = ", mass * g / k, "), max misalignment ", max_phi,
            " rad, max out-of-plane body axis components ", max_tilt, " (m g off / kr = ", mass * g * off / kr,
            "); ", seconds_since(t0), " s");
    CHECK(err < 1e-4);
    // Out of the plane: translation at the penalty level of the gap (m g / k = 1e-5 m, up to ~3 m g
    // at the bottom of the swing), rotation at the level of (pivot moment) / kr (m g off / kr = 1e-5).
    CHECK(max_x < 5 * mass * g / k);
    CHECK(max_phi < 5 * mass * g * off / kr);
    CHECK(max_tilt < 10 * mass * g * off / kr);
    CHECK(max_phi > 0.5 * mass * g * off / kr);  // the axes do turn: the moment is carried by kr
  }

  TEST_CASE("REV3: free rotation about the hinge under a torque, a perpendicular torque is resisted by kr") {
    // A body on a hinge along its principal axis Z through its centre of mass: a torque Mz about the axis
    // gives the uniformly accelerated rotation theta = Mz t^2 / (2 Jzz) (Euler's equation about a fixed
    // axis, e.g. Goldstein, Classical Mechanics, 3rd ed., section 5.5, with omega along a principal axis);
    // a torque Mx about X turns the axis by Mx / kr (the static penalty deflection of the hinge; Jxx =
    // Jyy, so the spin about the tilted axis needs no gyroscopic moment).
    const auto t0 = std::chrono::steady_clock::now();
    const double jxx = 0.01, jzz = 0.02, mz = 1.0, mx = 0.5, kr = 1e4, k = 1e6, end = 0.4, h = 1e-3;
    joints_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {1.0, jxx, jxx, jzz, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const auto hinge = m.add<revolute_joint>(
        "hinge", {{}, 0, 0, 2, 0, 0, 1, k, 0.4 * std::sqrt(k), kr, 0.4 * std::sqrt(kr * jxx)}, G, G, G, G, G, G, x[0],
        x[1], x[2], r);
    m.add<spatial_torque>("torque", {mx, 0, mz, 0, 0, 0, 0, 0}, r);
    simulation sim(m);
    double theta = 0, prev = 0;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, r);
      const double a = std::atan2(rot(1, 0), rot(0, 0));
      theta += std::remainder(a - prev, 2 * pi);
      prev = a;
    });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    const double exact = mz * end * end / (2 * jzz);
    const mat3 rot = node_rotation(sim, r);
    const double phi = m.work(hinge)[4];
    MESSAGE("REV3 free hinge: theta(", end, ") = ", theta, " rad vs Mz t^2 / (2 J) = ", exact, " (rel. error ",
            theta / exact - 1, "); misalignment ", phi, " rad vs Mx / kr = ", mx / kr, "; body Z axis ",
            rot.col(2).transpose(), "; moment on b ", m.work(hinge)[5], " ", m.work(hinge)[6], " ",
            m.work(hinge)[7], "; ", seconds_since(t0), " s");
    CHECK(theta == doctest::Approx(exact).epsilon(1e-4));
    // The tilt: about +X by Mx / kr (sin(phi) kr = Mx at equilibrium), body Z -> (0, -sin phi, cos phi).
    CHECK(phi == doctest::Approx(std::asin(mx / kr)).epsilon(1e-2));
    CHECK(-rot(1, 2) == doctest::Approx(mx / kr).epsilon(1e-2));
    CHECK(std::abs(rot(0, 2)) < 1e-2 * mx / kr);
    CHECK(m.work(hinge)[5] == doctest::Approx(-mx).epsilon(1e-2));  // the hinge holds b against Mx
  }

  TEST_CASE("REV3 with a zero hinge axis, kr <= 0, cr < 0 or a non-finite value stops the run with code 100") {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    struct bad {
      revolute_joint::parameters p;
      const char* mention;
    };
    const revolute_joint::parameters ok{{}, 1, 0, 0, 1, 0, 0, 1e4, 10, 1e3, 1};
    std::vector<bad> cases;
    auto with = [&](auto f, const char* mention) {
      revolute_joint::parameters p = ok;
      f(p);
      cases.push_back({p, mention});
    };
    with([](auto& p) { p.eax = 0; }, "zero hinge axis");
    with([](auto& p) { p.eby = nan; }, "hinge axis e_b");
    with([](auto& p) { p.kr = 0; }, "kr <= 0");
    with([](auto& p) { p.kr = -1; }, "kr <= 0");
    with([](auto& p) { p.cr = -1; }, "cr < 0");
    with([](auto& p) { p.cr = nan; }, "cr < 0");
    with([](auto& p) { p.geo.rbx = nan; }, "must be finite");
    with([](auto& p) { p.k = 0; }, "k <= 0");
    for (const bad& b : cases) {
      CAPTURE(b.mention);
      joints_model m;
      const auto x = m.add_dofs(3, "x");
      const rotation_node r = m.add_rotation_node("r");
      const dof G = m.ground();
      m.add<rigid_body>("body", {1, 1, 1, 1, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
      m.add<revolute_joint>("hinge", b.p, G, G, G, G, G, G, x[0], x[1], x[2], r);
      simulation sim(m);
      check_error(error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); }), error_code::invalid_parameter, "REV3",
                  "hinge", b.mention);
    }
  }

  TEST_CASE("joints evaluated for their flows alone give the flows of a full evaluation bit for bit") {
    // Without a Jacobian (local_output::want_jacobian false) the joints skip the
    // derivatives of their attached points (attached_point's `derivatives`); flows and
    // work outputs must not change. Random states, quaternions near unit length.
    std::mt19937 rng(11u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto compare = [&]<class E>(const E& e) {
      CAPTURE(E::passport.name);
      for (int trial = 0; trial < 20; ++trial) {
        local_input<E> in;
        for (int k = 0; k < element_traits<E>::n; ++k) {
          in.u(k) = 0.1 * u(rng);
          in.v(k) = u(rng);
        }
        in.u(12) += 1.0;
        in.u(13) += 1.0;
        std::vector<double> w1(static_cast<std::size_t>(E::passport.wrk)), w2 = w1;
        element_context c1(E::passport.name, "full"), c2(E::passport.name, "flows");
        c1.work = w1;
        c2.work = w2;
        local_output<E> full, flows;
        full.clear();
        flows.want_jacobian = false;
        e.evaluate(in, full, c1);
        e.evaluate(in, flows, c2);
        CHECK(flows.f == full.f);
        CHECK(w1 == w2);
      }
    };
    compare(exact_spherical_joint(exact_spherical_joint::example()));
    compare(exact_revolute_joint(exact_revolute_joint::example()));
    compare(exact_cylindrical_joint(exact_cylindrical_joint::example()));
    compare(exact_fixed_joint(exact_fixed_joint::example()));
    compare(spherical_joint(spherical_joint::example()));
    compare(revolute_joint(revolute_joint::example()));
  }

  TEST_CASE("attached_point without derivatives or at its position level: the missing derivatives are NaN") {
    const vec3 x0(0.1, -0.2, 0.3), a(0.4, 0.5, -0.6), x(0.01, 0.02, -0.03), xd(0.5, -0.1, 0.2);
    const quaternion q(0.1, -0.2, 0.3, 0.9), qd(0.3, 0.1, -0.2, 0.05);
    using point = pradis::elements::detail::attached_point;
    const point full(x0, a, x, xd, q, qd);
    CHECK(full.dv_dq.allFinite());
    // Without derivatives, and at the position level (the exact joints' Jacobians: dp/dq as
    // with all derivatives).
    for (const point::level l : {point::level::none, point::level::position}) {
      CAPTURE(static_cast<int>(l));
      const point p = l == point::level::none ? point(x0, a, x, xd, q, qd, false) : point(x0, a, x, xd, q, qd, l);
      CHECK(p.p == full.p);
      CHECK(p.v == full.v);
      CHECK(p.rho == full.rho);
      CHECK(p.omega == full.omega);
      CHECK(p.theta == full.theta);
      if (l == point::level::none)
        CHECK(p.dp_dq.hasNaN());
      else
        CHECK(p.dp_dq == full.dp_dq);
      CHECK(p.domega_dq.hasNaN());
      CHECK(p.dv_dq.hasNaN());
    }
  }
}
