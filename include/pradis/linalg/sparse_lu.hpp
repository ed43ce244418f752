#pragma once
/// \file
/// Sparse LU factorisation for structurally symmetric, numerically non-symmetric matrices
/// (Jacobians of mechanical and electrical systems): fill-reducing ordering with zero-diagonal
/// rows delayed, symbolic factorisation once per pattern, then equilibrated, allocation-free
/// numeric refactorisations and solves with residual check, iterative refinement and an
/// optional condition estimate. Pieces: lu_statistics.hpp (figures and report),
/// lu_symbolic.hpp (symbolic phase), lu_numeric.hpp (equilibration, elimination),
/// lu_substitution.hpp (triangular solves),
/// lu_condition.hpp (condition estimate).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/linalg/lu_condition.hpp"
#include "pradis/linalg/lu_numeric.hpp"
#include "pradis/linalg/lu_refinement.hpp"
#include "pradis/linalg/lu_statistics.hpp"
#include "pradis/linalg/lu_substitution.hpp"
#include "pradis/linalg/lu_symbolic.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// Sparse LU without row exchanges ("static pivoting") in a fill-reducing symmetric order.
///
/// Usage: analyze(pattern) once per sparsity pattern, then factorize(values) and solve(b) as
/// often as needed; neither of the latter two allocates (one exception, see "zero diagonals").
/// The factor is computed on the pattern of A + A^T (missing mirror entries are structural
/// zeros). Pivots are taken on the diagonal in the order of the `Ordering` policy.
///
/// Equilibration (`equilibrate`, on by default): factorize() scales rows, then columns, by
/// powers of two (exact: no rounding) so that every row and column of D_r A D_c has its
/// largest magnitude in [0.5, 1]; pivot tests, growth, backward error and condition estimate
/// all refer to that matrix, and solve() returns x = D_c y for (D_r A D_c) y = D_r b. A regular
/// matrix with rows or columns scaled by 1e-150..1e150 then solves to full accuracy.
///
/// Zero diagonals (`delay_zero_diagonals`, on by default): a row whose diagonal is missing from
/// the pattern, exactly zero, or tiny after equilibration (constraint rows of saddle-point
/// matrices, ideal voltage sources, ideal transformers) is eliminated only after all its
/// neighbours with a proper diagonal, which fill its diagonal with a Schur complement
/// (detail::delay_rows explains why that pivot is nonzero for [[K, G^T], [G, 0]] with K
/// positive definite and G of full rank). Rows missing their diagonal, or named in
/// analyze(pattern, zero_diagonal_rows), are delayed by analyze(); a diagonal that factorize()
/// finds (near) zero and that the current order does not yet respect makes that factorize()
/// redo the symbolic phase once (it allocates; counted in statistics().reanalyses); the rows
/// stay delayed for later factorisations.
///
/// Pivot watchdog (static_pivoting, on by default): a pivot that is still unacceptable, i.e.
/// tiny relative to its row, is replaced by sign * perturbation * scale instead of failing.
/// The factor is then that of a slightly perturbed matrix, and every solve() is corrected by
/// iterative refinement against the original matrix. The residual of EVERY solve is checked:
/// if the backward error is still above residual_tolerance after refinement, solve() throws
/// error_code::singular_matrix instead of returning a wrong answer. factorize() runs one
/// probe solve whenever it perturbed a pivot, so a (numerically) singular matrix is reported
/// by factorize() with the row of the first perturbed pivot.
///
/// Loss of precision: statistics() has the pivot growth, the backward error of the last solve
/// and, on request (estimate_condition(), or estimate_condition_on_factorize), a 1-norm
/// condition estimate; lu_statistics::precision_warning() words them for a log.
///
/// Not thread-safe: solve() and estimate_condition() are const but use internal work vectors.
template <OrderingPolicy Ordering = min_degree_ordering>
class sparse_lu {
 public:
  /// Relative pivot threshold, see factorize(). Why 1e-13: that is ~450 units of roundoff
  /// (eps = 2.2e-16). The rounding error in a pivot after elimination is a modest multiple of
  /// eps times the row magnitude, so a pivot at or below 1e-13 of its row's largest entry is
  /// indistinguishable from exact cancellation (e.g. two equal rows). Set it to 0 to reject only
  /// exact zero pivots. With static_pivoting on (the default) pivots below
  /// max(pivot_tolerance, perturbation) are perturbed instead of rejected.
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
  /// Scale rows and columns by powers of two before factorising (see the class comment).
  bool equilibrate = true;
  /// Delay the elimination of zero- or weak-diagonal rows (see the class comment). A row is
  /// weak when |a_rr| <= max(pivot_tolerance, perturbation) * max_j |a_rj| after equilibration
  /// (pivot_tolerance alone when static_pivoting is off).
  bool delay_zero_diagonals = true;
  /// When true, every factorize() also runs estimate_condition() (about 5 extra solves).
  bool estimate_condition_on_factorize = false;
  /// When true, every solve() reads the clock twice to fill
  /// statistics().last_solve_seconds. Off by default: on the small systems of a
  /// Newton iteration a solve takes well under a microsecond, and the clock reads
  /// cost a tenth of it.
  bool time_solves = false;
  /// When true, every factorize() reads the clock twice to fill
  /// statistics().last_factor_seconds. Off by default for the same reason: a
  /// factorisation of a Newton matrix of a few DOFs takes about a microsecond.
  bool time_factorizations = false;
  /// Condition estimate from which lu_statistics::ill_conditioned() holds: 1e-3 / eps (about
  /// 4.5e12), i.e. "near 1/eps": fewer than about 3 significant digits are guaranteed.
  double condition_warning_level = 1e-3 / std::numeric_limits<double>::epsilon();

  /// Default-constructed ordering policy.
  sparse_lu() = default;
  /// Uses a configured ordering policy object (e.g. optim_ordering{3}).
  explicit sparse_lu(Ordering ordering) : ordering_(std::move(ordering)) {}

  /// Ordering + symbolic fill of the structurally symmetric closure of `a`, rows without a
  /// diagonal entry delayed (see the class comment). Stores a map from every entry of `a` (its
  /// CSR position) to its slot in the factor storage, so factorize() does no search, and sizes
  /// every buffer factorize() and solve() need.
  ///
  /// Throws pradis::error(error_code::structurally_singular, msg, {}, {}, row) naming the
  /// original index when a row of `a` has no entries or a column has no entries (then no
  /// nonzero can ever reach that diagonal). Throws std::invalid_argument for a malformed
  /// pattern, std::logic_error if the ordering policy does not return a permutation, and
  /// std::length_error if the factor would exceed int indexing. On any throw the object is
  /// left un-analysed.
  void analyze(const sparsity_pattern& a) { analyze(a, std::span<const int>()); }

  /// As analyze(a), with rows known to have a zero diagonal (constraint rows, ideal sources)
  /// delayed from the start, so the first factorize() need not re-analyse. Throws
  /// std::invalid_argument for an index outside [0, n).
  void analyze(const sparsity_pattern& a, std::span<const int> zero_diagonal_rows) {
    const auto t0 = std::chrono::steady_clock::now();
    analyzed_ = false;
    factorized_ = false;
    detail::check_analysable(a, zero_diagonal_rows);
    const int n = a.n;

    std::vector<int> perm = ordering_(a);
    const auto t1 = std::chrono::steady_clock::now();
    detail::check_permutation(perm, n, Ordering::name);
    pattern_ = a;
    g_ = symmetric_adjacency(a);
    base_perm_ = std::move(perm);
    a_diag_.assign(n, -1);
    delayed_.assign(n, 0);
    long diag_in_a = 0;
    for (int r = 0; r < n; ++r) {
      a_diag_[r] = a.find(r, r);
      if (a_diag_[r] >= 0) ++diag_in_a;
      else if (delay_zero_diagonals) delayed_[r] = 1;
    }
    if (delay_zero_diagonals)
      for (const int r : zero_diagonal_rows) delayed_[r] = 1;
    build_structure();

    a_val_.assign(a.col.size(), 0.0);
    work_.assign(n, 0.0);
    row_scale_.assign(n, 0.0);
    row_norm1_.assign(n, 0.0);
    rs_.assign(n, 1.0);
    cs_.assign(n, 1.0);
    rhs_.assign(n, 0.0);
    rhs2_.assign(n, 0.0);
    work2_.assign(n, 0.0);
    res_.assign(n, 0.0);
    probe_.assign(n, 0.0);
    corr_.assign(n, 0.0);

    stats_ = lu_statistics{};
    stats_.ordering = Ordering::name;
    stats_.n = n;
    stats_.nnz_a = a.nnz();
    stats_.nnz_sym = static_cast<long>(g_.col.size()) + diag_in_a;
    set_structure_statistics();
    const auto t2 = std::chrono::steady_clock::now();
    stats_.order_seconds = std::chrono::duration<double>(t1 - t0).count();
    stats_.symbolic_seconds = std::chrono::duration<double>(t2 - t1).count();
    stats_.analyze_seconds = std::chrono::duration<double>(t2 - t0).count();
    analyzed_ = true;
  }

  /// Numeric LU without row exchanges in the analysed order. `values` are in the CSR order of
  /// the pattern given to analyze().
  ///
  /// Steps: equilibration (see the class comment); detection of new weak-diagonal rows (see
  /// delay_zero_diagonals; may redo the symbolic phase once); row-oriented (IKJ) elimination:
  /// factor row i is scattered into a dense work vector; for each k of its L pattern in
  /// ascending order, l_ik = w_k / u_kk and l_ik * (row k of U) is subtracted; the row is
  /// gathered back. The symbolic phase guarantees that row k of U lies inside the pattern of
  /// row i.
  ///
  /// Pivot test, with scale = max(max abs entry of the original (equilibrated) row (1 if the
  /// row is all zero), max |u_ij| of the eliminated row): with static_pivoting off, a pivot
  /// with |pivot| <= pivot_tolerance * scale throws; with it on (default), a pivot with
  /// |pivot| <= max(pivot_tolerance, perturbation) * scale is replaced by
  /// sign(pivot) * perturbation * scale, and a probe solve with refinement decides whether
  /// the matrix is regular (see the class comment).
  ///
  /// Throws pradis::error(error_code::non_finite, msg, {}, {}, row) naming the ORIGINAL row
  /// when a value is NaN or infinite; pradis::error(error_code::singular_matrix, msg, {}, {},
  /// row) when a pivot is not finite, when a pivot is tiny and static_pivoting is off, or when
  /// pivots were perturbed and the probe solve cannot be refined to residual_tolerance (row =
  /// first perturbed pivot). Throws std::logic_error before analyze() and
  /// std::invalid_argument when values.size() differs from the pattern's nnz. Does not
  /// allocate except for a re-analysis or to build an exception. After a throw the object
  /// stays analysed but is not factorised.
  void factorize(std::span<const double> values) {
    if (!analyzed_) throw std::logic_error("sparse_lu::factorize called before analyze");
    if (values.size() != a_val_.size())
      throw std::invalid_argument("sparse_lu::factorize: values.size() does not match the analysed pattern");
    const auto t0 = time_factorizations ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    factorized_ = false;
    const int n = stats_.n;
    detail::equilibrate(pattern_, values, equilibrate, rs_.data(), cs_.data(), a_val_.data(), row_scale_.data(),
                        row_norm1_.data(), lu_.a_map.data(), f_val_.data(), f_val_.size());
    const double threshold = static_pivoting ? std::max(pivot_tolerance, perturbation) : pivot_tolerance;
    if (delay_zero_diagonals && delay_new_weak_rows(threshold)) {  // new structure: reload the values
      std::fill(f_val_.begin(), f_val_.end(), 0.0);
      for (std::size_t q = 0; q < a_val_.size(); ++q) f_val_[lu_.a_map[q]] = a_val_[q];
    }
    double* const fv = f_val_.data();

    const detail::elimination_result el = detail::eliminate(lu_, fv, work_.data(), row_scale_.data(), threshold,
                                                            perturbation, static_pivoting);
    if (el.failed_step >= 0) {
      const int r = lu_.perm[el.failed_step];
      throw_singular(r, "pivot " + fmt(el.failed_pivot) + " of original row " + std::to_string(r) +
                            " (elimination step " + std::to_string(el.failed_step) + ", row scale " +
                            fmt(el.failed_scale) + ") is " +
                            (std::isfinite(el.failed_pivot) ? "zero or tiny"
                                                            : "not finite: element growth after tiny earlier pivots"));
    }
    for (int i = 0; i < n; ++i)
      inv_diag_[static_cast<std::size_t>(i)] = 1.0 / fv[lu_.d_pos[static_cast<std::size_t>(i)]];
    const long perturbed = el.perturbed;
    const int first_perturbed = el.first_perturbed;
    stats_.perturbed_pivots = perturbed;
    stats_.first_perturbed_row = first_perturbed;
    stats_.max_growth = el.growth;
    stats_.condition_estimate = 0;
    stats_.condition_warning_level = condition_warning_level;
    factorized_ = true;

    if (perturbed > 0) {
      detail::fill_probe(probe_.data(), n);
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
    if (estimate_condition_on_factorize) estimate_condition();
    ++stats_.factorizations;
    if (time_factorizations)
      stats_.last_factor_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// Solves A x = b in place (b in original numbering in, x out): y = D_r b, the equilibrated
  /// system is solved by permutation, forward and backward substitution, the residual against
  /// the ORIGINAL (equilibrated) matrix is computed and, while the backward error
  /// max_i |r_i| / (||A_i||_1 ||y||_inf + |b_i|) is above roundoff level (64 eps), up to
  /// max_refinement_steps steps of iterative refinement y += LU^{-1} r are taken (needed after
  /// perturbed pivots; a healthy factor passes the first check); finally x = D_c y.
  /// Does not allocate (except to build an exception). Throws std::logic_error when not
  /// factorised, std::invalid_argument when b.size() != n, pradis::error(error_code::non_finite,
  /// msg, {}, {}, row) when b has a NaN or infinite entry (its row), and
  /// pradis::error(error_code::singular_matrix, msg, {}, {}, row) when the final backward error
  /// exceeds residual_tolerance (row = first perturbed pivot, or the row with the largest
  /// residual) or a solution component is not finite (its index); b is then unspecified.
  void solve(std::span<double> b) const {
    const auto t0 = time_solves ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    prepare(b);
    finish(b, solve_refined(b.data()));
    if (time_solves)
      stats_.last_solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// Solves A x1 = b1 and A x2 = b2 in place with one pass over the factor for both
  /// substitutions (cheaper than two solve() calls on the small systems of a Newton
  /// iteration, where the traversal dominates). The results, the residual checks, the
  /// refinement and the exceptions are those of solve(b1) then solve(b2), except that
  /// the entries of both right-hand sides are checked before either is solved. Counts
  /// two solves.
  void solve(std::span<double> b1, std::span<double> b2) const {
    const auto t0 = time_solves ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    prepare(b1);
    prepare(b2);
    const int n = stats_.n;
    std::copy(b1.begin(), b1.end(), rhs_.begin());
    std::copy(b2.begin(), b2.end(), rhs2_.begin());
    detail::lu_solve2(lu_, f_val_.data(), work_.data(), work2_.data(), b1.data(), b2.data(), inv_diag_.data());
    finish(b1, refine(b1.data()));
    std::copy(rhs2_.begin(), rhs2_.begin() + n, rhs_.begin());
    finish(b2, refine(b2.data()));
    if (time_solves)
      stats_.last_solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// solve(b) and solve(b1, b2) for a caller that verifies the solution itself (a Newton
  /// convergence test, as in the BDF corrector): after a factorize() that perturbed no pivot,
  /// the substitutions alone (backward stable up to the factor's growth; not timed), with no
  /// residual check or refinement, and statistics().last_backward_error = -1 (not measured).
  /// After perturbed pivots they are solve(). solve()'s checks of b and of x remain.
  void solve_unchecked(std::span<double> b) const {
    if (stats_.perturbed_pivots > 0) return solve(b);
    prepare(b);
    detail::lu_solve(lu_, f_val_.data(), work_.data(), b.data(), inv_diag_.data());
    finish(b, -1);
  }
  void solve_unchecked(std::span<double> b1, std::span<double> b2) const {
    if (stats_.perturbed_pivots > 0) return solve(b1, b2);
    prepare(b1);
    prepare(b2);
    detail::lu_solve2(lu_, f_val_.data(), work_.data(), work2_.data(), b1.data(), b2.data(), inv_diag_.data());
    finish(b1, -1);
    finish(b2, -1);
  }

  /// Estimate of the 1-norm condition number ||B||_1 ||B^{-1}||_1 of the equilibrated matrix
  /// B = D_r A D_c of the last factorize() (detail::estimate_inverse_norm1: Hager/Higham, with
  /// solves by the factor and its transpose; a lower bound, usually within a factor 3). Also
  /// stored in statistics().condition_estimate; compare with condition_warning_level
  /// (lu_statistics::ill_conditioned()). Cost: about 5 solves; does not allocate. After
  /// perturbed pivots it estimates the condition of the perturbed factor. Throws
  /// std::logic_error when not factorised.
  double estimate_condition() const {
    if (!factorized_) throw std::logic_error("sparse_lu::estimate_condition called without a successful factorize");
    const double norm1 = detail::max_column_sum(pattern_, a_val_.data(), res_.data());
    const double inv = detail::estimate_inverse_norm1(
        stats_.n, [this](double* x) { detail::lu_solve(lu_, f_val_.data(), work_.data(), x); },
        [this](double* x) { detail::lu_solve_transposed(lu_, f_val_.data(), work_.data(), x); }, rhs_.data(),
        corr_.data());
    stats_.condition_estimate = norm1 * inv;
    return stats_.condition_estimate;
  }

  /// Size, cost and accuracy figures (see lu_statistics).
  const lu_statistics& statistics() const noexcept { return stats_; }
  /// The ordering policy (for a run-time policy such as optim_ordering, its settings).
  const Ordering& ordering() const noexcept { return ordering_; }
  /// The pivot order in use: perm[k] = original index of pivot k (the ordering policy's order
  /// with zero-diagonal rows delayed).
  const std::vector<int>& permutation() const noexcept { return lu_.perm; }
  /// True after a successful analyze().
  bool analyzed() const noexcept { return analyzed_; }
  /// True after a successful factorize() (and no failed one since).
  bool factorized() const noexcept { return factorized_; }

 private:
  /// Symbolic phase for the current delayed rows (base order with delayed rows moved), and the
  /// factor value storage.
  void build_structure() {
    const bool any = std::find(delayed_.begin(), delayed_.end(), 1) != delayed_.end();
    lu_ = detail::symbolic_lu(pattern_, g_, any ? detail::delay_rows(base_perm_, g_, delayed_) : base_perm_);
    f_val_.assign(static_cast<std::size_t>(lu_.f_ptr.back()), 0.0);
    inv_diag_.assign(lu_.perm.size(), 0.0);
  }

  void set_structure_statistics() {
    const auto delayed = static_cast<int>(std::count(delayed_.begin(), delayed_.end(), 1));
    stats_.set_structure(lu_.f_ptr.back(), lu_.flops, delayed);
  }

  /// Marks rows whose equilibrated diagonal is zero or below threshold * row scale as delayed;
  /// redoes the symbolic phase when the current order does not respect a delay (returns true
  /// then: the factor storage is new and empty).
  bool delay_new_weak_rows(double threshold) {
    const int n = stats_.n;
    bool any_new = false;
    for (int r = 0; r < n; ++r) {
      if (delayed_[r]) continue;
      const double d = a_diag_[r] >= 0 ? std::abs(a_val_[a_diag_[r]]) : 0.0;
      if (!(d > threshold * row_scale_[r])) {
        delayed_[r] = 1;
        any_new = true;
      }
    }
    if (!any_new) return false;
    bool respected = true;
    for (int r = 0; r < n && respected; ++r)
      if (delayed_[r]) respected = detail::delay_respected(r, lu_.iperm, g_, delayed_);
    if (!respected) {
      try {
        build_structure();
      } catch (...) {
        analyzed_ = false;
        throw;
      }
      ++stats_.reanalyses;
    }
    set_structure_statistics();
    return !respected;
  }

  /// x := A^{-1} b in place (b given in x; equilibrated system) with residual check and
  /// iterative refinement; returns the final backward error, leaves the final residual in res_,
  /// counts the steps. A step that does not reduce the backward error is undone and ends the
  /// refinement, as does one that reduces it by less than a factor 10 (stagnation: a singular
  /// matrix).
  double solve_refined(double* x) const {
    const int n = stats_.n;
    std::copy(x, x + n, rhs_.begin());
    detail::lu_solve(lu_, f_val_.data(), work_.data(), x, inv_diag_.data());
    return refine(x);
  }

  /// The checks of solve() on b (factorised, size, finite entries) and its row scaling.
  void prepare(std::span<double> b) const {
    if (!factorized_) throw std::logic_error("sparse_lu::solve called without a successful factorize");
    const int n = stats_.n;
    if (b.size() != static_cast<std::size_t>(n))
      throw std::invalid_argument("sparse_lu::solve: right-hand side has the wrong size");
    for (int r = 0; r < n; ++r) {
      if (!std::isfinite(b[r]))
        throw error(error_code::non_finite, "right-hand side entry " + std::to_string(r) + " is " + fmt(b[r]), {}, {},
                    r);
      b[r] *= rs_[r];
    }
  }

  /// The end of solve(): the column scaling of the solution in b, its checks against
  /// overflow and the final backward error eta (residual in res_), the count.
  void finish(std::span<double> b, double eta) const {
    const int n = stats_.n;
    stats_.last_backward_error = eta;
    for (int r = 0; r < n; ++r) b[r] *= cs_[r];
    for (int r = 0; r < n; ++r)
      if (!std::isfinite(b[r]))
        throw_singular(r, "solution component " + std::to_string(r) + " is " + fmt(b[r]) +
                              " (overflow): the matrix is singular or too ill-conditioned");
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
  }

  /// Residual check and iterative refinement of x = LU^{-1} b (equilibrated), with b in
  /// rhs_ (detail::refine); see solve_refined().
  double refine(double* x) const {
    return detail::refine({&pattern_, a_val_.data(), row_norm1_.data()}, lu_, f_val_.data(), inv_diag_.data(),
                          rhs_.data(), x, res_.data(), corr_.data(), work_.data(), max_refinement_steps,
                          stats_.refinement_steps);
  }

  [[noreturn]] static void throw_singular(int row, std::string msg) {
    throw error(error_code::singular_matrix, std::move(msg), {}, {}, row);
  }
  static std::string fmt(double v) { return detail::format_g6(v); }

  Ordering ordering_{};
  sparsity_pattern pattern_;          // the analysed A
  sparsity_pattern g_;                // adjacency of A + A^T (delays)
  std::vector<int> base_perm_;        // the ordering policy's order
  std::vector<int> a_diag_;           // CSR position of a_rr, or -1
  std::vector<char> delayed_;         // rows eliminated after their neighbours
  detail::lu_structure lu_;           // symbolic factor
  std::vector<double> f_val_;         // factor values
  std::vector<double> inv_diag_;      // 1 / U_ii by pivot, of the last factorisation
  std::vector<double> rs_, cs_;       // equilibration: row and column scales (powers of two)
  std::vector<double> a_val_;         // equilibrated values of the last factorize (residuals)
  std::vector<double> row_scale_;     // per original row: max |a_rj| (equilibrated)
  std::vector<double> row_norm1_;     // per original row: sum |a_rj| (equilibrated)
  std::vector<double> probe_;         // probe right-hand side (factorize)
  mutable std::vector<double> rhs_, res_, corr_;  // solve(): copy of b, residual, correction
  mutable std::vector<double> rhs2_, work2_;      // solve(b1, b2): copy of b2, its work vector
  mutable std::vector<double> work_;  // dense work vector (factorize and solve)
  mutable lu_statistics stats_;       // mutable: solve() counts itself
  bool analyzed_ = false;
  bool factorized_ = false;
};

}  // namespace pradis::linalg
