#pragma once
/// \file
/// The heavy symmetric top of examples/spinning_top, as a reusable scene (the example,
/// and the benchmark of time per simulated second in bench/bench_mechanisms.cpp).

#include <cmath>
#include <numbers>
#include <vector>

#include "pradis/elements/library.hpp"

namespace pradis_examples {

/// The data of the scene (all settable from outside, e.g. the example's --k and --exact).
struct top_parameters {
  double mass = 1.0;      ///< mass [kg]
  double l = 0.1;         ///< tip to centre of mass [m]
  double j1 = 0.01;       ///< transverse inertia about the centre of mass [kg m^2]
  double j3 = 0.02;       ///< polar inertia [kg m^2]
  double w3 = 30.0;       ///< spin [rad/s]
  double theta0 = 30 * std::numbers::pi / 180;  ///< initial tilt [rad]
  double k = 1e6;         ///< joint penalty stiffness [N/m] (SPH3; unused with exact_joint)
  bool exact_joint = false;  ///< hold the tip with the exact SPH3X instead of the penalty SPH3
  /// No joint: BODY3's reference point is the tip itself (translations grounded, centre of mass
  /// l along body Z from it) and the weight is F3A at the centre of mass (overrides exact_joint).
  bool pivot = false;
  /// With exact_joint: the tip held by a ground pivot, SPH3X's reduced form without multipliers
  /// (pradis::elements::add_ground_pivot; the body's translations follow its rotation).
  bool ground_pivot = false;
};

/// A rigid body (BODY3) symmetric about its Z axis, its tip held at the origin by a
/// spherical joint (SPH3, penalty stiffness k, or the exact SPH3X), under gravity (a
/// constant F3 on the centre of mass), spinning at w3 about its axis, released at
/// theta0 from the vertical with no precession or nutation rate (Goldstein, Classical
/// Mechanics, 3rd ed., section 5.7). With `pivot` the same top has its node at the tip
/// and no joint: the rotational node alone, the motion about a fixed point.
struct spinning_top {
  static constexpr double g = 9.81;
  double mass;        ///< mass [kg]
  double l;           ///< tip to centre of mass [m]
  double j1;          ///< transverse inertia about the centre of mass [kg m^2]
  double j3;          ///< polar inertia [kg m^2]
  double w3;          ///< spin [rad/s]
  double theta0;      ///< initial tilt [rad]
  double k;           ///< joint penalty stiffness [N/m]
  bool exact_joint;   ///< SPH3X instead of SPH3
  bool pivot;         ///< node at the tip, no joint
  bool ground_pivot;  ///< with exact_joint: a ground pivot instead of SPH3X

  using model_type =
      pradis::model<pradis::elements::rigid_body, pradis::elements::spherical_joint,
                    pradis::elements::exact_spherical_joint, pradis::elements::spatial_force,
                    pradis::elements::offset_force, pradis::elements::initial_rotation>;
  model_type m;
  std::vector<pradis::dof> x;  ///< the centre of mass (with `pivot`: the tip, three times the ground)
  pradis::rotation_node r;     ///< the top's orientation

  /// Damping of the joint's stiff mode, 0.4 sqrt(k m) (a damping ratio of 0.2) [N s/m].
  double joint_damping() const { return 0.4 * std::sqrt(k * mass); }

  /// The axis (body Z) at the start, after the tilt about X.
  pradis::spatial::vec3 axis0() const { return {0, -std::sin(theta0), std::cos(theta0)}; }

  explicit spinning_top(const top_parameters& p = {})
      : mass(p.mass), l(p.l), j1(p.j1), j3(p.j3), w3(p.w3), theta0(p.theta0), k(p.k), exact_joint(p.exact_joint),
        pivot(p.pivot), ground_pivot(p.ground_pivot) {
    using namespace pradis::elements;
    const pradis::dof G = m.ground();
    const pradis::spatial::vec3 a = axis0();
    if (pivot) {
      x = {G, G, G};
      r = m.add_rotation_node("r");
      m.add<rigid_body>("top", {mass, j1, j1, j3, 0, 0, 0, 0, 0, l}, G, G, G, r);
      m.add<offset_force>("gravity", {0, 0, l, {0, 0, -mass * g, 0, 0, 0, 0, 0}}, G, G, G, r);
    } else {
      x = m.add_dofs(3, "x");
      r = m.add_rotation_node("r");
      m.add<rigid_body>("top", {mass, j1, j1, j3, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
      // Joint point A: the origin (ground); B: the tip, l below the centre of mass along body Z.
      const pradis::elements::detail::joint_geometry tip{0, 0, 0, 0, 0, 0, l * a.x(), l * a.y(), l * a.z(), 0, 0, -l};
      if (exact_joint && ground_pivot)
        pradis::elements::add_ground_pivot(m, "tip", tip, x[0], x[1], x[2], r);
      else if (exact_joint)
        m.add<exact_spherical_joint>("tip", {tip}, G, G, G, G, G, G, x[0], x[1], x[2], r);
      else
        m.add<spherical_joint>("tip", {tip, k, joint_damping()}, G, G, G, G, G, G, x[0], x[1], x[2], r);
      m.add<spatial_force>("gravity", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    }
    m.add<initial_rotation>("start", {1, 0, 0, theta0 * 180 / std::numbers::pi, w3 * a.x(), w3 * a.y(), w3 * a.z()},
                            r);
  }
  spinning_top(const spinning_top&) = delete;
  spinning_top& operator=(const spinning_top&) = delete;
};

}  // namespace pradis_examples
