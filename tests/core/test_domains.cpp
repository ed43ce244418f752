// Physical domains of DOFs and per-DOF tolerances (core/domain.hpp): a DOF takes the
// domain an element declares for it, conflicting domains are refused, and the
// absolute Newton tolerances are scaled by the DOF's nominal flow, so that a volume
// flow of 1e-5 m^3/s is not passed by DABSI = 0.1 unchecked.

#include <doctest/doctest.h>

#include <cmath>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;

namespace {

// A nonlinear hydraulic conductance from a node to the tank with an inflow q0:
// flow G (p + p^3 / p0^2) - q0 on the node (p = pressure, the velocity-level
// unknown). Its pressure in steady state solves x + x^3 = q0 / (G p0), x = p / p0.
struct cubic_conductance {
  static constexpr pradis::passport passport{.name = "QCUB", .ext = 1, .par = 3, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 1> domains{domain::hydraulic};
  static constexpr element_help help{.title = "test conductance",
                                     .name = "nonlinear conductance to tank with inflow",
                                     .field = "hydraulics",
                                     .dofs = "1 - pressure node",
                                     .parameters = "1 - G\n2 - p0\n3 - q0",
                                     .special = "none"};
  struct parameters {
    double g = 1e-10, p0 = 1e5, q0 = 3e-5;
  } p;
  explicit cubic_conductance(parameters q) : p(q) {}
  static parameters example() { return {}; }
  static cubic_conductance from_parameters(std::span<const double> v) { return cubic_conductance({v[0], v[1], v[2]}); }
  void evaluate(const local_input<cubic_conductance>& in, local_output<cubic_conductance>& out,
                element_context&) const {
    const double x = in.v(0) / p.p0;
    out.f << p.g * p.p0 * (x + x * x * x) - p.q0;
    if (out.want_jacobian) out.C << p.g * (1 + 3 * x * x);
  }
};

// A test element that declares its single DOF electric.
struct electric_probe {
  static constexpr pradis::passport passport{.name = "EPRB", .ext = 1, .par = 1, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 1> domains{domain::electric};
  static constexpr element_help help{.title = "test", .name = "electric conductance to ground", .field = "electric",
                                     .dofs = "1 - node", .parameters = "1 - conductance", .special = "none"};
  struct parameters {
    double g = 1;
  } p;
  explicit electric_probe(parameters q) : p(q) {}
  static parameters example() { return {}; }
  static electric_probe from_parameters(std::span<const double> v) { return electric_probe({v[0]}); }
  void evaluate(const local_input<electric_probe>& in, local_output<electric_probe>& out, element_context&) const {
    out.f << p.g * in.v(0);
    if (out.want_jacobian) out.C << p.g;
  }
};

using test_model = model<cubic_conductance, electric_probe, elements::point_mass>;

// Residual of the conductance's node after one step with a correction test so loose
// that only the residual test decides when Newton stops.
double residual_after_one_step(bool mechanical_scale, double& pressure) {
  test_model m;
  const dof p = m.add_dof("p");
  m.add<cubic_conductance>("orifice", {}, p);
  if (mechanical_scale) m.set_scale(p, {1.0, 1.0});
  simulation sim(m);
  run_options o;
  o.end = 1e-3;
  o.smax = 1e-3;
  o.newton.dabsu = 1e30;
  o.newton.drltu = 1.0;
  sim.run(o);
  pressure = sim.v(p);
  return std::abs(sim.residual(p));
}

}  // namespace

TEST_CASE("domains: an element's declared domain sets the DOF's domain and nominal magnitudes") {
  test_model m;
  const dof p = m.add_dof("p");
  const dof plain = m.add_dof("x");
  CHECK(m.dof_domain(p) == domain::unspecified);
  CHECK(m.scale(p) == dof_scale{1.0, 1.0});
  m.add<cubic_conductance>("orifice", {}, p);
  CHECK(m.dof_domain(p) == domain::hydraulic);
  CHECK(m.scale(p) == default_scale(domain::hydraulic));
  m.add<elements::point_mass>("mass", {1.0}, plain);  // mechanical elements declare nothing
  CHECK(m.dof_domain(plain) == domain::unspecified);
  CHECK(m.scale(plain) == dof_scale{1.0, 1.0});
  const dof e = m.add_dof("v", domain::electric);
  CHECK(m.scale(e) == dof_scale{1.0, 1e-3});
}

TEST_CASE("domains: a user-set scale is kept whatever an element declares") {
  test_model m;
  const dof p = m.add_dof("p");
  m.set_scale(p, {2e5, 1e-6});
  m.add<cubic_conductance>("orifice", {}, p);
  CHECK(m.dof_domain(p) == domain::hydraulic);
  CHECK(m.scale(p) == dof_scale{2e5, 1e-6});
}

TEST_CASE("domains: bad input") {
  test_model m;
  const dof p = m.add_dof("p");
  m.add<cubic_conductance>("orifice", {}, p);
  SUBCASE("a hydraulic DOF connected to an electric slot is refused, naming both") {
    try {
      m.add<electric_probe>("probe", {}, p);
      FAIL("no error");
    } catch (const error& x) {
      CHECK(x.code() == error_code::invalid_model);
      CHECK(x.instance() == "probe");
      const std::string msg = x.what();
      CHECK(msg.find("'p' is hydraulic (set by QCUB 'orifice')") != std::string::npos);
      CHECK(msg.find("electric") != std::string::npos);
    }
    CHECK(m.element_count() == 1);  // nothing was added
  }
  SUBCASE("non-positive or non-finite nominal magnitudes") {
    CHECK_THROWS_AS(m.set_scale(p, {0.0, 1.0}), error);
    CHECK_THROWS_AS(m.set_scale(p, {1.0, -1.0}), error);
    CHECK_THROWS_AS(m.set_scale(p, {1.0, std::nan("")}), error);
    CHECK_THROWS_AS(m.set_scale(dof{99}, {1.0, 1.0}), error);
    CHECK(m.scale(p) == default_scale(domain::hydraulic));
  }
}

TEST_CASE("domains: the Newton residual test is scaled by the DOF's nominal flow") {
  // Steady state: x + x^3 = q0 / (G p0) = 3, x = p / p0 (Cardano: the real root of
  // x^3 + x - 3 = 0 is cbrt(3/2 + sqrt(9/4 + 1/27)) + cbrt(3/2 - sqrt(9/4 + 1/27))).
  const double r = std::sqrt(9.0 / 4 + 1.0 / 27);
  const double x_exact = std::cbrt(1.5 + r) + std::cbrt(1.5 - r);
  double p_scaled = 0, p_unscaled = 0;
  const double res_scaled = residual_after_one_step(false, p_scaled);
  const double res_unscaled = residual_after_one_step(true, p_unscaled);
  // Hydraulic scale: |F| <= DABSI * 1e-5 m^3/s + DRLTI * sum|f| = 1e-6 + 1e-3 * (6e-5) at most.
  CHECK(res_scaled <= 0.1 * 1e-5 + 1e-3 * 6e-5 + 1e-18);
  CHECK(std::abs(p_scaled / 1e5 - x_exact) < 0.1);
  // With a mechanical scale of 1 the same flow error passes DABSI = 0.1 unchecked:
  // Newton stops after its first correction with a flow error of the order of q0.
  CHECK(res_unscaled > 1e-6);
  CHECK(std::abs(p_unscaled / 1e5 - x_exact) > std::abs(p_scaled / 1e5 - x_exact));
}
