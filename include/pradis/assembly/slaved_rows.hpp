#pragma once
/// \file
/// The rows of slaved DOFs (core/node_kind.hpp, K::slaved): what the assembler does
/// for a node whose equation slaves some of its DOFs to the others. After the
/// elements are assembled, the flows of a slaved row and its entries of
/// cu dF/du + cv dF/dv + ca dF/da (in every column) are carried to the node's other
/// rows with the weights T(j, k) of K::carry, the derivative of the weights
/// (K::carry's D) is added to the node's block, and the slaved row is cleared;
/// the node's own equation (assembler::evaluate_nodes) then fills it with the
/// constraint c_k = 0. This is the elimination of the constraint's multiplier
/// lambda_k = -f_k: the model keeps its DOFs, the slaved ones follow the others.
/// Tables are made once per topology (build); the carry never allocates.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::detail {

/// Calls f(std::integral_constant<int, k>) for every DOF k of a node of kind K, in order, unrolled:
/// the slaved pattern is known at compile time.
template <class K, class F>
void for_each_node_dof(F&& f) {
  [&]<int... k>(std::integer_sequence<int, k...>) {
    (f(std::integral_constant<int, k>{}), ...);
  }(std::make_integer_sequence<int, K::size>{});
}

/// The carry tables of the nodes of one slaving kind K.
template <class K>
struct slaved_table {
  static constexpr int n = K::size;
  /// Per node: [first[i], first[i + 1]) in `entries`, one group per entry of a slaved row: the
  /// slaved DOF k, the slot of the entry, the count m of its targets, then m pairs (j, slot of the
  /// same column in the node's row j) over the node's rows j that are not slaved and have an equation.
  std::vector<int> first, entries;
  /// Per node: [block_first[i], block_first[i + 1]) in `block`, pairs (c * n + j, slot) of the
  /// node's block where row j is not slaved (the rows that K::carry's D reaches) and both DOFs
  /// have equations.
  std::vector<int> block_first, block;
  /// Per node, K::size entries: the element flows of its slaved rows at the last evaluation (0 in
  /// the other rows), before they were carried. A ground pivot's force on its body is these flows.
  std::vector<double> flows;

  /// The pattern entries the carry needs: the node's other rows get every column of a slaved row.
  /// `entries` holds the (row, column) equation pairs of the elements and nodes so far; the new
  /// pairs are appended. Throws code 110 for a slaved DOF without an equation (prescribed by a
  /// source): it cannot be both.
  template <class Nodes, class EqOf, class Name>
  static void add_entries(const Nodes& nodes, const EqOf& eq_of, const Name& name,
                          std::vector<std::pair<int, int>>& entries) {
    // owner[e]: the node (index into `nodes`) whose slaved DOF has equation e, or -1. One pass over the
    // entries then finds every entry of a slaved row.
    int rows = 0;
    for (const auto& [r, c] : entries) rows = std::max(rows, r + 1);
    std::vector<int> owner(static_cast<std::size_t>(rows), -1);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (int k = 0; k < n; ++k) {
        if (!slaved_dof<K>(k)) continue;
        const int ek = eq_of(nodes[i].dofs[static_cast<std::size_t>(k)]);
        if (ek < 0)
          throw error(error_code::invalid_model,
                      "the slaved DOF '" + name(nodes[i].dofs[static_cast<std::size_t>(k)]) + "' of a " +
                          std::string(K::label) +
                          " node is prescribed by a source (a DOF follows either its node's equation or a source, "
                          "not both)");
        if (ek < rows) owner[static_cast<std::size_t>(ek)] = static_cast<int>(i);
      }
    const std::size_t m = entries.size();
    for (std::size_t e = 0; e < m; ++e) {
      const int i = owner[static_cast<std::size_t>(entries[e].first)];
      if (i < 0) continue;
      const int col = entries[e].second;
      for (int j = 0; j < n; ++j) {
        const int ej = eq_of(nodes[static_cast<std::size_t>(i)].dofs[static_cast<std::size_t>(j)]);
        if (ej >= 0 && !slaved_dof<K>(j)) entries.emplace_back(ej, col);
      }
    }
  }

  /// The tables for the final pattern.
  template <class Nodes, class EqOf>
  void build(const Nodes& nodes, const EqOf& eq_of, const linalg::sparsity_pattern& p) {
    first.assign(1, 0);
    block_first.assign(1, 0);
    entries.clear();
    block.clear();
    flows.assign(nodes.size() * static_cast<std::size_t>(n), 0.0);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const auto& d = nodes[i].dofs;
      const auto eq = [&](int k) { return eq_of(d[static_cast<std::size_t>(k)]); };
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
          if (!slaved_dof<K>(r) && eq(r) >= 0 && eq(c) >= 0) {
            const int slot = p.find(eq(r), eq(c));
            if (slot < 0) continue;
            block.push_back(c * n + r);  // d(r, c) in Eigen's column-major storage
            block.push_back(slot);
          }
      for (int k = 0; k < n; ++k) {
        if (!slaved_dof<K>(k)) continue;
        const int ek = eq(k);
        for (int q = p.row_ptr[static_cast<std::size_t>(ek)]; q < p.row_ptr[static_cast<std::size_t>(ek) + 1]; ++q) {
          entries.push_back(k);
          entries.push_back(q);
          const std::size_t count = entries.size();
          entries.push_back(0);
          const int col = p.col[static_cast<std::size_t>(q)];
          for (int j = 0; j < n; ++j) {
            const int slot = slaved_dof<K>(j) || eq(j) < 0 ? -1 : p.find(eq(j), col);
            if (slot < 0) continue;
            entries.push_back(j);
            entries.push_back(slot);
            ++entries[count];
          }
        }
      }
      first.push_back(static_cast<int>(entries.size()));
      block_first.push_back(static_cast<int>(block.size()));
    }
  }
};

/// Carries the slaved rows of the nodes of kind K of model m (see the file comment). `values` and
/// the kept blocks (kept: K, C, M, or null) are in the pattern's order; `jac`: the Jacobian was
/// assembled in full. A weight or derivative that is not finite is code 150 in the name of the
/// node (K::label and its first slaved DOF).
template <class K, class Model, class Nodes, class State>
void carry_slaved_rows(const Model& m, const Nodes& nodes, slaved_table<K>& t, const State& s, double cu,
                       bool jac, Eigen::VectorXd& residual, Eigen::VectorXd& abs_sum, std::vector<double>& values,
                       std::vector<double>* kept[3], element_context& ctx) {
  constexpr int n = K::size;
  const auto fail = [&](const auto& node) {
    int k = 0;
    while (k + 1 < n && !slaved_dof<K>(k)) ++k;
    const std::string& dof = m.dof_name(node.dofs[static_cast<std::size_t>(k)]);
    ctx.set_identity(K::label, dof);
    ctx.fail(error_code::non_finite,
             std::string(K::label) + " node of DOF '" + dof + "': a weight that carries its slaved flows is NaN or "
                                                               "infinite");
  };
  node_values<n> x;
  Eigen::Matrix<double, n, n> weights, d;
  Eigen::Matrix<double, n, 1> w;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto& dofs = nodes[i].dofs;
    gather_node<n>(dofs, s, x);
    w.setZero();
    for (int k = 0; k < n; ++k)
      if (slaved_dof<K>(k)) w(k) = residual(static_cast<Eigen::Index>(dofs[static_cast<std::size_t>(k)]));
    std::copy(w.data(), w.data() + n, t.flows.begin() + static_cast<std::ptrdiff_t>(i * n));
    weights.setZero();
    if (jac) d.setZero();
    K::carry(nodes[i], x, w, weights, jac ? &d : nullptr);
    // x * 0 is 0 for a finite x and NaN otherwise (a vectorised sum instead of a branch per entry).
    const double check = (weights.array() * 0.0).sum() + (jac ? (d.array() * 0.0).sum() : 0.0);
    if (check != 0.0) fail(nodes[i]);  // NaN != 0 too
    for_each_node_dof<K>([&](auto kc) {
      constexpr int k = decltype(kc)::value;
      if constexpr (slaved_dof<K>(k)) {
        const auto gk = static_cast<Eigen::Index>(dofs[static_cast<std::size_t>(k)]);
        for_each_node_dof<K>([&](auto jc) {
          constexpr int j = decltype(jc)::value;
          if constexpr (!slaved_dof<K>(j)) {
            if (weights(j, k) == 0.0) return;
            const auto gj = static_cast<Eigen::Index>(dofs[static_cast<std::size_t>(j)]);
            residual(gj) += weights(j, k) * w(k);
            abs_sum(gj) += std::abs(weights(j, k)) * abs_sum(gk);
          }
        });
        residual(gk) = 0;
        abs_sum(gk) = 0;
      }
    });
    if (!jac) continue;
    std::vector<double>* const buffers[4] = {&values, kept[0], kept[1], kept[2]};
    for (const int *e = t.entries.data() + t.first[i], *end = t.entries.data() + t.first[i + 1]; e != end;
         e += 3 + 2 * e[2]) {
      const int k = e[0], targets = e[2];
      const auto src = static_cast<std::size_t>(e[1]);
      for (std::vector<double>* b : buffers) {
        if (b == nullptr) continue;
        double* v = b->data();
        const double x_src = v[src];
        if (x_src == 0.0) continue;
        for (int a = 0; a < targets; ++a) {
          const double wj = weights(e[3 + 2 * a], k);
          if (wj != 0.0) v[e[4 + 2 * a]] += wj * x_src;
        }
        v[src] = 0.0;
      }
    }
    for (const int *q = t.block.data() + t.block_first[i], *end = t.block.data() + t.block_first[i + 1]; q != end;
         q += 2) {
      const double dj = d.data()[q[0]];
      if (dj == 0.0) continue;
      values[static_cast<std::size_t>(q[1])] += cu * dj;
      if (kept[0] != nullptr) (*kept[0])[static_cast<std::size_t>(q[1])] += dj;
    }
  }
}

/// Puts the slaved DOFs of every node of m on their node's equation, u_k -= c_k(u) (exact for
/// c_k = u_k - g_k), and, with `rhs` (per equation, `eq_of(dof)`), writes -scale dc_k/dt =
/// -scale sum_j dc_k/du_j v_j into the rows of the slaved DOFs: the BDF corrector after each
/// update, bdf_detail::correct. Never allocates; a node state where the equation is undefined
/// is the node's error.
template <class Model, class State, class EqOf>
void project_slaved(const Model& m, State& s, diagnostics& log, std::vector<double>* rhs, double scale,
                    const EqOf& eq_of) {
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    if constexpr (SlavingNodeKind<K>) {
      constexpr int n = K::size;
      element_context ctx("node", "", &log);
      node_values<n> x;
      node_flows<n> out;
      for (const auto& node : nodes) {
        gather_node<n>(node.dofs, s, x);
        Eigen::Matrix<double, n, 1> rate;
        if (rhs == nullptr) {
          K::evaluate(node, x, node_call{0.1, false}, out, ctx);
        } else if constexpr (requires { K::slaved_rate(node, x, rate); }) {
          K::slaved_rate(node, x, rate);
        } else {
          K::evaluate(node, x, node_call{0.1, true}, out, ctx);
          rate = out.K * x.v;
        }
        for_each_node_dof<K>([&](auto kc) {
          constexpr int k = decltype(kc)::value;
          if constexpr (slaved_dof<K>(k)) {
            const int d = node.dofs[static_cast<std::size_t>(k)];
            if (rhs == nullptr) {
              s.u(static_cast<Eigen::Index>(d)) -= out.f(k);
              return;
            }
            const int e = eq_of(d);
            if (e >= 0) (*rhs)[static_cast<std::size_t>(e)] = -scale * rate(k);
          }
        });
      }
    }
  });
}

}  // namespace pradis::detail
