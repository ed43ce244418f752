#pragma once
/// \file
/// Reduction of a linear elastic part given by its stiffness and mass matrices
/// K and M (e.g. exported by a finite element program, io/matrix_market.hpp) to
/// a few boundary DOFs, for condensed elastic parts (super-elements):
///
/// - **static (Guyan) condensation**: the interior DOFs i follow the boundary
///   DOFs b statically, u_i = -K_ii^-1 K_ib u_b, so u = T u_b with
///   T = [I; -K_ii^-1 K_ib] (rows in the original order); K_r = T^T K T is the
///   exact static stiffness at the boundary (the Schur complement), M_r = T^T M T;
/// - **Craig-Bampton**: T = [T_guyan, Phi], adding the first n fixed-interface
///   modes Phi (the interior's modes with the boundary held, K_ii phi = w^2
///   M_ii phi, mass-normalised) as modal coordinates q: u = T (u_b, q). Then
///   K_r = diag(K_guyan, w_1^2 .. w_n^2) and M_r = T^T M T.
///
/// (Guyan, AIAA J. 3 (1965) 380; Craig and Bampton, AIAA J. 6 (1968) 1313.)
/// Dense matrices: parts of up to a few thousand DOFs.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"

namespace pradis::linalg {

/// A reduced linear part: K_r, M_r and the map T from the reduced coordinates
/// (the boundary DOFs in the order given, then the modal coordinates) to all DOFs.
struct reduced_part {
  Eigen::MatrixXd k;              ///< reduced stiffness T^T K T
  Eigen::MatrixXd m;              ///< reduced mass T^T M T
  Eigen::MatrixXd t;              ///< n_all x (n_boundary + n_modes)
  std::vector<int> boundary;      ///< the boundary DOFs (0-based indices into K)
  Eigen::VectorXd mode_frequencies;  ///< circular frequencies w of the kept fixed-interface modes [rad/s]
};

namespace detail {
inline void check_part(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m, const std::vector<int>& boundary,
                       const char* what) {
  const std::string f = std::string(what) + ": ";
  if (k.rows() != k.cols() || m.rows() != m.cols() || k.rows() != m.rows())
    throw error(error_code::invalid_model, f + "K (" + std::to_string(k.rows()) + " x " + std::to_string(k.cols()) +
                                               ") and M (" + std::to_string(m.rows()) + " x " +
                                               std::to_string(m.cols()) + ") must be square and of one size");
  if (!k.allFinite() || !m.allFinite()) throw error(error_code::invalid_model, f + "K or M has a non-finite entry");
  const double sk = std::max(k.cwiseAbs().maxCoeff(), 1e-300), sm = std::max(m.cwiseAbs().maxCoeff(), 1e-300);
  if ((k - k.transpose()).cwiseAbs().maxCoeff() > 1e-12 * sk || (m - m.transpose()).cwiseAbs().maxCoeff() > 1e-12 * sm)
    throw error(error_code::invalid_model, f + "K and M must be symmetric (to 1e-12 of their largest entry)");
  if (boundary.empty()) throw error(error_code::invalid_model, f + "no boundary DOF");
  std::vector<char> used(static_cast<std::size_t>(k.rows()), 0);
  for (int b : boundary) {
    if (b < 0 || b >= k.rows())
      throw error(error_code::invalid_model, f + "boundary DOF " + std::to_string(b) + " is outside 0.." +
                                                 std::to_string(k.rows() - 1));
    if (used[static_cast<std::size_t>(b)]++)
      throw error(error_code::invalid_model, f + "boundary DOF " + std::to_string(b) + " is given twice");
  }
}
/// The interior DOFs (those not in `boundary`), in increasing order.
inline std::vector<int> interior_of(Eigen::Index n, const std::vector<int>& boundary) {
  std::vector<char> b(static_cast<std::size_t>(n), 0);
  for (int x : boundary) b[static_cast<std::size_t>(x)] = 1;
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (!b[static_cast<std::size_t>(i)]) out.push_back(i);
  return out;
}
inline Eigen::MatrixXd pick(const Eigen::MatrixXd& a, const std::vector<int>& r, const std::vector<int>& c) {
  Eigen::MatrixXd o(static_cast<Eigen::Index>(r.size()), static_cast<Eigen::Index>(c.size()));
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = 0; j < c.size(); ++j) o(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = a(r[i], c[j]);
  return o;
}
}  // namespace detail

/// Craig-Bampton reduction to the boundary DOFs `boundary` (0-based, in the order
/// the reduced coordinates take) and the first `modes` fixed-interface modes
/// (0: Guyan). Throws pradis::error: invalid_model for matrices that are not
/// square, of one size, finite and symmetric, or a bad boundary list;
/// invalid_option for more modes than interior DOFs; singular_matrix if K_ii is
/// not positive definite (the boundary does not hold the part) or M_ii is not
/// positive definite with modes asked for.
template <class = void>  // compiled only in units that call it
reduced_part craig_bampton(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m, const std::vector<int>& boundary,
                                  int modes) {
  detail::check_part(k, m, boundary, "craig_bampton");
  const Eigen::Index n = k.rows();
  const std::vector<int> in = detail::interior_of(n, boundary);
  const auto nb = static_cast<Eigen::Index>(boundary.size()), ni = static_cast<Eigen::Index>(in.size());
  if (modes < 0 || modes > ni)
    throw error(error_code::invalid_option, "craig_bampton: " + std::to_string(modes) +
                                                " modes asked for, the part has " + std::to_string(ni) +
                                                " interior DOFs");
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(ni, nb), phi(ni, modes);
  Eigen::VectorXd w(modes);
  if (ni > 0) {
    const Eigen::MatrixXd kii = detail::pick(k, in, in), kib = detail::pick(k, in, boundary);
    const Eigen::LLT<Eigen::MatrixXd> llt(kii);
    if (llt.info() != Eigen::Success)
      throw error(error_code::singular_matrix,
                  "craig_bampton: the interior stiffness K_ii is not positive definite: the boundary DOFs do not hold "
                  "the part (a rigid-body motion or a mechanism is left)");
    psi = -llt.solve(kib);
    if (modes > 0) {
      const Eigen::MatrixXd mii = detail::pick(m, in, in);
      const Eigen::LLT<Eigen::MatrixXd> mllt(mii);
      if (mllt.info() != Eigen::Success)
        throw error(error_code::singular_matrix,
                    "craig_bampton: the interior mass M_ii is not positive definite (a massless interior DOF)");
      const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(kii, mii);
      if (eig.info() != Eigen::Success)
        throw error(error_code::singular_matrix, "craig_bampton: the fixed-interface eigenproblem did not converge");
      phi = eig.eigenvectors().leftCols(modes);  // ascending, M_ii-normalised
      w = eig.eigenvalues().head(modes).cwiseMax(0.0).cwiseSqrt();
    }
  }
  reduced_part r;
  r.boundary = boundary;
  r.mode_frequencies = w;
  r.t = Eigen::MatrixXd::Zero(n, nb + modes);
  for (Eigen::Index j = 0; j < nb; ++j) r.t(boundary[static_cast<std::size_t>(j)], j) = 1.0;
  for (Eigen::Index i = 0; i < ni; ++i) {
    const int row = in[static_cast<std::size_t>(i)];
    r.t.row(row).head(nb) = psi.row(i);
    if (modes > 0) r.t.row(row).tail(modes) = phi.row(i);  // phi.row(i) of an ni x 0 matrix offsets a null pointer
  }
  r.k = r.t.transpose() * k * r.t;
  r.m = r.t.transpose() * m * r.t;
  // Symmetric to round-off by construction; make it exact (halves first: K + K^T of a
  // finite K near the largest double would overflow).
  r.k = (0.5 * r.k + 0.5 * r.k.transpose()).eval();
  r.m = (0.5 * r.m + 0.5 * r.m.transpose()).eval();
  if (!r.k.allFinite() || !r.m.allFinite())
    throw error(error_code::non_finite,
                "craig_bampton: the reduced K or M is not finite (the reduction overflows the range of double)");
  return r;
}

/// Static (Guyan) condensation to the boundary DOFs: craig_bampton(k, m, boundary, 0).
template <class = void>  // compiled only in units that call it
reduced_part guyan(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m, const std::vector<int>& boundary) {
  return craig_bampton(k, m, boundary, 0);
}

}  // namespace pradis::linalg
