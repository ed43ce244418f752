#pragma once
/// \file
/// Cheap estimate of the 1-norm of the inverse of a factorised matrix (Hager 1984, with
/// Higham's refinements as in LAPACK xLACN2), from a few solves with A and A^T.

#include <algorithm>
#include <cmath>

#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg::detail {

/// ||A||_1, the largest column sum of |a_ij|, of a matrix with pattern a and values
/// (CSR order); w is a work vector of size n (0 when n = 0).
inline double max_column_sum(const sparsity_pattern& a, const double* values, double* w) {
  const auto n = static_cast<std::size_t>(a.n);
  std::fill(w, w + n, 0.0);
  for (std::size_t q = 0; q < a.col.size(); ++q) w[a.col[q]] += std::abs(values[q]);
  return n > 0 ? *std::max_element(w, w + n) : 0.0;
}

/// Lower-bound estimate of ||A^{-1}||_1, usually within a factor 3 and very often exact
/// (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., Algorithm 15.4 and
/// section 15.3). `solve(x)` must overwrite x (size n) by A^{-1} x, `solve_t(x)` by A^{-T} x.
/// x and z are work vectors of size n. Cost: at most 5 solves with each of A and A^T plus one
/// more with A (typically 2 + 2 + 1).
///
/// The method: maximise the convex function ||A^{-1} x||_1 over the unit ball of the 1-norm by
/// a gradient ascent that moves from vertex to vertex (unit vectors e_j); the gradient is
/// A^{-T} sign(A^{-1} x). Higham's extra vector x_i = (-1)^i (1 + i/(n-1)) guards against the
/// (rare) cases where the ascent stops at a poor local maximum.
template <class Solve, class SolveT>
double estimate_inverse_norm1(int n, Solve&& solve, SolveT&& solve_t, double* x, double* z) {
  if (n <= 0) return 0;
  for (int i = 0; i < n; ++i) x[i] = 1.0 / n;
  double est = 0;
  int j_prev = -1;
  for (int iter = 0; iter < 5; ++iter) {
    solve(x);
    double ynorm = 0;
    for (int i = 0; i < n; ++i) ynorm += std::abs(x[i]);
    if (iter > 0 && ynorm <= est) break;  // no increase: converged
    est = ynorm;
    for (int i = 0; i < n; ++i) z[i] = x[i] >= 0 ? 1.0 : -1.0;
    solve_t(z);
    int j = 0;
    for (int i = 1; i < n; ++i)
      if (std::abs(z[i]) > std::abs(z[j])) j = i;
    // Hager's optimality test: ||z||_inf <= z^T x with x = e_{j_prev} (x = ones/n at first).
    if (iter > 0 && (j == j_prev || std::abs(z[j]) <= z[j_prev])) break;
    for (int i = 0; i < n; ++i) x[i] = 0;
    x[j] = 1;
    j_prev = j;
  }
  for (int i = 0; i < n; ++i) x[i] = (i % 2 == 0 ? 1.0 : -1.0) * (1.0 + (n > 1 ? double(i) / (n - 1) : 0.0));
  solve(x);
  double alt = 0;
  for (int i = 0; i < n; ++i) alt += std::abs(x[i]);
  return std::max(est, 2.0 * alt / (3.0 * n));
}

}  // namespace pradis::linalg::detail
