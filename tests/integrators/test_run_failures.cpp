// Run failures and lost input reported rather than passed on silently: a state
// that overflows ends the run with non_finite naming the DOF and the time; a DOF
// outside the model is refused by the result accessors; an initial condition
// the first step cannot keep (X0 on a DOF without mass and viscosity, V0 on a
// DOF without mass) is named in the diagnostics log.

#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
using failure_model = model<point_mass, linear_spring, linear_damper, constant_force, initial_displacement, initial_velocity>;
}

TEST_SUITE("integrators/run failures") {
  TEST_CASE("a state that overflows ends the run with non_finite, naming the DOF and the time") {
    // A damper c = 1 to the ground pushed by 1e300 N: v = F / c = 1e300 (finite
    // flows), u = v t overflows at the first step of 1e9 s.
    failure_model m;
    const dof x = m.add_dof("x");
    m.add<linear_damper>("damper", {1.0}, x, m.ground());
    m.add<constant_force>("push", {.force = 1e300}, x);
    simulation sim(m, newmark{});
    std::ostringstream log;
    sim.log().to(log);
    try {
      sim.run({.end = 1e10, .smax = 1e9});
      FAIL("must throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::non_finite);
      CHECK(e.dof() == x.index);
      const std::string w = e.what();
      CHECK(w.find("displacement of DOF 'x' is no longer finite at t = 1000000000") != std::string::npos);
    }
    CHECK(log.str().find("no longer finite") != std::string::npos);
  }

  TEST_CASE("u, v, a and residual of a DOF outside the model throw invalid_model") {
    failure_model m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("spring", {100.0}, x, m.ground());
    simulation sim(m, newmark{});
    CHECK_THROWS_WITH_AS(sim.u(x), doctest::Contains("before the first stage"), error);
    sim.run({.end = 0.01, .smax = 0.01});
    CHECK(sim.u(x) == sim.state().u(x.index));
    failure_model bigger;
    const auto many = bigger.add_dofs(5, "y");
    // many[0] has index 1, a valid index here (x's): only its owner tells it apart.
    REQUIRE(many[0].index == x.index);
    for (dof bad : {dof{-1}, dof{m.dof_count()}, many[4], many[0]}) {
      CAPTURE(bad.index);
      const bool foreign = bad.owner != 0;
      CHECK_THROWS_WITH_AS(sim.u(bad),
                           doctest::Contains(foreign ? "belongs to another model" : "is not a DOF of this model"), error);
      CHECK_THROWS_AS(sim.v(bad), error);
      CHECK_THROWS_AS(sim.a(bad), error);
      CHECK_THROWS_AS(sim.residual(bad), error);
      try {
        (void)sim.a(bad);
      } catch (const error& e) {
        CHECK(e.code() == error_code::invalid_model);
      }
    }
    // A copy of the model keeps its serial number: its DOFs stay valid there.
    failure_model copy = m;
    CHECK(copy.owns(x));
    CHECK_FALSE(copy.owns(many[0]));
  }

  TEST_CASE("a DOF of another model is refused when elements are placed and scales are set") {
    failure_model m, other;
    const dof x = m.add_dof("x");
    const dof y = other.add_dof("y");
    REQUIRE(x.index == y.index);
    try {
      other.add<point_mass>("mass", {1.0}, x);
      FAIL("must throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_model);
      CHECK(std::string(e.what()).find("belongs to another model (connection 1)") != std::string::npos);
    }
    CHECK_THROWS_WITH_AS(other.set_scale(x, dof_scale{1.0, 1.0}), doctest::Contains("belongs to another model"), error);
    CHECK_THROWS_WITH_AS((void)other.scale(x), doctest::Contains("belongs to another model"), error);
    // A DOF made from a bare index is taken by any model (owner 0).
    CHECK_NOTHROW(other.add<point_mass>("mass", {1.0}, dof{y.index}));
  }

  TEST_CASE("X0 on a DOF without mass or viscosity and V0 on a massless DOF are named in the log") {
    // x: springs only (algebraic: its displacement follows from k1 x = k2 (y - x));
    // y: a mass. X0 on x is not kept (the zero step puts x on its equation), X0 on y is kept.
    failure_model m;
    const dof x = m.add_dof("x"), y = m.add_dof("y"), z = m.add_dof("z");
    m.add<linear_spring>("k1", {100.0}, x, m.ground());
    m.add<linear_spring>("k2", {100.0}, x, y);
    m.add<point_mass>("mass", {1.0}, y);
    m.add<linear_damper>("damper", {1.0}, z, m.ground());
    m.add<linear_spring>("k3", {10.0}, z, m.ground());
    m.add<initial_displacement>("x0", {0.2}, x);
    m.add<initial_displacement>("y0", {0.1}, y);
    m.add<initial_velocity>("vz", {3.0}, z);
    simulation sim(m, newmark{});
    std::ostringstream log;
    sim.log().to(log);
    sim.run({.end = 0.01, .smax = 0.01});
    const std::string w = log.str();
    CHECK(w.find("initial displacement set by 'x0' on DOF 'x' is not kept") != std::string::npos);
    CHECK(w.find("'y0'") == std::string::npos);
    CHECK(w.find("initial velocity set by 'vz' on DOF 'z' is not kept") != std::string::npos);
    // Indeed: x follows k1 x = k2 (y - x), i.e. x = y / 2.
    CHECK(sim.u(x) == doctest::Approx(sim.u(y) / 2).epsilon(1e-6));
    // and z's velocity is the consistent one, -k3 z / c = -1 at t = 0 (not 3).
    CHECK(sim.v(z) == doctest::Approx(-10.0 * sim.u(z)).epsilon(1e-6));
  }
}
