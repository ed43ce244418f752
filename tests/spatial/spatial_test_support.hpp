#pragma once
// Shared scenes of the spatial tests: a free rigid body (BODY3) on a translational
// point and a rotational node, started by ROT0 with a global angular velocity.

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "pradis/pradis.hpp"
#include "pradis/spatial/node_state.hpp"

namespace pradis_spatial_tests {

inline constexpr double pi = std::numbers::pi;
/// Standard gravity used by the spatial scenes [m/s^2].
inline constexpr double g = 9.81;

/// BODY3 parameters: mass and principal moments of inertia, no initial motion.
inline pradis::elements::rigid_body::parameters body(double m, double jx, double jy, double jz) {
  return {m, jx, jy, jz, 0, 0, 0, 0, 0, 0};
}

/// Wall-clock seconds since t0 (reported by the tests next to their figures).
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Newton tolerances far below every accuracy the spatial tests check.
inline constexpr pradis::newton_options tight_newton{.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-10, .drlti = 0};

/// Free rigid body with principal inertias (i1, i2, i3) about body axes aligned with the
/// global axes at t = 0, centre of mass at the reference point, initial global angular
/// velocity w0 (ROT0 with angle 0).
struct free_body {
  using model_type = pradis::model<pradis::elements::rigid_body, pradis::elements::initial_rotation>;
  model_type m;
  std::vector<pradis::dof> x;
  pradis::rotation_node r;
  pradis::element_ref<pradis::elements::rigid_body> body;
  pradis::spatial::vec3 inertia;

  free_body(pradis::spatial::vec3 i, pradis::spatial::vec3 w0,
            pradis::elements::initial_rotation::parameters start = {1, 0, 0, 0, 0, 0, 0})
      : inertia(i) {
    x = m.add_dofs(3, "x");
    r = m.add_rotation_node("r");
    body = m.add<pradis::elements::rigid_body>("body", {1.0, i.x(), i.y(), i.z(), 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    start.wx = w0.x();
    start.wy = w0.y();
    start.wz = w0.z();
    m.add<pradis::elements::initial_rotation>("start", start, r);
  }
  /// Body-frame angular momentum I omega' of the current state.
  template <class Sim>
  pradis::spatial::vec3 body_momentum(const Sim& s) const {
    return inertia.cwiseProduct(pradis::spatial::node_body_angular_velocity(s, r));
  }
  /// Kinetic energy of rotation (1/2) omega' . I omega'.
  template <class Sim>
  double energy(const Sim& s) const {
    const pradis::spatial::vec3 w = pradis::spatial::node_body_angular_velocity(s, r);
    return 0.5 * w.dot(inertia.cwiseProduct(w));
  }
};

}  // namespace pradis_spatial_tests
