// Singular situations (code 75) of the pneumatic elements: PNCYL whose rod is driven
// until a chamber volume is no longer positive ("a chamber volume is not positive
// (VA = ..., VB = ...)"), and the shared absolute-pressure check of pneumatic/gas.hpp
// ("the absolute pressure ... Pa is not positive"), reached in a run by a PNVOL drained
// by a constant mass flow, and by direct evaluations of PNVOL, PNCHP, PNCYL and PNORF
// at a gauge pressure below -101325 Pa. Each error names the element type and instance.

#include <doctest/doctest.h>

#include <array>
#include <optional>
#include <string>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
namespace pp = pradis::elements::pneumatic;

// Newton tolerances for pneumatic nodes (the DOF scale is 1e5 Pa, 1e-5 kg/s).
constexpr newton_options pp_newton{.dabsu = 1e-14, .drltu = 0, .dabsi = 1e-9, .drlti = 0};

// PNCYL of the tests: A1 = 1e-3, A2 = 8e-4, VA0 = VB0 = 1e-4, isothermal, p0 = 0.
// VA = VA0 + A1 x > 0 for x > -0.1 m, VB = VB0 - A2 x > 0 for x < 0.125 m.
const pneumatic_cylinder::parameters pp_cylinder{1e-3, 8e-4, 1e-4, 1e-4, 1.0, 0.0, 293.15};

// Evaluates E (after its NEWINT) with the instance name "bad" at the input `in`; returns the error.
template <class E, std::size_t W>
std::optional<pradis::error> pp_evaluate(const E& e, const local_input<E>& in) {
  element_context ctx(E::passport.name, "bad");
  std::array<double, W> work{};
  ctx.work = work;
  e.new_integration(ctx);
  local_output<E> out;
  return error_from([&] { e.evaluate(in, out, ctx); });
}

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using pneumatic_errors_model = pradis::model<pneumatic_cylinder, displacement_source, gas_chamber,
    pneumatic_flow_source>;
// Runs a PNCYL "cyl" with its rod driven by XSRC x = amp sin(2 pi t) and returns the error.
std::optional<pradis::error> pp_driven_cylinder_error(double amp) {
  pneumatic_errors_model md;
  const dof ca = md.add_dof("A"), cb = md.add_dof("B"), x = md.add_dof("rod");
  md.add<pneumatic_cylinder>("cyl", pp_cylinder, ca, cb, x);
  md.add<displacement_source>("drive", {amp, 1.0, 0.0, 0.0}, x);
  simulation sim(md);
  return error_from([&] { sim.run({.end = 0.25, .smax = 1e-3, .smin = 1e-9, .newton = pp_newton}); });
}
}  // namespace

TEST_SUITE("pneumatic/pneumatic errors") {
  TEST_CASE("PNCYL: a rod driven out until chamber B vanishes is a singular situation (code 75)") {
    // x = 0.05 sin(2 pi t) keeps both chambers: no error.
    CHECK_FALSE(pp_driven_cylinder_error(0.05).has_value());
    // x = 0.2 sin(2 pi t) passes VB0 / A2 = 0.125 m at t = asin(0.625) / (2 pi) = 0.107 s.
    const auto e = pp_driven_cylinder_error(0.2);
    check_error(e, error_code::singular_situation, "PNCYL", "cyl", "a chamber volume is not positive (VA = ");
    REQUIRE(e.has_value());
    CHECK(e->message().find(", VB = ") != std::string::npos);
    CHECK(e->message().find("absolute pressure") == std::string::npos);
    CHECK(std::string(e->what()).find("cyl") != std::string::npos);
  }

  TEST_CASE("PNCYL: direct evaluation with either chamber volume not positive") {
    const pneumatic_cylinder cyl(pp_cylinder);
    local_input<pneumatic_cylinder> in;
    in.u(2) = 0.05;  // VA = 1.5e-4, VB = 6e-5: fine
    CHECK_FALSE((pp_evaluate<pneumatic_cylinder, 5>(cyl, in)).has_value());
    in.u(2) = 0.25;  // VB = 1e-4 - 2e-4 = -1e-4
    check_error(pp_evaluate<pneumatic_cylinder, 5>(cyl, in), error_code::singular_situation, "PNCYL", "bad",
                "a chamber volume is not positive (VA = 0.00035, VB = -0.0001 m^3)");
    in.u(2) = -0.2;  // VA = 1e-4 - 2e-4 = -1e-4
    check_error(pp_evaluate<pneumatic_cylinder, 5>(cyl, in), error_code::singular_situation, "PNCYL", "bad",
                "a chamber volume is not positive (VA = -0.0001, VB = 0.00026 m^3)");
  }

  TEST_CASE("PNVOL drained by a constant mass flow: the absolute pressure reaches zero (code 75)") {
    // Isothermal: P = P_atm + R T q t / V with q = -1e-3 kg/s, V = 2e-3 m^3: P = 0 at t = 2.41 s.
    const double vol = 2e-3, q = -1e-3, t = 293.15;
    pneumatic_errors_model md;
    const dof node = md.add_dof("tank");
    md.add<gas_chamber>("tank", {vol, 1.0, 0.0, t}, node);
    md.add<pneumatic_flow_source>("drain", {q}, node, md.ground());
    simulation sim(md);
    const auto e = error_from([&] { sim.run({.end = 5.0, .smax = 0.01, .smin = 1e-9, .newton = pp_newton}); });
    check_error(e, error_code::singular_situation, "PNVOL", "tank", "the absolute pressure ");
    REQUIRE(e.has_value());
    CHECK(e->message().find(" Pa is not positive") != std::string::npos);
    // The run got close to the time at which P reaches zero, and no further.
    const double t_zero = pp::atmosphere * vol / (pp::air_gas_constant * t * -q);
    CHECK(sim.time() < t_zero);
    CHECK(sim.time() > t_zero - 0.02);
  }

  TEST_CASE("absolute pressure not positive: direct evaluations of PNVOL, PNCHP, PNCYL and PNORF") {
    const double below = -pp::atmosphere - 1000.0;  // gauge pressure of P = -1000 Pa
    {
      const gas_chamber e({1e-3, 1.0, 0.0, 293.15});
      local_input<gas_chamber> in;
      in.v(0) = below;
      check_error(pp_evaluate<gas_chamber, 4>(e, in), error_code::singular_situation, "PNVOL", "bad",
                  "the absolute pressure -1000 Pa is not positive");
      in.v(0) = -pp::atmosphere;  // exactly zero absolute
      check_error(pp_evaluate<gas_chamber, 4>(e, in), error_code::singular_situation, "PNVOL", "bad",
                  "the absolute pressure 0 Pa is not positive");
    }
    {
      const gas_piston_chamber e({1e-3, 1e-4, 1.0, 0.0, 293.15});
      local_input<gas_piston_chamber> in;
      in.v(0) = below;
      check_error(pp_evaluate<gas_piston_chamber, 6>(e, in), error_code::singular_situation, "PNCHP", "bad",
                  "the absolute pressure -1000 Pa is not positive");
    }
    {
      const pneumatic_cylinder e(pp_cylinder);
      local_input<pneumatic_cylinder> in;
      in.v(1) = below;  // chamber B
      check_error(pp_evaluate<pneumatic_cylinder, 5>(e, in), error_code::singular_situation, "PNCYL", "bad",
                  "the absolute pressure -1000 Pa is not positive");
    }
    {
      const pneumatic_orifice e({1e-8, 0.3, 293.15, 0.999});
      local_input<pneumatic_orifice> in;
      in.v(0) = 1e5;
      in.v(1) = below;  // downstream
      check_error(pp_evaluate<pneumatic_orifice, 2>(e, in), error_code::singular_situation, "PNORF", "bad",
                  "the absolute pressure -1000 Pa is not positive");
      in.v(1) = 0;
      CHECK_FALSE((pp_evaluate<pneumatic_orifice, 2>(e, in)).has_value());
    }
  }
}
