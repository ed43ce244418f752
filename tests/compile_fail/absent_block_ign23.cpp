// pradis-expect: pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero
//
// Compile-fail test: a pure-stiffness passport (ADR=1, IGN=23, like LINKD and
// SPRING) whose evaluate also writes the velocity block out.C.

#include <span>

#include "pradis/core/element.hpp"

struct spring_with_damping {
  static constexpr pradis::passport passport{.name = "SPRD", .ext = 2, .par = 2, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "spring-damper with IGN=23",
                                             .name = "Spring-damper whose passport denies its velocity block",
                                             .field = "tests",
                                             .dofs = "1 - end 1 [m]\n2 - end 2 [m]",
                                             .parameters = "1 - stiffness [N/m]\n2 - damping coefficient [N s/m]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double k = 0, c = 0;
  };
  parameters p;
  explicit spring_with_damping(parameters q) : p(q) {}
  static spring_with_damping from_parameters(std::span<const double> v) { return spring_with_damping({v[0], v[1]}); }
  void evaluate(const pradis::local_input<spring_with_damping>& in, pradis::local_output<spring_with_damping>& out,
                pradis::element_context&) const {
    const double f = p.k * (in.u(0) - in.u(1)) + p.c * (in.v(0) - in.v(1));
    out.f << f, -f;
    out.K << p.k, -p.k, -p.k, p.k;
    out.C(0, 0) = p.c;  // the velocity block does not exist for IGN=23
  }
};

static_assert(pradis::check_element<spring_with_damping>());
