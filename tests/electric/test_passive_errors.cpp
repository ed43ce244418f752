// Bad parameters of the passive electric elements R, C and L: a non-positive or
// non-finite resistance, capacitance or inductance, or a non-finite initial current
// of L, stops the run at the new integration with code 100 naming the element type,
// the instance and the parameter. Each case runs one small circuit (a DC source
// feeding R into C and L in parallel) that runs cleanly with good parameters.

#include <doctest/doctest.h>

#include <optional>
#include <string>

#include "elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
// Parameters of the test circuit; the good values give a well-posed RC || L circuit.
struct pe_values {
  double r = 100.0, c = 1e-6, l = 0.1, i0 = 0.0;
};

// Runs V -- R1 -- out, C1 and L1 from out to ground, and returns the error it throws, or nothing.
std::optional<pradis::error> pe_circuit_error(const pe_values& x) {
  model<voltage_dc, resistor, capacitor, inductor> md;
  const dof in = md.add_dof("in"), out = md.add_dof("out");
  md.add<voltage_dc>("V", {5.0}, in);
  md.add<resistor>("R1", {x.r}, in, out);
  md.add<capacitor>("C1", {x.c}, out, md.ground());
  md.add<inductor>("L1", {x.l, x.i0}, out, md.ground());
  simulation sim(md);
  return error_from([&] { sim.run(fixed_step(1e-3, 1e-4)); });
}

// The code-100 error of the circuit with one bad value.
void pe_check_bad(const pe_values& x, const char* type, const char* instance, const char* mention) {
  CAPTURE(x.r);
  CAPTURE(x.c);
  CAPTURE(x.l);
  CAPTURE(x.i0);
  check_error(pe_circuit_error(x), error_code::invalid_parameter, type, instance, mention);
}
}  // namespace

TEST_SUITE("electric/passive errors") {
  TEST_CASE("the reference circuit with good R, C and L runs without error") {
    CHECK_FALSE(pe_circuit_error(pe_values{}).has_value());
    CHECK_FALSE(pe_circuit_error(pe_values{.i0 = -0.02}).has_value());  // any finite i0 is accepted
  }

  TEST_CASE("R: a zero, negative or non-finite resistance is code 100 naming R") {
    for (const double r : {0.0, -10.0, not_a_number, inf}) pe_check_bad({.r = r}, "R", "R1", "resistance R =");
    // The message gives the value and the rule.
    const auto e = pe_circuit_error({.r = -10.0});
    REQUIRE(e.has_value());
    CHECK(e->message().find("resistance R = -10") != std::string::npos);
    CHECK(e->message().find("must be finite and > 0") != std::string::npos);
    CHECK(std::string(e->what()).find("R1") != std::string::npos);
  }

  TEST_CASE("C: a zero, negative or non-finite capacitance is code 100 naming C") {
    for (const double c : {0.0, -1e-6, not_a_number, inf}) pe_check_bad({.c = c}, "C", "C1", "capacitance C =");
    const auto e = pe_circuit_error({.c = 0.0});
    REQUIRE(e.has_value());
    CHECK(e->message().find("must be finite and > 0") != std::string::npos);
    CHECK(std::string(e->what()).find("C1") != std::string::npos);
  }

  TEST_CASE("L: a zero, negative or non-finite inductance is code 100 naming L") {
    for (const double l : {0.0, -0.1, not_a_number, inf}) pe_check_bad({.l = l}, "L", "L1", "inductance L =");
    const auto e = pe_circuit_error({.l = -0.1});
    REQUIRE(e.has_value());
    CHECK(e->message().find("must be finite and > 0") != std::string::npos);
    CHECK(std::string(e->what()).find("L1") != std::string::npos);
  }

  TEST_CASE("L: a non-finite initial current i0 is code 100 naming i0") {
    for (const double i0 : {not_a_number, inf, -inf})
      pe_check_bad({.i0 = i0}, "L", "L1", "initial current i0 must be finite");
    // The inductance is checked first: with both bad, the message is about L.
    const auto e = pe_circuit_error({.l = 0.0, .i0 = not_a_number});
    REQUIRE(e.has_value());
    CHECK(e->code() == error_code::invalid_parameter);
    CHECK(e->message().find("inductance L") != std::string::npos);
    CHECK(e->message().find("initial current") == std::string::npos);
  }
}
