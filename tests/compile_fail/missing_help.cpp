// pradis-expect: pradis: an element type needs `static constexpr pradis::element_help help = {...};`
//
// Compile-fail test: an element without help text (manual section 3.4). The
// passport, parameters, from_parameters and evaluate are all correct.

#include <span>

#include "pradis/core/element.hpp"

struct silent_spring {
  static constexpr pradis::passport passport{.name = "SILENT", .ext = 2, .par = 1, .adr = 1, .ign = 23};
  struct parameters {
    double k = 0;
  };
  parameters p;
  explicit silent_spring(parameters q) : p(q) {}
  static silent_spring from_parameters(std::span<const double> v) { return silent_spring({v[0]}); }
  void evaluate(const pradis::local_input<silent_spring>& in, pradis::local_output<silent_spring>& out,
                pradis::element_context&) const {
    const double f = p.k * (in.u(0) - in.u(1));
    out.f << f, -f;
    out.K << p.k, -p.k, -p.k, p.k;
  }
};

static_assert(pradis::check_element<silent_spring>());
