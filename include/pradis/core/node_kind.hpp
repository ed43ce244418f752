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
/// - K::zero_step_row([record,] values, k, row, rhs): at the zero step (consistent
///   initial derivatives) the unknown of a hidden DOF k is its acceleration: the
///   row of d/dt of the node's equation over the accelerations of the node's DOFs
///   and its right-hand side.
/// - K::inertial_block: a non-hidden DOF of the node is inertial at the zero step
///   when the assembled inertia block has an entry anywhere in the node's columns
///   of its row (not only on the diagonal).
///
/// Optional, for a kind whose equation slaves DOFs to the node's others (an explicit
/// constraint u_k = g_k(u), as a body point held at a ground point: the node at the
/// pivot, spatial/ground_pivot.hpp), without a multiplier:
/// - K::slaved[k]: DOF k is slaved. Its row is the node's equation
///   c_k(u) = u_k - g_k(u) = 0 (K::rows[k] true, dF_k/du_k = 1, no dF/dv), and the
///   element flows of its row are carried to the node's other rows: row j gets
///   T(j, k) f_k, which takes the constraint force -f_k into the node's equations
///   (so T is the transpose of the map from a virtual displacement of the node's
///   DOFs to the slaved point's: for a point on a rotational node, -[rho x] on q1..q3).
///   Like a hidden DOF, a slaved DOF belongs to one node's equation, is not counted as
///   massless, and at the zero step its acceleration is the unknown of
///   K::zero_step_row; its position and velocity are set from c = 0 and dc/dt = 0.
/// - K::carry(record, values, w, T, D): the weights T (size x size; columns of slaved
///   DOFs used) and, if D is not null, D(j, i) = d(sum_k T(j, k) w_k) / du_i at fixed w,
///   w the element flows of the slaved rows (the part of the carried flows' dF/du that
///   the element blocks do not give). Never allocates.
/// - K::slaved_rate(record, values, r) (optional): r_k = dc_k/dt for the slaved k (else
///   the kernel takes sum_j dc_k/du_j v_j from K::evaluate's block).

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

/// Copies the potentials of a node's DOFs (global indices `dofs`) from a global state s (u, v, a).
template <int N, class Dofs, class State>
void gather_node(const Dofs& dofs, const State& s, node_values<N>& x) {
  for (int k = 0; k < N; ++k) {
    const auto d = static_cast<Eigen::Index>(dofs[static_cast<std::size_t>(k)]);
    x.u(k) = s.u(d);
    x.v(k) = s.v(d);
    x.a(k) = s.a(d);
  }
}

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
} && (requires(const node_values<K::size>& x, Eigen::Matrix<double, K::size, 1>& row, double& rhs) {
  K::zero_step_row(x, 0, row, rhs);
} || requires(const typename K::record& r, const node_values<K::size>& x, Eigen::Matrix<double, K::size, 1>& row,
              double& rhs) { K::zero_step_row(r, x, 0, row, rhs); });

/// Calls K::zero_step_row with the node's record if it takes one.
template <class K>
void zero_step_row_of(const typename K::record& r, const node_values<K::size>& x, int k,
                      Eigen::Matrix<double, K::size, 1>& row, double& rhs) {
  if constexpr (requires { K::zero_step_row(r, x, k, row, rhs); })
    K::zero_step_row(r, x, k, row, rhs);
  else
    K::zero_step_row(x, k, row, rhs);
}

/// Whether a node kind slaves DOFs (K::slaved, see the file comment).
template <class K>
concept SlavingNodeKind =
    NodeKind<K> && requires(const typename K::record& r, const node_values<K::size>& x,
                            const Eigen::Matrix<double, K::size, 1>& w, Eigen::Matrix<double, K::size, K::size>& t) {
      { K::slaved } -> std::convertible_to<std::array<bool, static_cast<std::size_t>(K::size)>>;
      K::carry(r, x, w, t, &t);
    };

/// Whether DOF k of a node of kind K is slaved (false for a kind without K::slaved).
template <class K>
constexpr bool slaved_dof(int k) {
  if constexpr (SlavingNodeKind<K>)
    return K::slaved[static_cast<std::size_t>(k)];
  else
    return false;
}

/// Whether DOF k of a node of kind K belongs to the node's equation: hidden or slaved.
template <class K>
constexpr bool owned_dof(int k) {
  return K::hidden[static_cast<std::size_t>(k)] || slaved_dof<K>(k);
}

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
