// SHC3, the shaft coupling from a one-dimensional rotation to a spatial rotational
// node (PRADIS's Fig. 2): a body driven through it by a velocity source follows the
// exact solution of the twist oscillator over several revolutions about a skew axis;
// a constant moment twists a coupling in series with a one-dimensional spring by the
// static M / k + M / k1; bad parameters stop the run with code 100 and an undefined
// twist (the node turned 180 degrees about a perpendicular axis) with code 75.

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <numbers>

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
/// An isotropic body: mass m, central inertia j about every axis.
rigid_body::parameters sphere(double m, double j) { return {m, j, j, j, 0, 0, 0, 0, 0, 0}; }
}  // namespace

/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using coupling_model = pradis::model<rigid_body, shaft_coupling, velocity_source, spatial_torque, point_mass,
    linear_spring, linear_damper, revolute_joint, initial_rotation>;
TEST_SUITE("spatial/coupling") {
  TEST_CASE("SHC3: a velocity source drives a body over three revolutions about a skew axis; the twist is the exact "
            "damped oscillation") {
    // The 1D end turns at the constant rate W (VSRC, phi = W t); the body (isotropic inertia J,
    // centre fixed) starts at rest. Its angle theta about the axis obeys J theta'' = -k e - c e',
    // e = theta - phi, so J e'' + c e' + k e = 0 with e(0) = 0, e'(0) = -W:
    // e(t) = -(W / wd) exp(-sigma t) sin(wd t), sigma = c / (2 J), wd = sqrt(k / J - sigma^2)
    // (damped free vibration, e.g. Meirovitch, Elements of Vibration Analysis, 2.4). The body
    // must turn about the axis only: its orientation is the rotation by W t + e(t) about a.
    const auto t0 = std::chrono::steady_clock::now();
    const double j = 0.1, k = 40.0, c = 0.4, w = 2 * pi, h = 1e-3, end = 3.0;
    const vec3 a = vec3(1, 2, 2) / 3.0;
    coupling_model m;
    const dof phi = m.add_dof("phi");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", sphere(1, j), G, G, G, r);
    const auto cp = m.add<shaft_coupling>("shaft", {1, 2, 2, k, c, 0}, phi, r);
    m.add<velocity_source>("drive", {0, 0, 0, w}, phi);
    simulation sim(m);
    const double sigma = c / (2 * j), wd = std::sqrt(k / j - sigma * sigma), wn = std::sqrt(k / j);
    double worst_twist = 0, worst_orientation = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), e = -(w / wd) * std::exp(-sigma * t) * std::sin(wd * t);
      worst_twist = std::max(worst_twist, std::abs(m.work(cp)[0] - e));
      const quaternion expected = from_axis_angle(a, w * t + e);
      worst_orientation =
          std::max(worst_orientation, to_axis_angle(relative_rotation(node_quaternion(s, r), expected)).angle);
    });
    sim.run({.end = end, .out = 0.01, .smax = h, .newton = tight_newton});
    // Trapezoidal phase error of the oscillation, wn^3 h^2 t / 12 times its amplitude W / wn.
    const double bound = wn * wn * wn * h * h * end / 12 * (w / wn);
    MESSAGE("SHC3 drive: max twist error ", worst_twist, " rad, max orientation error ", worst_orientation,
            " rad (amplitude ", w / wd, " rad, bound ", bound, "), ", w * end / (2 * pi), " revolutions, ",
            seconds_since(t0), " s");
    CHECK(worst_twist < bound);
    CHECK(worst_orientation < bound);
    // The shaft torque at the end is J theta'' = J e'' (the 1D side is a kinematic source).
    const double t = end, ex = std::exp(-sigma * t), sn = std::sin(wd * t), cs = std::cos(wd * t);
    const double e2 = -(w / wd) * ex * ((sigma * sigma - wd * wd) * sn - 2 * sigma * wd * cs);
    CHECK(m.work(cp)[2] == doctest::Approx(-j * e2).epsilon(1e-2).scale(1e-3 * k * w / wd));
  }

  TEST_CASE("SHC3 in series with a one-dimensional spring: a moment about the axis twists both by M / k and M / k1") {
    // A moment M a on the node, the 1D end held by a torsion spring k1 (SPRING to the ground)
    // with a rotational inertia and damping so that the motion settles, the node in a REV3
    // bearing about a (without it the swing perpendicular to a is free, and a constant global
    // moment on a free body is not conservative): statics of two springs
    // in series, delta = M / k, phi = M / k1, the node's angle about a = M / k + M / k1. The
    // signs check that the coupling passes the torque to the 1D side as a flow.
    const double k = 50.0, k1 = 20.0, mom = 3.0;
    const vec3 a = vec3(2, -1, 2) / 3.0;
    coupling_model m;
    const dof phi = m.add_dof("phi");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", sphere(1, 0.05), G, G, G, r);
    const auto cp = m.add<shaft_coupling>("shaft", {2, -1, 2, k, 2.0, 0}, phi, r);
    m.add<spatial_torque>("load", {.p0x = mom * a.x(), .p0y = mom * a.y(), .p0z = mom * a.z()}, r);
    m.add<point_mass>("J1", {0.05}, phi);
    m.add<linear_spring>("k1", {k1}, phi, G);
    m.add<linear_damper>("c1", {1.5}, phi, G);
    m.add<revolute_joint>("bearing", {{}, a.x(), a.y(), a.z(), a.x(), a.y(), a.z(), 1e6, 0, 1e5, 10.0}, G, G, G, G, G, G,
                          G, G, G, r);
    simulation sim(m);
    sim.run({.end = 20.0, .smax = 1e-2, .newton = tight_newton});
    const quaternion q = node_quaternion(sim, r);
    const axis_angle aa = to_axis_angle(q);
    MESSAGE("SHC3 statics: twist ", m.work(cp)[0], " (M/k = ", mom / k, "), phi ", sim.u(phi), " (M/k1 = ", mom / k1,
            "), node angle ", aa.angle, " about (", aa.axis.transpose(), ")");
    CHECK(m.work(cp)[0] == doctest::Approx(mom / k).epsilon(1e-7));
    CHECK(m.work(cp)[2] == doctest::Approx(mom).epsilon(1e-7));
    CHECK(sim.u(phi) == doctest::Approx(mom / k1).epsilon(1e-7));
    CHECK(aa.angle == doctest::Approx(mom / k + mom / k1).epsilon(1e-7));
    CHECK((aa.axis - a).norm() < 1e-9);
  }

  TEST_CASE("SHC3 with a zero axis, k <= 0, c < 0 or a non-finite parameter stops the run with code 100 in its name") {
    struct bad {
      shaft_coupling::parameters p;
      const char* mention;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const bad b : {bad{{0, 0, 0, 10, 1, 0}, "zero axis"}, bad{{0, 0, 1, 0, 1, 0}, "k <= 0"},
                        bad{{0, 0, 1, -5, 1, 0}, "k <= 0"}, bad{{0, 0, 1, 10, -1, 0}, "c < 0"},
                        bad{{0, nan, 1, 10, 1, 0}, "must be finite"}, bad{{0, 0, 1, 10, 1, nan}, "must be finite"}}) {
      coupling_model m;
      const dof phi = m.add_dof("phi");
      const rotation_node r = m.add_rotation_node("r");
      const dof G = m.ground();
      m.add<rigid_body>("body", sphere(1, 1), G, G, G, r);
      m.add<shaft_coupling>("cpl", b.p, phi, r);
      simulation sim(m);
      check_error(error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); }), error_code::invalid_parameter, "SHC3",
                  "cpl", b.mention);
    }
  }

  TEST_CASE("SHC3 whose node starts turned 180 degrees about an axis perpendicular to the shaft stops with code 75") {
    // The twist about a is undefined there (t = a.v = 0 and w = 0).
    coupling_model m;
    const dof phi = m.add_dof("phi");
    const rotation_node r = m.add_rotation_node("r");
    const dof G = m.ground();
    m.add<rigid_body>("body", sphere(1, 1), G, G, G, r);
    m.add<shaft_coupling>("cpl", {0, 0, 1, 10, 1, 0}, phi, r);
    m.add<initial_rotation>("flip", {1, 0, 0, 180, 0, 0, 0}, r);
    simulation sim(m);
    check_error(error_from([&] { sim.run({.end = 0.1, .smax = 0.01}); }), error_code::singular_situation, "SHC3", "cpl",
                "180 degrees about an axis perpendicular");
  }
}
