// HCYL: the piston driven through the far end stop empties chamber B (rod side), a
// singular situation (code 75) reported when it persists down to SMIN, naming HCYL,
// the instance and chamber B; the twin of the chamber-A test in
// test_hydraulic_bad_input.cpp. A direct evaluation shows the same check at the state
// where VB = VB0 + AB (stroke - s) is negative.

#include <doctest/doctest.h>

#include <array>
#include <string>

#include "../elements/element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// AA = 2e-3, AB = 1e-3, stroke 0.5, s0 = 0.1, VA0 = VB0 = 1e-4, B = 1e9, no end-stop force.
// VB = VB0 + AB (stroke - s) vanishes at s = stroke + VB0 / AB = 0.6 m, i.e. x = 0.5 m.
const hydraulic_cylinder::parameters ce_cylinder{2e-3, 1e-3, 0.5, 0.1, 1e-4, 1e-4, 1e9, 0, 0, 1e-3};
}  // namespace

TEST_SUITE("hydraulic/cylinder errors") {
  TEST_CASE("HCYL: a piston driven through the end stop empties chamber B: code 75") {
    // The piston is driven at +1 m/s (extending), so chamber B shrinks and empties at t = 0.5 s.
    model<hydraulic_cylinder, velocity_source> md;
    const dof pb = md.add_dof("pB"), x = md.add_dof("x");
    md.add<hydraulic_cylinder>("cyl", ce_cylinder, md.ground(), pb, x);
    md.add<velocity_source>("drive", {.offset = 1.0}, x);
    simulation sim(md);
    const auto e = error_from([&] { sim.run({.end = 1.0, .smax = 1e-3, .smin = 1e-9}); });
    check_error(e, error_code::singular_situation, "HCYL", "cyl", "volume of chamber B has reached zero");
    REQUIRE(e.has_value());
    CHECK(e->message().find("chamber A") == std::string::npos);
    CHECK(e->message().find("piston position") != std::string::npos);
    CHECK(std::string(e->what()).find("cyl") != std::string::npos);
    // The last accepted state still has a positive volume of B, and the piston got close to s = 0.6 m.
    CHECK(md.work("cyl")[3] > 0);
    CHECK(md.work("cyl")[0] < 0.6);
    CHECK(md.work("cyl")[0] > 0.59);
  }

  TEST_CASE("HCYL: direct evaluation beyond the rod-side end: chamber B, not A") {
    const hydraulic_cylinder cyl(ce_cylinder);
    element_context ctx("HCYL", "cyl");
    std::array<double, 5> w{};
    ctx.work = w;
    cyl.new_integration(ctx);  // the parameters are good
    local_input<hydraulic_cylinder> in;
    local_output<hydraulic_cylinder> out;
    in.u(2) = 0.45;  // s = 0.55: VB = 5e-5 > 0
    CHECK_FALSE(error_from([&] { cyl.evaluate(in, out, ctx); }).has_value());
    CHECK(w[3] == doctest::Approx(5e-5));
    in.u(2) = 0.55;  // s = 0.65: VB = -5e-5
    check_error(error_from([&] { cyl.evaluate(in, out, ctx); }), error_code::singular_situation, "HCYL", "cyl",
                "volume of chamber B has reached zero (piston position 0.65 m)");
    in.u(2) = 0.7;  // s = 0.8: VB = -2e-4
    check_error(error_from([&] { cyl.evaluate(in, out, ctx); }), error_code::singular_situation, "HCYL", "cyl",
                "volume of chamber B has reached zero");
  }
}
