#pragma once
/// \file
/// Reading the state of a spatial rotational node from a simulation: its
/// quaternion q = (q1, q2, q3, q4) (including the hidden q4), q', q'', the rotation
/// matrix, and the global and body angular velocities.

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

}  // namespace pradis::spatial
