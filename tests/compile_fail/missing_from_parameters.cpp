// pradis-expect: pradis: an element type needs `static E from_parameters(std::span<const double>)` (the flat PAR vector)
//
// Compile-fail test: an element that cannot be built from the flat parameter
// vector (what the model language and model::add_by_name pass).

#include <span>

#include "pradis/core/element.hpp"

struct typed_only_spring {
  static constexpr pradis::passport passport{.name = "TYPED", .ext = 2, .par = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "spring without from_parameters",
                                             .name = "Linear spring that only accepts typed parameters",
                                             .field = "tests",
                                             .dofs = "1 - end 1 [m]\n2 - end 2 [m]",
                                             .parameters = "1 - stiffness [N/m]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double k = 0;
  };
  parameters p;
  explicit typed_only_spring(parameters q) : p(q) {}
  void evaluate(const pradis::local_input<typed_only_spring>& in, pradis::local_output<typed_only_spring>& out,
                pradis::element_context&) const {
    const double f = p.k * (in.u(0) - in.u(1));
    out.f << f, -f;
    out.K << p.k, -p.k, -p.k, p.k;
  }
};

static_assert(pradis::check_element<typed_only_spring>());
