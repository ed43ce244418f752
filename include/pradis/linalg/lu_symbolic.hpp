#pragma once
/// \file
/// Symbolic phase of the sparse LU: the delayed-elimination constraint for rows with a zero
/// diagonal, and the symbolic factorisation (elimination tree, fill pattern, factor row
/// layout, entry map) of a structurally symmetric closure in a given pivot order.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg::detail {

/// Result of the symbolic factorisation: everything the numeric phase needs, as flat arrays.
/// Factor rows are in the permuted numbering; row i holds, in ascending column order, the L
/// multipliers l_ik (k < i, unit diagonal not stored), the pivot u_ii, then u_ij (j > i).
struct lu_structure {
  std::vector<int> perm;   ///< perm[k] = original index of pivot k
  std::vector<int> iperm;  ///< iperm[perm[k]] = k
  std::vector<int> f_ptr;  ///< factor row starts, size n+1
  std::vector<int> f_col;  ///< factor column indices (permuted numbering), sorted per row
  std::vector<int> d_pos;  ///< position of the diagonal in each factor row
  std::vector<int> a_map;  ///< CSR position in A -> slot in the factor storage
  double flops = 0;        ///< multiply-adds of one numeric factorisation
};

/// Changes a pivot order so that every `delayed` row comes after all of its neighbours that
/// are not delayed themselves (neighbours in the graph `g` of A + A^T). The other rows keep
/// their relative order; a delayed row is placed right after its last non-delayed neighbour,
/// so the fill stays close to that of the given order.
///
/// Why: in a saddle-point matrix [[K, G^T], [G, 0]] the pivot of a constraint row eliminated
/// after ALL its primal neighbours is the Schur complement -g^T K_E^{-1} g restricted to what
/// was eliminated, which is nonzero (negative) when K is positive definite and G has full row
/// rank (Bridson, "An ordering method for the direct solution of saddle-point matrices",
/// 2007). A zero diagonal eliminated too early is the zero pivot itself.
inline std::vector<int> delay_rows(const std::vector<int>& perm, const sparsity_pattern& g,
                                   const std::vector<char>& delayed) {
  const int n = g.n;
  std::vector<int> need(static_cast<std::size_t>(n), 0), out;
  std::vector<char> waiting(static_cast<std::size_t>(n), 0);
  out.reserve(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r)
    if (delayed[r])
      for (int q = g.row_ptr[r]; q < g.row_ptr[r + 1]; ++q)
        if (!delayed[g.col[q]]) ++need[r];
  for (const int v : perm) {
    if (delayed[v]) {
      if (need[v] > 0) waiting[v] = 1;
      else out.push_back(v);
      continue;
    }
    out.push_back(v);
    for (int q = g.row_ptr[v]; q < g.row_ptr[v + 1]; ++q) {
      const int z = g.col[q];
      if (delayed[z] && --need[z] == 0 && waiting[z]) out.push_back(z);
    }
  }
  return out;  // every waiting row was released: its non-delayed neighbours all appear in perm
}

/// True when the delayed row `r` comes after all its non-delayed neighbours in `iperm`.
inline bool delay_respected(int r, const std::vector<int>& iperm, const sparsity_pattern& g,
                            const std::vector<char>& delayed) {
  for (int q = g.row_ptr[r]; q < g.row_ptr[r + 1]; ++q) {
    const int j = g.col[q];
    if (!delayed[j] && iperm[j] > iperm[r]) return false;
  }
  return true;
}

/// Symbolic LU of the structurally symmetric closure of `a` (its adjacency graph `g`) in the
/// pivot order `perm` (checked to be a permutation by the caller). Elimination tree by Liu's
/// algorithm, row structures of U by merging the etree children, then the factor rows and the
/// map of every entry of A to its factor slot. Throws std::length_error if the factor would
/// exceed int indexing.
inline lu_structure symbolic_lu(const sparsity_pattern& a, const sparsity_pattern& g, std::vector<int> perm) {
  const int n = a.n;
  lu_structure s;
  s.iperm.assign(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k) s.iperm[perm[k]] = k;
  const std::vector<int>& iperm = s.iperm;

  // Graph in the new numbering (unsorted rows suffice for what follows).
  std::vector<int> pg_ptr(n + 1, 0), pg_col(g.col.size());
  for (int k = 0; k < n; ++k) {
    const int o = perm[k];
    int w = pg_ptr[k];
    for (int q = g.row_ptr[o]; q < g.row_ptr[o + 1]; ++q) pg_col[w++] = iperm[g.col[q]];
    pg_ptr[k + 1] = w;
  }

  // Elimination tree with path compression via `ancestor`:
  // parent[k] = min{ i > k : l_ik != 0 structurally }.
  std::vector<int> parent(n, -1), ancestor(n, -1);
  for (int i = 0; i < n; ++i)
    for (int q = pg_ptr[i]; q < pg_ptr[i + 1]; ++q) {
      int r = pg_col[q];
      if (r >= i) continue;
      while (ancestor[r] != -1 && ancestor[r] != i) {
        const int t = ancestor[r];
        ancestor[r] = i;
        r = t;
      }
      if (ancestor[r] == -1) {
        ancestor[r] = i;
        parent[r] = i;
      }
    }

  // Strict upper part, row by row in pivot order:
  // struct(U_k) = {j > k adjacent to k}  U  (union over etree children c of struct(U_c)) \ {k}.
  // A child's row only contains indices >= its parent k, so the union costs O(nnz(U)) in
  // total (each row is read once, by its parent) instead of a merge over all earlier rows.
  std::vector<int> child_head(n, -1), child_next(n, -1);
  for (int k = n - 1; k >= 0; --k)
    if (parent[k] >= 0) {
      child_next[k] = child_head[parent[k]];
      child_head[parent[k]] = k;
    }
  std::vector<int> u_ptr(n + 1, 0), u_col, mark(n, -1);
  u_col.reserve(g.col.size());
  for (int k = 0; k < n; ++k) {
    mark[k] = k;
    const std::size_t start = u_col.size();
    for (int q = pg_ptr[k]; q < pg_ptr[k + 1]; ++q) {
      const int j = pg_col[q];
      if (j > k && mark[j] != k) { mark[j] = k; u_col.push_back(j); }
    }
    for (int c = child_head[k]; c != -1; c = child_next[c])
      for (int q = u_ptr[c]; q < u_ptr[c + 1]; ++q) {
        const int j = u_col[q];
        if (mark[j] != k) { mark[j] = k; u_col.push_back(j); }
      }
    std::sort(u_col.begin() + static_cast<long>(start), u_col.end());
    if (u_col.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) / 2 - n)
      throw std::length_error("sparse_lu::analyze: factor too large for int indexing");
    u_ptr[k + 1] = static_cast<int>(u_col.size());
  }

  // Factor rows: [L part (k < i, ascending) | diagonal | U part (ascending)]. The L pattern is
  // the transpose of the U pattern; appending k to row j while k ascends keeps L parts sorted.
  std::vector<int> lcount(n, 0);
  for (const int j : u_col) ++lcount[j];
  s.f_ptr.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) s.f_ptr[i + 1] = s.f_ptr[i] + lcount[i] + 1 + (u_ptr[i + 1] - u_ptr[i]);
  s.f_col.assign(static_cast<std::size_t>(s.f_ptr[n]), 0);
  s.d_pos.assign(n, 0);
  {
    std::vector<int> next(n);
    for (int i = 0; i < n; ++i) {
      next[i] = s.f_ptr[i];
      s.d_pos[i] = s.f_ptr[i] + lcount[i];
      s.f_col[s.d_pos[i]] = i;
      std::copy(u_col.begin() + u_ptr[i], u_col.begin() + u_ptr[i + 1], s.f_col.begin() + s.d_pos[i] + 1);
    }
    for (int k = 0; k < n; ++k)
      for (int q = u_ptr[k]; q < u_ptr[k + 1]; ++q) s.f_col[next[u_col[q]]++] = k;
  }
  for (int k = 0; k < n; ++k) {
    const double c = u_ptr[k + 1] - u_ptr[k];
    s.flops += c * c;
  }

  // Map every entry of A to its slot (factor rows are sorted: binary search, once).
  s.a_map.assign(a.col.size(), 0);
  for (int r = 0; r < n; ++r) {
    const int i = iperm[r];
    const auto first = s.f_col.begin() + s.f_ptr[i];
    const auto last = s.f_col.begin() + s.f_ptr[i + 1];
    for (int q = a.row_ptr[r]; q < a.row_ptr[r + 1]; ++q) {
      const auto it = std::lower_bound(first, last, iperm[a.col[q]]);
      s.a_map[q] = static_cast<int>(it - s.f_col.begin());  // always found: A+A^T is in the factor
    }
  }
  s.perm = std::move(perm);
  return s;
}

/// The checks of sparse_lu::analyze on its input: a well-formed pattern (else
/// std::invalid_argument), zero-diagonal rows inside [0, n) (std::invalid_argument), and
/// no row or column without entries (pradis::error structurally_singular naming it).
inline void check_analysable(const sparsity_pattern& a, std::span<const int> zero_diagonal_rows) {
  if (!a.is_valid()) throw std::invalid_argument("sparse_lu::analyze: malformed CSR sparsity pattern");
  const int n = a.n;
  for (const int r : zero_diagonal_rows)
    if (r < 0 || r >= n)
      throw std::invalid_argument("sparse_lu::analyze: zero-diagonal row " + std::to_string(r) + " outside [0, " +
                                  std::to_string(n) + ")");
  for (int i = 0; i < n; ++i)
    if (a.row_ptr[i] == a.row_ptr[i + 1])
      throw error(error_code::structurally_singular, "row " + std::to_string(i) + " of the matrix has no entries",
                  {}, {}, i);
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  for (const int j : a.col) seen[static_cast<std::size_t>(j)] = 1;
  for (int j = 0; j < n; ++j)
    if (!seen[static_cast<std::size_t>(j)])
      throw error(error_code::structurally_singular, "column " + std::to_string(j) + " of the matrix has no entries",
                  {}, {}, j);
}

/// Throws std::logic_error unless `perm`, returned by the ordering policy `name`, is a
/// permutation of 0..n-1.
inline void check_permutation(const std::vector<int>& perm, int n, std::string_view name) {
  if (static_cast<long>(perm.size()) != n)
    throw std::logic_error("sparse_lu::analyze: ordering '" + std::string(name) +
                           "' returned a permutation of the wrong size");
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  for (const int o : perm) {
    if (o < 0 || o >= n || seen[static_cast<std::size_t>(o)])
      throw std::logic_error("sparse_lu::analyze: ordering '" + std::string(name) + "' did not return a permutation");
    seen[static_cast<std::size_t>(o)] = 1;
  }
}

}  // namespace pradis::linalg::detail
