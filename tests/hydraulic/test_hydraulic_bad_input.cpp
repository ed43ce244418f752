// Bad input of the hydraulic elements: non-positive bulk moduli, volumes, areas and the like
// stop the run at the zero step with code 100 naming the element, the instance and the
// parameter; a chamber volume or an absolute pressure reaching zero during the run is a
// singular situation (code 75), reported when it persists down to SMIN.

#include <doctest/doctest.h>

#include <array>
#include <limits>
#include <string>

#include "../elements/element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();

// Runs a model holding only E (on fresh DOFs) and checks the code-100 error.
template <class E>
void check_bad(const typename E::parameters& p, std::string_view mention) {
  model<E> md;
  std::array<dof, element_traits<E>::ext> d{};
  for (auto& x : d) x = md.add_dof();
  std::apply([&](auto... dd) { md.template add<E>("bad", p, dd...); }, d);
  simulation sim(md);
  check_error(error_from([&] { sim.run(fixed_step(0.01, 1e-3)); }), error_code::invalid_parameter,
              E::passport.name, "bad", mention);
}
}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using hydraulic_bad_input_model = pradis::model<hydraulic_cylinder, velocity_source, accumulator, constant_force>;
TEST_SUITE("hydraulic/bad input") {
  TEST_CASE("HVOL: non-positive volume or bulk modulus, air fraction outside [0, 1)") {
    check_bad<hydraulic_volume>({0.0, 1e9}, "volume V");
    check_bad<hydraulic_volume>({1e-3, 0.0}, "bulk modulus B");
    check_bad<hydraulic_volume>({1e-3, -1e9}, "bulk modulus B");
    check_bad<hydraulic_volume>({1e-3, nan_value}, "bulk modulus B");
    check_bad<hydraulic_volume>({1e-3, 1e9, 1.0}, "air fraction");
    check_bad<hydraulic_volume>({1e-3, 1e9, 0.1, 0.0}, "ambient pressure");
    check_bad<hydraulic_volume>({1e-3, 1e9, 0.1, 1e5, 0.0}, "polytropic exponent");
  }
  TEST_CASE("HORL and HORT: non-positive resistance, coefficient, area, density or transition") {
    check_bad<laminar_orifice>({0.0}, "resistance R");
    check_bad<turbulent_orifice>({0.0, 1e-5, 850, 1e3}, "discharge coefficient");
    check_bad<turbulent_orifice>({0.7, 0.0, 850, 1e3}, "area A");
    check_bad<turbulent_orifice>({0.7, 1e-5, -850, 1e3}, "density rho");
    check_bad<turbulent_orifice>({0.7, 1e-5, 850, 0.0}, "transition pressure");
  }
  TEST_CASE("HLINE: non-positive length, diameter, bulk modulus, density or viscosity") {
    check_bad<hydraulic_line>({0.0, 0.01, 1e9, 850, 0.03}, "length l");
    check_bad<hydraulic_line>({1.0, 0.0, 1e9, 850, 0.03}, "diameter d");
    check_bad<hydraulic_line>({1.0, 0.01, 0.0, 850, 0.03}, "bulk modulus B");
    check_bad<hydraulic_line>({1.0, 0.01, 1e9, 0.0, 0.03}, "density rho");
    check_bad<hydraulic_line>({1.0, 0.01, 1e9, 850, 0.0}, "viscosity mu");
  }
  TEST_CASE("HPUMP and HMOTOR: non-positive displacement, negative leakage or friction") {
    check_bad<hydraulic_pump>({0.0, 0, 0}, "displacement D");
    check_bad<hydraulic_pump>({1e-6, -1e-12, 0}, "leakage conductance");
    check_bad<hydraulic_motor>({1e-6, 0, -1.0}, "friction coefficient");
    check_bad<hydraulic_motor>({-1e-6, 0, 0}, "displacement D");
  }
  TEST_CASE("HCYL: non-positive areas, stroke, dead volumes, bulk modulus; s0 outside the stroke") {
    const hydraulic_cylinder::parameters ok{2e-3, 1e-3, 0.5, 0.1, 1e-4, 1e-4, 1e9, 1e8, 1e4, 1e-3};
    auto with = [&](auto f) {
      auto p = ok;
      f(p);
      return p;
    };
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.area_a = 0; }), "area AA");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.area_b = -1e-3; }), "area AB");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.stroke = 0; }), "stroke");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.s0 = 0.6; }), "initial position s0");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.dead_a = 0; }), "dead volume VA0");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.dead_b = 0; }), "dead volume VB0");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.bulk_modulus = 0; }), "bulk modulus B");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.stop_stiffness = -1; }), "end-stop stiffness");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.stop_damping = -1; }), "end-stop damping");
    check_bad<hydraulic_cylinder>(with([](auto& p) { p.stop_width = 0; }), "end-stop width");
  }
  TEST_CASE("valves: non-positive areas, strokes, bands; negative leakage or cracking pressure") {
    check_bad<valve_22>({0.7, 0.0, 850, 1e3, 1e-3, 0}, "maximum area");
    check_bad<valve_22>({0.7, 1e-5, 850, 1e3, 0.0, 0}, "spool stroke");
    check_bad<valve_43>({0.7, 1e-5, 850, 1e3, 1e-3, -1e-9}, "leakage area");
    check_bad<valve_43>({0.7, 1e-5, 0.0, 1e3, 1e-3, 0}, "density rho");
    check_bad<relief_valve>({0.7, 1e-5, 850, 1e3, 100e5, 0.0, 0}, "opening band");
    check_bad<relief_valve>({0.7, 1e-5, 850, 1e3, -1.0, 1e5, 0}, "cracking pressure");
    check_bad<check_valve>({0.7, 1e-5, 850, 0.0, 0.5e5, 1e5, 0}, "transition pressure");
  }
  TEST_CASE("HACC: non-positive gas volume, pre-charge, exponent, ambient, dead volume or bulk modulus") {
    check_bad<accumulator>({0.0, 20e5, 1.4, 1e5, 1e-5, 1e9}, "gas volume V0");
    check_bad<accumulator>({1e-3, 0.0, 1.4, 1e5, 1e-5, 1e9}, "pre-charge");
    check_bad<accumulator>({1e-3, 20e5, 0.0, 1e5, 1e-5, 1e9}, "polytropic exponent");
    check_bad<accumulator>({1e-3, 20e5, 1.4, 0.0, 1e-5, 1e9}, "ambient pressure");
    check_bad<accumulator>({1e-3, 20e5, 1.4, 1e5, 0.0, 1e9}, "dead volume Vd");
    check_bad<accumulator>({1e-3, 20e5, 1.4, 1e5, 1e-5, 0.0}, "bulk modulus B");
  }

  TEST_CASE("HCYL: a piston driven through the end stop empties chamber A: code 75") {
    // The piston is driven at 1 m/s towards s = 0; VA = VA0 + AA s vanishes at s = -VA0 / AA = -0.05 m.
    hydraulic_bad_input_model md;
    const dof pa = md.add_dof("pA"), x = md.add_dof("x");
    md.add<hydraulic_cylinder>("cyl", {2e-3, 1e-3, 0.5, 0.1, 1e-4, 1e-4, 1e9, 0, 0, 1e-3}, pa, md.ground(), x);
    md.add<velocity_source>("drive", {.offset = -1.0}, x);
    simulation sim(md);
    check_error(error_from([&] { sim.run({.end = 1.0, .smax = 1e-3, .smin = 1e-9}); }),
                error_code::singular_situation, "HCYL", "cyl", "volume of chamber A has reached zero");
    CHECK(md.work("cyl")[0] > -0.05);  // the last accepted state still has a positive volume
  }

  TEST_CASE("HVOL with air and HACC: a state below absolute zero pressure: code 75") {
    // In the air-laden volume the air expands without bound as the absolute pressure falls
    // towards zero, so a run approaches it only asymptotically; a Newton iterate can overshoot
    // it, and the element then reports a singular situation (the step is cut).
    {
      const hydraulic_volume e({1e-3, 1e9, 0.01, 1e5, 1.0});
      element_context ctx("HVOL", "vol");
      std::array<double, 2> w{};
      ctx.work = w;
      local_input<hydraulic_volume> in;
      in.v(0) = -1.5e5;
      local_output<hydraulic_volume> out;
      check_error(error_from([&] { e.evaluate(in, out, ctx); }), error_code::singular_situation, "HVOL", "vol",
                  "absolute pressure");
    }
    // Below the pre-charge the accumulator holds only its dead volume: a constant outflow then
    // pulls the pressure down linearly, through absolute zero.
    {
      hydraulic_bad_input_model md;
      const dof p = md.add_dof("p");
      md.add<accumulator>("acc", {1e-3, 20e5, 1.4, 1e5, 1e-5, 1e9}, p);
      md.add<constant_force>("outflow", {-1e-4}, p);
      simulation sim(md);
      check_error(error_from([&] { sim.run({.end = 1.0, .smax = 1e-3, .smin = 1e-9}); }),
                  error_code::singular_situation, "HACC", "acc", "absolute pressure");
    }
  }
}
