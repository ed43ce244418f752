#pragma once
/// \file
/// The identity ordering: pivots are taken in the original equation order.

#include <numeric>
#include <string_view>
#include <vector>

#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// Ordering policy that keeps the original order (perm[k] == k). Useful as a reference
/// and for matrices whose numbering is already good (banded, chains).
struct natural_ordering {
  /// Policy name, "natural".
  static constexpr std::string_view name = "natural";
  /// Returns the identity permutation 0..n-1 of the pattern's dimension.
  std::vector<int> operator()(const sparsity_pattern& a) const {
    std::vector<int> perm(static_cast<std::size_t>(a.n > 0 ? a.n : 0));
    std::iota(perm.begin(), perm.end(), 0);
    return perm;
  }
};

}  // namespace pradis::linalg
