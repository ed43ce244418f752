#pragma once
/// \file
/// Which equations of a singular Newton matrix depend on each other: the support of the
/// matrix's left null space, for the error that ends a run on a singular matrix
/// (failures.hpp, singular_error). Two joints that hold the same motion, such as two
/// REV3X bearings on one rigid shaft or two SPH3X at one point, give constraint rows
/// whose gradients are linearly dependent: the multipliers' rows of the Newton matrix
/// then have a left null vector y (y^T J = 0) that lives on those rows alone, and the
/// joints can be named. Used only when a run has already failed; dense, so only up to
/// `max_equations` equations.

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace pradis::detail {

/// The dependent equations of a singular matrix.
struct dependent_equations {
  int deficiency = 0;        ///< dimension of the left null space (equations too many)
  std::vector<int> rows;     ///< equations (in the assembler's numbering) with a share in it, ascending
  std::vector<char> no_diagonal;  ///< per entry of rows: the equation has no diagonal entry (a multiplier's row)
};

/// The left null space of the assembled Newton matrix (as.pattern(), as.values()), found
/// by a full-pivoting LU of its transpose after scaling every row and then every column to
/// a largest entry of 1 (so that units do not decide), with pivots below `threshold` taken
/// as zero. An equation belongs to the dependence when it has more than 1e-8 of the largest
/// entry of a null-space basis vector. None when the matrix has more than `max_equations`
/// equations, entries that are not finite, or full rank at that threshold.
template <class Assembler>
std::optional<dependent_equations> find_dependent_equations(const Assembler& as, int max_equations = 1000,
                                                            double threshold = 1e-10) {
  const int n = as.equations();
  if (n <= 0 || n > max_equations) return std::nullopt;
  const auto& pat = as.pattern();
  const auto& val = as.values();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int r = 0; r < n; ++r)
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q)
      a(r, pat.col[static_cast<std::size_t>(q)]) = val[static_cast<std::size_t>(q)];
  if (!a.allFinite()) return std::nullopt;
  for (int r = 0; r < n; ++r) {
    const double s = a.row(r).cwiseAbs().maxCoeff();
    if (s > 0) a.row(r) /= s;
  }
  for (int c = 0; c < n; ++c) {
    const double s = a.col(c).cwiseAbs().maxCoeff();
    if (s > 0) a.col(c) /= s;
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(a.transpose());
  lu.setThreshold(threshold);
  if (lu.rank() == n) return std::nullopt;
  const Eigen::MatrixXd z = lu.kernel();  // columns y with a^T y = 0; positive scalings keep their support
  dependent_equations d;
  d.deficiency = n - static_cast<int>(lu.rank());
  std::vector<char> in(static_cast<std::size_t>(n), 0);
  for (Eigen::Index k = 0; k < z.cols(); ++k) {
    const double big = z.col(k).cwiseAbs().maxCoeff();
    for (int r = 0; r < n; ++r)
      if (std::abs(z(r, k)) > 1e-8 * big) in[static_cast<std::size_t>(r)] = 1;
  }
  for (int r = 0; r < n; ++r)
    if (in[static_cast<std::size_t>(r)]) {
      d.rows.push_back(r);
      const int q = pat.find(r, r);
      d.no_diagonal.push_back(q < 0 || val[static_cast<std::size_t>(q)] == 0.0 ? 1 : 0);
    }
  return d;
}

}  // namespace pradis::detail
