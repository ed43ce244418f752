#pragma once
// A node kind written outside the library (pradis::NodeKind, include/pradis/core/node_kind.hpp):
// the integral node (x, h), whose hidden DOF h carries the equation h' - x = 0, so that
// h(t) = h(0) + integral of x from 0 to t. Its flow sits in the row of h; x keeps its own
// equation. Used by the PI controller of examples/pi_control and by tests/core/test_node_kind.cpp.
//
// What the kernel does with each member: docs/architecture.md, "Node kinds". At the zero
// step h starts at 0 with h' = x(0) (from the equation, detail::hidden_dof_velocities) and
// h'' = x'(0) (zero_step_row: the equation differentiated once more).

#include <array>
#include <string_view>
#include <vector>

#include <pradis/pradis.hpp>

namespace pradis_examples {

/// What a model keeps about one integral node: its DOFs x (the integrand) and h (the
/// integral, hidden: a DOF the node's equation owns).
struct integral_record {
  std::array<int, 2> dofs{};  ///< x, h (DOF indices)
};

/// What a model keeps about all its integral nodes (model::add_node<integral_node> adds them).
struct integral_registry {
  std::vector<integral_record> nodes;  ///< the nodes, in the order added
  /// The nodes (NodeKind's registry interface).
  const std::vector<integral_record>& records() const noexcept { return nodes; }
  /// Adds a node (model::add_node checks its DOFs first).
  void add(integral_record r) { nodes.push_back(r); }
};

/// The integral node: the equation h' - x = 0 in the row of the hidden h.
struct integral_node {
  using record = integral_record;
  using registry = integral_registry;
  static constexpr int size = 2;
  static constexpr std::string_view label = "INTEGRAL";
  static constexpr std::array<bool, 2> hidden{false, true};  ///< h is the node's own DOF
  static constexpr std::array<bool, 2> rows{false, true};    ///< its equation is in h's row
  static constexpr std::array<double, 2> start{0, 0};        ///< h(0) = 0
  static constexpr bool inertial_block = false;
  /// The flow h' - x and its derivatives dF/du (K) and dF/dv (C) in the row of h.
  static void evaluate(const record&, const pradis::node_values<2>& x, const pradis::node_call& call,
                       pradis::node_flows<2>& out, pradis::element_context&) {
    out.f(1) = x.v(1) - x.u(0);
    if (!call.want_jacobian) return;
    out.K(1, 0) = -1;
    out.K(1, 1) = 0;
    out.C(1, 0) = 0;
    out.C(1, 1) = 1;
  }
  /// The zero step's row of h: d/dt (h' - x) = h'' - x' = 0 over the accelerations.
  static void zero_step_row(const pradis::node_values<2>& x, int, Eigen::Vector2d& row, double& rhs) {
    row << 0, 1;
    rhs = -(x.a(1) - x.v(0));
  }
};
static_assert(pradis::NodeKind<integral_node>);

}  // namespace pradis_examples
