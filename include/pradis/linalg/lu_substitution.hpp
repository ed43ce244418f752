#pragma once
/// \file
/// Forward and backward substitution with the factor of a sparse_lu (lu_structure layout),
/// for A and for A^T. Allocation-free kernels; the work vector has the matrix dimension.

#include "pradis/linalg/lu_symbolic.hpp"

namespace pradis::linalg::detail {

/// y := A^{-1} y in place (original numbering) for P A P^T = L U stored in `s` / `f_val`:
/// gather into the pivot order, forward substitution with the unit lower factor (rows of L),
/// backward substitution with U (rows of U), scatter back. `w` is a work vector of size n.
/// `inv_diag`, if given, holds 1 / U_ii by pivot (a multiplication instead of a division on
/// the substitution's critical path).
inline void lu_solve(const lu_structure& s, const double* f_val, double* w, double* y,
                     const double* inv_diag = nullptr) {
  const int n = static_cast<int>(s.perm.size());
  const int* const fc = s.f_col.data();
  const int* const fp = s.f_ptr.data();
  const int* const dp = s.d_pos.data();
  for (int k = 0; k < n; ++k) w[k] = y[s.perm[k]];
  for (int i = 0; i < n; ++i) {
    double t = w[i];
    for (int p = fp[i]; p < dp[i]; ++p) t -= f_val[p] * w[fc[p]];
    w[i] = t;
  }
  if (inv_diag) {
    for (int i = n - 1; i >= 0; --i) {
      double t = w[i];
      for (int p = dp[i] + 1; p < fp[i + 1]; ++p) t -= f_val[p] * w[fc[p]];
      w[i] = t * inv_diag[i];
    }
  } else {
    for (int i = n - 1; i >= 0; --i) {
      double t = w[i];
      for (int p = dp[i] + 1; p < fp[i + 1]; ++p) t -= f_val[p] * w[fc[p]];
      w[i] = t / f_val[dp[i]];
    }
  }
  for (int k = 0; k < n; ++k) y[s.perm[k]] = w[k];
}

/// y1 := A^{-1} y1 and y2 := A^{-1} y2 in one pass over the factor, with the same
/// operations per vector, in the same order, as lu_solve (the results are identical);
/// w1, w2 are work vectors of size n.
inline void lu_solve2(const lu_structure& s, const double* f_val, double* w1, double* w2, double* y1, double* y2,
                      const double* inv_diag) {
  const int n = static_cast<int>(s.perm.size());
  const int* const fc = s.f_col.data();
  const int* const fp = s.f_ptr.data();
  const int* const dp = s.d_pos.data();
  for (int k = 0; k < n; ++k) {
    w1[k] = y1[s.perm[k]];
    w2[k] = y2[s.perm[k]];
  }
  for (int i = 0; i < n; ++i) {
    double t1 = w1[i], t2 = w2[i];
    for (int p = fp[i]; p < dp[i]; ++p) {
      t1 -= f_val[p] * w1[fc[p]];
      t2 -= f_val[p] * w2[fc[p]];
    }
    w1[i] = t1;
    w2[i] = t2;
  }
  for (int i = n - 1; i >= 0; --i) {
    double t1 = w1[i], t2 = w2[i];
    for (int p = dp[i] + 1; p < fp[i + 1]; ++p) {
      t1 -= f_val[p] * w1[fc[p]];
      t2 -= f_val[p] * w2[fc[p]];
    }
    w1[i] = t1 * inv_diag[i];
    w2[i] = t2 * inv_diag[i];
  }
  for (int k = 0; k < n; ++k) {
    y1[s.perm[k]] = w1[k];
    y2[s.perm[k]] = w2[k];
  }
}

/// y := A^{-T} y in place (original numbering): A^T = P^T U^T L^T P, so U^T is solved forward
/// and L^T backward; both go through the stored ROWS of U and L column-wise (each solved
/// unknown is subtracted from the later ones), so no transposed copy is needed.
inline void lu_solve_transposed(const lu_structure& s, const double* f_val, double* w, double* y) {
  const int n = static_cast<int>(s.perm.size());
  const int* const fc = s.f_col.data();
  const int* const fp = s.f_ptr.data();
  const int* const dp = s.d_pos.data();
  for (int k = 0; k < n; ++k) w[k] = y[s.perm[k]];
  for (int k = 0; k < n; ++k) {  // U^T v = w: column k of U^T is row k of U
    const double v = w[k] / f_val[dp[k]];
    w[k] = v;
    for (int p = dp[k] + 1; p < fp[k + 1]; ++p) w[fc[p]] -= f_val[p] * v;
  }
  for (int i = n - 1; i >= 0; --i) {  // L^T y = v: column i of L^T is row i of L (unit diagonal)
    const double v = w[i];
    for (int p = fp[i]; p < dp[i]; ++p) w[fc[p]] -= f_val[p] * v;
  }
  for (int k = 0; k < n; ++k) y[s.perm[k]] = w[k];
}

}  // namespace pradis::linalg::detail
