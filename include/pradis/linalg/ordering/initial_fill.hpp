#pragma once
/// \file
/// PRADIS renumbering level OPTIM 2: rows by the fill each would create if it were eliminated
/// first in the original graph (a static, never updated minimum-deficiency key).

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string_view>
#include <vector>

#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

namespace detail {

/// Deficiency (number of missing edges among the neighbours) of every node of the symmetric
/// graph `g` (symmetric_adjacency form: sorted, no diagonal): for node v of degree d,
/// d(d-1)/2 minus the number of edges between neighbours of v (= triangles through v), i.e.
/// the fill that eliminating v first would create (each new edge counted once, as a
/// symmetric pair). Triangles are counted once each with edges oriented from lower to higher
/// (degree, index): O(nnz * sqrt(nnz)), also when a few nodes have very high degree.
inline std::vector<std::int64_t> node_deficiencies(const sparsity_pattern& g) {
  const int n = g.n;
  const auto un = static_cast<std::size_t>(n > 0 ? n : 0);
  std::vector<std::int64_t> tri(un, 0);
  auto deg = [&g](int v) { return g.row_ptr[v + 1] - g.row_ptr[v]; };
  auto higher = [&](int u, int v) { return deg(u) > deg(v) || (deg(u) == deg(v) && u > v); };
  std::vector<int> out_ptr(un + 1, 0), out;
  out.reserve(g.col.size() / 2);
  for (int v = 0; v < n; ++v) {
    for (int q = g.row_ptr[v]; q < g.row_ptr[v + 1]; ++q)
      if (higher(g.col[q], v)) out.push_back(g.col[q]);
    out_ptr[static_cast<std::size_t>(v) + 1] = static_cast<int>(out.size());
  }
  std::vector<int> mark(un, -1);
  for (int v = 0; v < n; ++v) {
    for (int q = out_ptr[v]; q < out_ptr[v + 1]; ++q) mark[out[q]] = v;
    for (int q = out_ptr[v]; q < out_ptr[v + 1]; ++q) {
      const int u = out[q];
      for (int r = out_ptr[u]; r < out_ptr[u + 1]; ++r) {
        const int w = out[r];
        if (mark[w] == v) {  // triangle v < u < w in the orientation: found exactly once
          ++tri[v];
          ++tri[u];
          ++tri[w];
        }
      }
    }
  }
  std::vector<std::int64_t> def(un, 0);
  for (int v = 0; v < n; ++v) {
    const std::int64_t d = deg(v);
    def[v] = d * (d - 1) / 2 - tri[v];
  }
  return def;
}

}  // namespace detail

/// Ordering policy "initial_fill" (PRADIS OPTIM 2): rows sorted by the fill each would create
/// if it were eliminated first in the original graph of A + A^T (its deficiency), ties by
/// smaller initial degree, then by lower original index. Like row_count the key is computed
/// once and never updated, but it sees the structure around a row, not just its length: a
/// row whose neighbours are already coupled (a clique corner, a chain end) goes first.
struct initial_fill_ordering {
  /// Policy name, "initial_fill".
  static constexpr std::string_view name = "initial_fill";

  /// Returns perm with perm[k] = original index of the k-th pivot.
  /// `a` must satisfy sparsity_pattern::is_valid().
  std::vector<int> operator()(const sparsity_pattern& a) const {
    const int n = a.n > 0 ? a.n : 0;
    std::vector<int> perm(static_cast<std::size_t>(n));
    if (n == 0) return perm;
    const sparsity_pattern g = symmetric_adjacency(a);
    const std::vector<std::int64_t> def = detail::node_deficiencies(g);
    std::iota(perm.begin(), perm.end(), 0);
    std::sort(perm.begin(), perm.end(), [&](int x, int y) {
      if (def[x] != def[y]) return def[x] < def[y];
      const int dx = g.row_ptr[x + 1] - g.row_ptr[x], dy = g.row_ptr[y + 1] - g.row_ptr[y];
      if (dx != dy) return dx < dy;
      return x < y;
    });
    return perm;
  }
};

}  // namespace pradis::linalg
