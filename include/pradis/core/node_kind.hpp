#pragma once
/// \file
/// Node kinds: groups of DOFs that carry equations of their own besides the
/// flows of the elements connected to them. The kernel (model, assembler,
/// drivers, consistent initialisation) knows nodes only through this concept;
/// a domain supplies its kinds. spatial/ supplies the rotational node
/// (spatial/rotation_node_kind.hpp): the quaternion q1..q4 whose hidden q4
/// carries the norm equation Mu d|q|/dt, which every model has. Another kind
/// enters a model through the element types that declare it
/// (`using node_kinds = type_list<K>;`, node_kinds_of), and its nodes through
/// model::add_node<K> (tests/core/test_node_kind.cpp is an example).
///
/// What a node kind K says (K::record: what a model keeps about one node, with its
/// DOFs in `dofs`; K::registry: what a model keeps about all its nodes of kind K,
/// with the records in `records()`), for a node of K::size DOFs (global indices in
/// `record.dofs`, 0 = a component fixed to the ground):
/// - K::hidden[k]: DOF k is added with the node and never named by the user. It
///   starts at K::start[k] and is not counted as a massless equation.
/// - K::rows[k]: the node's own equation has a flow in row k (K::evaluate fills
///   row k of f and of the blocks dF/du, dF/dv, over the node's columns).
/// - K::evaluate(record, values, call, out, ctx): the node's flows and, with
///   call.want_jacobian, their derivatives. Never allocates; a node state in which
///   its equation is undefined is a pradis::error through ctx (the node's owner is
///   named). At the zero step it also gives the hidden DOFs' start velocities: those
///   that make the flows of the hidden rows vanish, where their dF/dv block is regular
///   (detail::hidden_dof_velocities).
/// - K::zero_step_row(values, k, row, rhs): at the zero step (consistent
///   initial derivatives) the unknown of a hidden DOF k is its acceleration: the
///   row of d/dt of the node's equation over the accelerations of the node's DOFs
///   and its right-hand side.
/// - K::inertial_block: a non-hidden DOF of the node is inertial at the zero step
///   when the assembled inertia block has an entry anywhere in the node's columns
///   of its row (not only on the diagonal).

#include <Eigen/Core>
#include <array>
#include <concepts>
#include <cstddef>
#include <string_view>
#include <tuple>

#include "pradis/core/element.hpp"
#include "pradis/core/type_list.hpp"

namespace pradis {

/// The potentials of a node's DOFs (0 for a component on the ground).
template <int N>
struct node_values {
  Eigen::Matrix<double, N, 1> u, v, a;
};

/// What the assembler hands to a node kind's evaluate().
struct node_call {
  double dabsi = 0.1;         ///< DABSI of the run (the rotational node's Mu)
  bool want_jacobian = true;  ///< fill out.K and out.C
};

/// A node's flows f (in the rows of K::rows) and their derivatives dF/du (K) and
/// dF/dv (C), rows and columns in the node's DOF order.
template <int N>
struct node_flows {
  Eigen::Matrix<double, N, 1> f;
  Eigen::Matrix<double, N, N> K, C;
};

/// A node kind (see the file comment).
template <class K>
concept NodeKind = requires {
  typename K::record;
  { K::size } -> std::convertible_to<int>;
  { K::label } -> std::convertible_to<std::string_view>;
  { K::hidden } -> std::convertible_to<std::array<bool, static_cast<std::size_t>(K::size)>>;
  { K::rows } -> std::convertible_to<std::array<bool, static_cast<std::size_t>(K::size)>>;
  { K::start } -> std::convertible_to<std::array<double, static_cast<std::size_t>(K::size)>>;
  { K::inertial_block } -> std::convertible_to<bool>;
} && requires(const typename K::record& r, const node_values<K::size>& x, const node_call& c,
              node_flows<K::size>& out, element_context& ctx, Eigen::Matrix<double, K::size, 1>& row, double& rhs) {
  { r.dofs[0] } -> std::convertible_to<int>;
  K::evaluate(r, x, c, out, ctx);
  K::zero_step_row(x, 0, row, rhs);
};

/// The node kinds an element type E brings into every model that lists it: E::node_kinds
/// (a type_list of node kinds) if E declares it, else none.
template <class E>
struct node_kinds_of {
  using type = type_list<>;
};
template <class E>
  requires requires { typename E::node_kinds; }
struct node_kinds_of<E> {
  using type = typename E::node_kinds;
};

/// The tuple of the registries (K::registry, what a model keeps about its nodes of
/// kind K) of the node kinds of a type_list.
template <class L>
struct node_registries;
template <class... Ks>
struct node_registries<type_list<Ks...>> {
  using type = std::tuple<typename Ks::registry...>;
};
template <class L>
using node_registries_t = typename node_registries<L>::type;

}  // namespace pradis
