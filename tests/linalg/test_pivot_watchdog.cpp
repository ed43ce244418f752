// Tests of the sparse LU pivot watchdog (static pivot perturbation + iterative refinement +
// residual check) and of the factorisation report.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace {

using pradis::error;
using pradis::error_code;
using namespace pradis::linalg;
using entries_t = std::vector<std::pair<int, int>>;

struct coo {
  int n = 0;
  std::vector<std::pair<int, int>> ij;
  std::vector<double> v;
  void add(int i, int j, double x) {
    ij.emplace_back(i, j);
    v.push_back(x);
  }
};

/// CSR pattern + values (duplicates summed) from triplets.
struct csr_matrix {
  sparsity_pattern pattern;
  std::vector<double> values;
  explicit csr_matrix(const coo& c) {
    pattern = sparsity_pattern::from_entries(c.n, c.ij);
    values.assign(pattern.nnz(), 0.0);
    for (std::size_t k = 0; k < c.v.size(); ++k) values[pattern.find(c.ij[k].first, c.ij[k].second)] += c.v[k];
  }
  Eigen::MatrixXd dense() const {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(pattern.n, pattern.n);
    for (int i = 0; i < pattern.n; ++i)
      for (int q = pattern.row_ptr[i]; q < pattern.row_ptr[i + 1]; ++q) m(i, pattern.col[q]) += values[q];
    return m;
  }
};

/// Saddle-point (KKT) matrix [[K, B^T], [B, 0]]: K a non-symmetric stiffness-like chain of nk
/// nodes, B = nc constraint rows each tying two distinct nodes (u_a - u_b = 0); the constraint block has
/// ZERO diagonal entries stored in the pattern. duplicate: the last constraint repeats the first
/// (rank deficient: singular).
csr_matrix saddle(int nk, int nc, bool duplicate) {
  coo c;
  c.n = nk + nc;
  for (int i = 0; i < nk; ++i) {
    c.add(i, i, 4.0 + 0.1 * i);
    if (i > 0) c.add(i, i - 1, -1.0);
    if (i + 1 < nk) c.add(i, i + 1, -1.5);
  }
  for (int k = 0; k < nc; ++k) {
    // Disjoint node pairs (a forest): independent constraints; needs 3 * nc <= nk.
    int a = 3 * k + 1, b = 3 * k + 2;
    if (duplicate && k == nc - 1) { a = 1; b = 2; }
    const int r = nk + k;
    c.add(r, a, 1.0);
    c.add(r, b, -1.0);
    c.add(a, r, 1.0);
    c.add(b, r, -1.0);
    c.add(r, r, 0.0);
  }
  return csr_matrix(c);
}

std::vector<double> rhs(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (auto& x : b) x = u(rng);
  return b;
}

template <class Ordering>
double error_vs_dense(const csr_matrix& m, sparse_lu<Ordering>& lu, unsigned seed) {
  const int n = m.pattern.n;
  const auto b = rhs(n, seed);
  lu.analyze(m.pattern);
  lu.factorize(m.values);
  std::vector<double> x = b;
  lu.solve(x);
  const Eigen::VectorXd xd = m.dense().fullPivLu().solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
  double err = 0;
  for (int i = 0; i < n; ++i) err = std::max(err, std::abs(x[i] - xd[i]) / std::max(1.0, xd.cwiseAbs().maxCoeff()));
  return err;
}

}  // namespace

TEST_SUITE("linalg") {
  TEST_CASE("watchdog: [[0,1],[1,0]] is solved exactly after one perturbed pivot and refinement") {
    const auto p = sparsity_pattern::from_entries(2, entries_t{{0, 0}, {0, 1}, {1, 0}, {1, 1}});
    const std::vector<double> v{0.0, 1.0, 1.0, 0.0};
    sparse_lu<natural_ordering> lu;
    lu.analyze(p);
    lu.factorize(v);
    CHECK(lu.factorized());
    CHECK(lu.statistics().perturbed_pivots == 1);
    CHECK(lu.statistics().first_perturbed_row == 0);
    std::vector<double> x{3.0, -2.0};
    lu.solve(x);
    CHECK(x[0] == doctest::Approx(-2.0).epsilon(1e-14));
    CHECK(x[1] == doctest::Approx(3.0).epsilon(1e-14));
    CHECK(lu.statistics().refinement_steps >= 1);
    CHECK(lu.statistics().last_backward_error < 1e-15);
    CHECK(lu.statistics().solves == 1);
  }

  TEST_CASE("watchdog: saddle-point matrices with zero diagonal blocks match dense LU under every ordering") {
    for (const int nc : {1, 4, 12}) {
      const auto m = saddle(40, nc, false);
      CAPTURE(nc);
      sparse_lu<natural_ordering> nat;
      sparse_lu<min_degree_ordering> md;
      sparse_lu<min_fill_ordering> mf;
      sparse_lu<row_count_ordering> rc;
      sparse_lu<row_count_ordering> rc_plain;  // zero diagonals not delayed: the watchdog repairs
      rc_plain.delay_zero_diagonals = false;
      CHECK(error_vs_dense(m, nat, 1u) < 1e-12);
      CHECK(error_vs_dense(m, md, 2u) < 1e-12);
      CHECK(error_vs_dense(m, mf, 3u) < 1e-12);
      CHECK(error_vs_dense(m, rc, 4u) < 1e-12);
      CHECK(error_vs_dense(m, rc_plain, 4u) < 1e-12);
      // Delayed constraint rows get Schur complement pivots under every ordering ...
      for (const lu_statistics* s : {&nat.statistics(), &md.statistics(), &mf.statistics(), &rc.statistics()}) {
        CHECK(s->perturbed_pivots == 0);
        CHECK(s->delayed_rows == nc);
      }
      // ... while row_count without the delay puts the constraint rows (2 entries) first: zero pivots.
      CHECK(rc_plain.statistics().perturbed_pivots > 0);
      // The solution is refined to roundoff in every case.
      for (const lu_statistics* s :
           {&nat.statistics(), &md.statistics(), &mf.statistics(), &rc.statistics(), &rc_plain.statistics()})
        CHECK(s->last_backward_error < 1e-14);
    }
  }

  TEST_CASE("watchdog: a tiny but nonzero pivot is perturbed instead of amplifying roundoff") {
    const auto p = sparsity_pattern::from_entries(2, entries_t{{0, 0}, {0, 1}, {1, 0}, {1, 1}});
    const std::vector<double> v{1e-12, 1.0, 1.0, 1.0};
    sparse_lu<natural_ordering> lu;
    lu.delay_zero_diagonals = false;  // by default the weak row 0 would be eliminated second
    lu.analyze(p);
    lu.factorize(v);
    CHECK(lu.statistics().perturbed_pivots == 1);
    std::vector<double> x{1.0, 2.0};
    lu.solve(x);
    // Exact solution of [[d,1],[1,1]] x = (1,2): x0 = 1/(1-d), x1 = (1-2d)/(1-d).
    const double d = 1e-12;
    CHECK(x[0] == doctest::Approx(1.0 / (1.0 - d)).epsilon(1e-15));
    CHECK(x[1] == doctest::Approx((1.0 - 2.0 * d) / (1.0 - d)).epsilon(1e-15));
  }

  TEST_CASE("watchdog: a genuinely singular matrix is still reported by factorize, naming the row") {
    {  // [[1,1],[1,1]]: the second pivot cancels exactly.
      const auto p = sparsity_pattern::from_entries(2, entries_t{{0, 0}, {0, 1}, {1, 0}, {1, 1}});
      sparse_lu<natural_ordering> lu;
      lu.analyze(p);
      try {
        lu.factorize(std::vector<double>{1.0, 1.0, 1.0, 1.0});
        FAIL("factorize did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::singular_matrix);
        CHECK(e.dof() == 1);
      }
      CHECK_FALSE(lu.factorized());
    }
    {  // a 1x1 zero matrix
      const auto p = sparsity_pattern::from_entries(1, entries_t{{0, 0}});
      sparse_lu<> lu;
      lu.analyze(p);
      try {
        lu.factorize(std::vector<double>{0.0});
        FAIL("factorize did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::singular_matrix);
        CHECK(e.dof() == 0);
      }
    }
    {  // a saddle-point matrix with a repeated constraint (rank deficient B)
      const auto m = saddle(40, 6, true);
      sparse_lu<natural_ordering> nat;
      nat.analyze(m.pattern);
      try {
        nat.factorize(m.values);
        FAIL("factorize did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::singular_matrix);
        CHECK(e.dof() == 40 + 5);  // the repeated constraint's row, eliminated after the first
      }
      sparse_lu<min_fill_ordering> mf;
      mf.analyze(m.pattern);
      CHECK_THROWS_AS(mf.factorize(m.values), error);
      CHECK_FALSE(mf.factorized());
    }
  }

  TEST_CASE("every solve checks its residual: an impossible tolerance is reported, never ignored") {
    const auto m = saddle(60, 5, false);
    sparse_lu<min_degree_ordering> lu;
    lu.analyze(m.pattern);
    lu.factorize(m.values);
    auto b = rhs(65, 9u);
    lu.solve(b);
    CHECK(lu.statistics().last_backward_error < 1e-14);
    lu.residual_tolerance = -1.0;  // nothing passes
    auto b2 = rhs(65, 9u);
    try {
      lu.solve(b2);
      FAIL("solve did not throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::singular_matrix);
      CHECK(e.dof() >= 0);
      CHECK(e.dof() < 65);
    }
    CHECK(lu.statistics().solves == 1);
  }

  TEST_CASE("the factorisation report has the PRADIS figures and prints them") {
    coo c;
    const int k = 12;
    c.n = k * k;
    for (int y = 0; y < k; ++y)
      for (int x = 0; x < k; ++x) {
        const int i = y * k + x;
        c.add(i, i, 4.0);
        if (x > 0) c.add(i, i - 1, -1.0);
        if (x + 1 < k) c.add(i, i + 1, -1.0);
        if (y > 0) c.add(i, i - k, -1.0);
        if (y + 1 < k) c.add(i, i + k, -1.0);
      }
    const csr_matrix m(c);
    sparse_lu<min_fill_ordering> lu;
    lu.analyze(m.pattern);
    lu.factorize(m.values);
    auto b = rhs(k * k, 3u);
    lu.solve(b);
    const auto& s = lu.statistics();
    CHECK(s.ordering == "min_fill");
    CHECK(s.nnz_a == m.pattern.nnz());
    CHECK(s.nnz_sym == m.pattern.nnz());
    CHECK(s.nnz_factor == s.nnz_sym + s.fill);
    CHECK(s.mean_right_of_diagonal * 2.0 * s.n + s.n == doctest::Approx(static_cast<double>(s.nnz_factor)));
    CHECK(s.solve_flops == static_cast<double>(s.nnz_factor - s.n));
    CHECK(s.flops > 0);
    CHECK(s.order_seconds >= 0);
    CHECK(s.symbolic_seconds >= 0);
    CHECK(s.analyze_seconds >= s.order_seconds);
    CHECK(s.perturbed_pivots == 0);
    CHECK(s.first_perturbed_row == -1);
    CHECK(s.max_growth >= 1.0);
    CHECK(s.max_growth < 2.0);
    CHECK(s.refinement_steps == 0);
    std::ostringstream os;
    s.print(os);
    const std::string txt = os.str();
    MESSAGE(txt);
    CHECK(txt.find("min_fill") != std::string::npos);
    CHECK(txt.find("fill " + std::to_string(s.fill)) != std::string::npos);
    CHECK(txt.find("mean nonzeros right of the diagonal") != std::string::npos);
    CHECK(txt.find("perturbed pivot") != std::string::npos);
  }

  TEST_CASE("solve_unchecked: the substitutions alone on a clean factor, solve() after perturbed pivots") {
    // A clean factor (no perturbed pivot, delayed zero-diagonal rows): the solution
    // matches dense LU to roundoff without a residual check (last_backward_error -1),
    // and solve_unchecked(b1, b2) equals two single calls bit for bit.
    const auto m = saddle(60, 5, false);
    sparse_lu<min_degree_ordering> lu;
    lu.analyze(m.pattern);
    lu.factorize(m.values);
    REQUIRE(lu.statistics().perturbed_pivots == 0);
    const auto b = rhs(65, 9u);
    const Eigen::VectorXd xd = m.dense().fullPivLu().solve(Eigen::Map<const Eigen::VectorXd>(b.data(), 65));
    std::vector<double> x = b;
    const long steps = lu.statistics().refinement_steps;
    lu.solve_unchecked(x);
    double err = 0;
    for (int i = 0; i < 65; ++i) err = std::max(err, std::abs(x[static_cast<std::size_t>(i)] - xd(i)));
    CHECK(err < 1e-13 * std::max(1.0, xd.cwiseAbs().maxCoeff()));
    CHECK(lu.statistics().last_backward_error == -1.0);
    std::ostringstream report;
    lu.statistics().print(report);
    CHECK(report.str().find("last backward error not measured (unchecked solve)") != std::string::npos);
    CHECK(lu.statistics().refinement_steps == steps);
    CHECK(lu.statistics().solves == 1);
    const auto b2 = rhs(65, 10u);
    std::vector<double> y1 = b, y2 = b2, z2 = b2;
    lu.solve_unchecked(std::span<double>(y1), std::span<double>(y2));
    lu.solve_unchecked(z2);
    CHECK(y1 == x);
    CHECK(y2 == z2);
    CHECK(lu.statistics().solves == 4);
    // The checks of the right-hand side and of the state remain.
    std::vector<double> bad = b;
    bad[3] = std::numeric_limits<double>::infinity();
    try {
      lu.solve_unchecked(bad);
      FAIL("solve_unchecked did not throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::non_finite);
      CHECK(e.dof() == 3);
    }
    std::vector<double> short_b(10);
    CHECK_THROWS_AS(lu.solve_unchecked(short_b), std::invalid_argument);
    sparse_lu<> unfactorised;
    CHECK_THROWS_AS(unfactorised.solve_unchecked(short_b), std::logic_error);

    // After a perturbed pivot ([[0,1],[1,0]] in natural order) solve_unchecked is solve():
    // refined to the exact answer, its backward error measured, and an impossible residual
    // tolerance still reported.
    const auto p = sparsity_pattern::from_entries(2, entries_t{{0, 0}, {0, 1}, {1, 0}, {1, 1}});
    sparse_lu<natural_ordering> swap;
    swap.analyze(p);
    swap.factorize(std::vector<double>{0.0, 1.0, 1.0, 0.0});
    REQUIRE(swap.statistics().perturbed_pivots == 1);
    std::vector<double> s1{3.0, -2.0}, s2{3.0, -2.0}, t1{1.0, 4.0}, t2{1.0, 4.0};
    swap.solve_unchecked(s1);
    swap.solve(s2);
    CHECK(s1 == s2);
    CHECK(s1[0] == doctest::Approx(-2.0).epsilon(1e-14));
    CHECK(swap.statistics().last_backward_error >= 0);
    CHECK(swap.statistics().last_backward_error < 1e-15);
    swap.solve_unchecked(std::span<double>(s2), std::span<double>(t1));
    swap.solve(t2);
    CHECK(t1 == t2);
    swap.residual_tolerance = -1.0;  // nothing passes
    std::vector<double> s3{3.0, -2.0};
    try {
      swap.solve_unchecked(s3);
      FAIL("solve_unchecked did not throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::singular_matrix);
    }
  }
}
