// SPH3X, the exact spherical joint (constraint rows with the joint force as
// Lagrange multipliers), against closed forms: a compound pendulum swings with
// the exact period 4 sqrt(I_pivot / (m g d)) K(sin(theta0 / 2)) (Landau-Lifshitz,
// Mechanics, section 11) with the joint closed to round-off; the heavy symmetric
// top (Lagrange top) keeps its conserved quantities, the energy, the spin
// omega_3 about the symmetry axis and the vertical angular momentum about the
// pivot (Goldstein, Classical Mechanics, 3rd ed., section 5.7), and stays between
// the exact nutation bounds.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/spatial/node_state.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_spatial_tests::tight_newton;

namespace {
using pradis_spatial_tests::pi;
using pradis_spatial_tests::g;
using joint_model = model<rigid_body, exact_spherical_joint, exact_revolute_joint, spatial_force, spatial_torque,
                          initial_rotation, initial_displacement>;
}  // namespace

TEST_SUITE("spatial/exact joints") {
  TEST_CASE("SPH3X: a compound pendulum swings with the exact period and the joint stays closed") {
    // Body m = 1, Jxx = 0.02, centre of mass d = 0.5 below the pivot, released at rest at
    // theta0 = 3 degrees about X. The penalty SPH3 at k = 1e6 gave a period error of 5e-5
    // (tests/spatial/test_joints.cpp); exactly jointed, only the scheme's phase error
    // (w h)^2 / 12 ~ 3e-6 remains at h = 1e-3.
    const double mass = 1.0, jxx = 0.02, d = 0.5, theta0 = 3 * pi / 180, h = 1e-3, end = 3.2;
    const double exact = 4 * std::sqrt((jxx + mass * d * d) / (mass * g * d)) * std::comp_ellint_1(std::sin(theta0 / 2));
    joint_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {mass, jxx, jxx, 0.01, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const auto joint = m.add<exact_spherical_joint>("pivot", {{0, 0, 0, 0, 0, 0, 0, 0, -d, 0, 0, d}}, G, G, G, G, G,
                                                    G, x[0], x[1], x[2], r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, r);
    m.add<initial_displacement>("y0", {d * std::sin(theta0)}, x[1]);
    m.add<initial_displacement>("z0", {d * (1 - std::cos(theta0))}, x[2]);
    simulation<joint_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    std::vector<double> crossings;
    double prev_t = 0, prev_a = theta0, gap = 0, force_z = 0, pin_drift = 0, pin_speed = 0, cm_check = 0;
    sim.on_output([&](const auto& s) {
      const quaternion q = node_quaternion(s, r);
      const double t = s.time(), a = 2 * std::atan2(q(0), q(3));
      if (prev_a > 0 && a <= 0) crossings.push_back(prev_t + (t - prev_t) * prev_a / (prev_a - a));
      prev_t = t;
      prev_a = a;
      gap = std::max(gap, m.work(joint)[0]);
      force_z = m.work(joint)[3];
      // The body's joint point (offset (0, 0, d) from the centre of mass, which
      // starts at (0, 0, -d)) stays at the pivot, at rest (spatial::body_point).
      const point_motion pin = body_point(s, {x[0], x[1], x[2]}, r, vec3(0, 0, -d), vec3(0, 0, d));
      pin_drift = std::max(pin_drift, pin.position.norm());
      pin_speed = std::max(pin_speed, pin.velocity.norm());
      // The centre of mass (offset 0) moves with the translational DOFs.
      const point_motion cm = body_point(s, {x[0], x[1], x[2]}, r, vec3(0, 0, -d), vec3::Zero());
      cm_check = std::max(cm_check, std::abs(cm.velocity.y() - s.v(x[1])) + std::abs(cm.position.z() + d - s.u(x[2])));
    });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    REQUIRE(crossings.size() >= 2);
    const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    CAPTURE(period);
    CAPTURE(exact);
    CHECK(std::abs(period / exact - 1) < 1e-5);
    CHECK(gap < 1e-12);
    CHECK(pin_drift < 1e-12);
    // Positions are constrained (index 3), velocities only through the scheme's
    // u-v relation: the joint point's velocity is zero to the discretisation
    // error (measured 9e-5 m/s at h = 1e-3, against a peak centre-of-mass speed of 0.11 m/s).
    CAPTURE(pin_speed);
    CHECK(pin_speed < 2e-4);
    CHECK(cm_check < 1e-15);
    // The joint carries the weight (plus the small centripetal part at 3 degrees).
    CHECK(force_z == doctest::Approx(mass * g).epsilon(2e-3));
  }

  // The heavy top on SPH3X (Goldstein section 5.7, as in test_joints.cpp): released
  // at theta0 with spin w3 about its axis only, the axis moves between theta0 and
  // acos(u1). Returns the largest deviations of the energy (relative), the spin
  // omega_3 (relative) and the vertical angular momentum about the pivot (relative
  // to I3 w3), the extreme polar angles, the exact bounds and the largest gap.
  struct top_result {
    std::array<double, 3> drift{};
    double th_min = pi, th_max = 0, theta0 = 0, theta1 = 0, gap = 0;
  };
  top_result heavy_top(double h, double end) {
    const double mass = 1.0, l = 0.1, j1 = 0.01, j3 = 0.02, w3 = 30.0, theta0 = 30 * pi / 180;
    const double i1 = j1 + mass * l * l, a = j3 * w3 / i1, beta = 2 * mass * g * l / i1, u0 = std::cos(theta0);
    const double disc = std::sqrt(a * a * a * a - 4 * beta * (a * a * u0 - beta));
    top_result out;
    out.theta0 = theta0;
    out.theta1 = std::acos((a * a - disc) / (2 * beta));
    joint_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("top", {mass, j1, j1, j3, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const vec3 axis0(0, -std::sin(theta0), std::cos(theta0));
    const auto joint = m.add<exact_spherical_joint>(
        "tip", {{0, 0, 0, 0, 0, 0, l * axis0.x(), l * axis0.y(), l * axis0.z(), 0, 0, -l}}, G, G, G, G, G, G, x[0],
        x[1], x[2], r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, w3 * axis0.x(), w3 * axis0.y(), w3 * axis0.z()},
                            r);
    simulation<joint_model, alpha_family> sim(m, alpha_family(newmark{}));
    // Conserved: E = T + m g z_c; omega_3 = omega . axis; L_z about the pivot (gravity
    // and the joint force have no moment about the vertical through the pivot).
    const vec3 c0 = l * axis0;
    std::array<double, 3> first{};
    const std::array<double, 3> scale{1.0, w3, j3 * w3};
    bool started = false;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, r);
      const vec3 w = node_angular_velocity(s, r), axis = rot.col(2);
      const vec3 c = c0 + vec3(s.u(x[0]), s.u(x[1]), s.u(x[2])), v(s.v(x[0]), s.v(x[1]), s.v(x[2]));
      const mat3 jg = rot * vec3(j1, j1, j3).asDiagonal() * rot.transpose();
      const double e = 0.5 * mass * v.squaredNorm() + 0.5 * w.dot(jg * w) + mass * g * c.z();
      const std::array<double, 3> iv{e, w.dot(axis), (jg * w + mass * c.cross(v)).z()};
      if (!started) first = iv, started = true;
      for (std::size_t k = 0; k < 3; ++k) {
        const double sc = k == 0 ? std::abs(first[0]) : scale[k];
        out.drift[k] = std::max(out.drift[k], std::abs(iv[k] - first[k]) / sc);
      }
      const double th = std::acos(std::clamp(axis.z(), -1.0, 1.0));
      out.th_min = std::min(out.th_min, th);
      out.th_max = std::max(out.th_max, th);
      out.gap = std::max(out.gap, m.work(joint)[0]);
    });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    return out;
  }

  TEST_CASE("SPH3X: the heavy symmetric top keeps energy, spin and vertical momentum to O(h^2), within the nutation bounds") {
    // One nutation period is about 0.23 s; 0.3 s covers the full range of theta.
    const top_result coarse = heavy_top(1e-3, 0.3), fine = heavy_top(5e-4, 0.3);
    for (std::size_t k = 0; k < 3; ++k) {
      CAPTURE(k);
      CAPTURE(coarse.drift[k]);
      CAPTURE(fine.drift[k]);
      CHECK(fine.drift[k] < 2e-5);
      // Second order: halving h divides the deviation by about 4.
      CHECK(coarse.drift[k] / fine.drift[k] > 3.5);
      CHECK(coarse.drift[k] / fine.drift[k] < 4.5);
    }
    CHECK(fine.gap < 1e-12);
    const double amp = fine.theta1 - fine.theta0;
    CHECK(std::abs(fine.th_min - fine.theta0) < 0.01 * amp);
    CHECK(std::abs(fine.th_max - fine.theta1) < 0.01 * amp);
  }

  TEST_CASE("REV3X: a hinge pendulum at 60 degrees swings with the exact period and stays in its plane") {
    // I_O theta'' = -m g d sin(theta) about a rigid hinge (Landau-Lifshitz, Mechanics, section 11).
    // The pivot is 0.1 m off the centre of mass along the axis and the body has a product of
    // inertia Jxy, so the hinge carries moments about Y and Z (the penalty REV3 turns under them
    // by moment / kr; the exact hinge does not turn at all).
    const double mass = 1.0, jxx = 0.02, d = 0.5, off = 0.1, theta0 = 60 * pi / 180, h = 1e-3;
    const double exact =
        4 * std::sqrt((jxx + mass * d * d) / (mass * g * d)) * std::comp_ellint_1(std::sin(theta0 / 2));
    joint_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {mass, jxx, 0.015, 0.01, 0.004, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const auto hinge = m.add<exact_revolute_joint>(
        "hinge", {{0, 0, 0, 0, 0, 0, -off, 0, -d, off, 0, d}, 1, 0, 0, 1, 0, 0}, G, G, G, G, G, G, x[0], x[1], x[2],
        r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, r);
    m.add<initial_displacement>("y0", {d * std::sin(theta0)}, x[1]);
    m.add<initial_displacement>("z0", {d * (1 - std::cos(theta0))}, x[2]);
    simulation<joint_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    std::vector<double> crossings;
    double prev_t = 0, prev_a = theta0, max_x = 0, max_tilt = 0, max_phi = 0, max_gap = 0;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, r);
      const double t = s.time(), a = std::atan2(rot(2, 1), rot(1, 1));
      if (prev_a > 0 && a <= 0) crossings.push_back(prev_t + (t - prev_t) * prev_a / (prev_a - a));
      prev_t = t;
      prev_a = a;
      max_x = std::max(max_x, std::abs(s.u(x[0])));
      max_tilt = std::max(max_tilt, std::abs(rot(0, 1)) + std::abs(rot(0, 2)));
      max_phi = std::max(max_phi, m.work(hinge)[4]);
      max_gap = std::max(max_gap, m.work(hinge)[0]);
    });
    sim.run({.end = 1.3 * exact, .out = h, .smax = h, .newton = tight_newton});
    REQUIRE(crossings.size() >= 2);
    const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    CAPTURE(period);
    CAPTURE(exact);
    // The penalty REV3 (k = 1e6, kr = 1e5) is checked to 1e-4 in test_joints.cpp.
    CHECK(std::abs(period / exact - 1) < 2e-5);
    CHECK(max_x < 1e-12);
    CHECK(max_tilt < 1e-12);
    CHECK(max_phi < 1e-12);
    CHECK(max_gap < 1e-12);
  }

  TEST_CASE("REV3X: free rotation about the hinge under a torque; a perpendicular torque is carried exactly") {
    // A body on a hinge along its principal axis Z through its centre of mass: theta = Mz t^2 /
    // (2 Jzz) (Euler's equation about a fixed principal axis; Goldstein, section 5.5). The torque
    // Mx about X is carried by the hinge: the moment on the body is -Mx and the axis does not turn.
    const double jxx = 0.01, jzz = 0.02, mz = 1.0, mx = 0.5, end = 0.4, h = 1e-3;
    joint_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {1.0, jxx, jxx, jzz, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    const auto hinge = m.add<exact_revolute_joint>("hinge", {{}, 0, 0, 2, 0, 0, 1}, G, G, G, G, G, G, x[0], x[1],
                                                   x[2], r);
    m.add<spatial_torque>("torque", {mx, 0, mz, 0, 0, 0, 0, 0}, r);
    simulation<joint_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
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
    // theta is uniformly accelerated, but the quaternion is not quadratic in time:
    // the scheme's O((w h)^2) error is 1e-5 here (also with Mx = 0).
    CHECK(theta == doctest::Approx(exact).epsilon(2e-5));
    CHECK(std::abs(rot(0, 2)) + std::abs(rot(1, 2)) < 1e-12);  // the body's Z axis stays along Z
    CHECK(m.work(hinge)[4] < 1e-12);
    CHECK(m.work(hinge)[5] == doctest::Approx(-mx).epsilon(1e-6));
    CHECK(std::abs(m.work(hinge)[6]) < 1e-6);
    CHECK(std::abs(m.work(hinge)[7]) < 1e-6);
  }

  TEST_CASE("REV3X with a zero hinge axis stops the run with code 100 naming the joint") {
    joint_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {1, 1, 1, 1, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    m.add<exact_revolute_joint>("hinge", {{}, 0, 0, 0, 0, 0, 1}, G, G, G, G, G, G, x[0], x[1], x[2], r);
    simulation sim(m);
    try {
      sim.run({.end = 0.01, .smax = 1e-3});
      FAIL("must throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_parameter);
      CHECK(e.element_type() == "REV3X");
      CHECK(e.instance() == "hinge");
      CHECK(std::string(e.what()).find("hinge axis e_a") != std::string::npos);
    }
  }

  TEST_CASE("SPH3X with a non-finite parameter stops the run with code 100 naming the joint") {
    joint_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", {1, 1, 1, 1, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    m.add<exact_spherical_joint>("ball", {{0, 0, 0, NAN, 0, 0, 0, 0, 0, 0, 0, 0}}, G, G, G, G, G, G, x[0], x[1], x[2],
                                 r);
    simulation sim(m);
    try {
      sim.run({.end = 0.01, .smax = 1e-3});
      FAIL("must throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_parameter);
      CHECK(e.element_type() == "SPH3X");
      CHECK(e.instance() == "ball");
    }
  }
}
