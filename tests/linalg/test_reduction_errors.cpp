// The non-finite input check of the reductions (linalg/reduction.hpp): a NaN
// or infinite entry in K or in M, on the boundary or in the interior, is refused
// by guyan and craig_bampton as invalid_model before any factorisation, with a
// message naming the function (tests/linalg/test_reduction.cpp covers the other
// input checks).

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pradis/linalg/reduction.hpp"
#include "testing/test_support.hpp"

using namespace pradis;

namespace {

/// A chain of three unit springs fixed at DOF 0's left (K positive definite)
/// with unit lumped masses.
void rde_chain(Eigen::MatrixXd& k, Eigen::MatrixXd& m) {
  k.resize(3, 3);
  k << 2, -1, 0, -1, 2, -1, 0, -1, 1;
  m = Eigen::MatrixXd::Identity(3, 3);
}

}  // namespace

TEST_SUITE("linalg/reduction errors") {
  TEST_CASE("a NaN or infinite entry of K or M: invalid_model 'K or M has a non-finite entry'") {
    Eigen::MatrixXd k, m;
    rde_chain(k, m);
    // Valid input reduces: the checks below fail on the bad entry alone.
    REQUIRE_NOTHROW((void)linalg::guyan(k, m, {2}));
    REQUIRE_NOTHROW((void)linalg::craig_bampton(k, m, {2}, 1));
    constexpr double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    struct case_t {
      bool in_k;
      int i, j;
      double x;
    };
    // Diagonal and symmetric off-diagonal entries, on the boundary (DOF 2) and in the interior.
    for (const case_t c : {case_t{true, 0, 0, nan}, case_t{true, 2, 2, inf}, case_t{true, 1, 0, -inf},
                           case_t{false, 1, 1, nan}, case_t{false, 2, 2, -inf}, case_t{false, 2, 1, inf}}) {
      CAPTURE(c.in_k);
      CAPTURE(c.i);
      CAPTURE(c.j);
      CAPTURE(c.x);
      Eigen::MatrixXd kb = k, mb = m;
      Eigen::MatrixXd& bad = c.in_k ? kb : mb;
      bad(c.i, c.j) = c.x;
      bad(c.j, c.i) = c.x;  // still symmetric in pattern: the finiteness check is what refuses it
      for (const int modes : {0, 1}) {
        CAPTURE(modes);
        const auto e = pradis_test::error_of([&] {
          if (modes == 0)
            (void)linalg::guyan(kb, mb, {2});
          else
            (void)linalg::craig_bampton(kb, mb, {2}, modes);
        });
        REQUIRE(e);
        CHECK(e->code() == error_code::invalid_model);
        CHECK(e->number() == 110);
        CHECK(pradis_test::contains(e->message(), "K or M has a non-finite entry"));
        if (modes > 0) CHECK(e->message() == "craig_bampton: K or M has a non-finite entry");
        CHECK(e->instance().empty());
      }
    }
  }
}
