#pragma once
// A user's dense LU for the integrator tests: it satisfies pradis::LinearSolver
// with analyze, factorize and a plain solve() only (no two-right-hand-side and
// no unchecked solve), so the drivers take their fallback paths with it. It
// counts its factorisations and solves.

#include <Eigen/Dense>
#include <cstddef>
#include <span>

#include "pradis/linalg/sparsity.hpp"

namespace pradis_test {

/// Dense LU of the assembled Newton matrix; Decomposition is an Eigen LU
/// (PartialPivLU or FullPivLU of Eigen::MatrixXd).
template <class Decomposition = Eigen::PartialPivLU<Eigen::MatrixXd>>
class dense_test_solver {
 public:
  void analyze(const pradis::linalg::sparsity_pattern& p) { pattern_ = p; }
  void factorize(std::span<const double> values) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(pattern_.n, pattern_.n);
    for (int r = 0; r < pattern_.n; ++r)
      for (int q = pattern_.row_ptr[static_cast<std::size_t>(r)]; q < pattern_.row_ptr[static_cast<std::size_t>(r) + 1];
           ++q)
        a(r, pattern_.col[static_cast<std::size_t>(q)]) = values[static_cast<std::size_t>(q)];
    lu_.compute(a);
    ++factorizations;
  }
  void solve(std::span<double> b) const {
    Eigen::Map<Eigen::VectorXd> x(b.data(), static_cast<Eigen::Index>(b.size()));
    x = lu_.solve(Eigen::VectorXd(x));
    ++solves;
  }
  int factorizations = 0;  ///< factorize() calls
  mutable long solves = 0; ///< solve() calls

 private:
  pradis::linalg::sparsity_pattern pattern_;
  Decomposition lu_;
};

}  // namespace pradis_test
