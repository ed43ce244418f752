// LINKX (exact planar rigid link): the two code-75 situations of its evaluation,
// reached by direct evaluations after its NEWINT: the current length |B - A| close
// to zero (the direction of the link is undefined), and a direction that reversed
// against the state of the last accepted step (the link passed through zero length
// within one step). Each error names LINKX and the instance.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// One LINKX instance "rod" from A = (0, 0) to B = (2, 0) (L0 = 2) with its own work and state
// vectors, after its NEWINT.
struct rl_link {
  planar_rigid_link e{{0.0, 0.0, 2.0, 0.0}};
  std::array<double, 3> work{};
  std::array<double, 2> old_state{};
  std::array<double, 2> new_state{};
  element_context ctx{"LINKX", "rod"};
  explicit rl_link(bool with_state) {
    ctx.work = work;
    if (with_state) {
      ctx.old_state = old_state;
      ctx.new_state = new_state;
    }
    e.new_integration(ctx);
  }
  // Evaluates with B displaced by (bx, by) (A fixed) and the previous direction (oc, os).
  std::optional<pradis::error> rl_evaluate(double bx, double by, double oc = 0, double os = 0) {
    old_state = {oc, os};
    local_input<planar_rigid_link> in;
    in.u(2) = bx;
    in.u(3) = by;
    in.v(4) = 10.0;  // some axial force
    local_output<planar_rigid_link> out;
    return error_from([&] { e.evaluate(in, out, ctx); });
  }
};
}  // namespace

TEST_SUITE("elements/rigid link errors") {
  TEST_CASE("LINKX: NEWINT stores L0 and a state away from zero length evaluates without error") {
    rl_link l(true);
    CHECK(l.work[0] == doctest::Approx(2.0));
    CHECK_FALSE(l.rl_evaluate(-1.0, 0.5, 1.0, 0.0).has_value());  // B at (1, 0.5): same side as before
    CHECK(l.work[1] == doctest::Approx(std::hypot(1.0, 0.5)));
    CHECK(l.new_state[0] == doctest::Approx(1.0 / std::hypot(1.0, 0.5)));
    CHECK(l.new_state[1] == doctest::Approx(0.5 / std::hypot(1.0, 0.5)));
  }

  TEST_CASE("LINKX: a current length close to zero is code 75") {
    rl_link l(false);
    // B moved exactly onto A.
    check_error(l.rl_evaluate(-2.0, 0.0), error_code::singular_situation, "LINKX", "rod",
                "the length of the link has become close to zero");
    // B within 1e-12 L0 of A (the threshold is relative to L0 when L0 > 1 m).
    check_error(l.rl_evaluate(-2.0 + 1e-12, 1e-12), error_code::singular_situation, "LINKX", "rod",
                "close to zero");
    // Just above the threshold the link still has a direction.
    CHECK_FALSE(l.rl_evaluate(-2.0 + 1e-9, 0.0).has_value());
    // With a state too, the length is checked first.
    rl_link s(true);
    check_error(s.rl_evaluate(-2.0, 0.0, 1.0, 0.0), error_code::singular_situation, "LINKX", "rod",
                "close to zero");
  }

  TEST_CASE("LINKX: a direction reversed within one step is code 75") {
    rl_link l(true);
    // Last accepted direction +X; now B is at (-1, 0), 1 m on the other side of A: L = 1 > 0 but e = -X.
    const auto e = l.rl_evaluate(-3.0, 0.0, 1.0, 0.0);
    check_error(e, error_code::singular_situation, "LINKX", "rod", "passed through zero length");
    REQUIRE(e.has_value());
    CHECK(e->message().find("direction reversed within one step") != std::string::npos);
    CHECK(std::string(e->what()).find("rod") != std::string::npos);
    // An oblique reversal (the dot product with the old direction is negative) too.
    check_error(l.rl_evaluate(-2.5, -0.3, 0.6, 0.8), error_code::singular_situation, "LINKX", "rod",
                "passed through zero length");
    // A turn of less than 90 degrees is not a reversal; nor is any direction at the first step
    // (the old state is still zero).
    CHECK_FALSE(l.rl_evaluate(-2.0, 1.0, 1.0, 0.0).has_value());
    CHECK_FALSE(l.rl_evaluate(-3.0, 0.0, 0.0, 0.0).has_value());
    CHECK(l.new_state[0] == doctest::Approx(-1.0));
    // Without a state vector (a context that does not pass one) the reversal is not checked.
    rl_link n(false);
    CHECK_FALSE(n.rl_evaluate(-3.0, 0.0).has_value());
  }
}
