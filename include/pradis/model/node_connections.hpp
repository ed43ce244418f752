#pragma once
/// \file
/// The connection checks of model::add_node (code 110): the DOFs of a node record
/// of kind K (core/node_kind.hpp) against the model they are added to.

#include <cstddef>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/core/node_kind.hpp"

namespace pradis::detail {

/// Throws code 110 unless every DOF of r exists (0 .. dof_count - 1) and appears once
/// in r (the ground excepted), and every DOF the node's equation owns (K::hidden or
/// K::slaved) is neither the ground nor already owned by a node (`hidden()`: per DOF,
/// whether it is a hidden or slaved DOF of a node; called only for a kind with one).
/// `name(d)` is the name of DOF d.
template <NodeKind K, class Name, class Hidden>
void check_node_connections(const typename K::record& r, int dof_count, const Name& name, const Hidden& hidden) {
  const std::string label(K::label);
  std::vector<char> taken;  // the hidden DOFs of the nodes so far, then of this one
  for (std::size_t k = 0; k < static_cast<std::size_t>(K::size); ++k) {
    const int d = r.dofs[k];
    if (d < 0 || d >= dof_count)
      throw error(error_code::invalid_model, "DOF " + std::to_string(d) + " of a " + label +
                                                 " node does not exist in this model (connection " +
                                                 std::to_string(k + 1) + ")");
    for (std::size_t j = 0; j < k; ++j)
      if (d != 0 && r.dofs[j] == d)
        throw error(error_code::invalid_model, "DOF '" + name(d) + "' is connection " + std::to_string(j + 1) +
                                                   " and " + std::to_string(k + 1) + " of a " + label +
                                                   " node (a DOF other than the ground appears once per node)");
    if (!owned_dof<K>(static_cast<int>(k))) continue;
    const std::string what = K::hidden[k] ? "hidden" : "slaved";
    if (d == 0)
      throw error(error_code::invalid_model,
                  "the " + what + " DOF " + std::to_string(k + 1) + " of a " + label + " node cannot be the ground");
    if (taken.empty()) taken = hidden();
    if (taken[static_cast<std::size_t>(d)])
      throw error(error_code::invalid_model, "the " + what + " DOF " + std::to_string(k + 1) + " of a " + label +
                                                 " node, '" + name(d) +
                                                 "', is already the hidden or slaved DOF of a node (one node's "
                                                 "equation per row)");
    taken[static_cast<std::size_t>(d)] = 1;
  }
}

}  // namespace pradis::detail
