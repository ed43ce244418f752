#pragma once
/// \file
/// The rotational nodes of a model whose four DOFs q1..q4 are all free
/// equations, with their DOFs and equations: the nodes that the rate form
/// (rate_form.hpp) and the turned Newton matrix (rotated_jacobian.hpp) of
/// pradis::bdf_simulation act on. A node with a component on the ground or held
/// by a kinematic source is left out. body_fixed_nodes() tells which nodes turn
/// their elements' flows with them (core/element.hpp, HasBodyFixedFlows).

#include <array>
#include <cstddef>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pradis/core/element.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/model/handles.hpp"

namespace pradis::bdf_detail {

/// A rotational node with four free DOFs.
struct free_rotation_node {
  std::array<int, 4> dof{};  ///< global DOFs of q1..q4
  std::array<int, 4> eq{};   ///< their equations
  int node = -1;             ///< index among the model's rotational nodes
};

/// The rotational nodes whose four DOFs are free equations of `as`.
template <class Assembler>
std::vector<free_rotation_node> free_rotation_nodes(const std::vector<rotation_node_record>& nodes,
                                                    const Assembler& as) {
  std::vector<free_rotation_node> out;
  for (const rotation_node_record& n : nodes) {
    free_rotation_node e;
    e.node = static_cast<int>(&n - nodes.data());
    bool free = true;
    for (std::size_t j = 0; j < 4; ++j) {
      e.dof[j] = n.dofs[j];
      e.eq[j] = e.dof[j] > 0 ? as.equation_of(e.dof[j]) : -1;
      free = free && e.eq[j] >= 0;
    }
    if (free) out.push_back(e);
  }
  return out;
}

/// For each rotational node of m: whether every element connected to it (to
/// q1, q2, q3 or q4) connects through a rotational slot and has body-fixed flows
/// (body_fixed_flows_of). An element on a node's q1..q3 without a slot (a
/// moment source about a global axis, a spring of one DOF) makes it false, as
/// does a node no element is connected to.
template <class Model>
std::vector<char> body_fixed_nodes(const Model& m) {
  const auto& nodes = m.rotation_nodes();
  std::vector<char> fixed(nodes.size(), 0), seen(nodes.size(), 0);
  std::unordered_map<int, std::size_t> node_of;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    fixed[i] = 1;
    for (const int d : nodes[i].dofs)
      if (d > 0) node_of[d] = i;
  }
  m.for_each_instances([&](const auto& vec) {
    using I = typename std::remove_cvref_t<decltype(vec)>::value_type;
    using E = std::remove_cvref_t<decltype(std::declval<I&>().element)>;
    constexpr auto slots = rotation_slots_of<E>();
    for (const auto& inst : vec) {
      const bool body = body_fixed_flows_of(inst.element);
      for (std::size_t k = 0; k < inst.dofs.size(); ++k) {
        const auto it = node_of.find(inst.dofs[k]);
        if (it == node_of.end()) continue;
        const int local = static_cast<int>(k);
        bool in_slot = false;
        for (const rotation_slot& sl : slots)
          in_slot = in_slot || local == sl.q4 || (local >= sl.q1 && local < sl.q1 + 3);
        seen[it->second] = 1;
        if (!(in_slot && body)) fixed[it->second] = 0;
      }
    }
  });
  // A node that a slaving node kind carries flows to (core/node_kind.hpp, K::slaved) gets
  // them in global axes (a joint force at an offset): not body-fixed.
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& knodes) {
    if constexpr (SlavingNodeKind<K>)
      for (const auto& kn : knodes)
        for (const int d : kn.dofs) {
          const auto it = node_of.find(d);
          if (it != node_of.end()) fixed[it->second] = 0;
        }
  });
  for (std::size_t i = 0; i < nodes.size(); ++i) fixed[i] = fixed[i] && seen[i];
  return fixed;
}

}  // namespace pradis::bdf_detail
