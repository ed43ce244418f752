// pradis-expect: pradis: an element type needs `void evaluate(const local_input<E>&, local_output<E>&, element_context&) const`
//
// Compile-fail test: an element without its evaluation (the manual's
// SUBROUTINE body: flows and Jacobian).

#include <span>

#include "pradis/core/element.hpp"

struct lazy_spring {
  static constexpr pradis::passport passport{.name = "LAZY", .ext = 2, .par = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "spring without evaluate",
                                             .name = "Linear spring that never computes anything",
                                             .field = "tests",
                                             .dofs = "1 - end 1 [m]\n2 - end 2 [m]",
                                             .parameters = "1 - stiffness [N/m]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double k = 0;
  };
  parameters p;
  explicit lazy_spring(parameters q) : p(q) {}
  static lazy_spring from_parameters(std::span<const double> v) { return lazy_spring({v[0]}); }
};

static_assert(pradis::check_element<lazy_spring>());
