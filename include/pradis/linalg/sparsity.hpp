#pragma once
/// \file
/// Square sparsity patterns in compressed sparse row (CSR) form, and the structural
/// symmetrisation (A + A^T) that the orderings and the sparse LU work on.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pradis::linalg {

/// Square sparsity pattern in CSR form, columns sorted ascending within each row, no duplicates.
///
/// Row i owns the positions row_ptr[i] .. row_ptr[i+1]-1 of `col`; a values array that
/// belongs to the pattern uses the same positions ("CSR order"). A default-constructed
/// pattern is the empty 0x0 pattern (row_ptr may then be empty as well as {0}).
struct sparsity_pattern {
  /// Number of rows (= number of columns).
  int n = 0;
  /// Row start offsets into `col`, size n+1, row_ptr[0] == 0, non-decreasing.
  std::vector<int> row_ptr;
  /// Column index of every stored entry, size nnz, ascending within each row.
  std::vector<int> col;

  /// Number of stored entries.
  int nnz() const { return static_cast<int>(col.size()); }

  /// Position of entry (i,j) in col/values, or -1. Binary search; for setup code only.
  int find(int i, int j) const {
    if (i < 0 || i >= n || j < 0 || j >= n || row_ptr.size() != static_cast<std::size_t>(n) + 1)
      return -1;
    const auto first = col.begin() + row_ptr[static_cast<std::size_t>(i)];
    const auto last = col.begin() + row_ptr[static_cast<std::size_t>(i) + 1];
    const auto it = std::lower_bound(first, last, j);
    return (it != last && *it == j) ? static_cast<int>(it - col.begin()) : -1;
  }

  /// True when the CSR invariants hold: n >= 0, row_ptr of size n+1 starting at 0 and
  /// non-decreasing up to col.size(), every column index in [0,n), strictly ascending
  /// within each row (sorted, no duplicates). The empty pattern (n == 0) may have an empty row_ptr.
  bool is_valid() const noexcept {
    if (n < 0) return false;
    if (n == 0) return col.empty() && (row_ptr.empty() || (row_ptr.size() == 1 && row_ptr[0] == 0));
    if (row_ptr.size() != static_cast<std::size_t>(n) + 1 || row_ptr[0] != 0) return false;
    if (static_cast<std::size_t>(row_ptr.back()) != col.size()) return false;
    for (int i = 0; i < n; ++i) {
      const int b = row_ptr[static_cast<std::size_t>(i)];
      const int e = row_ptr[static_cast<std::size_t>(i) + 1];
      if (e < b) return false;
      for (int p = b; p < e; ++p) {
        const int j = col[static_cast<std::size_t>(p)];
        if (j < 0 || j >= n) return false;
        if (p > b && col[static_cast<std::size_t>(p) - 1] >= j) return false;
      }
    }
    return true;
  }

  /// Builds a pattern from (i,j) pairs (duplicates allowed, merged); adds nothing else.
  /// Throws std::invalid_argument when n < 0 or an index is outside [0,n), and
  /// std::length_error when the entry count does not fit an int.
  static sparsity_pattern from_entries(int n, std::span<const std::pair<int, int>> entries) {
    if (n < 0) throw std::invalid_argument("sparsity_pattern::from_entries: negative dimension");
    if (entries.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::length_error("sparsity_pattern::from_entries: too many entries for int indices");
    const auto un = static_cast<std::size_t>(n);
    for (const auto& [i, j] : entries)
      if (i < 0 || i >= n || j < 0 || j >= n)
        throw std::invalid_argument("sparsity_pattern::from_entries: entry (" + std::to_string(i) +
                                    "," + std::to_string(j) + ") outside a " + std::to_string(n) +
                                    "x" + std::to_string(n) + " pattern");
    // Two stable counting sorts (by column, then by row) give rows with ascending columns in
    // O(n + entries) without comparisons; duplicates are then adjacent and dropped.
    std::vector<int> cnt(un + 1, 0);
    for (const auto& e : entries) ++cnt[static_cast<std::size_t>(e.second) + 1];
    for (std::size_t k = 0; k < un; ++k) cnt[k + 1] += cnt[k];
    std::vector<int> by_col(entries.size());
    for (std::size_t q = 0; q < entries.size(); ++q)
      by_col[static_cast<std::size_t>(cnt[static_cast<std::size_t>(entries[q].second)]++)] =
          static_cast<int>(q);
    std::vector<int> rp(un + 1, 0);
    for (const auto& e : entries) ++rp[static_cast<std::size_t>(e.first) + 1];
    for (std::size_t k = 0; k < un; ++k) rp[k + 1] += rp[k];
    std::vector<int> next(rp.begin(), rp.end() - 1);
    std::vector<int> cols(entries.size());
    for (const int q : by_col) {
      const auto& e = entries[static_cast<std::size_t>(q)];
      cols[static_cast<std::size_t>(next[static_cast<std::size_t>(e.first)]++)] = e.second;
    }
    sparsity_pattern s;
    s.n = n;
    s.row_ptr.assign(un + 1, 0);
    s.col.reserve(cols.size());
    for (std::size_t i = 0; i < un; ++i) {
      for (int p = rp[i]; p < rp[i + 1]; ++p) {
        const int j = cols[static_cast<std::size_t>(p)];
        if (static_cast<int>(s.col.size()) > s.row_ptr[i] && s.col.back() == j) continue;
        s.col.push_back(j);
      }
      s.row_ptr[i + 1] = static_cast<int>(s.col.size());
    }
    return s;
  }
};

/// Adjacency graph of the structural symmetrisation of `a`: the pattern of A + A^T
/// WITHOUT its diagonal (entry (i,j), i != j, is present when (i,j) or (j,i) is in `a`).
/// Sorted, duplicate-free CSR. `a` must satisfy sparsity_pattern::is_valid().
/// Used by every ordering (they must see a symmetric graph) and by the sparse LU.
inline sparsity_pattern symmetric_adjacency(const sparsity_pattern& a) {
  sparsity_pattern g;
  g.n = a.n;
  const auto un = static_cast<std::size_t>(a.n);
  g.row_ptr.assign(un + 1, 0);
  if (a.n == 0) return g;
  // Transpose by counting sort (gives ascending row indices per column), then merge
  // row i of A with row i of A^T; both are sorted so the merge is linear and duplicate-free.
  std::vector<int> tp(un + 1, 0);
  for (const int j : a.col) ++tp[static_cast<std::size_t>(j) + 1];
  for (std::size_t k = 0; k < un; ++k) tp[k + 1] += tp[k];
  std::vector<int> tcol(a.col.size());
  {
    std::vector<int> next(tp.begin(), tp.end() - 1);
    for (std::size_t i = 0; i < un; ++i)
      for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p)
        tcol[static_cast<std::size_t>(next[static_cast<std::size_t>(a.col[static_cast<std::size_t>(p)])]++)] =
            static_cast<int>(i);
  }
  g.col.reserve(2 * a.col.size());
  for (std::size_t i = 0; i < un; ++i) {
    int p = a.row_ptr[i];
    const int pe = a.row_ptr[i + 1];
    int q = tp[i];
    const int qe = tp[i + 1];
    const int ii = static_cast<int>(i);
    while (p < pe || q < qe) {
      int j;
      if (q >= qe || (p < pe && a.col[static_cast<std::size_t>(p)] < tcol[static_cast<std::size_t>(q)])) {
        j = a.col[static_cast<std::size_t>(p++)];
      } else if (p >= pe || tcol[static_cast<std::size_t>(q)] < a.col[static_cast<std::size_t>(p)]) {
        j = tcol[static_cast<std::size_t>(q++)];
      } else {
        j = a.col[static_cast<std::size_t>(p++)];
        ++q;
      }
      if (j != ii) g.col.push_back(j);
    }
    g.row_ptr[i + 1] = static_cast<int>(g.col.size());
  }
  return g;
}

}  // namespace pradis::linalg
