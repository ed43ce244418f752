// Positive control of the compile-fail harness: a correct element, checked with
// pradis::check_element, listed in a model next to library elements and run
// through the simulation driver. This file MUST compile (files named ok_*.cpp
// are compiled with MODE=pass by tests/build_tests.cmake); if the harness passed
// it as a "compile failure", every compile_fail test would be worthless.
// It differs from the failing files only in the defect they each carry.

#include <span>
#include <string>

#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/model/model.hpp"

/// KC: linear spring and damper in parallel between two DOFs (ADR=1, IGN=3:
/// stiffness and viscosity blocks, no inertia block).
struct spring_damper {
  static constexpr pradis::passport passport{.name = "KC", .ext = 2, .par = 2, .wrk = 1, .adr = 1, .ign = 3};
  static constexpr pradis::element_help help{.title = "spring and damper in parallel",
                                             .name = "Linear visco-elastic element between two DOFs",
                                             .field = "mechanics",
                                             .dofs = "1 - displacement of end 1 [m]\n2 - displacement of end 2 [m]",
                                             .parameters = "1 - stiffness k [N/m] (>= 0)\n"
                                                           "2 - damping coefficient c [N s/m] (>= 0)",
                                             .work = "1 - element force [N], positive in tension",
                                             .special = "code 100 if k < 0 or c < 0"};
  struct parameters {
    double k = 0;  ///< stiffness [N/m]
    double c = 0;  ///< damping coefficient [N s/m]
  };
  parameters p;
  explicit spring_damper(parameters q) : p(q) {}
  static parameters example() { return {100.0, 2.0}; }
  static spring_damper from_parameters(std::span<const double> v) { return spring_damper({v[0], v[1]}); }

  void new_integration(pradis::element_context& ctx) const {
    if (!(p.k >= 0)) ctx.invalid_parameter("stiffness k = " + std::to_string(p.k) + " must be >= 0");
    if (!(p.c >= 0)) ctx.invalid_parameter("damping coefficient c = " + std::to_string(p.c) + " must be >= 0");
  }
  void evaluate(const pradis::local_input<spring_damper>& in, pradis::local_output<spring_damper>& out,
                pradis::element_context& ctx) const {
    const double f = p.k * (in.u(0) - in.u(1)) + p.c * (in.v(0) - in.v(1));
    out.f << f, -f;
    ctx.work[0] = -f;
    if (!out.want_jacobian) return;
    out.K << p.k, -p.k, -p.k, p.k;
    out.C << p.c, -p.c, -p.c, p.c;
  }
};

static_assert(pradis::check_element<spring_damper>());
static_assert(pradis::element_traits<spring_damper>::has_k && pradis::element_traits<spring_damper>::has_c &&
              !pradis::element_traits<spring_damper>::has_m);

int main() {
  using pradis::elements::point_mass;
  pradis::model<point_mass, spring_damper> m;
  const pradis::dof x = m.add_dof("x");
  m.add<point_mass>("mass", {.m = 1.0}, x);
  m.add<spring_damper>("mount", {.k = 100.0, .c = 2.0}, x, m.ground());
  pradis::simulation sim(m, pradis::stoermer{});
  sim.run({.end = 0.1});
  return sim.u(x) == 0.0 ? 0 : 1;
}
