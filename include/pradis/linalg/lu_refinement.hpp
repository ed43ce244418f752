#pragma once
/// \file
/// Backward error and iterative refinement of a solve with the factor of a sparse_lu:
/// allocation-free kernels on the equilibrated system, used by sparse_lu::solve().

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "pradis/linalg/lu_substitution.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg::detail {

/// The equilibrated matrix A of a factorisation, for residuals: its pattern, values and
/// the 1-norms of its rows.
struct residual_matrix {
  const sparsity_pattern* pattern;
  const double* values;
  const double* row_norm1;
};

/// The probe right-hand side of a factorisation with perturbed pivots: a fixed
/// pseudo-random vector in [-1, 1) (in no special subspace, so for a singular matrix it is
/// almost surely inconsistent and refinement cannot reduce its residual).
inline void fill_probe(double* b, int n) {
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (int r = 0; r < n; ++r) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    b[r] = static_cast<double>(state >> 11) * 0x1.0p-52 - 1.0;
  }
}

/// res := b - A x; returns the backward error max_i |r_i| / (||A_i||_1 ||x||_inf + |b_i|)
/// (0/0 counts as 0, r/0 and a non-finite x as infinity).
inline double backward_error(const residual_matrix& a, const double* b, const double* x, double* res) {
  const int n = static_cast<int>(a.pattern->row_ptr.size()) - 1;
  double xmax = 0;
  for (int r = 0; r < n; ++r) xmax = std::max(xmax, std::abs(x[r]));
  if (!std::isfinite(xmax)) return std::numeric_limits<double>::infinity();
  const int* const rp = a.pattern->row_ptr.data();
  const int* const ac = a.pattern->col.data();
  double eta = 0;
  for (int r = 0; r < n; ++r) {
    double s = b[r];
    for (int q = rp[r]; q < rp[r + 1]; ++q) s -= a.values[q] * x[ac[q]];
    res[r] = s;
    const double den = a.row_norm1[r] * xmax + std::abs(b[r]);
    if (s != 0) eta = std::max(eta, den > 0 ? std::abs(s) / den : std::numeric_limits<double>::infinity());
  }
  return eta;
}

/// Residual check and iterative refinement of x = (LU)^{-1} b: at most max_steps steps
/// x += (LU)^{-1} r while the backward error is above the roundoff level (64 eps). A step
/// that does not reduce the backward error is undone and ends the refinement, as does one
/// that reduces it by less than a factor 10 (stagnation: a singular matrix). Returns the
/// final backward error and leaves the final residual in res; adds the steps taken to
/// `steps`. `corr` and `w` are work vectors of size n.
inline double refine(const residual_matrix& a, const lu_structure& s, const double* f_val, const double* inv_diag,
                     const double* b, double* x, double* res, double* corr, double* w, int max_steps, long& steps) {
  const int n = static_cast<int>(s.perm.size());
  double eta = backward_error(a, b, x, res);
  constexpr double target = 64 * std::numeric_limits<double>::epsilon();
  for (int step = 0; step < max_steps && eta > target; ++step) {
    std::copy(res, res + n, corr);
    lu_solve(s, f_val, w, corr, inv_diag);
    for (int r = 0; r < n; ++r) x[r] += corr[r];
    ++steps;
    const double next = backward_error(a, b, x, res);
    if (!(next < eta)) {  // worse (or NaN): undo and stop
      for (int r = 0; r < n; ++r) x[r] -= corr[r];
      eta = backward_error(a, b, x, res);
      break;
    }
    const bool stalled = next > 0.1 * eta;
    eta = next;
    if (stalled) break;
  }
  return eta;
}

}  // namespace pradis::linalg::detail
