// pradis-expect: pradis: passport ADR=3 allows IGN=0 only
//
// Compile-fail test: ADR=3 (acceleration block only) combined with IGN=2. With
// ADR=3 there is no velocity block to ignore; the only valid IGN is 0.

#include <span>

#include "pradis/core/element.hpp"

struct bad_mass {
  static constexpr pradis::passport passport{.name = "BADM", .ext = 1, .par = 1, .adr = 3, .ign = 2};
  static constexpr pradis::element_help help{.title = "mass with a contradictory passport",
                                             .name = "Point mass with ADR=3, IGN=2",
                                             .field = "tests",
                                             .dofs = "1 - displacement [m]",
                                             .parameters = "1 - mass [kg]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double m = 0;
  };
  parameters p;
  explicit bad_mass(parameters q) : p(q) {}
  static bad_mass from_parameters(std::span<const double> v) { return bad_mass({v[0]}); }
  void evaluate(const pradis::local_input<bad_mass>& in, pradis::local_output<bad_mass>& out,
                pradis::element_context&) const {
    out.f(0) = p.m * in.a(0);
  }
};

static_assert(pradis::check_element<bad_mass>());
