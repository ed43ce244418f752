// pradis-expect: pradis: passport ADR=2 allows IGN=0 or IGN=3 only
//
// Compile-fail test: ADR=2 ("written relative to velocities": velocity and
// acceleration blocks) combined with IGN=23 (both ignored) leaves no block at all.

#include <span>

#include "pradis/core/element.hpp"

struct bad_damper {
  static constexpr pradis::passport passport{.name = "BADD", .ext = 2, .par = 1, .adr = 2, .ign = 23};
  static constexpr pradis::element_help help{.title = "damper with a contradictory passport",
                                             .name = "Linear damper with ADR=2, IGN=23",
                                             .field = "tests",
                                             .dofs = "1 - end 1 [m]\n2 - end 2 [m]",
                                             .parameters = "1 - damping coefficient [N s/m]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double c = 0;
  };
  parameters p;
  explicit bad_damper(parameters q) : p(q) {}
  static bad_damper from_parameters(std::span<const double> v) { return bad_damper({v[0]}); }
  void evaluate(const pradis::local_input<bad_damper>& in, pradis::local_output<bad_damper>& out,
                pradis::element_context&) const {
    const double f = p.c * (in.v(0) - in.v(1));
    out.f << f, -f;
  }
};

static_assert(pradis::check_element<bad_damper>());
