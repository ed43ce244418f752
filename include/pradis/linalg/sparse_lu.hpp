#pragma once
/// \file
/// Sparse LU factorisation for structurally symmetric, numerically non-symmetric matrices
/// (Jacobians of mechanical systems): fill-reducing ordering, symbolic factorisation with the
/// elimination tree once per pattern, then allocation-free numeric refactorisations and solves.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// Size and cost figures of a sparse_lu, updated by analyze(), factorize() and solve(); the
/// counterpart of the PRADIS factorisation report (print() writes it).
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
  /// Pivots replaced by sign * perturbation * row scale in the last factorize() (static
  /// pivot perturbation, see sparse_lu::static_pivoting); 0 for a healthy matrix.
  long perturbed_pivots = 0;
  /// Original row of the first perturbed pivot of the last factorize(), or -1.
  int first_perturbed_row = -1;
  /// Iterative-refinement steps taken by all solve() calls since the last analyze().
  long refinement_steps = 0;
  /// Largest |u_ij| / (max |a_rj| of its original row) over the factor rows of the last
  /// factorize(): element growth; about 1 for diagonally dominant matrices.
  double max_growth = 0;
  /// Backward error of the last solve(): max_i |b - A x|_i / (||A_i||_1 ||x||_inf + |b_i|).
  double last_backward_error = 0;
  /// Wall time of the last analyze() (ordering + symbolic), in seconds.
  double analyze_seconds = 0;
  /// Part of analyze_seconds spent in the ordering policy.
  double order_seconds = 0;
  /// Part of analyze_seconds spent in the symbolic factorisation (etree, fill, maps).
  double symbolic_seconds = 0;
  /// Wall time of the last successful factorize(), in seconds.
  double last_factor_seconds = 0;
  /// Wall time of the last successful solve() (including its residual check), in seconds.
  double last_solve_seconds = 0;

  /// Writes the factorisation report (sizes, fill, mean row length, flops, perturbations,
  /// refinement, phase times) as a few human-readable lines.
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
                  "  numerics: %ld factorisation(s), %ld solve(s), %ld perturbed pivot(s) (first row %d), "
                  "%ld refinement step(s), growth %.3g, last backward error %.3g\n",
                  factorizations, solves, perturbed_pivots, first_perturbed_row, refinement_steps, max_growth,
                  last_backward_error);
    os << buf;
    std::snprintf(buf, sizeof buf,
                  "  time [s]: ordering %.6f, symbolic %.6f, last factorisation %.6f (%.1f Mflop/s), "
                  "last solve %.6f\n",
                  order_seconds, symbolic_seconds, last_factor_seconds,
                  last_factor_seconds > 0 ? flops / last_factor_seconds * 1e-6 : 0.0, last_solve_seconds);
    os << buf;
  }
};

/// Sparse LU without row exchanges ("static pivoting") in a fill-reducing symmetric order.
///
/// Usage: analyze(pattern) once per sparsity pattern, then factorize(values) and solve(b) as
/// often as needed; neither of the latter two allocates. The matrix is assumed structurally
/// symmetric, or is made so: the factor is computed on the pattern of A + A^T (missing
/// mirror entries are structural zeros). Pivots are taken on the diagonal in the order of
/// the `Ordering` policy; there is no numerical pivoting, which is adequate for the
/// diagonally significant Jacobians of transient analysis and keeps the symbolic phase
/// reusable.
///
/// Pivot watchdog (static_pivoting, on by default): a pivot that is unacceptable, i.e. tiny
/// relative to its row (the original row of A, or the eliminated row if elimination made it
/// grow), is replaced by sign * perturbation * scale instead of failing, so regular matrices
/// with zero or tiny diagonal entries (saddle-point blocks, constraint rows) still factorise.
/// The factor is then that of a slightly perturbed matrix, and every solve() is corrected by
/// iterative refinement against the original matrix (a copy of the values is kept). The
/// residual of EVERY solve is checked: if the backward error is still above
/// residual_tolerance after refinement, solve() throws error_code::singular_matrix instead
/// of returning a wrong answer. factorize() itself runs one probe solve with a fixed
/// pseudo-random right-hand side whenever it perturbed a pivot, so a (numerically) singular
/// matrix is reported by factorize() with the row of the first perturbed pivot.
///
/// Storage: one CSR array of "factor rows" in the permuted numbering. Row i holds, in
/// ascending column order, the L multipliers l_ik (k < i, unit diagonal not stored), the
/// pivot u_ii, then u_ij (j > i). A row is therefore sorted, the diagonal position is kept
/// in a separate array, and row k of U is the contiguous tail of factor row k.
///
/// Not thread-safe: solve() is const but uses an internal work vector.
template <OrderingPolicy Ordering = min_degree_ordering>
class sparse_lu {
 public:
  /// Relative pivot threshold, see factorize(). Why 1e-13: that is ~450 units of roundoff
  /// (eps = 2.2e-16). The rounding error in a pivot after elimination is a modest multiple of
  /// eps times the row magnitude, so a pivot at or below 1e-13 of its row's largest entry is
  /// indistinguishable from exact cancellation (e.g. two equal rows) and would yield a
  /// solution without correct digits, while regular but badly scaled Jacobians (condition
  /// numbers up to ~1e12) still pass. Set it to 0 to reject only exact zero pivots. With
  /// static_pivoting on (the default) pivots below max(pivot_tolerance, perturbation) are
  /// perturbed instead of rejected.
  double pivot_tolerance = 1e-13;

  /// Pivot watchdog switch. true (default): unacceptable pivots are perturbed and repaired by
  /// iterative refinement, see the class comment. false: the first pivot with
  /// |pivot| <= pivot_tolerance * row scale throws singular_matrix (no perturbation).
  bool static_pivoting = true;
  /// Relative size of a perturbed pivot, and the threshold below which a pivot is perturbed
  /// when static_pivoting is on (the larger of this and pivot_tolerance is used): sqrt(eps),
  /// the usual choice of static-pivoting solvers (SuperLU_DIST, PARDISO use 1e-8..sqrt(eps)):
  /// it bounds element growth by ~1/sqrt(eps) per step while the perturbation, of relative
  /// size sqrt(eps), is removed by refinement in one or two steps on a well-conditioned matrix.
  double perturbation = 1.4901161193847656e-08;
  /// Maximum iterative-refinement steps per solve().
  int max_refinement_steps = 4;
  /// Largest backward error (see lu_statistics::last_backward_error) a solve() may return.
  /// Between roundoff (~1e-16) and what a perturbed pivot of a singular matrix leaves
  /// (~perturbation, 1e-8): 1e-10.
  double residual_tolerance = 1e-10;

  /// Default-constructed ordering policy.
  sparse_lu() = default;
  /// Uses a configured ordering policy object (e.g. optim_ordering{3}).
  explicit sparse_lu(Ordering ordering) : ordering_(std::move(ordering)) {}

  /// Ordering + symbolic fill of the structurally symmetric closure of `a`. Stores a map from
  /// every entry of `a` (its CSR position) to its slot in the factor storage, so factorize()
  /// does no search, and sizes every buffer factorize() and solve() need.
  ///
  /// Throws pradis::error(error_code::structurally_singular, msg, {}, {}, row) naming the
  /// original index when a row of `a` has no entries or a column has no entries (then no
  /// nonzero can ever reach that diagonal). Throws std::invalid_argument for a malformed
  /// pattern, std::logic_error if the ordering policy does not return a permutation, and
  /// std::length_error if the factor would exceed int indexing. On any throw the object is
  /// left un-analysed.
  void analyze(const sparsity_pattern& a) {
    const auto t0 = std::chrono::steady_clock::now();
    analyzed_ = false;
    factorized_ = false;
    if (!a.is_valid())
      throw std::invalid_argument("sparse_lu::analyze: malformed CSR sparsity pattern");
    const int n = a.n;

    // --- structural checks: every row and every column needs at least one entry.
    for (int i = 0; i < n; ++i)
      if (a.row_ptr[i] == a.row_ptr[i + 1])
        throw error(error_code::structurally_singular,
                    "row " + std::to_string(i) + " of the matrix has no entries", {}, {}, i);
    {
      std::vector<char> seen(n, 0);
      for (const int j : a.col) seen[j] = 1;
      for (int j = 0; j < n; ++j)
        if (!seen[j])
          throw error(error_code::structurally_singular,
                      "column " + std::to_string(j) + " of the matrix has no entries", {}, {}, j);
    }

    // --- ordering
    std::vector<int> perm = ordering_(a);
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<int> iperm(n, -1);
    if (static_cast<long>(perm.size()) != n)
      throw std::logic_error("sparse_lu::analyze: ordering '" + std::string(Ordering::name) +
                             "' returned a permutation of the wrong size");
    for (int k = 0; k < n; ++k) {
      const int o = perm[k];
      if (o < 0 || o >= n || iperm[o] != -1)
        throw std::logic_error("sparse_lu::analyze: ordering '" + std::string(Ordering::name) +
                               "' did not return a permutation");
      iperm[o] = k;
    }

    // --- symmetrised graph in the new numbering (unsorted rows suffice for what follows).
    const sparsity_pattern g = symmetric_adjacency(a);
    long diag_in_a = 0;
    for (int i = 0; i < n; ++i)
      if (a.find(i, i) >= 0) ++diag_in_a;
    std::vector<int> pg_ptr(n + 1, 0), pg_col(g.col.size());
    for (int k = 0; k < n; ++k) {
      const int o = perm[k];
      int w = pg_ptr[k];
      for (int q = g.row_ptr[o]; q < g.row_ptr[o + 1]; ++q) pg_col[w++] = iperm[g.col[q]];
      pg_ptr[k + 1] = w;
    }

    // --- elimination tree (Liu's algorithm with path compression via `ancestor`):
    // parent[k] = min{ i > k : l_ik != 0 structurally }.
    std::vector<int> parent(n, -1), ancestor(n, -1);
    for (int i = 0; i < n; ++i) {
      for (int q = pg_ptr[i]; q < pg_ptr[i + 1]; ++q) {
        int r = pg_col[q];
        if (r >= i) continue;
        while (ancestor[r] != -1 && ancestor[r] != i) {
          const int t = ancestor[r];
          ancestor[r] = i;
          r = t;
        }
        if (ancestor[r] == -1) {
          ancestor[r] = i;
          parent[r] = i;
        }
      }
    }

    // --- symbolic factorisation of the strict upper part, row by row in pivot order:
    // struct(U_k) = {j > k adjacent to k}  U  (union over etree children c of struct(U_c)) \ {k}.
    // A child's row only contains indices >= its parent k, so the union costs O(nnz(U)) in
    // total (each row is read once, by its parent) instead of a merge over all earlier rows.
    std::vector<int> child_head(n, -1), child_next(n, -1);
    for (int k = n - 1; k >= 0; --k)
      if (parent[k] >= 0) {
        child_next[k] = child_head[parent[k]];
        child_head[parent[k]] = k;
      }
    std::vector<int> u_ptr(n + 1, 0), u_col, mark(n, -1);
    u_col.reserve(g.col.size());
    for (int k = 0; k < n; ++k) {
      mark[k] = k;
      const std::size_t start = u_col.size();
      for (int q = pg_ptr[k]; q < pg_ptr[k + 1]; ++q) {
        const int j = pg_col[q];
        if (j > k && mark[j] != k) { mark[j] = k; u_col.push_back(j); }
      }
      for (int c = child_head[k]; c != -1; c = child_next[c])
        for (int q = u_ptr[c]; q < u_ptr[c + 1]; ++q) {
          const int j = u_col[q];
          if (mark[j] != k) { mark[j] = k; u_col.push_back(j); }
        }
      std::sort(u_col.begin() + static_cast<long>(start), u_col.end());
      if (u_col.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()) / 2 - n)
        throw std::length_error("sparse_lu::analyze: factor too large for int indexing");
      u_ptr[k + 1] = static_cast<int>(u_col.size());
    }

    // --- factor rows: [L part (k < i, ascending) | diagonal | U part (ascending)].
    // The L pattern is the transpose of the U pattern; appending k to row j while k ascends
    // leaves every L part sorted.
    std::vector<int> lcount(n, 0);
    for (const int j : u_col) ++lcount[j];
    f_ptr_.assign(n + 1, 0);
    for (int i = 0; i < n; ++i) f_ptr_[i + 1] = f_ptr_[i] + lcount[i] + 1 + (u_ptr[i + 1] - u_ptr[i]);
    const long nnz_factor = f_ptr_[n];
    f_col_.assign(nnz_factor, 0);
    d_pos_.assign(n, 0);
    {
      std::vector<int> next(n);
      for (int i = 0; i < n; ++i) {
        next[i] = f_ptr_[i];
        d_pos_[i] = f_ptr_[i] + lcount[i];
        f_col_[d_pos_[i]] = i;
        std::copy(u_col.begin() + u_ptr[i], u_col.begin() + u_ptr[i + 1], f_col_.begin() + d_pos_[i] + 1);
      }
      for (int k = 0; k < n; ++k)
        for (int q = u_ptr[k]; q < u_ptr[k + 1]; ++q) f_col_[next[u_col[q]]++] = k;
    }
    double flops = 0;
    for (int k = 0; k < n; ++k) {
      const double c = u_ptr[k + 1] - u_ptr[k];
      flops += c * c;
    }
    std::vector<int>().swap(u_col);

    // --- map every entry of A to its slot (factor rows are sorted: binary search, once).
    a_row_ptr_ = a.row_ptr;
    a_map_.assign(a.col.size(), 0);
    for (int r = 0; r < n; ++r) {
      const int i = iperm[r];
      const auto first = f_col_.begin() + f_ptr_[i];
      const auto last = f_col_.begin() + f_ptr_[i + 1];
      for (int q = a.row_ptr[r]; q < a.row_ptr[r + 1]; ++q) {
        const auto it = std::lower_bound(first, last, iperm[a.col[q]]);
        a_map_[q] = static_cast<int>(it - f_col_.begin());  // always found: A+A^T is in the factor
      }
    }

    f_val_.assign(nnz_factor, 0.0);
    work_.assign(n, 0.0);
    row_scale_.assign(n, 0.0);
    row_norm1_.assign(n, 0.0);
    a_col_ = a.col;
    a_val_.assign(a.col.size(), 0.0);
    rhs_.assign(n, 0.0);
    res_.assign(n, 0.0);
    probe_.assign(n, 0.0);
    corr_.assign(n, 0.0);
    perm_ = std::move(perm);
    iperm_ = std::move(iperm);

    stats_ = lu_statistics{};
    stats_.ordering = Ordering::name;
    stats_.n = n;
    stats_.nnz_a = a.nnz();
    stats_.nnz_sym = static_cast<long>(g.col.size()) + diag_in_a;
    stats_.nnz_factor = nnz_factor;
    stats_.fill = nnz_factor - stats_.nnz_sym;
    stats_.mean_right_of_diagonal = n > 0 ? static_cast<double>(nnz_factor - n) / 2.0 / n : 0.0;
    stats_.flops = flops;
    stats_.solve_flops = static_cast<double>(nnz_factor - n);
    const auto t2 = std::chrono::steady_clock::now();
    stats_.order_seconds = std::chrono::duration<double>(t1 - t0).count();
    stats_.symbolic_seconds = std::chrono::duration<double>(t2 - t1).count();
    stats_.analyze_seconds = std::chrono::duration<double>(t2 - t0).count();
    analyzed_ = true;
  }

  /// Numeric LU without row exchanges in the analysed order (static pivoting on the diagonal).
  /// `values` are in the CSR order of the pattern given to analyze().
  ///
  /// Row-oriented (IKJ) elimination: factor row i is scattered into a dense work vector; for
  /// each k of its L pattern in ascending order, l_ik = w_k / u_kk and l_ik * (row k of U) is
  /// subtracted; the row is gathered back. The symbolic phase guarantees that row k of U lies
  /// inside the pattern of row i, so only the row's own positions of the work vector are used.
  ///
  /// Pivot test, with scale = max(max abs entry of the original row of A (1 if the row is all
  /// zero), max |u_ij| of the eliminated row): with static_pivoting off, a pivot with
  /// |pivot| <= pivot_tolerance * scale throws; with it on (default), a pivot with
  /// |pivot| <= max(pivot_tolerance, perturbation) * scale is replaced by
  /// sign(pivot) * perturbation * scale (counted in statistics().perturbed_pivots), and a
  /// probe solve with refinement decides whether the matrix is regular (see the class comment).
  ///
  /// Throws pradis::error(error_code::singular_matrix, msg, {}, {}, row) with the ORIGINAL row
  /// index when a value is not finite, when a pivot is not finite, when a pivot is tiny and
  /// static_pivoting is off, or when pivots were perturbed and the probe solve cannot be
  /// refined to residual_tolerance (row = first perturbed pivot). Throws std::logic_error
  /// before analyze() and std::invalid_argument when values.size() differs from the pattern's
  /// nnz. Does not allocate (except to build an exception). After a throw the object stays
  /// analysed but is not factorised.
  void factorize(std::span<const double> values) {
    if (!analyzed_) throw std::logic_error("sparse_lu::factorize called before analyze");
    if (values.size() != a_map_.size())
      throw std::invalid_argument("sparse_lu::factorize: values.size() does not match the analysed pattern");
    const auto t0 = std::chrono::steady_clock::now();
    factorized_ = false;
    const int n = stats_.n;

    // Row scales (for the relative pivot test), row 1-norms (for the backward error), a copy of
    // the values (for residuals) and rejection of NaN/Inf input, per original row.
    for (int r = 0; r < n; ++r) {
      double m = 0, s1 = 0;
      for (int q = a_row_ptr_[r]; q < a_row_ptr_[r + 1]; ++q) {
        const double v = values[q];
        if (!std::isfinite(v)) throw_singular(r, "non-finite matrix entry " + fmt(v) + " in row " + std::to_string(r));
        m = std::max(m, std::abs(v));
        s1 += std::abs(v);
        a_val_[q] = v;
      }
      row_scale_[r] = m > 0 ? m : 1.0;
      row_norm1_[r] = s1;
    }

    std::fill(f_val_.begin(), f_val_.end(), 0.0);
    for (std::size_t q = 0; q < a_map_.size(); ++q) f_val_[a_map_[q]] += values[q];

    const double threshold = static_pivoting ? std::max(pivot_tolerance, perturbation) : pivot_tolerance;
    long perturbed = 0;
    int first_perturbed = -1;
    double growth = 0;
    double* const w = work_.data();
    const int* const fc = f_col_.data();
    double* const fv = f_val_.data();
    for (int i = 0; i < n; ++i) {
      const int b = f_ptr_[i], d = d_pos_[i], e = f_ptr_[i + 1];
      for (int p = b; p < e; ++p) w[fc[p]] = fv[p];
      for (int p = b; p < d; ++p) {
        const int k = fc[p];
        const double l = w[k] / fv[d_pos_[k]];
        w[k] = l;
        const int ke = f_ptr_[k + 1];
        for (int q = d_pos_[k] + 1; q < ke; ++q) w[fc[q]] -= l * fv[q];
      }
      double umax = 0;
      for (int p = b; p < d; ++p) fv[p] = w[fc[p]];
      for (int p = d; p < e; ++p) {
        const double v = w[fc[p]];
        fv[p] = v;
        umax = std::max(umax, std::abs(v));
      }
      const int r = perm_[i];
      const double piv = fv[d];
      if (!std::isfinite(piv) || !std::isfinite(umax))
        throw_singular(r, "pivot " + fmt(piv) + " of original row " + std::to_string(r) + " (elimination step " +
                              std::to_string(i) + ") is not finite: element growth after tiny earlier pivots");
      const double scale = std::max(row_scale_[r], umax);
      growth = std::max(growth, umax / row_scale_[r]);
      if (!(std::abs(piv) > threshold * scale)) {
        if (!static_pivoting)
          throw_singular(r, "pivot " + fmt(piv) + " of original row " + std::to_string(r) +
                                " (elimination step " + std::to_string(i) + ", row scale " + fmt(scale) +
                                ") is zero or tiny");
        fv[d] = (piv < 0 ? -perturbation : perturbation) * scale;
        if (perturbed++ == 0) first_perturbed = r;
      }
    }
    stats_.perturbed_pivots = perturbed;
    stats_.first_perturbed_row = first_perturbed;
    stats_.max_growth = growth;
    factorized_ = true;

    if (perturbed > 0) {
      // Probe: a fixed pseudo-random right-hand side in [-1,1) (in no special subspace, so for a
      // singular matrix it is almost surely inconsistent and refinement cannot reduce it).
      std::uint64_t state = 0x9E3779B97F4A7C15ull;
      for (int r = 0; r < n; ++r) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        probe_[r] = static_cast<double>(state >> 11) * 0x1.0p-52 - 1.0;
      }
      const double eta = solve_refined(probe_.data());
      if (!(eta <= residual_tolerance)) {
        factorized_ = false;
        throw_singular(first_perturbed,
                       "matrix is singular or too ill-conditioned for static pivoting: " + std::to_string(perturbed) +
                           " pivot(s) had to be perturbed, the first in original row " +
                           std::to_string(first_perturbed) +
                           ", and iterative refinement of a test solve stalls at backward error " + fmt(eta) +
                           " > " + fmt(residual_tolerance));
      }
    }
    ++stats_.factorizations;
    stats_.last_factor_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// Solves A x = b in place (b in original numbering in, x out): y = P b, forward
  /// substitution with the unit lower factor, backward substitution with U, x = P^T y; then
  /// the residual r = b - A x against the ORIGINAL matrix is computed and, while the backward
  /// error max_i |r_i| / (||A_i||_1 ||x||_inf + |b_i|) is above roundoff level (64 eps), up to
  /// max_refinement_steps steps of iterative refinement x += LU^{-1} r are taken (needed
  /// after perturbed pivots; a healthy factor passes the first check).
  /// Does not allocate. Throws std::logic_error when not factorised, std::invalid_argument
  /// when b.size() != n, and pradis::error(error_code::singular_matrix, msg, {}, {}, row) when
  /// the final backward error exceeds residual_tolerance (row = first perturbed pivot, or the
  /// row with the largest residual); b is then unspecified.
  void solve(std::span<double> b) const {
    if (!factorized_) throw std::logic_error("sparse_lu::solve called without a successful factorize");
    const int n = stats_.n;
    if (b.size() != static_cast<std::size_t>(n))
      throw std::invalid_argument("sparse_lu::solve: right-hand side has the wrong size");
    const auto t0 = std::chrono::steady_clock::now();
    const double eta = solve_refined(b.data());
    stats_.last_backward_error = eta;
    if (!(eta <= residual_tolerance)) {
      int row = stats_.first_perturbed_row;
      if (row < 0) {
        double worst = -1;
        for (int r = 0; r < n; ++r)
          if (std::abs(res_[r]) > worst) { worst = std::abs(res_[r]); row = r; }
      }
      throw_singular(row, "solution rejected: backward error " + fmt(eta) + " after refinement exceeds " +
                              fmt(residual_tolerance) + " (" + std::to_string(stats_.perturbed_pivots) +
                              " perturbed pivot(s)); the matrix is singular or too ill-conditioned");
    }
    ++stats_.solves;
    stats_.last_solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// Size and cost figures (see lu_statistics).
  const lu_statistics& statistics() const noexcept { return stats_; }
  /// The ordering policy (for a run-time policy such as optim_ordering, its settings).
  const Ordering& ordering() const noexcept { return ordering_; }
  /// The pivot order of the last analyze(): perm[k] = original index of pivot k.
  const std::vector<int>& permutation() const noexcept { return perm_; }
  /// True after a successful analyze().
  bool analyzed() const noexcept { return analyzed_; }
  /// True after a successful factorize() (and no failed one since).
  bool factorized() const noexcept { return factorized_; }

 private:
  /// y := LU^{-1} y in place (original numbering), using work_.
  void lu_solve(double* y_io) const {
    const int n = stats_.n;
    double* const y = work_.data();
    const int* const fc = f_col_.data();
    const double* const fv = f_val_.data();
    for (int k = 0; k < n; ++k) y[k] = y_io[perm_[k]];
    for (int i = 0; i < n; ++i) {
      double s = y[i];
      for (int p = f_ptr_[i]; p < d_pos_[i]; ++p) s -= fv[p] * y[fc[p]];
      y[i] = s;
    }
    for (int i = n - 1; i >= 0; --i) {
      double s = y[i];
      for (int p = d_pos_[i] + 1; p < f_ptr_[i + 1]; ++p) s -= fv[p] * y[fc[p]];
      y[i] = s / fv[d_pos_[i]];
    }
    for (int k = 0; k < n; ++k) y_io[perm_[k]] = y[k];
  }

  /// res_ := rhs_ - A x; returns the backward error max_i |r_i| / (||A_i||_1 ||x||_inf + |b_i|)
  /// (0/0 counts as 0, r/0 and a non-finite x as infinity).
  double residual(const double* x) const {
    const int n = stats_.n;
    double xmax = 0;
    for (int r = 0; r < n; ++r) xmax = std::max(xmax, std::abs(x[r]));
    if (!std::isfinite(xmax)) return std::numeric_limits<double>::infinity();
    double eta = 0;
    for (int r = 0; r < n; ++r) {
      double s = rhs_[r];
      for (int q = a_row_ptr_[r]; q < a_row_ptr_[r + 1]; ++q) s -= a_val_[q] * x[a_col_[q]];
      res_[r] = s;
      const double den = row_norm1_[r] * xmax + std::abs(rhs_[r]);
      if (s != 0) eta = std::max(eta, den > 0 ? std::abs(s) / den : std::numeric_limits<double>::infinity());
    }
    return eta;
  }

  /// x := A^{-1} b in place (b given in x) with residual check and iterative refinement;
  /// returns the final backward error, leaves the final residual in res_, counts the steps.
  /// A step that does not reduce the backward error is undone and ends the refinement, as does
  /// one that reduces it by less than a factor 10 (stagnation: a singular matrix).
  double solve_refined(double* x) const {
    const int n = stats_.n;
    std::copy(x, x + n, rhs_.begin());
    lu_solve(x);
    double eta = residual(x);
    constexpr double target = 64 * std::numeric_limits<double>::epsilon();  // roundoff level
    for (int step = 0; step < max_refinement_steps && eta > target; ++step) {
      std::copy(res_.begin(), res_.end(), corr_.begin());
      lu_solve(corr_.data());
      for (int r = 0; r < n; ++r) x[r] += corr_[r];
      ++stats_.refinement_steps;
      const double next = residual(x);
      if (!(next < eta)) {  // worse (or NaN): undo and stop
        for (int r = 0; r < n; ++r) x[r] -= corr_[r];
        eta = residual(x);
        break;
      }
      const bool stalled = next > 0.1 * eta;
      eta = next;
      if (stalled) break;
    }
    return eta;
  }

  [[noreturn]] static void throw_singular(int row, std::string msg) {
    throw error(error_code::singular_matrix, std::move(msg), {}, {}, row);
  }
  static std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
  }

  Ordering ordering_{};
  std::vector<int> perm_, iperm_;
  std::vector<int> a_row_ptr_;  // row starts of the analysed A (row scales)
  std::vector<int> a_map_;      // CSR position in A -> slot in f_val_
  std::vector<int> f_ptr_, f_col_, d_pos_;  // factor rows, permuted numbering
  std::vector<double> f_val_;
  std::vector<double> row_scale_;          // per original row, filled by factorize()
  std::vector<double> row_norm1_;          // per original row: sum |a_rj| (backward error)
  std::vector<int> a_col_;                 // columns of the analysed A (residuals)
  std::vector<double> a_val_;              // copy of the last factorised values (residuals)
  std::vector<double> probe_;              // probe right-hand side (factorize)
  mutable std::vector<double> rhs_, res_, corr_;  // solve(): copy of b, residual, correction
  mutable std::vector<double> work_;       // dense work vector (factorize and solve)
  mutable lu_statistics stats_;            // mutable: solve() counts itself
  bool analyzed_ = false;
  bool factorized_ = false;
};

}  // namespace pradis::linalg
