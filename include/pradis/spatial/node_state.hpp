#pragma once
/// \file
/// Reading the state of a spatial rotational node from a simulation: its
/// quaternion q = (q1, q2, q3, q4) (including the hidden q4), q', q'', the rotation
/// matrix, the global and body angular velocities, and the position and
/// velocity of a point fixed in a body (body_point).

#include <array>

#include "pradis/model/model.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::spatial {

/// The quaternion of a rotational node (u of q1..q4; a component fixed to the ground reads 0).
template <class Sim>
quaternion node_quaternion(const Sim& sim, const rotation_node& n) {
  return quaternion(sim.u(n.q1), sim.u(n.q2), sim.u(n.q3), sim.u(n.q4));
}
/// q' of a rotational node (not the angular velocity: see node_angular_velocity).
template <class Sim>
quaternion node_rate(const Sim& sim, const rotation_node& n) {
  return quaternion(sim.v(n.q1), sim.v(n.q2), sim.v(n.q3), sim.v(n.q4));
}
/// q'' of a rotational node.
template <class Sim>
quaternion node_acceleration(const Sim& sim, const rotation_node& n) {
  return quaternion(sim.a(n.q1), sim.a(n.q2), sim.a(n.q3), sim.a(n.q4));
}
/// Lq = |q| of a rotational node (1 at the start; the norm equation keeps it there).
template <class Sim>
double node_norm(const Sim& sim, const rotation_node& n) {
  return node_quaternion(sim, n).norm();
}
/// Rotation matrix (body -> global) of a rotational node.
template <class Sim>
mat3 node_rotation(const Sim& sim, const rotation_node& n) {
  return rotation_matrix(node_quaternion(sim, n));
}
/// Global angular velocity (2/s) E(q) q' of a rotational node.
template <class Sim>
vec3 node_angular_velocity(const Sim& sim, const rotation_node& n) {
  return global_angular_velocity(node_quaternion(sim, n), node_rate(sim, n));
}
/// Body angular velocity (2/s) G(q) q' of a rotational node.
template <class Sim>
vec3 node_body_angular_velocity(const Sim& sim, const rotation_node& n) {
  return body_angular_velocity(node_quaternion(sim, n), node_rate(sim, n));
}

/// Global position and velocity of a point fixed in a body.
struct point_motion {
  vec3 position;  ///< p = X0 + x + R(q) a [m]
  vec3 velocity;  ///< v = x' + omega x R(q) a [m/s]
};
/// The motion of the point at `offset` (body frame) of the body whose reference
/// point started at the global position `x0`, moves by the translational DOFs `x`
/// (X, Y, Z) and turns with the rotational node `n` (the same convention as the
/// joints and attachments of SD3, SPH3, SPH3X: p = X0 + x + R(q) a).
template <class Sim>
point_motion body_point(const Sim& sim, const std::array<dof, 3>& x, const rotation_node& n, const vec3& x0,
                        const vec3& offset) {
  const vec3 rho = node_rotation(sim, n) * offset;
  const vec3 xd(sim.v(x[0]), sim.v(x[1]), sim.v(x[2]));
  return {x0 + vec3(sim.u(x[0]), sim.u(x[1]), sim.u(x[2])) + rho, xd + node_angular_velocity(sim, n).cross(rho)};
}

}  // namespace pradis::spatial
