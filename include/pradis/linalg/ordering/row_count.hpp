#pragma once
/// \file
/// PRADIS renumbering method I (OPTIM 1, Tinney scheme 1): rows by increasing initial
/// nonzero count.

#include <algorithm>
#include <numeric>
#include <string_view>
#include <vector>

#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// Ordering policy "row_count": rows sorted by increasing number of nonzeros of the
/// symmetrised pattern A + A^T (off-diagonal entries, i.e. the initial degree), stable, so
/// equal counts keep the original order. Nothing is updated during elimination, which is why
/// the method is only good for small systems (the paper: < 100 equations; catastrophic fill
/// above ~200). O(n + nnz) apart from the sort.
struct row_count_ordering {
  /// Policy name, "row_count".
  static constexpr std::string_view name = "row_count";

  /// Returns perm with perm[k] = original index of the k-th pivot.
  /// `a` must satisfy sparsity_pattern::is_valid().
  std::vector<int> operator()(const sparsity_pattern& a) const {
    const int n = a.n > 0 ? a.n : 0;
    std::vector<int> perm(static_cast<std::size_t>(n));
    if (n == 0) return perm;
    const sparsity_pattern g = symmetric_adjacency(a);
    std::iota(perm.begin(), perm.end(), 0);
    std::stable_sort(perm.begin(), perm.end(), [&g](int x, int y) {
      return g.row_ptr[x + 1] - g.row_ptr[x] < g.row_ptr[y + 1] - g.row_ptr[y];
    });
    return perm;
  }
};

}  // namespace pradis::linalg
