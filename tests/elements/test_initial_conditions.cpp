// X0 and V0: initial displacement and velocity set at the zero step, with the
// conflict rules of code 90 (a DOF set twice to different values, a DOF driven
// by a source or the ground, two sources on one DOF) and code 100 (a value
// changed after the zero step, a non-finite value).

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>

#include "element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using ic_model = pradis::model<point_mass, initial_displacement, initial_velocity, displacement_source, velocity_source,
    linear_spring>;

/// Runs a short first stage of `md` and returns the error it throws, if any.
std::optional<pradis::error> first_stage_error(ic_model& md) {
  simulation sim(md);
  return error_from([&] { sim.run(fixed_step(0.1, 0.01)); });
}
}  // namespace

TEST_SUITE("elements/X0") {
  TEST_CASE("X0 and V0 start a free mass at u0 with speed v0 so that u = u0 + v0 t, and record the values in W(1)") {
    // A free mass keeps its velocity (Newton's first law); Newmark integrates a = 0 exactly.
    const double u0 = -0.4, v0 = 1.25;
    ic_model md;
    const dof d = md.add_dof();
    md.add<point_mass>("body", {2.0}, d);
    const auto x0 = md.add<initial_displacement>("x0", {u0}, d);
    const auto vel0 = md.add<initial_velocity>("v0", {v0}, d);
    simulation sim(md);
    double worst = 0, first_time = -1, first_u = 0, first_v = 0;
    sim.on_output([&](const auto& s) {
      if (first_time < 0) {
        first_time = s.time();
        first_u = s.u(d);
        first_v = s.v(d);
      }
      worst = std::max({worst, std::abs(s.u(d) - (u0 + v0 * s.time())), std::abs(s.v(d) - v0), std::abs(s.a(d))});
    });
    sim.run(fixed_step(1.0, 0.01));
    CHECK(first_time == 0.0);
    CHECK(first_u == u0);  // the zero-step output already shows the initial values
    CHECK(first_v == v0);
    CHECK(worst < 1e-13);
    CHECK(md.work(x0)[0] == u0);
    CHECK(md.work(vel0)[0] == v0);
  }

  TEST_CASE("two X0 with different values on one DOF stop the run with code 90 naming the second") {
    ic_model md;
    const dof d = md.add_dof("x");
    md.add<point_mass>("body", {1.0}, d);
    md.add<initial_displacement>("first", {0.1}, d);
    md.add<initial_displacement>("second", {0.2}, d);
    check_error(first_stage_error(md), error_code::conflicting_initial, "X0", "second", "conflicts");
  }

  TEST_CASE("two X0 with the same value on one DOF are not a conflict") {
    ic_model md;
    const dof d = md.add_dof("x");
    md.add<point_mass>("body", {1.0}, d);
    md.add<initial_displacement>("first", {0.1}, d);
    md.add<initial_displacement>("second", {0.1}, d);
    simulation sim(md);
    CHECK_NOTHROW(sim.run(fixed_step(0.1, 0.01)));
    CHECK(sim.u(d) == doctest::Approx(0.1).epsilon(1e-14));
  }

  TEST_CASE("X0 on a DOF driven by XSRC stops the run with code 90 naming the X0") {
    ic_model md;
    const dof d = md.add_dof("x");
    md.add<point_mass>("body", {1.0}, d);
    md.add<displacement_source>("src", {0.1, 1.0, 0.0, 0.0}, d);
    md.add<initial_displacement>("x0", {0.1}, d);
    check_error(first_stage_error(md), error_code::conflicting_initial, "X0", "x0", "driven by XSRC 'src'");
  }

  TEST_CASE("X0 on the ground stops the run with code 90") {
    ic_model md;
    md.add<point_mass>("body", {1.0}, md.add_dof());
    md.add<initial_displacement>("x0", {0.1}, md.ground());
    check_error(first_stage_error(md), error_code::conflicting_initial, "X0", "x0", "ground");
  }

  TEST_CASE("two kinematic sources on one DOF stop the run with code 90 naming the second source") {
    SUBCASE("two XSRC: the second placed") {
      ic_model md;
      const dof d = md.add_dof("x");
      md.add<point_mass>("body", {1.0}, d);
      md.add<displacement_source>("a", {0.1, 1.0, 0.0, 0.0}, d);
      md.add<displacement_source>("b", {0.2, 1.0, 0.0, 0.0}, d);
      check_error(first_stage_error(md), error_code::conflicting_initial, "XSRC", "b", "already driven by XSRC 'a'");
    }
    SUBCASE("XSRC and VSRC: the type listed later in the model") {
      ic_model md;
      const dof d = md.add_dof("x");
      md.add<point_mass>("body", {1.0}, d);
      md.add<velocity_source>("v", {0.0, 0.0, 0.0, 1.0}, d);
      md.add<displacement_source>("x", {0.0, 0.0, 0.0, 0.0}, d);
      check_error(first_stage_error(md), error_code::conflicting_initial, "VSRC", "v", "already driven by XSRC 'x'");
    }
  }

  TEST_CASE("changing X0 after the zero step stops the next stage with code 100; keeping it does not") {
    ic_model md;
    const dof d = md.add_dof();
    md.add<point_mass>("body", {1.0}, d);
    const auto x0 = md.add<initial_displacement>("x0", {0.1}, d);
    simulation sim(md);
    sim.run(fixed_step(0.1, 0.01));
    CHECK_NOTHROW(sim.run(fixed_step(0.2, 0.01)));  // same value: a plain second stage
    md.element(x0).p.u0 = 0.3;                      // $REPLACE of the initial value
    check_error(error_from([&] { sim.run(fixed_step(0.3, 0.01)); }), error_code::invalid_parameter, "X0", "x0",
                "cannot be changed");
  }

  TEST_CASE("a flat X0 with a wrong parameter count is refused with code 101 naming X0 and the instance") {
    ic_model md;
    const std::array<dof, 1> d{md.add_dof()};
    const std::array<double, 2> two{1.0, 2.0};
    check_error(flat_add_error<initial_displacement>(md, "x0", d, two), error_code::parameter_count, "X0", "x0",
                "got 2 parameters");
  }

  TEST_CASE("a non-finite initial displacement stops the run with code 100 naming the instance") {
    for (const double bad : {not_a_number, inf}) {
      CAPTURE(bad);
      ic_model md;
      const dof d = md.add_dof();
      md.add<point_mass>("body", {1.0}, d);
      md.add<initial_displacement>("x0", {bad}, d);
      check_error(first_stage_error(md), error_code::invalid_parameter, "X0", "x0", "initial displacement");
    }
  }
}

TEST_SUITE("elements/V0") {
  TEST_CASE("V0 alone launches a mass on a spring as (v0/w) sin(wt) within the trapezoidal phase error") {
    // Undamped oscillator from u = 0 with speed v0: u = (v0/w) sin(wt); bound (v0/w)(w - wd) t
    // (element_test_support.hpp, trapezoidal_frequency).
    const double m = 2.0, k = 18.0, w = std::sqrt(k / m), v0 = 0.6, h = 1e-3;
    ic_model md;
    const dof d = md.add_dof();
    md.add<point_mass>("body", {m}, d);
    md.add<linear_spring>("spring", {k}, d, md.ground());
    md.add<initial_velocity>("v0", {v0}, d);
    simulation sim(md);
    const double wd = trapezoidal_frequency(w, h);
    double worst_ratio = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      worst_ratio = std::max(worst_ratio, std::abs(s.u(d) - v0 / w * std::sin(w * t)) / (v0 / w * (w - wd) * t + 1e-11));
    });
    sim.run(fixed_step(2.0, h));
    CHECK(worst_ratio <= 1.0);
  }

  TEST_CASE("two V0 with different values on one DOF stop the run with code 90 naming the second") {
    ic_model md;
    const dof d = md.add_dof("x");
    md.add<point_mass>("body", {1.0}, d);
    md.add<initial_velocity>("first", {1.0}, d);
    md.add<initial_velocity>("second", {-1.0}, d);
    check_error(first_stage_error(md), error_code::conflicting_initial, "V0", "second", "conflicts");
  }

  TEST_CASE("two V0 with the same value on one DOF are not a conflict") {
    ic_model md;
    const dof d = md.add_dof("x");
    md.add<point_mass>("body", {1.0}, d);
    md.add<initial_velocity>("first", {0.5}, d);
    md.add<initial_velocity>("second", {0.5}, d);
    simulation sim(md);
    CHECK_NOTHROW(sim.run(fixed_step(0.2, 0.01)));
    CHECK(sim.v(d) == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(sim.u(d) == doctest::Approx(0.1).epsilon(1e-13));
  }

  TEST_CASE("V0 on a DOF driven by VSRC stops the run with code 90 naming the V0") {
    ic_model md;
    const dof d = md.add_dof("x");
    md.add<point_mass>("body", {1.0}, d);
    md.add<velocity_source>("src", {0.0, 0.0, 0.0, 1.0}, d);
    md.add<initial_velocity>("v0", {1.0}, d);
    check_error(first_stage_error(md), error_code::conflicting_initial, "V0", "v0", "driven by VSRC 'src'");
  }

  TEST_CASE("V0 on the ground stops the run with code 90") {
    ic_model md;
    md.add<point_mass>("body", {1.0}, md.add_dof());
    md.add<initial_velocity>("v0", {2.0}, md.ground());
    check_error(first_stage_error(md), error_code::conflicting_initial, "V0", "v0", "ground");
  }

  TEST_CASE("changing V0 after the zero step stops the next stage with code 100; keeping it does not") {
    ic_model md;
    const dof d = md.add_dof();
    md.add<point_mass>("body", {1.0}, d);
    const auto v0 = md.add<initial_velocity>("v0", {1.0}, d);
    simulation sim(md);
    sim.run(fixed_step(0.1, 0.01));
    CHECK_NOTHROW(sim.run(fixed_step(0.2, 0.01)));
    CHECK(sim.u(d) == doctest::Approx(0.2).epsilon(1e-13));
    md.element(v0).p.v0 = 2.0;
    check_error(error_from([&] { sim.run(fixed_step(0.3, 0.01)); }), error_code::invalid_parameter, "V0", "v0",
                "cannot be changed");
  }

  TEST_CASE("a flat V0 with a wrong parameter count is refused with code 101 naming V0 and the instance") {
    ic_model md;
    const std::array<dof, 1> d{md.add_dof()};
    check_error(flat_add_error<initial_velocity>(md, "v0", d, {}), error_code::parameter_count, "V0", "v0",
                "got 0 parameters");
  }

  TEST_CASE("a non-finite initial velocity stops the run with code 100 naming the instance") {
    for (const double bad : {not_a_number, -inf}) {
      CAPTURE(bad);
      ic_model md;
      const dof d = md.add_dof();
      md.add<point_mass>("body", {1.0}, d);
      md.add<initial_velocity>("v0", {bad}, d);
      check_error(first_stage_error(md), error_code::invalid_parameter, "V0", "v0", "initial velocity");
    }
  }
}
