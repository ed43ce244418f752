// Accuracy safeguards of the sparse LU: non-finite input and output, equilibration of badly
// scaled matrices, zero-diagonal rows (modified nodal analysis, Lagrange multipliers,
// saddle-point matrices), the condition estimate and the figures that reveal loss of precision.

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
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

/// Triplet collector; CSR pattern + values (duplicates summed); dense copy for references.
struct sparse_matrix {
  int n = 0;
  std::vector<std::pair<int, int>> ij;
  std::vector<double> v;
  sparsity_pattern pattern;
  std::vector<double> values;

  explicit sparse_matrix(int dim) : n(dim) {}
  void add(int i, int j, double x) {
    ij.emplace_back(i, j);
    v.push_back(x);
  }
  void finish() {
    pattern = sparsity_pattern::from_entries(n, ij);
    values.assign(static_cast<std::size_t>(pattern.nnz()), 0.0);
    for (std::size_t k = 0; k < v.size(); ++k) values[pattern.find(ij[k].first, ij[k].second)] += v[k];
  }
  Eigen::MatrixXd dense() const {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t k = 0; k < v.size(); ++k) m(ij[k].first, ij[k].second) += v[k];
    return m;
  }
};

template <class Lu>
std::vector<double> solve_with(Lu& lu, const sparse_matrix& m, std::vector<double> b) {
  lu.analyze(m.pattern);
  lu.factorize(m.values);
  lu.solve(b);
  return b;
}

/// Modified nodal analysis of: ideal source E between node 1 and ground, R1 from node 1 to
/// node 2, R2 from node 2 to ground, R3 from node 2 to node 3, R4 from node 3 to ground.
/// Unknowns v1, v2, v3, i_s (source current); the source row v1 = E has no diagonal.
/// store_zero: the pattern holds the (zero) diagonal entry of the source row.
sparse_matrix mna_circuit(bool store_zero) {
  const double g1 = 1 / 2.0, g2 = 1 / 3.0, g3 = 1 / 1.0, g4 = 1 / 2.0;
  sparse_matrix m(4);
  m.add(0, 0, g1), m.add(0, 1, -g1), m.add(0, 3, 1.0);
  m.add(1, 0, -g1), m.add(1, 1, g1 + g2 + g3), m.add(1, 2, -g3);
  m.add(2, 1, -g3), m.add(2, 2, g3 + g4);
  m.add(3, 0, 1.0);
  if (store_zero) m.add(3, 3, 0.0);
  m.finish();
  return m;
}

/// Saddle-point matrix [[K, G^T], [G, 0]] under a random symmetric renumbering: K is a
/// non-symmetric k x k grid operator (positive definite symmetric part), G has nc rows, row c
/// ties node a_c (distinct for every c, so G has full row rank) to a neighbour with random
/// weights. The zero diagonal of every other constraint row is stored, the rest is absent.
/// redundant: the last constraint row is the sum of the first two (rank deficient).
struct saddle_problem {
  sparse_matrix m{0};
  std::vector<int> constraint_rows;  // new indices of the constraint rows
};
saddle_problem saddle(int k, int nc, bool redundant, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  const int nk = k * k, n = nk + nc;
  std::vector<int> num(n);
  std::iota(num.begin(), num.end(), 0);
  std::shuffle(num.begin(), num.end(), rng);
  saddle_problem s;
  s.m = sparse_matrix(n);
  auto add = [&](int i, int j, double x) { s.m.add(num[i], num[j], x); };
  for (int y = 0; y < k; ++y)
    for (int x = 0; x < k; ++x) {
      const int i = y * k + x;
      add(i, i, 4.2);
      if (x > 0) add(i, i - 1, -1.2);
      if (x + 1 < k) add(i, i + 1, -0.8);
      if (y > 0) add(i, i - k, -1.1);
      if (y + 1 < k) add(i, i + k, -0.9);
    }
  std::vector<int> nodes(nk);
  std::iota(nodes.begin(), nodes.end(), 0);
  std::shuffle(nodes.begin(), nodes.end(), rng);
  std::vector<std::vector<std::pair<int, double>>> rows;
  for (int c = 0; c < nc; ++c) {
    const int a = nodes[c];
    const int b = (a % k + 1 < k) ? a + 1 : a - 1;
    rows.push_back({{a, u(rng)}, {b, -u(rng)}});
  }
  if (redundant) {
    rows.back() = rows[0];
    rows.back().insert(rows.back().end(), rows[1].begin(), rows[1].end());
  }
  for (int c = 0; c < nc; ++c) {
    const int r = nk + c;
    for (const auto& [j, w] : rows[c]) {
      add(r, j, w);
      add(j, r, w);
    }
    if (c % 2 == 0) add(r, r, 0.0);
    s.constraint_rows.push_back(num[r]);
  }
  s.m.finish();
  return s;
}

}  // namespace

TEST_SUITE("linalg/accuracy") {
  TEST_CASE("a NaN or infinite matrix entry or right-hand side is rejected naming its row") {
    sparse_matrix m(3);
    for (int i = 0; i < 3; ++i) {
      m.add(i, i, 4.0);
      if (i > 0) m.add(i, i - 1, -1.0), m.add(i - 1, i, -1.0);
    }
    m.finish();
    sparse_lu<> lu;
    lu.analyze(m.pattern);
    auto bad = m.values;
    bad[static_cast<std::size_t>(m.pattern.find(2, 1))] = std::numeric_limits<double>::infinity();
    try {
      lu.factorize(bad);
      FAIL("factorize did not throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::non_finite);
      CHECK(e.dof() == 2);
      CHECK(std::string(e.what()).find("row 2, column 1") != std::string::npos);
    }
    CHECK_FALSE(lu.factorized());
    lu.factorize(m.values);
    for (const double v : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
      std::vector<double> b{1.0, v, 1.0};
      try {
        lu.solve(b);
        FAIL("solve did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::non_finite);
        CHECK(e.dof() == 1);
        CHECK(std::string(e.what()).find("right-hand side entry 1") != std::string::npos);
      }
    }
    CHECK(lu.statistics().solves == 0);
  }

  TEST_CASE("a solution that overflows is rejected as a singular matrix naming the component") {
    // diag(1, 1e-300) x = (1, 1e300): x_1 = 1e600 is not a double.
    sparse_matrix m(2);
    m.add(0, 0, 1.0), m.add(1, 1, 1e-300);
    m.finish();
    sparse_lu<natural_ordering> lu;
    lu.analyze(m.pattern);
    lu.factorize(m.values);
    std::vector<double> b{1.0, 1e300};
    try {
      lu.solve(b);
      FAIL("solve did not throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::singular_matrix);
      CHECK(e.dof() == 1);
    }
  }

  TEST_CASE("equilibration: rows scaled by 1e-150..1e+150 solve to full accuracy with a small condition estimate") {
    // A = D_r B D_c with B = tridiag(-1, 4, -1) plus a few long-range entries (diagonally
    // dominant, so cond(B) is small), row scales r_i = 10^e_i with e_i scattered over
    // -150..150 and column scales c_j = 10^(j mod 7 - 3). With integer y_j = 1 + j mod 3,
    // B y = f is exact, b = D_r f and x_j = y_j / c_j up to the rounding of the data (a
    // componentwise relative perturbation of a few eps, amplified by the small condition of B).
    // Without equilibration the 1-norm condition number of A is about 1e300 and would raise a
    // false "nearly singular" warning; the equilibrated matrix is B up to powers of two.
    const int n = 31;
    sparse_matrix m(n);
    std::vector<double> r(n), c(n), y(n), f(n, 0.0);
    for (int i = 0; i < n; ++i) {
      r[i] = std::pow(10.0, -150 + (i * 17) % n * 10);
      c[i] = std::pow(10.0, i % 7 - 3);
      y[i] = 1 + i % 3;
    }
    auto add = [&](int i, int j, double bij) {
      m.add(i, j, r[i] * bij * c[j]);
      f[i] += bij * y[j];
    };
    for (int i = 0; i < n; ++i) {
      add(i, i, 4.0);
      if (i > 0) add(i, i - 1, -1.0);
      if (i + 1 < n) add(i, i + 1, -1.0);
      if (i + 10 < n) add(i, i + 10, 1.0), add(i + 10, i, -1.0);
    }
    m.finish();
    std::vector<double> b(n);
    for (int i = 0; i < n; ++i) b[i] = r[i] * f[i];
    auto check = [&](auto lu) {
      lu.estimate_condition_on_factorize = true;
      const auto x = solve_with(lu, m, b);
      const auto& st = lu.statistics();
      double err = 0;
      for (int j = 0; j < n; ++j) err = std::max(err, std::abs(x[j] - y[j] / c[j]) / (y[j] / c[j]));
      CHECK(err < 1e-14);
      CHECK(st.perturbed_pivots == 0);
      CHECK(st.last_backward_error < 1e-15);
      CHECK(st.condition_estimate < 1e4);
      CHECK_FALSE(st.ill_conditioned());
    };
    check(sparse_lu<natural_ordering>{});
    check(sparse_lu<min_degree_ordering>{});
    sparse_lu<natural_ordering> raw;  // the same matrix without equilibration
    raw.equilibrate = false;
    raw.estimate_condition_on_factorize = true;
    solve_with(raw, m, b);
    CHECK(raw.statistics().condition_estimate > 1e250);
  }

  TEST_CASE("ideal voltage source in modified nodal form: exact node voltages and source current") {
    // E = 10 V, R1 = 2, R2 = 3, R3 = 1, R4 = 2 ohm. R3 + R4 = 3 in parallel with R2 = 3 gives
    // 1.5 ohm, so the source drives 10 / 3.5 = 20/7 A: v2 = 1.5 * 20/7 = 30/7 V,
    // v3 = v2 * R4 / (R3 + R4) = 20/7 V, and the source current (into node 1 by the MNA sign
    // convention) is i_s = -(v1 - v2) / R1 = -20/7 A.
    const std::vector<double> exact{10.0, 30.0 / 7, 20.0 / 7, -20.0 / 7};
    for (const bool store_zero : {false, true}) {
      const auto m = mna_circuit(store_zero);
      sparse_lu<min_degree_ordering> lu;  // min_degree picks the source row (degree 1) first
      const auto x = solve_with(lu, m, {0.0, 0.0, 0.0, 10.0});
      for (int i = 0; i < 4; ++i) CHECK(x[i] == doctest::Approx(exact[i]).epsilon(1e-15));
      const auto& st = lu.statistics();
      CHECK(st.perturbed_pivots == 0);
      CHECK(st.delayed_rows == 1);
      CHECK(st.reanalyses == (store_zero ? 1 : 0));  // a stored zero is found by factorize()
      const auto& perm = lu.permutation();  // the source row follows its only neighbour, node 1
      CHECK(std::find(perm.begin(), perm.end(), 3) > std::find(perm.begin(), perm.end(), 0));
      CHECK(st.refinement_steps == 0);
    }
    // The source row named in analyze(): no re-analysis even with the zero stored.
    const auto m = mna_circuit(true);
    sparse_lu<min_degree_ordering> lu;
    const std::vector<int> zero_rows{3};
    lu.analyze(m.pattern, zero_rows);
    lu.factorize(m.values);
    CHECK(lu.statistics().reanalyses == 0);
    CHECK(lu.statistics().delayed_rows == 1);
    CHECK_THROWS_AS(lu.analyze(m.pattern, std::vector<int>{4}), std::invalid_argument);
  }

  TEST_CASE("spring-mass chain with a Lagrange-multiplier constraint row: exact displacements and reaction") {
    // Ground -k1- mass 1 -k2- mass 2, force f on mass 1, constraint x2 = d enforced by the
    // multiplier lambda (the reaction on mass 2): [[k1+k2, -k2, 0], [-k2, k2, 1], [0, 1, 0]].
    // Row 3: x2 = d; row 1: (k1 + k2) x1 = f + k2 d; row 2: lambda = k2 (x1 - d).
    const double k1 = 100, k2 = 50, f = 10, d = 0.2;
    sparse_matrix m(3);
    m.add(0, 0, k1 + k2), m.add(0, 1, -k2), m.add(1, 0, -k2), m.add(1, 1, k2);
    m.add(1, 2, 1.0), m.add(2, 1, 1.0), m.add(2, 2, 0.0);
    m.finish();
    const double x1 = (f + k2 * d) / (k1 + k2), lambda = k2 * (x1 - d);
    sparse_lu<min_degree_ordering> lu;
    const auto x = solve_with(lu, m, {f, 0.0, d});
    CHECK(x[0] == doctest::Approx(x1).epsilon(1e-15));
    CHECK(x[1] == doctest::Approx(d).epsilon(1e-15));
    CHECK(x[2] == doctest::Approx(lambda).epsilon(1e-14));
    CHECK(lu.statistics().perturbed_pivots == 0);
  }

  TEST_CASE("a saddle point with 120 constraints matches dense partial-pivoting LU to 1e-12 under every ordering") {
    const auto s = saddle(15, 120, false, 5u);
    const int n = s.m.n;
    std::mt19937 rng(11u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> b(n);
    for (auto& x : b) x = u(rng);
    const Eigen::VectorXd ref = s.m.dense().partialPivLu().solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
    auto check = [&](auto lu) {
      const auto x = solve_with(lu, s.m, b);
      double err = 0;
      for (int i = 0; i < n; ++i) err = std::max(err, std::abs(x[i] - ref[i]));
      CHECK(err / ref.cwiseAbs().maxCoeff() < 1e-12);
      CHECK(lu.statistics().perturbed_pivots == 0);
      CHECK(lu.statistics().delayed_rows == 120);
      // Every constraint row comes after its primal neighbours.
      std::vector<int> pos(n);
      for (int k = 0; k < n; ++k) pos[lu.permutation()[k]] = k;
      const std::set<int> cons(s.constraint_rows.begin(), s.constraint_rows.end());
      for (const int r : s.constraint_rows)
        for (int q = s.m.pattern.row_ptr[r]; q < s.m.pattern.row_ptr[r + 1]; ++q) {
          const int j = s.m.pattern.col[q];
          if (!cons.count(j)) CHECK(pos[j] < pos[r]);
        }
    };
    check(sparse_lu<natural_ordering>{});
    check(sparse_lu<min_degree_ordering>{});
    check(sparse_lu<min_fill_ordering>{});
    check(sparse_lu<automatic_ordering>{});
  }

  TEST_CASE("a saddle point with a redundant constraint is reported as singular, naming a dependent row") {
    const auto s = saddle(8, 20, true, 7u);
    // Dependent rows: the first two constraints and the last (their sum).
    const std::set<int> dependent{s.constraint_rows[0], s.constraint_rows[1], s.constraint_rows[19]};
    auto check = [&](auto lu) {
      lu.analyze(s.m.pattern);
      try {
        lu.factorize(s.m.values);
        FAIL("factorize did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::singular_matrix);
        CHECK(dependent.count(e.dof()) == 1);
      }
      CHECK_FALSE(lu.factorized());
    };
    check(sparse_lu<natural_ordering>{});
    check(sparse_lu<min_degree_ordering>{});
    check(sparse_lu<min_fill_ordering>{});
  }

  TEST_CASE("the condition estimate is a lower bound of the exact 1-norm condition number, within a factor 3") {
    // Matrices whose equilibration is a uniform power of two (every row and column has the same
    // largest magnitude), so the exact condition number of A is that of the equilibrated matrix.
    for (const int n : {1, 2, 10, 60}) {
      for (const bool nonsym : {false, true}) {
        sparse_matrix m(n);
        for (int i = 0; i < n; ++i) {
          m.add(i, i, 2.0);
          if (i > 0) m.add(i, i - 1, -1.0);
          if (i + 1 < n) m.add(i, i + 1, nonsym ? -0.5 - 0.5 * ((i % 3) == 0) : -1.0);
        }
        m.finish();
        const Eigen::MatrixXd a = m.dense();
        const Eigen::MatrixXd inv = a.inverse();
        const double exact = a.cwiseAbs().colwise().sum().maxCoeff() * inv.cwiseAbs().colwise().sum().maxCoeff();
        sparse_lu<min_degree_ordering> lu;
        lu.analyze(m.pattern);
        CHECK_THROWS_AS(lu.estimate_condition(), std::logic_error);  // nothing factorised yet
        lu.factorize(m.values);
        CHECK(lu.statistics().condition_estimate == 0);  // not estimated unless asked
        const double est = lu.estimate_condition();
        CHECK(est <= exact * (1 + 1e-12));
        CHECK(est >= exact / 3);
        CHECK(lu.statistics().condition_estimate == est);
        CHECK_FALSE(lu.statistics().ill_conditioned());
        CHECK(lu.statistics().precision_warning().empty());
      }
    }
  }

  TEST_CASE("loss of precision: masses of 1e-12 on a spring of 1e12 are rejected or flagged, never silent") {
    // Two free masses m joined by a spring k; Newton matrix of an implicit step with
    // M / (beta h^2) = mu: J = [[k + mu, -k], [-k, k + mu]], eigenvalues mu and 2k + mu, so
    // cond = (2k + mu) / mu. For b = (1, 1) the exact solution is x1 = x2 = 1 / mu. With
    // k = 1e12 and m = 1e-12 the stored k + mu keeps only a few digits of mu, and the second
    // pivot 2 mu (1 + O(mu/k)) is formed by cancellation of numbers of size k.
    const double k = 1e12;
    auto make = [&](double mu) {
      sparse_matrix m(2);
      m.add(0, 0, k + mu), m.add(0, 1, -k), m.add(1, 0, -k), m.add(1, 1, k + mu);
      m.finish();
      return m;
    };
    {  // h = 3e-6: mu = 0.111, cond = 1.8e13. Default (static pivoting): the second pivot is
       // 1.1e-13 of its row, below the perturbation threshold; refinement cannot repair a
       // perturbation of 1.5e-8 at that condition, so factorize() reports the row.
      const auto m = make(1e-12 / (3e-6 * 3e-6));
      sparse_lu<natural_ordering> lu;
      lu.analyze(m.pattern);
      try {
        lu.factorize(m.values);
        FAIL("factorize did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::singular_matrix);
        CHECK(e.dof() == 1);
      }
    }
    {  // The same with static pivoting off (pivots accepted down to 1e-13 of their row): the
       // factorisation succeeds and the solve is backward stable, yet at least 10 of 16 digits
       // are gone; the residual cannot show this, the condition estimate does.
      const double mu = 1e-12 / (3e-6 * 3e-6);
      const auto m = make(mu);
      sparse_lu<natural_ordering> lu;
      lu.static_pivoting = false;
      lu.estimate_condition_on_factorize = true;
      const auto x = solve_with(lu, m, {1.0, 1.0});
      const auto& st = lu.statistics();
      const double err = std::abs(x[0] - 1 / mu) * mu;
      MESSAGE("relative error " << err << ", condition estimate " << st.condition_estimate << ", backward error "
                                << st.last_backward_error << ", growth " << st.max_growth);
      CHECK(st.last_backward_error < 1e-15);
      CHECK(err > 1e-6);
      CHECK(err < 10 * st.condition_estimate * std::numeric_limits<double>::epsilon());
      CHECK(st.condition_estimate > 1e13);
      CHECK(st.ill_conditioned());
      CHECK(st.precision_warning().find("condition estimate") != std::string::npos);
    }
    {  // h = 1e-3: mu = 1e-6 vanishes in k + mu entirely; the stored matrix is exactly singular.
      const auto m = make(1e-12 / (1e-3 * 1e-3));
      sparse_lu<natural_ordering> lu;
      lu.analyze(m.pattern);
      try {
        lu.factorize(m.values);
        FAIL("factorize did not throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::singular_matrix);
        CHECK(e.dof() == 1);
      }
    }
    {  // Healthy masses (m = 1, k = 1e3, h = 1e-3: mu = 1e6): cond = (1e6 + 2e3) / 1e6, no warning.
      sparse_matrix m(2);
      m.add(0, 0, 1e3 + 1e6), m.add(0, 1, -1e3), m.add(1, 0, -1e3), m.add(1, 1, 1e3 + 1e6);
      m.finish();
      sparse_lu<natural_ordering> lu;
      lu.estimate_condition_on_factorize = true;
      solve_with(lu, m, {1.0, 1.0});
      CHECK(lu.statistics().condition_estimate == doctest::Approx((1e6 + 2e3) / 1e6));
      CHECK(lu.statistics().precision_warning().empty());
    }
  }

  TEST_CASE("pivot growth reports a perturbed pivot when zero diagonals are not delayed") {
    // [[0, 1], [1, 1]] in natural order without the delay: the zero pivot is replaced by
    // delta = perturbation * 1, and u22 = 1 - 1/delta: growth 1/delta - 1 (Higham's growth
    // factor of static pivoting); with the delay the row is eliminated second and growth is 1.
    sparse_matrix m(2);
    m.add(0, 0, 0.0), m.add(0, 1, 1.0), m.add(1, 0, 1.0), m.add(1, 1, 1.0);
    m.finish();
    sparse_lu<natural_ordering> plain;
    plain.delay_zero_diagonals = false;
    const auto x = solve_with(plain, m, {1.0, 3.0});
    CHECK(x[0] == doctest::Approx(2.0).epsilon(1e-15));
    CHECK(x[1] == doctest::Approx(1.0).epsilon(1e-15));
    CHECK(plain.statistics().perturbed_pivots == 1);
    CHECK(plain.statistics().max_growth == doctest::Approx(1 / plain.perturbation - 1).epsilon(1e-12));
    CHECK(plain.statistics().precision_warning().empty());  // 6.7e7 < 1e8: refinement repairs it
    sparse_lu<natural_ordering> delayed;
    const auto y = solve_with(delayed, m, {1.0, 3.0});
    CHECK(y[0] == doctest::Approx(2.0).epsilon(1e-15));
    CHECK(delayed.statistics().perturbed_pivots == 0);
    CHECK(delayed.statistics().max_growth == doctest::Approx(1.0));
  }
}
