// A singular Newton matrix whose dependent equations are the rows of exact joints: the run
// ends with code 131 and a message that names the redundant joints and the number of
// surplus equations (integrators/dependent_equations.hpp, failures.hpp singular_error).
//
// The counts are those of the constraint rows against the motion they hold (Gruebler's
// count, e.g. Shabana, Dynamics of Multibody Systems, 3rd ed., section 3.4, redundant
// constraints): two SPH3X at one body point write 6 rows that hold 3 translations, 3 too
// many; two REV3X bearings on one rigid shaft write 10 rows (3 for the point, 2 for the
// axis, each) that hold the 5 motions other than the spin, 5 too many. A linear chain of
// springs that is not held anywhere is singular for another reason (a rigid motion of the
// unknowns): its dependent equations are those of its DOFs, not a joint's.

#include <doctest/doctest.h>

#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using redc_model = pradis::model<rigid_body, exact_spherical_joint, exact_revolute_joint, spatial_force,
    initial_rotation, linear_spring>;

struct redc_body {
  std::vector<dof> x;
  rotation_node r;
  explicit redc_body(redc_model& m) {
    x = m.add_dofs(3, "shaft.x");
    r = m.add_rotation_node("shaft.r");
    m.add<rigid_body>("shaft", {2.0, 0.01, 0.05, 0.05, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
  }
};

/// The error that ends a run of `m` (both drivers), or none.
template <class M>
std::optional<error> redc_run(M& m, bool bdf) {
  try {
    const run_options o{.end = 1e-2, .out = 1e-2, .smax = 1e-3};
    if (bdf) {
      bdf_simulation sim(m);
      sim.run(o);
    } else {
      simulation sim(m);
      sim.run(o);
    }
  } catch (const error& e) {
    return e;
  }
  return std::nullopt;
}

bool redc_has(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }
}  // namespace

TEST_SUITE("spatial/redundant constraints") {
  TEST_CASE("two SPH3X at one body point: code 131 naming both joints and 3 surplus equations") {
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      redc_model m;
      const redc_body b(m);
      const dof G = m.ground();
      // The body's centre at (0, 0, -0.3), the joint point at the origin, under gravity.
      for (const char* name : {"tip a", "tip b"})
        m.add<exact_spherical_joint>(name, {{0, 0, 0, 0, 0, 0, 0, 0, -0.3, 0, 0, 0.3}}, G, G, G, G, G, G, b.x[0],
                                     b.x[1], b.x[2], b.r);
      m.add<spatial_force>("gravity", {0, 0, -2 * 9.81, 0, 0, 0, 0, 0}, b.x[0], b.x[1], b.x[2]);
      const auto e = redc_run(m, bdf);
      REQUIRE(e);
      CAPTURE(e->message());
      CHECK(e->code() == error_code::singular_matrix);
      CHECK(redc_has(e->message(), "redundant constraints: the equations of SPH3X 'tip a', SPH3X 'tip b' depend "
                                   "on each other (3 more than the motion they hold needs)"));
      CHECK(redc_has(e->message(), "[t = 0]"));
    }
  }

  TEST_CASE("two REV3X bearings on one rigid shaft: code 131 naming both and 5 surplus equations") {
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      redc_model m;
      const redc_body b(m);
      const dof G = m.ground();
      // The shaft along X through its centre at the origin, bearings at x = -0.2 and x = 0.2, spinning.
      m.add<exact_revolute_joint>("left", {{0, 0, 0, -0.2, 0, 0, 0, 0, 0, -0.2, 0, 0}, 1, 0, 0, 1, 0, 0}, G, G, G, G,
                                  G, G, b.x[0], b.x[1], b.x[2], b.r);
      m.add<exact_revolute_joint>("right", {{0, 0, 0, 0.2, 0, 0, 0, 0, 0, 0.2, 0, 0}, 1, 0, 0, 1, 0, 0}, G, G, G, G,
                                  G, G, b.x[0], b.x[1], b.x[2], b.r);
      m.add<initial_rotation>("spin", {1, 0, 0, 0, 10, 0, 0}, b.r);
      const auto e = redc_run(m, bdf);
      REQUIRE(e);
      CAPTURE(e->message());
      CHECK(e->code() == error_code::singular_matrix);
      CHECK(redc_has(e->message(), "redundant constraints: the equations of REV3X 'left', REV3X 'right' depend on "
                                   "each other (5 more than the motion they hold needs)"));
      CHECK(redc_has(e->message(), "PTL3X or CYL3X instead of REV3X"));
    }
  }

  TEST_CASE("a free chain of springs: the dependent equations are its DOFs', not a constraint's") {
    // K = k [[1, -1, 0], [-1, 2, -1], [0, -1, 1]] has the left null vector (1, 1, 1): a rigid
    // translation of the chain that no element resists. The old message (a DOF needs stiffness,
    // viscosity or mass, or a support) stays, with the three DOFs named.
    redc_model m;
    const dof a = m.add_dof("a"), b = m.add_dof("b"), c = m.add_dof("c");
    m.add<linear_spring>("ab", {100.0}, a, b);
    m.add<linear_spring>("bc", {100.0}, b, c);
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      const auto e = redc_run(m, bdf);
      REQUIRE(e);
      CAPTURE(e->message());
      CHECK(e->code() == error_code::singular_matrix);
      CHECK(redc_has(e->message(), "a DOF needs stiffness, viscosity or mass, or a support"));
      CHECK(redc_has(e->message(), "; the equations of DOFs 'a', 'b', 'c' depend on each other"));
      CHECK(!redc_has(e->message(), "redundant"));
    }
  }
}
