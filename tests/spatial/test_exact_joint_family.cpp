// The exact joint family beyond SPH3X and REV3X (UNI3X, CYL3X, PRI3X, FIX3X,
// PTL3X, PTP3X and the planar PIN2X), against closed forms:
// - a body on a frictionless slider, wire or plane under constant loads moves with
//   the constant acceleration of the free direction, (F . e) e / m (Newton's second
//   law with ideal constraints, Goldstein, Classical Mechanics, 3rd ed., section 1.4),
//   and the reactions are m a - F and minus the applied moment;
// - a free rotation about a principal axis under a torque M turns by
//   M t^2 / (2 J) (Euler's equations, Goldstein section 5.5);
// - pendulums on a universal joint, on a welded pair of bodies and on a planar pin
//   swing with the exact period 4 sqrt(I_O / (m g d)) K(sin(theta0 / 2))
//   (Landau-Lifshitz, Mechanics, section 11);
// and every constraint residual stays at round-off (index-3 constraints on positions).
// The zero step starts the multipliers at the consistent joint forces: those of
// Newton-Euler's equations at the initial state (Goldstein, section 5.5).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
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
using family_model =
    model<rigid_body, exact_spherical_joint, exact_revolute_joint, exact_universal_joint, exact_cylindrical_joint, exact_prismatic_joint,
          exact_fixed_joint, exact_point_on_line, exact_point_on_plane, spatial_force, spatial_torque, body_torque,
          initial_rotation, initial_displacement>;

/// A rigid body with principal inertias j (body axes along the global axes at t = 0).
struct family_body {
  std::vector<dof> x;
  rotation_node r;
  family_body(family_model& m, const std::string& name, double mass, const vec3& j) {
    x = m.add_dofs(3, name + ".x");
    r = m.add_rotation_node(name + ".r");
    m.add<rigid_body>(name, {mass, j.x(), j.y(), j.z(), 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
  }
  vec3 position(const auto& s) const { return {s.u(x[0]), s.u(x[1]), s.u(x[2])}; }
};

/// Period from the downward zero crossings of an angle, interpolated linearly.
struct crossings {
  std::vector<double> at;
  double prev_t = 0, prev_a = 0;
  bool started = false;
  void add(double t, double a) {
    if (started && prev_a > 0 && a <= 0) at.push_back(prev_t + (t - prev_t) * prev_a / (prev_a - a));
    prev_t = t;
    prev_a = a;
    started = true;
  }
  double period() const { return (at.back() - at.front()) / static_cast<double>(at.size() - 1); }
};

/// The exact period of a compound pendulum (I_O about the pivot, m g d) from theta0.
double pendulum_period(double i_o, double mgd, double theta0) {
  return 4 * std::sqrt(i_o / mgd) * std::comp_ellint_1(std::sin(theta0 / 2));
}

vec3 work3(std::span<const double> w, int k) { return {w[k], w[k + 1], w[k + 2]}; }

/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using exact_joint_family_model = pradis::model<planar_inertia, planar_pin_joint, constant_force, initial_displacement>;
/// A planar compound pendulum (MD) on PIN2X to the ground, released at rest at
/// theta0: the centre hangs d below the pin at rotation 0, the pin point is d above
/// the centre.
struct planar_pendulum {
  using model_type = exact_joint_family_model;
  model_type m;
  dof x, y, th;
  element_ref<planar_pin_joint> pin;
  planar_pendulum(double mass, double j, double d, double theta0) {
    x = m.add_dof("x");
    y = m.add_dof("y");
    th = m.add_dof("theta");
    const dof G = m.ground();
    m.add<planar_inertia>("body", {mass, j}, x, y, th);
    pin = m.add<planar_pin_joint>("pin", {0, 0, 0, 0, 0, -d, 0, d}, G, G, G, x, y, th);
    m.add<constant_force>("weight", {-mass * g}, y);
    m.add<initial_displacement>("theta0", {theta0}, th);
    m.add<initial_displacement>("x0", {d * std::sin(theta0)}, x);
    m.add<initial_displacement>("y0", {d * (1 - std::cos(theta0))}, y);
  }
};
}  // namespace

TEST_SUITE("spatial/exact joint family") {
  TEST_CASE("PRI3X: a body slides down an inclined axis with g sin(alpha); it does not turn, and the joint carries "
            "the rest") {
    const double mass = 2.0, alpha = 30 * pi / 180, end = 1.0, h = 1e-3;
    const vec3 e(std::cos(alpha), 0, std::sin(alpha)), load(0, 1.5, -mass * g), torque(0.3, -0.2, 0.5);
    family_model m;
    const family_body b(m, "body", mass, {0.1, 0.2, 0.3});
    const dof G = m.ground();
    const auto slider = m.add<exact_prismatic_joint>(
        "slider", {{}, e.x(), e.y(), e.z(), 0, 1, 0, e.x(), e.y(), e.z(), 0, 1, 0}, G, G, G, G, G, G, b.x[0], b.x[1],
        b.x[2], b.r);
    m.add<spatial_force>("loads", {load.x(), load.y(), load.z(), 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
    m.add<spatial_torque>("torque", {torque.x(), torque.y(), torque.z(), 0, 0, 0, 0, 0}, b.r);
    simulation<family_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    double off_axis = 0, turn = 0;
    sim.on_output([&](const auto& s) {
      off_axis = std::max(off_axis, m.work(slider)[0]);
      turn = std::max(turn, (node_rotation(s, b.r) - mat3::Identity()).norm());
    });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    const double a = load.dot(e) / mass;  // = -g sin(alpha)
    const vec3 expected = 0.5 * a * end * end * e;
    CAPTURE(b.position(sim).transpose());
    CHECK((b.position(sim) - expected).norm() < 1e-9 * expected.norm());
    CHECK(m.work(slider)[9] == doctest::Approx(0.5 * a * end * end).epsilon(1e-9));
    CHECK(off_axis < 1e-12);
    CHECK(turn < 1e-12);
    CHECK(std::abs(m.work(slider)[4]) + std::abs(m.work(slider)[5]) < 1e-12);
    // Reactions on the body: the force m a - F (perpendicular to the axis), the moment -M.
    CHECK((work3(m.work(slider), 1) - (mass * a * e - load)).norm() < 1e-6);
    CHECK((work3(m.work(slider), 6) + torque).norm() < 1e-6);
  }

  TEST_CASE("CYL3X: a body falls along a vertical axis and spins about it under a torque; lateral loads are "
            "carried") {
    const double mass = 1.5, jzz = 0.04, end = 0.4, h = 1e-3;
    const vec3 load(0, 0.7, -mass * g), torque(0.3, 0, 0.8);
    family_model m;
    const family_body b(m, "body", mass, {0.02, 0.02, jzz});
    const dof G = m.ground();
    const auto joint = m.add<exact_cylindrical_joint>("cyl", {{}, 0, 0, 1, 0, 0, 1}, G, G, G, G, G, G, b.x[0],
                                                      b.x[1], b.x[2], b.r);
    m.add<spatial_force>("loads", {load.x(), load.y(), load.z(), 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
    m.add<spatial_torque>("torque", {torque.x(), torque.y(), torque.z(), 0, 0, 0, 0, 0}, b.r);
    simulation<family_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    double theta = 0, prev = 0, off_axis = 0, tilt = 0;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, b.r);
      const double a = std::atan2(rot(1, 0), rot(0, 0));
      theta += std::remainder(a - prev, 2 * pi);
      prev = a;
      off_axis = std::max(off_axis, m.work(joint)[0]);
      tilt = std::max({tilt, std::abs(rot(0, 2)) + std::abs(rot(1, 2)), m.work(joint)[4]});
    });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    const double z = -0.5 * g * end * end;
    CHECK(sim.u(b.x[2]) == doctest::Approx(z).epsilon(1e-9));
    CHECK(m.work(joint)[8] == doctest::Approx(z).epsilon(1e-9));
    // The quaternion is not quadratic in time: the scheme's O((w h)^2) error (as for REV3X).
    CHECK(theta == doctest::Approx(torque.z() * end * end / (2 * jzz)).epsilon(2e-5));
    CHECK(off_axis < 1e-12);
    CHECK(tilt < 1e-12);
    CHECK((work3(m.work(joint), 1) - vec3(0, -load.y(), 0)).norm() < 1e-6);
    CHECK((work3(m.work(joint), 5) - vec3(-torque.x(), 0, 0)).norm() < 1e-6);
  }

  TEST_CASE("UNI3X: a pendulum on a Cardan joint swings with the exact period and does not spin under a torque "
            "about its own axis") {
    const double mass = 1.0, jxx = 0.02, d = 0.5, theta0 = 30 * pi / 180, h = 1e-3, spin_torque = 0.3;
    const double exact = pendulum_period(jxx + mass * d * d, mass * g * d, theta0);
    family_model m;
    const family_body b(m, "body", mass, {jxx, 0.015, 0.01});
    const dof G = m.ground();
    // Cross axis X fixed in the ground, cross axis Y fixed in the body.
    const auto joint = m.add<exact_universal_joint>("cardan", {{0, 0, 0, 0, 0, 0, 0, 0, -d, 0, 0, d}, 1, 0, 0, 0, 1, 0},
                                                    G, G, G, G, G, G, b.x[0], b.x[1], b.x[2], b.r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
    m.add<body_torque>("spin", {0, 0, spin_torque, 0, 0, 0, 0, 0}, b.r);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, b.r);
    m.add<initial_displacement>("y0", {d * std::sin(theta0)}, b.x[1]);
    m.add<initial_displacement>("z0", {d * (1 - std::cos(theta0))}, b.x[2]);
    simulation<family_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    crossings c;
    double gap = 0, right_angle = 0, body_x = 0, moment_error = 0;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, b.r);
      c.add(s.time(), std::atan2(rot(2, 1), rot(1, 1)));
      gap = std::max(gap, m.work(joint)[0]);
      right_angle = std::max(right_angle, std::abs(m.work(joint)[4]));
      body_x = std::max(body_x, std::abs(rot(1, 0)) + std::abs(rot(2, 0)));
      // The joint holds the body against the torque about its own Z axis.
      moment_error = std::max(moment_error, (work3(m.work(joint), 5) + spin_torque * rot.col(2)).norm());
    });
    sim.run({.end = 1.3 * exact, .out = h, .smax = h, .newton = tight_newton});
    REQUIRE(c.at.size() >= 2);
    CAPTURE(c.period());
    CAPTURE(exact);
    CHECK(std::abs(c.period() / exact - 1) < 2e-5);
    CHECK(gap < 1e-12);
    CHECK(right_angle < 1e-12);
    CHECK(body_x < 1e-12);
    CHECK(moment_error < 1e-6);
  }

  TEST_CASE("FIX3X: two welded bodies on an exact hinge swing as one compound pendulum") {
    // Body a (centre at the pivot) on REV3X about X; body b welded 0.4 below it.
    // I_O = Jxx_a + Jxx_b + m_b d^2, m g d = m_b g d.
    const double ma = 1.0, mb = 0.5, jxa = 0.02, jxb = 0.01, d = 0.4, theta0 = 30 * pi / 180, h = 1e-3;
    const double exact = pendulum_period(jxa + jxb + mb * d * d, mb * g * d, theta0);
    family_model m;
    const family_body a(m, "a", ma, {jxa, 0.02, 0.01});
    const family_body b(m, "b", mb, {jxb, 0.008, 0.004});
    const dof G = m.ground();
    m.add<exact_revolute_joint>("hinge", {{}, 1, 0, 0, 1, 0, 0}, G, G, G, G, G, G, a.x[0], a.x[1], a.x[2], a.r);
    const auto weld =
        m.add<exact_fixed_joint>("weld", {{0, 0, 0, 0, 0, -d / 2, 0, 0, -d, 0, 0, d / 2}, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0},
                                 a.x[0], a.x[1], a.x[2], a.r, b.x[0], b.x[1], b.x[2], b.r);
    m.add<spatial_force>("gravity", {0, 0, -mb * g, 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
    m.add<initial_rotation>("start_a", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, a.r);
    m.add<initial_rotation>("start_b", {1, 0, 0, theta0 * 180 / pi, 0, 0, 0}, b.r);
    m.add<initial_displacement>("y0", {d * std::sin(theta0)}, b.x[1]);
    m.add<initial_displacement>("z0", {d * (1 - std::cos(theta0))}, b.x[2]);
    simulation<family_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    crossings c;
    double gap = 0, angles = 0, relative = 0;
    sim.on_output([&](const auto& s) {
      const mat3 ra = node_rotation(s, a.r), rb = node_rotation(s, b.r);
      c.add(s.time(), std::atan2(rb(2, 1), rb(1, 1)));
      gap = std::max(gap, m.work(weld)[0]);
      angles = std::max(angles, std::abs(m.work(weld)[4]) + std::abs(m.work(weld)[5]));
      relative = std::max(relative, (ra.transpose() * rb - mat3::Identity()).norm());
    });
    sim.run({.end = 1.3 * exact, .out = h, .smax = h, .newton = tight_newton});
    REQUIRE(c.at.size() >= 2);
    CAPTURE(c.period());
    CAPTURE(exact);
    CHECK(std::abs(c.period() / exact - 1) < 2e-5);
    CHECK(gap < 1e-12);
    CHECK(angles < 1e-12);
    CHECK(relative < 1e-12);
  }

  TEST_CASE("PTL3X: a bead slides down an inclined wire with g sin(alpha) and spins freely under a torque") {
    const double mass = 1.2, jzz = 0.03, alpha = 40 * pi / 180, end = 0.5, h = 1e-3;
    const vec3 e(std::cos(alpha), 0, std::sin(alpha)), load(0, 0, -mass * g);
    family_model m;
    const family_body b(m, "bead", mass, {0.01, 0.02, jzz});
    const dof G = m.ground();
    const auto wire = m.add<exact_point_on_line>("wire", {{}, e.x(), e.y(), e.z()}, G, G, G, G, G, G, b.x[0], b.x[1],
                                                 b.x[2], b.r);
    m.add<spatial_force>("gravity", {load.x(), load.y(), load.z(), 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
    m.add<spatial_torque>("torque", {0, 0, 0.2, 0, 0, 0, 0, 0}, b.r);
    simulation<family_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    double theta = 0, prev = 0, off_line = 0;
    sim.on_output([&](const auto& s) {
      const mat3 rot = node_rotation(s, b.r);
      const double a = std::atan2(rot(1, 0), rot(0, 0));
      theta += std::remainder(a - prev, 2 * pi);
      prev = a;
      off_line = std::max(off_line, m.work(wire)[0]);
    });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    const double a = load.dot(e) / mass;
    const vec3 expected = 0.5 * a * end * end * e;
    CHECK((b.position(sim) - expected).norm() < 1e-9 * expected.norm());
    CHECK(m.work(wire)[4] == doctest::Approx(0.5 * a * end * end).epsilon(1e-9));
    CHECK(theta == doctest::Approx(0.2 * end * end / (2 * jzz)).epsilon(2e-5));
    CHECK(off_line < 1e-12);
    CHECK((work3(m.work(wire), 1) - (mass * a * e - load)).norm() < 1e-6);
  }

  TEST_CASE("PTP3X: a body slides on an inclined plane with the in-plane part of its loads; the normal force is "
            "m g cos(alpha)") {
    const double mass = 2.0, alpha = 25 * pi / 180, end = 0.5, h = 1e-3;
    const vec3 n(0, -std::sin(alpha), std::cos(alpha)), load(1.0, 0, -mass * g);
    family_model m;
    const family_body b(m, "block", mass, {0.1, 0.1, 0.1});
    const dof G = m.ground();
    const auto plane = m.add<exact_point_on_plane>("plane", {{}, n.x(), n.y(), n.z()}, G, G, G, G, G, G, b.x[0],
                                                   b.x[1], b.x[2], b.r);
    m.add<spatial_force>("loads", {load.x(), load.y(), load.z(), 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
    simulation<family_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    double off_plane = 0;
    sim.on_output([&](const auto&) { off_plane = std::max(off_plane, std::abs(m.work(plane)[0])); });
    sim.run({.end = end, .out = h, .smax = h, .newton = tight_newton});
    const vec3 acc = (load - load.dot(n) * n) / mass;
    const vec3 expected = 0.5 * acc * end * end;
    CHECK((b.position(sim) - expected).norm() < 1e-9 * expected.norm());
    CHECK(off_plane < 1e-12);
    CHECK((work3(m.work(plane), 1) - mass * g * std::cos(alpha) * n).norm() < 1e-6);
  }

  TEST_CASE("PIN2X: a planar compound pendulum at 60 degrees swings with the exact period, the pin closed") {
    const double mass = 1.0, j = 0.02, d = 0.5, theta0 = 60 * pi / 180, h = 1e-3;
    const double exact = pendulum_period(j + mass * d * d, mass * g * d, theta0);
    planar_pendulum p(mass, j, d, theta0);
    auto& m = p.m;
    const dof th = p.th;
    const auto pin = p.pin;
    simulation<planar_pendulum::model_type, alpha_family> sim(m, alpha_family(hht{-0.05}));
    crossings c;
    double gap = 0;
    sim.on_output([&](const auto& s) {
      c.add(s.time(), s.u(th));
      gap = std::max(gap, m.work(pin)[0]);
    });
    sim.run({.end = 1.3 * exact, .out = h, .smax = h, .newton = tight_newton});
    REQUIRE(c.at.size() >= 2);
    CAPTURE(c.period());
    CAPTURE(exact);
    CHECK(std::abs(c.period() / exact - 1) < 2e-5);
    CHECK(gap < 1e-12);
  }

  TEST_CASE("zero step: the pin force of a pendulum released at rest starts at its exact value") {
    // At rest at theta0: theta'' = -m g d sin(theta0) / I_O; the centre (d sin, -d cos)
    // accelerates tangentially by theta'' d (cos, sin); the pin force on the body is
    // m a_c - m g_vec.
    const double mass = 1.3, j = 0.02, d = 0.5, theta0 = 60 * pi / 180;
    planar_pendulum p(mass, j, d, theta0);
    auto& m = p.m;
    const dof th = p.th;
    const auto pin = p.pin;
    simulation<planar_pendulum::model_type, alpha_family> sim(m, alpha_family(hht{-0.05}));
    double fx0 = NAN, fy0 = NAN, acc0 = NAN;
    sim.on_output([&](const auto& s) {
      if (s.time() != 0.0) return;
      fx0 = m.work(pin)[1];
      fy0 = m.work(pin)[2];
      acc0 = s.a(th);
    });
    sim.run({.end = 1e-3, .out = 1e-3, .smax = 1e-3, .newton = tight_newton});
    const double alpha = -mass * g * d * std::sin(theta0) / (j + mass * d * d);
    CHECK(acc0 == doctest::Approx(alpha).epsilon(1e-9));
    CHECK(fx0 == doctest::Approx(mass * alpha * d * std::cos(theta0)).epsilon(1e-7));
    CHECK(fy0 == doctest::Approx(mass * alpha * d * std::sin(theta0) + mass * g).epsilon(1e-7));
  }

  TEST_CASE("zero step: the joint force of a spinning heavy top starts at its Newton-Euler value") {
    // Euler's equations about the pivot, I_O w' + w x I_O w = c x m g_vec, give w';
    // the centre accelerates by w' x c + w x (w x c); the joint force on the top is
    // m a_c - m g_vec. The spin makes the velocity term (dG/dt) v of the constraint
    // matter: without it the force would be off by m |w x (w x c)|.
    const double mass = 1.0, l = 0.1, j1 = 0.01, j3 = 0.02, w3 = 30.0, theta0 = 30 * pi / 180;
    family_model m;
    const family_body top(m, "top", mass, {j1, j1, j3});
    const dof G = m.ground();
    const vec3 axis0(0, -std::sin(theta0), std::cos(theta0)), c = l * axis0, w = w3 * axis0, gv(0, 0, -g);
    const auto joint = m.add<exact_spherical_joint>(
        "tip", {{0, 0, 0, 0, 0, 0, c.x(), c.y(), c.z(), 0, 0, -l}}, G, G, G, G, G, G, top.x[0], top.x[1], top.x[2],
        top.r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, top.x[0], top.x[1], top.x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, w.x(), w.y(), w.z()}, top.r);
    simulation<family_model, alpha_family> sim(m, alpha_family(newmark{}));
    vec3 f0 = vec3::Constant(NAN);
    sim.on_output([&](const auto& s) {
      if (s.time() == 0.0) f0 = work3(m.work(joint), 1);
    });
    sim.run({.end = 1e-4, .out = 1e-4, .smax = 1e-4, .newton = tight_newton});
    const mat3 rot = Eigen::AngleAxisd(theta0, vec3::UnitX()).toRotationMatrix();
    const mat3 io = rot * vec3(j1, j1, j3).asDiagonal() * rot.transpose() +
                    mass * (c.squaredNorm() * mat3::Identity() - c * c.transpose());
    const vec3 wd = io.inverse() * (c.cross(mass * gv) - w.cross(io * w));
    const vec3 expected = mass * (wd.cross(c) + w.cross(w.cross(c))) - mass * gv;
    CAPTURE(f0.transpose());
    CAPTURE(expected.transpose());
    CHECK((f0 - expected).norm() < 1e-6 * expected.norm());
  }

  // The heavy top on SPH3X (as in test_exact_joints.cpp) to `end` under error control:
  // the largest change of the energy (conserved, Goldstein section 5.7) relative to the
  // spin energy I3 w3^2 / 2, the largest joint gap, steps and error rejections.
  struct controlled_top {
    double energy = 0, gap = 0;
    run_statistics stats;
    mat3 rot = mat3::Identity();  ///< final rotation R(q)
    vec3 omega_b = vec3::Zero();  ///< final body angular velocity R^T omega
  };
  // The independent reference: Euler's equations of the same top about its fixed tip,
  // I_O w_b' + w_b x I_O w_b = r_c x R^T (0, 0, -m g), I_O = diag(j1 + m l^2, j1 + m l^2, j3),
  // r_c = (0, 0, l), with q' = (1/2) q (x) (w_b, 0), by RK4 at h = 1e-5 (Goldstein,
  // section 5.7). Returns (R, w_b) at `end`.
  std::pair<mat3, vec3> top_reference(double end) {
    const double mass = 1.0, l = 0.1, j1 = 0.01, j3 = 0.02, w3 = 30.0, theta0 = 30 * pi / 180;
    const vec3 io(j1 + mass * l * l, j1 + mass * l * l, j3);
    using state = Eigen::Matrix<double, 7, 1>;
    auto rhs = [&](const state& y) {
      const quaternion q = y.head<4>();
      const vec3 w = y.tail<3>();
      const vec3 torque = vec3(0, 0, l).cross(rotation_matrix(q).transpose() * vec3(0, 0, -mass * g));
      state d;
      d.head<4>() = 0.5 * multiply(q, quaternion(w.x(), w.y(), w.z(), 0));
      d.tail<3>() = (torque - w.cross(io.cwiseProduct(w))).cwiseQuotient(io);
      return d;
    };
    state y;
    y << std::sin(theta0 / 2), 0, 0, std::cos(theta0 / 2), 0, 0, w3;
    const int n = static_cast<int>(std::lround(end / 1e-5));
    const double h = end / n;
    for (int i = 0; i < n; ++i) {
      const state k1 = rhs(y), k2 = rhs(y + 0.5 * h * k1), k3 = rhs(y + 0.5 * h * k2), k4 = rhs(y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return {rotation_matrix(quaternion(y.head<4>())), y.tail<3>()};
  }
  namespace {  // internal linkage: the lambda below captures a type of the file's anonymous namespace
  template <class Scheme>
  controlled_top heavy_top_under_error_control(Scheme scheme, double tol, double end = 0.2, std::ostream* log = nullptr,
                                               double smin = 1e-11, newton_options newton = {}) {
    const double mass = 1.0, l = 0.1, j1 = 0.01, j3 = 0.02, w3 = 30.0, theta0 = 30 * pi / 180;
    family_model m;
    const family_body top(m, "top", mass, {j1, j1, j3});
    const dof G = m.ground();
    const vec3 axis0(0, -std::sin(theta0), std::cos(theta0)), c = l * axis0, w = w3 * axis0;
    const auto joint = m.add<exact_spherical_joint>(
        "tip", {{0, 0, 0, 0, 0, 0, c.x(), c.y(), c.z(), 0, 0, -l}}, G, G, G, G, G, G, top.x[0], top.x[1], top.x[2],
        top.r);
    m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, top.x[0], top.x[1], top.x[2]);
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / pi, w.x(), w.y(), w.z()}, top.r);
    simulation<family_model, alpha_family> sim(m, alpha_family(scheme));
    if (log) sim.log().to(*log);
    controlled_top out;
    double e0 = NAN;
    sim.on_step([&](const auto& s) {
      const mat3 rot = node_rotation(s, top.r);
      const vec3 om = node_angular_velocity(s, top.r), v(s.v(top.x[0]), s.v(top.x[1]), s.v(top.x[2]));
      const double e = 0.5 * mass * v.squaredNorm() +
                       0.5 * om.dot(rot * vec3(j1, j1, j3).asDiagonal() * rot.transpose() * om) +
                       mass * g * (c.z() + s.u(top.x[2]));
      if (std::isnan(e0)) e0 = e;
      out.energy = std::max(out.energy, std::abs(e - e0) / (0.5 * j3 * w3 * w3));
      out.gap = std::max(out.gap, m.work(joint)[0]);
    });
    out.stats = sim.run(
        {.end = end, .smax = 0.01, .smin = smin, .newton = newton, .error_control = true, .dabsx = tol, .drltx = tol});
    out.rot = node_rotation(sim, top.r);
    out.omega_b = out.rot.transpose() * node_angular_velocity(sim, top.r);
    return out;
  }
  }  // namespace

  TEST_CASE("error control with exact joints: the multipliers are left out of the error test; the energy error "
            "falls with the tolerance and is below it") {
    // Measured: 127, 1210 and 12058 steps at DRLTX = 1e-4, 1e-6, 1e-8, no rejection; the
    // energy error falls in proportion (2.9e-6, 2.3e-8, 2.3e-10 of I3 w3^2 / 2).
    std::vector<double> energy;
    for (double tol : {1e-4, 1e-6, 1e-8}) {
      CAPTURE(tol);
      const controlled_top r = heavy_top_under_error_control(hht{-0.05}, tol);
      CAPTURE(r.energy);
      CHECK(r.energy < tol);
      CHECK(r.gap < 1e-12);
      CHECK(r.stats.error_rejections <= r.stats.steps / 100);
      CHECK(r.stats.rejected_steps == 0);
      energy.push_back(r.energy);
    }
    CHECK(energy[1] < energy[0] / 30);
    CHECK(energy[2] < energy[1] / 30);
  }

  TEST_CASE("the heavy top on SPH3X under error control at 1e-8 agrees with Euler's equations about the tip to "
            "1e-6") {
    // Measured: rotation error 3.2e-8 rad, body angular velocity error 3.4e-9 (relative)
    // after 0.2 s (the axis precesses and nutates; 6 rad of spin).
    const controlled_top r = heavy_top_under_error_control(hht{-0.05}, 1e-8);
    const auto [rot, omega_b] = top_reference(0.2);
    const double angle = Eigen::AngleAxisd(rot.transpose() * r.rot).angle();
    const double rate = (r.omega_b - omega_b).norm() / omega_b.norm();
    CAPTURE(angle);
    CAPTURE(rate);
    CHECK(angle < 1e-6);
    CHECK(rate < 1e-6);
    CHECK((r.rot * vec3::UnitZ() - vec3(0, -std::sin(pi / 6), std::cos(pi / 6))).norm() > 0.01);  // it has moved
  }

  TEST_CASE("the heavy top on SPH3X started at SMIN = 1e-12 s under HHT at 1e-8: the error test's round-off floor "
            "lets the first steps grow") {
    // Error control starts at SMIN. There the step's accelerations carry the round-off of the
    // displacements over beta h^2 (Newton, with the work-precision benchmark's tolerances
    // DABSU = DRLTU = 1e-11, holds the joint's positions to round-off), and the estimate
    // about eps |u| / h: 2.8e-6 on q1 at h = 1e-12 s, above DRLTX = 1e-8, so the steps shrank
    // below SMIN at t = 4e-8 s (code 141) until the test counted that floor
    // (step_control.hpp). Checked against Euler's equations about the tip (RK4) after 0.05 s.
    const newton_options tight{.dabsu = 1e-11, .drltu = 1e-11, .dabsi = 1e-8, .drlti = 1e-11, .itr = 8};
    const controlled_top r = heavy_top_under_error_control(hht{-0.1}, 1e-8, 0.05, nullptr, 1e-12, tight);
    const auto [rot, omega_b] = top_reference(0.05);
    const double angle = Eigen::AngleAxisd(rot.transpose() * r.rot).angle();
    const double rate = (r.omega_b - omega_b).norm() / omega_b.norm();
    MESSAGE("HHT-0.1 from SMIN 1e-12 at 1e-8: ", r.stats.steps, " steps, rotation error ", angle, " rad, rate error ",
            rate, ", energy ", r.energy, ", gap ", r.gap, " m");
    CHECK(angle < 1e-6);
    CHECK(rate < 1e-6);
    CHECK(r.energy < 1e-8);
    CHECK(r.gap < 1e-12);
  }

  TEST_CASE("error control with exact joints under undamped NEWMARK: a failure at SMIN names the cause") {
    // The multipliers alternate under NEWMARK (no numerical damping); the alternation
    // reaches the accelerations the error estimate differences.
    std::ostringstream log;
    try {
      heavy_top_under_error_control(newmark{}, 1e-3, 1.0, &log);
      FAIL("NEWMARK was expected to fail at SMIN on this model");
    } catch (const error& e) {
      CHECK(e.code() == error_code::step_too_small);
      CHECK(std::string(e.what()).find("constraint multipliers and NEWMARK") != std::string::npos);
      CHECK(std::string(e.what()).find("use HHT or GALPHA") != std::string::npos);
    }
  }

  TEST_CASE("bdf_simulation warns about exact joints in the plain index-3 form only") {
    using planar_model = exact_joint_family_model;
    for (const bool stabilised : {true, false}) {
      CAPTURE(stabilised);
      planar_model m;
      const dof x = m.add_dof("x"), y = m.add_dof("y"), th = m.add_dof("theta"), G = m.ground();
      m.add<planar_inertia>("body", {1.0, 0.02}, x, y, th);
      m.add<planar_pin_joint>("pin", {0, 0, 0, 0, 0, -0.5, 0, 0.5}, G, G, G, x, y, th);
      m.add<constant_force>("weight", {-g}, y);
      bdf_simulation<planar_model> sim(m, bdf_options{.stabilised_index2 = stabilised});
      std::ostringstream log;
      sim.log().to(log);
      run_options o;
      o.end = 0.01;
      o.smax = 1e-3;
      sim.run(o);
      CHECK((log.str().find("warning: the model has index-3 constraints") != std::string::npos) == !stabilised);
    }
  }

  TEST_CASE("bad parameters of the exact joint family stop the run with code 100 naming the joint") {
    struct bad_case {
      std::string type, message;
      std::function<void(family_model&, const family_body&, dof)> add;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<bad_case> cases{
        {"UNI3X", "cross axis e_b",
         [](family_model& m, const family_body& b, dof G) {
           m.add<exact_universal_joint>("joint", {{}, 1, 0, 0, 0, 0, 0}, G, G, G, G, G, G, b.x[0], b.x[1], b.x[2], b.r);
         }},
        {"CYL3X", "not finite",
         [nan](family_model& m, const family_body& b, dof G) {
           m.add<exact_cylindrical_joint>("joint", {{0, 0, 0, 0, 0, 0, 0, 0, nan, 0, 0, 0}, 0, 0, 1, 0, 0, 1}, G, G, G,
                                          G, G, G, b.x[0], b.x[1], b.x[2], b.r);
         }},
        {"CYL3X", "axis e_a",
         [](family_model& m, const family_body& b, dof G) {
           m.add<exact_cylindrical_joint>("joint", {{}, 0, 0, 0, 0, 0, 1}, G, G, G, G, G, G, b.x[0], b.x[1], b.x[2],
                                          b.r);
         }},
        {"PRI3X", "reference vector t_a is parallel to the axis e_a",
         [](family_model& m, const family_body& b, dof G) {
           m.add<exact_prismatic_joint>("joint", {{}, 0, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0, 0}, G, G, G, G, G, G, b.x[0],
                                        b.x[1], b.x[2], b.r);
         }},
        {"FIX3X", "t_b",
         [](family_model& m, const family_body& b, dof G) {
           m.add<exact_fixed_joint>("joint", {{}, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0}, G, G, G, G, G, G, b.x[0], b.x[1],
                                    b.x[2], b.r);
         }},
        {"PTL3X", "direction e",
         [](family_model& m, const family_body& b, dof G) {
           m.add<exact_point_on_line>("joint", {{}, 0, 0, 0}, G, G, G, G, G, G, b.x[0], b.x[1], b.x[2], b.r);
         }},
        {"PTP3X", "normal n",
         [nan](family_model& m, const family_body& b, dof G) {
           m.add<exact_point_on_plane>("joint", {{}, 0, nan, 1}, G, G, G, G, G, G, b.x[0], b.x[1], b.x[2], b.r);
         }},
    };
    for (const bad_case& c : cases) {
      CAPTURE(c.type);
      CAPTURE(c.message);
      family_model m;
      const family_body b(m, "body", 1.0, {1, 1, 1});
      c.add(m, b, m.ground());
      simulation sim(m);
      try {
        sim.run({.end = 0.01, .smax = 1e-3});
        FAIL("must throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::invalid_parameter);
        CHECK(e.element_type() == c.type);
        CHECK(e.instance() == "joint");
        CHECK(std::string(e.what()).find(c.message) != std::string::npos);
      }
    }
  }

  TEST_CASE("PIN2X with a non-finite parameter stops the run with code 100 naming the pin") {
    using planar_model = exact_joint_family_model;
    planar_model m;
    const dof x = m.add_dof("x"), y = m.add_dof("y"), th = m.add_dof("theta"), G = m.ground();
    m.add<planar_inertia>("body", {1.0, 0.1}, x, y, th);
    m.add<planar_pin_joint>("pin", {0, 0, 0, 0, 0, std::numeric_limits<double>::infinity(), 0, 0}, G, G, G, x, y, th);
    simulation sim(m);
    try {
      sim.run({.end = 0.01, .smax = 1e-3});
      FAIL("must throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_parameter);
      CHECK(e.element_type() == "PIN2X");
      CHECK(e.instance() == "pin");
      CHECK(std::string(e.what()).find("not finite") != std::string::npos);
    }
  }
}
