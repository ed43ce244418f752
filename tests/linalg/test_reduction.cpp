// Guyan and Craig-Bampton reduction (linalg/reduction.hpp) and Matrix Market
// files (io/matrix_market.hpp) on a cantilever of Euler-Bernoulli beam elements
// (Hermite cubics, consistent mass; Przemieniecki, Theory of Matrix Structural
// Analysis, 1968, ch. 5 and 11), clamped at the root:
// - Guyan to the tip's deflection and rotation gives the exact static tip
//   response: w = P L^3 / (3 EI), theta = P L^2 / (2 EI) under a tip force,
//   w = M L^2 / (2 EI), theta = M L / EI under a tip moment (Hermite elements
//   are exact for nodal loads, so the full model and the reduction agree with
//   the closed form to round-off);
// - Craig-Bampton with the tip as boundary reproduces the full model's first two
//   bending frequencies within 0.01 % from 5 fixed-interface modes, converging
//   with the number of modes; the full model's first two frequencies match the
//   continuous beam's, (1.87510407)^2 and (4.69409113)^2 sqrt(EI / (rho A L^4))
//   (Blevins, Formulas for Natural Frequency and Mode Shape, table 8-1);
// - the files round-trip exactly, and every defect of a file and of the input to
//   the reduction is a clear error.

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pradis/io/matrix_market.hpp"
#include "pradis/linalg/reduction.hpp"

using namespace pradis;

namespace {
constexpr double ei = 2.0e3, rho_a = 1.5, length = 2.0;

/// K and M of a cantilever of n elements; DOFs (w, theta) of nodes 1..n (node 0 clamped).
void cantilever(int n, Eigen::MatrixXd& k, Eigen::MatrixXd& m) {
  const double l = length / n;
  Eigen::Matrix4d ke, me;
  ke << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l, 6 * l, 2 * l * l, -6 * l,
      4 * l * l;
  ke *= ei / (l * l * l);
  me << 156, 22 * l, 54, -13 * l, 22 * l, 4 * l * l, 13 * l, -3 * l * l, 54, 13 * l, 156, -22 * l, -13 * l, -3 * l * l,
      -22 * l, 4 * l * l;
  me *= rho_a * l / 420;
  const int nd = 2 * n;
  k = Eigen::MatrixXd::Zero(nd, nd);
  m = Eigen::MatrixXd::Zero(nd, nd);
  for (int e = 0; e < n; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int ra = 2 * e + a - 2, rb = 2 * e + b - 2;  // global DOF, -1/-2 = clamped root
        if (ra < 0 || rb < 0) continue;
        k(ra, rb) += ke(a, b);
        m(ra, rb) += me(a, b);
      }
}
/// The lowest `count` circular frequencies of (K, M).
Eigen::VectorXd frequencies(const Eigen::MatrixXd& k, const Eigen::MatrixXd& m, int count) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> s(k, m);
  return s.eigenvalues().head(count).cwiseSqrt();
}
/// The message of the pradis::error that f throws (empty if none).
template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const error& e) {
    return e.what();
  }
  return {};
}
}  // namespace

TEST_SUITE("linalg/reduction") {
  TEST_CASE("Guyan to the tip gives the exact static tip deflection and rotation of the cantilever") {
    Eigen::MatrixXd k, m;
    cantilever(10, k, m);
    const std::vector<int> tip{18, 19};
    const linalg::reduced_part g = linalg::guyan(k, m, tip);
    REQUIRE(g.k.rows() == 2);
    const double p = 3.0, mt = 5.0;
    const Eigen::Vector2d by_force = g.k.ldlt().solve(Eigen::Vector2d(p, 0));
    const Eigen::Vector2d by_moment = g.k.ldlt().solve(Eigen::Vector2d(0, mt));
    const double l3 = length * length * length;
    CHECK(by_force(0) == doctest::Approx(p * l3 / (3 * ei)).epsilon(1e-12));
    CHECK(by_force(1) == doctest::Approx(p * length * length / (2 * ei)).epsilon(1e-12));
    CHECK(by_moment(0) == doctest::Approx(mt * length * length / (2 * ei)).epsilon(1e-12));
    CHECK(by_moment(1) == doctest::Approx(mt * length / ei).epsilon(1e-12));
    // T maps the tip motion to the full static deflection: the full solve agrees.
    Eigen::VectorXd f = Eigen::VectorXd::Zero(20);
    f(18) = p;
    const Eigen::VectorXd full = k.ldlt().solve(f);
    CHECK((g.t * by_force - full).norm() <= 1e-12 * full.norm());
    CHECK(g.mode_frequencies.size() == 0);
    // The reduced mass T^T M T is positive definite.
    CHECK(g.m.llt().info() == Eigen::Success);
  }

  TEST_CASE("Craig-Bampton reproduces the first two bending frequencies within 0.01 % (5 modes) and converges with the modes") {
    Eigen::MatrixXd k, m;
    cantilever(20, k, m);
    const Eigen::VectorXd full = frequencies(k, m, 2);
    const double scale = std::sqrt(ei / (rho_a * std::pow(length, 4)));
    CHECK(full(0) == doctest::Approx(1.87510407 * 1.87510407 * scale).epsilon(1e-6));
    CHECK(full(1) == doctest::Approx(4.69409113 * 4.69409113 * scale).epsilon(1e-5));
    const std::vector<int> tip{38, 39};
    double previous = 1;
    for (int modes : {0, 1, 2, 3, 5, 8}) {
      const linalg::reduced_part r = linalg::craig_bampton(k, m, tip, modes);
      REQUIRE(r.k.rows() == 2 + modes);
      REQUIRE(r.mode_frequencies.size() == modes);
      const Eigen::VectorXd red = frequencies(r.k, r.m, 2);
      const double err = std::max(std::abs(red(0) / full(0) - 1), std::abs(red(1) / full(1) - 1));
      CAPTURE(modes);
      CAPTURE(err);
      CHECK(red(0) >= full(0) * (1 - 1e-12));  // a Ritz reduction never lowers a frequency
      CHECK(err <= previous * (1 + 1e-9));     // more modes, no worse
      if (modes >= 5) CHECK(err < 1e-4);  // measured: 4.2e-3, 1.1e-3, 3.6e-4, 6.3e-5, 9.7e-6 at 1, 2, 3, 5, 8 modes
      previous = err;
      // The modal block is diagonal: K_qq = diag(w^2), M_qq = I.
      for (int a = 0; a < modes; ++a) {
        CHECK(r.k(2 + a, 2 + a) == doctest::Approx(r.mode_frequencies(a) * r.mode_frequencies(a)).epsilon(1e-9));
        CHECK(r.m(2 + a, 2 + a) == doctest::Approx(1).epsilon(1e-9));
        CHECK(std::abs(r.k(0, 2 + a)) <= 1e-9 * r.k.cwiseAbs().maxCoeff());  // static and modal parts decouple in K
      }
    }
  }

  TEST_CASE("bad input to the reduction is refused with its code and a clear message") {
    Eigen::MatrixXd k, m;
    cantilever(4, k, m);
    CHECK(message_of([&] { (void)linalg::guyan(k, m.topLeftCorner(4, 4), {6, 7}); }).find("of one size") !=
          std::string::npos);
    Eigen::MatrixXd kn = k;
    kn(0, 1) += 1;
    CHECK(message_of([&] { (void)linalg::guyan(kn, m, {6, 7}); }).find("symmetric") != std::string::npos);
    CHECK(message_of([&] { (void)linalg::guyan(k, m, {}); }).find("no boundary DOF") != std::string::npos);
    CHECK(message_of([&] { (void)linalg::guyan(k, m, {6, 8}); }).find("boundary DOF 8 is outside 0..7") !=
          std::string::npos);
    CHECK(message_of([&] { (void)linalg::guyan(k, m, {6, 6}); }).find("given twice") != std::string::npos);
    CHECK(message_of([&] { (void)linalg::craig_bampton(k, m, {6, 7}, 7); }).find("7 modes asked for") !=
          std::string::npos);
    // A free-free beam held at one DOF only: a rigid-body motion is left.
    Eigen::MatrixXd kf = Eigen::MatrixXd::Zero(4, 4), mf = Eigen::MatrixXd::Identity(4, 4);
    kf << 12, 6, -12, 6, 6, 4, -6, 2, -12, -6, 12, -6, 6, 2, -6, 4;
    try {
      (void)linalg::guyan(kf, mf, {0});
      FAIL("no error");
    } catch (const error& e) {
      CHECK(e.code() == error_code::singular_matrix);
      CHECK(e.message().find("do not hold the part") != std::string::npos);
    }
    Eigen::MatrixXd mz = m;
    mz.row(0).setZero();
    mz.col(0).setZero();
    CHECK(message_of([&] { (void)linalg::craig_bampton(k, mz, {6, 7}, 2); }).find("M_ii is not positive definite") !=
          std::string::npos);
  }

  TEST_CASE("a reduction near the largest double stays finite or is refused as non-finite") {
    // Every DOF on the boundary: K_r = K, also for K = 1e308 (the symmetrisation halves
    // before it adds, so K + K^T does not overflow).
    const Eigen::MatrixXd big = Eigen::MatrixXd::Constant(1, 1, 1e308), one = Eigen::MatrixXd::Identity(1, 1);
    const linalg::reduced_part r = linalg::guyan(big, one, {0});
    CHECK(r.k(0, 0) == 1e308);
    CHECK(r.m(0, 0) == 1.0);
    // K = [[1e308, 1e308], [1e308, 1]] held at DOF 0: K_r = 1e308 - 1e308^2 / 1 overflows.
    Eigen::MatrixXd k2(2, 2);
    k2 << 1e308, 1e308, 1e308, 1;
    try {
      (void)linalg::guyan(k2, Eigen::MatrixXd::Identity(2, 2), {0});
      FAIL("no error");
    } catch (const error& e) {
      CHECK(e.code() == error_code::non_finite);
      CHECK(e.message().find("the reduced K or M is not finite") != std::string::npos);
    }
  }

  TEST_CASE("Matrix Market files round-trip exactly and each defect is located at file:line:column") {
    Eigen::MatrixXd k, m;
    cantilever(6, k, m);
    const auto dir = std::filesystem::temp_directory_path() / "pradis_mm_test";
    std::filesystem::create_directories(dir);
    io::write_matrix_market((dir / "k.mtx").string(), k, true);
    io::write_matrix_market((dir / "m.mtx").string(), m, false);
    CHECK(io::read_matrix_market((dir / "k.mtx").string()) == k);
    CHECK(io::read_matrix_market((dir / "m.mtx").string()) == m);
    // The array format, symmetric (lower triangle column by column).
    const Eigen::MatrixXd a =
        io::parse_matrix_market("%%MatrixMarket matrix array real symmetric\n% comment\n2 2\n4\n1\n3\n", "a.mtx");
    CHECK(a == (Eigen::Matrix2d() << 4, 1, 1, 3).finished());
    const auto bad = [](const std::string& text) { return message_of([&] { (void)io::parse_matrix_market(text, "f.mtx"); }); };
    const std::string h = "%%MatrixMarket matrix coordinate real symmetric\n";
    CHECK(bad("hello\n").find("f.mtx:1:1: not a Matrix Market file") != std::string::npos);
    CHECK(bad("%%MatrixMarket matrix coordinate complex general\n").find("f.mtx:1:34: field 'complex'") !=
          std::string::npos);
    CHECK(bad(h + "2 2\n").find("f.mtx:2:1: the size line must be") != std::string::npos);
    // More rows than the default limit (dense 10000 x 10000, 800 MB) is refused before any allocation.
    CHECK(bad(h + "100000 100000 1\n1 1 1\n").find("f.mtx:2:1: the row count '100000' is not a whole number in 1..10000") !=
          std::string::npos);
    CHECK(message_of([&] { (void)io::parse_matrix_market(h + "3 3 1\n1 1 1\n", "f.mtx", 2); })
              .find("the row count '3' is not a whole number in 1..2") != std::string::npos);
    CHECK(bad(h + "2 3 1\n1 1 1\n").find("must be square") != std::string::npos);
    CHECK(bad(h + "2 2 2\n1 1 4\n").find("ends after 1 of its 2 entries") != std::string::npos);
    CHECK(bad(h + "2 2 1\n1 2 4\n").find("f.mtx:3:1: entry (1, 2) is above the diagonal") != std::string::npos);
    CHECK(bad(h + "2 2 1\n3 1 4\n").find("f.mtx:3:1: the row index '3' is not a whole number in 1..2") !=
          std::string::npos);
    CHECK(bad(h + "2 2 1\n2 1 x4\n").find("f.mtx:3:5: 'x4' is not a finite number") != std::string::npos);
    CHECK(bad(h + "2 2 2\n2 1 4\n2 1 5\n").find("f.mtx:4:1: entry (2, 1) is given twice") != std::string::npos);
    CHECK(bad(h + "2 2 1\n2 1 4\n1 1 1\n").find("f.mtx:4:1: more entries than the size line announces") !=
          std::string::npos);
    CHECK(message_of([&] { (void)io::read_matrix_market((dir / "none.mtx").string()); }).find("cannot read") !=
          std::string::npos);
    std::filesystem::remove_all(dir);
  }
}
