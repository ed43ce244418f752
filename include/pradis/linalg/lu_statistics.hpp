#pragma once
/// \file
/// Size, cost and accuracy figures of a sparse_lu (lu_statistics), and the PRADIS-style
/// factorisation report that prints them.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>

namespace pradis::linalg {

/// Size, cost and accuracy figures of a sparse_lu, updated by analyze(), factorize(),
/// solve() and estimate_condition(); the counterpart of the PRADIS factorisation report
/// (print() writes it). The accuracy figures a caller should watch (see docs/sparse.md,
/// "Detecting loss of precision") are max_growth, last_backward_error and
/// condition_estimate; precision_warning() turns them into one sentence.
struct lu_statistics {
  /// Name of the ordering policy used by the last analyze().
  std::string_view ordering = "";
  /// Dimension of the analysed matrix.
  int n = 0;
  /// Stored entries of the analysed pattern A ("nonzeros before").
  long nnz_a = 0;
  /// Stored entries of the structurally symmetric closure A + A^T (diagonal counted only
  /// where A has it).
  long nnz_sym = 0;
  /// nnz(L) + nnz(U) with the diagonal counted once (= stored entries of the factor,
  /// "nonzeros after").
  long nnz_factor = 0;
  /// nnz_factor - nnz of the symmetrised pattern A + A^T (its diagonal entries counted only
  /// where A has them; a missing diagonal entry the factor must store counts as fill).
  long fill = 0;
  /// Mean number of nonzeros right of the diagonal per factor row, nnz(strict U) / n (the
  /// "mean row length" of the PRADIS report; the cost of one row update in the inner loop).
  double mean_right_of_diagonal = 0;
  /// Multiply-add count of one numeric factorisation: sum over pivots k of c_k^2, where c_k
  /// is the number of off-diagonal entries of column k of L (= of row k of U). The c_k
  /// divisions that form the multipliers are not counted.
  double flops = 0;
  /// Multiply-adds of one forward + backward substitution: nnz_factor - n.
  double solve_flops = 0;
  /// Successful numeric factorisations since the last analyze().
  long factorizations = 0;
  /// Solves since the last analyze().
  long solves = 0;
  /// Rows whose elimination is delayed until their neighbours have filled their diagonal
  /// (zero or weak diagonal: constraint rows, ideal sources), see sparse_lu.
  int delayed_rows = 0;
  /// Times factorize() found new zero-diagonal rows the order did not yet respect and redid
  /// the symbolic phase (the only allocation factorize() may make), since the last analyze().
  long reanalyses = 0;
  /// Pivots replaced by sign * perturbation * row scale in the last factorize() (static
  /// pivot perturbation, see sparse_lu::static_pivoting); 0 for a healthy matrix.
  long perturbed_pivots = 0;
  /// Original row of the first perturbed pivot of the last factorize(), or -1.
  int first_perturbed_row = -1;
  /// Iterative-refinement steps taken by all solve() calls since the last analyze().
  long refinement_steps = 0;
  /// Pivot growth of the last factorize(): largest |u_ij| / (max |a_rj| of its original
  /// row), both of the equilibrated matrix, over all factor rows. About 1 for diagonally
  /// dominant matrices; large values (say above 1e8) mean the factor carries rounding errors
  /// that large relative to the matrix, i.e. the LU itself lost digits.
  double max_growth = 0;
  /// Backward error of the last solve() (the scaled residual), on the equilibrated system
  /// D_r A D_c y = D_r b: max_i |D_r (b - A x)|_i / (||(D_r A D_c)_i||_1 ||D_c^{-1} x||_inf +
  /// |D_r b|_i). Near eps = 2.2e-16 for a backward-stable solve; -1 after a
  /// sparse_lu::solve_unchecked() that did not measure it.
  double last_backward_error = 0;
  /// Estimate of the 1-norm condition number of the equilibrated matrix of the last
  /// factorize() (Hager/Higham, see sparse_lu::estimate_condition()); 0 when not estimated
  /// since that factorize(). The relative error of a solution can reach about
  /// condition_estimate * last_backward_error (in the equilibrated variables).
  double condition_estimate = 0;
  /// Level at or above which condition_estimate counts as "near 1/eps" (copied from
  /// sparse_lu::condition_warning_level), see ill_conditioned().
  double condition_warning_level = 1e-3 / std::numeric_limits<double>::epsilon();
  /// Wall time of the last analyze() (ordering + symbolic), in seconds.
  double analyze_seconds = 0;
  /// Part of analyze_seconds spent in the ordering policy.
  double order_seconds = 0;
  /// Part of analyze_seconds spent in the symbolic factorisation (etree, fill, maps).
  double symbolic_seconds = 0;
  /// Wall time of the last successful factorize(), in seconds; measured only with
  /// sparse_lu::time_factorizations (0 otherwise).
  double last_factor_seconds = 0;
  /// Wall time of the last successful solve() (including its residual check), in
  /// seconds; measured only with sparse_lu::time_solves (0 otherwise).
  double last_solve_seconds = 0;

  /// Sets the figures of a symbolic factor: nnz_factor, fill, mean_right_of_diagonal, flops,
  /// solve_flops and delayed_rows (n and nnz_sym must be set).
  void set_structure(long factor_entries, double factor_flops, int delayed) noexcept {
    nnz_factor = factor_entries;
    fill = factor_entries - nnz_sym;
    mean_right_of_diagonal = n > 0 ? static_cast<double>(factor_entries - n) / 2.0 / n : 0.0;
    flops = factor_flops;
    solve_flops = static_cast<double>(factor_entries - n);
    delayed_rows = delayed;
  }

  /// True when the condition estimate of the last factorisation is at or above
  /// condition_warning_level: fewer than about -log10(eps * condition_estimate) digits of a
  /// solution can be trusted. False when no estimate was made.
  bool ill_conditioned() const noexcept { return condition_estimate >= condition_warning_level; }

  /// One plain sentence for a caller's log when the figures signal loss of precision (an
  /// ill-conditioned matrix, or pivot growth above 1e8), or an empty string. Allocates;
  /// call it when logging, not in an inner loop.
  std::string precision_warning() const {
    char buf[320];
    std::string s;
    if (ill_conditioned()) {
      std::snprintf(buf, sizeof buf,
                    "linear system nearly singular: condition estimate %.3g (level %.3g), about %.0f of 16 "
                    "digits of the Newton correction may be lost",
                    condition_estimate, condition_warning_level,
                    std::min(16.0, std::log10(condition_estimate)));
      s += buf;
    }
    if (max_growth > 1e8) {
      std::snprintf(buf, sizeof buf, "%spivot growth %.3g in the LU factor (%ld perturbed pivot(s))",
                    s.empty() ? "" : "; ", max_growth, perturbed_pivots);
      s += buf;
    }
    return s;
  }

  /// Writes the factorisation report (sizes, fill, mean row length, flops, perturbations,
  /// refinement, accuracy figures, phase times) as a few human-readable lines.
  void print(std::ostream& os) const {
    char buf[512];
    std::snprintf(buf, sizeof buf, "sparse LU report (ordering %.*s), n = %d\n", static_cast<int>(ordering.size()),
                  ordering.data(), n);
    os << buf;
    std::snprintf(buf, sizeof buf, "  nonzeros: A %ld, A+A^T %ld, factor %ld, fill %ld (factor/(A+A^T) %.2f)\n",
                  nnz_a, nnz_sym, nnz_factor, fill,
                  nnz_sym > 0 ? static_cast<double>(nnz_factor) / static_cast<double>(nnz_sym) : 0.0);
    os << buf;
    std::snprintf(buf, sizeof buf, "  mean nonzeros right of the diagonal: %.2f\n", mean_right_of_diagonal);
    os << buf;
    std::snprintf(buf, sizeof buf, "  multiply-adds: factorisation %.4g, solve %.4g\n", flops, solve_flops);
    os << buf;
    std::snprintf(buf, sizeof buf,
                  "  numerics: %ld factorisation(s), %ld solve(s), %d delayed zero-diagonal row(s), "
                  "%ld re-analysis(es), %ld perturbed pivot(s) (first row %d), %ld refinement step(s)\n",
                  factorizations, solves, delayed_rows, reanalyses, perturbed_pivots, first_perturbed_row,
                  refinement_steps);
    os << buf;
    char eta[48] = "not measured (unchecked solve)";
    if (last_backward_error >= 0) std::snprintf(eta, sizeof eta, "%.3g", last_backward_error);
    std::snprintf(buf, sizeof buf, "  accuracy: pivot growth %.3g, last backward error %s, condition estimate %.3g%s\n",
                  max_growth, eta, condition_estimate,
                  condition_estimate > 0 ? (ill_conditioned() ? " (near 1/eps)" : "") : " (not estimated)");
    os << buf;
    std::snprintf(buf, sizeof buf, "  time [s]: ordering %.6f, symbolic %.6f, ", order_seconds, symbolic_seconds);
    os << buf;
    if (last_factor_seconds > 0) {
      std::snprintf(buf, sizeof buf, "last factorisation %.6f (%.1f Mflop/s), ", last_factor_seconds,
                    flops / last_factor_seconds * 1e-6);
      os << buf;
    } else {
      os << "last factorisation not timed (sparse_lu::time_factorizations), ";
    }
    if (last_solve_seconds > 0) {
      std::snprintf(buf, sizeof buf, "last solve %.6f\n", last_solve_seconds);
      os << buf;
    } else {
      os << "last solve not timed (sparse_lu::time_solves)\n";
    }
  }
};

namespace detail {
/// A number in messages of the sparse LU: %.6g.
inline std::string format_g6(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
}  // namespace detail

}  // namespace pradis::linalg
