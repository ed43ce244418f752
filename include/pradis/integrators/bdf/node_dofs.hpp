#pragma once
/// \file
/// The rotational nodes of a model whose four DOFs q1..q4 are all free
/// equations, with their DOFs and equations: the nodes that the rate form
/// (rate_form.hpp) and the turned Newton matrix (rotated_jacobian.hpp) of
/// pradis::bdf_simulation act on. A node with a component on the ground or held
/// by a kinematic source is left out.

#include <array>
#include <vector>

#include "pradis/model/handles.hpp"

namespace pradis::bdf_detail {

/// A rotational node with four free DOFs.
struct free_rotation_node {
  std::array<int, 4> dof{};  ///< global DOFs of q1..q4
  std::array<int, 4> eq{};   ///< their equations
};

/// The rotational nodes whose four DOFs are free equations of `as`.
template <class Assembler>
std::vector<free_rotation_node> free_rotation_nodes(const std::vector<rotation_node_record>& nodes,
                                                    const Assembler& as) {
  std::vector<free_rotation_node> out;
  for (const rotation_node_record& n : nodes) {
    free_rotation_node e;
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

}  // namespace pradis::bdf_detail
