#pragma once
/// \file
/// The handles and records of a model: a DOF, a spatial rotational node, a
/// reference to a placed element, a placed element with its DOFs and pools, and
/// where an instance lives. model.hpp includes this; user code rarely needs it
/// alone.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis {

/// A degree of freedom (node) of a model. DOF 0 is the ground: fixed at zero.
/// A DOF handed out by a model carries that model's serial number, so that the
/// model and its simulation refuse a DOF of another model (code 110 or 120); a
/// DOF made from a bare index (`dof{3}`) has owner 0 and is taken by any model.
/// Two DOFs compare equal when their indices do.
struct dof {
  int index = 0;
  std::uint32_t owner = 0;  ///< serial number of the model that made it (0: none)
  friend constexpr bool operator==(dof a, dof b) noexcept { return a.index == b.index; }
};

namespace detail {
/// A new serial number for a model (never 0).
inline std::uint32_t next_model_serial() noexcept {
  static std::atomic<std::uint32_t> n{0};
  std::uint32_t s = ++n;
  if (s == 0) s = ++n;  // after wrap-around
  return s;
}
}  // namespace detail

/// A spatial rotational node (PRADIS's four rotational potentials of a point in
/// spatial motion): the non-normalised quaternion q = (q1, q2, q3, q4). q1, q2, q3
/// are external DOFs: the user connects, fixes (connects to the ground) or loads
/// only these, and their flows are the moments about the global X, Y, Z axes. q4 is
/// the hidden fourth potential: an internal DOF the user never names, initialised
/// to 1 and shared by every element connected to the node; its norm equation
/// Mu d|q|/dt is assembled once per node (spatial::rotation_node_kind, a node kind of
/// core/node_kind.hpp; see docs/rotations.md).
struct rotation_node {
  dof q1{}, q2{}, q3{};  ///< external potentials (a component connected to the ground is fixed)
  dof q4{};              ///< the hidden fourth potential
  int index = -1;        ///< index among the model's rotational nodes
};

/// What the model keeps about a rotational node.
struct rotation_node_record {
  std::string name;                 ///< node name (used in messages)
  std::array<int, 4> dofs{};        ///< global indices of q1, q2, q3 (0 = fixed to the ground) and of the hidden q4
  std::string owner_type;           ///< catalog name of the first element connected through a rotational slot
  std::string owner_instance;       ///< instance name of that element (errors of the node name it)
};

/// Handle to an element instance of type E in a model.
template <class E>
struct element_ref {
  int index = -1;
};

/// One placed element: the element object, its instance name, the global
/// indices of its N = EXT + ENT DOFs, its parameter count and where its work and
/// state vectors live in the model's pools.
template <class E>
struct element_instance {
  static constexpr int n = element_traits<E>::n;
  E element;
  std::string name;
  std::array<int, n> dofs{};
  int npar = 0;
  std::size_t work_offset = 0, work_size = 0;
  std::size_t state_offset = 0, state_size = 0;
};

/// Where an instance lives: the index of its type in the model's list and its index among that type's instances.
struct instance_location {
  std::size_t type = 0;
  int index = -1;
};

}  // namespace pradis
