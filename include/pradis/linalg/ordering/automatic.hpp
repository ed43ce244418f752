#pragma once
/// \file
/// PRADIS key OPTIM: pick the renumbering level by number (optim_ordering, ordering_for_level)
/// or by model size (automatic_ordering), as the factorisation program does when OPTIM is unset.

#include <string>
#include <string_view>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/linalg/ordering/initial_fill.hpp"
#include "pradis/linalg/ordering/min_degree.hpp"
#include "pradis/linalg/ordering/min_fill.hpp"
#include "pradis/linalg/ordering/natural.hpp"
#include "pradis/linalg/ordering/row_count.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// Lowest and highest valid OPTIM level.
inline constexpr int optim_min_level = 0;
/// Highest valid OPTIM level.
inline constexpr int optim_max_level = 4;

/// Largest size for which automatic_level() picks level 0 (natural).
inline constexpr int automatic_natural_max = 2;
/// Largest size for which automatic_level() picks level 1 (row_count).
inline constexpr int automatic_row_count_max = 9;
/// Largest size for which automatic_level() picks level 3 (min_degree); min_fill above.
inline constexpr int automatic_min_degree_max = 499;

/// The OPTIM level chosen by size for an n x n system:
/// 0 (natural) for n <= 2, 1 (row_count) for 3 <= n <= 9, 3 (min_degree) for 10 <= n <= 499,
/// 4 (min_fill) for n >= 500. Level 2 (initial_fill) is never chosen by size.
///
/// PRADIS's own defaults are 0 up to 2, 1 up to 9, 2 up to 49, 3 up to 199 and 4 above. The
/// thresholds were re-measured for pradis's kernel (`pradis_bench_sparse --thresholds=...`,
/// docs/data/ordering_thresholds.csv, discussed in docs/sparse.md): row_count and initial_fill
/// give 1.5x to 13x the fill of min_degree on meshes from n = 25 on, so level 2 never wins;
/// min_degree repays its extra analysis against natural within about 13 refactorisations from
/// n = 16 on; min_fill has 6-13% less fill than min_degree on truss girders from n = 500 and
/// repays its longer ordering within 26-60 refactorisations there (on 2D meshes only from a
/// few thousand DOFs; on 3D meshes it does not pay: choose level 3 for those).
constexpr int automatic_level(int n) noexcept {
  if (n <= automatic_natural_max) return 0;
  if (n <= automatic_row_count_max) return 1;
  if (n <= automatic_min_degree_max) return 3;
  return 4;
}

/// Name of the policy behind an OPTIM level ("natural", "row_count", "initial_fill",
/// "min_degree", "min_fill"); throws pradis::error(error_code::invalid_option) naming the
/// valid range 0..4 for any other level.
inline std::string_view ordering_name_for_level(int level) {
  switch (level) {
    case 0: return natural_ordering::name;
    case 1: return row_count_ordering::name;
    case 2: return initial_fill_ordering::name;
    case 3: return min_degree_ordering::name;
    case 4: return min_fill_ordering::name;
    default:
      throw error(error_code::invalid_option,
                  "ordering level OPTIM=" + std::to_string(level) + " is invalid; valid levels are " +
                      std::to_string(optim_min_level) + ".." + std::to_string(optim_max_level) +
                      " (0 natural, 1 row_count, 2 initial_fill, 3 min_degree, 4 min_fill)");
  }
}

/// Ordering policy selected at run time by OPTIM level (0..4), e.g.
/// `sparse_lu<optim_ordering> lu(optim_ordering{3});`. A default-constructed optim_ordering
/// (level = -1) chooses the level from the size like automatic_ordering. The level is checked
/// when the ordering is applied (and by ordering_for_level()): outside -1..4 it throws
/// pradis::error(error_code::invalid_option).
struct optim_ordering {
  /// Policy name, "optim".
  static constexpr std::string_view name = "optim";
  /// OPTIM level 0..4, or -1 for "by size".
  int level = -1;

  /// The level that will be used for an n x n pattern.
  int effective_level(int n) const {
    if (level == -1) return automatic_level(n);
    (void)ordering_name_for_level(level);  // validates
    return level;
  }

  /// Returns perm with perm[k] = original index of the k-th pivot.
  std::vector<int> operator()(const sparsity_pattern& a) const {
    switch (effective_level(a.n)) {
      case 0: return natural_ordering{}(a);
      case 1: return row_count_ordering{}(a);
      case 2: return initial_fill_ordering{}(a);
      case 3: return min_degree_ordering{}(a);
      default: return min_fill_ordering{}(a);
    }
  }
};

/// Validated run-time policy for an OPTIM level 0..4; throws pradis::error(invalid_option)
/// naming the valid range 0..4 otherwise.
inline optim_ordering ordering_for_level(int level) {
  (void)ordering_name_for_level(level);
  return optim_ordering{level};
}

/// Ordering policy "automatic": the PRADIS default level for the pattern's size
/// (see automatic_level()).
struct automatic_ordering {
  /// Policy name, "automatic".
  static constexpr std::string_view name = "automatic";
  /// Returns perm with perm[k] = original index of the k-th pivot.
  std::vector<int> operator()(const sparsity_pattern& a) const { return optim_ordering{}(a); }
};

}  // namespace pradis::linalg
