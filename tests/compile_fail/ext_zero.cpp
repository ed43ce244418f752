// pradis-expect: pradis: passport EXT must be > 0 (an element needs external DOFs)
//
// Compile-fail test: EXT = 0 (every element needs at least one external DOF,
// manual section 3.3). Everything else about the element is correct.

#include <span>

#include "pradis/core/element.hpp"

struct no_dofs {
  static constexpr pradis::passport passport{.name = "NODOF", .ext = 0, .par = 1};
  static constexpr pradis::element_help help{.title = "element without DOFs",
                                             .name = "Element without external DOFs",
                                             .field = "tests",
                                             .dofs = "",
                                             .parameters = "1 - unused",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double x = 0;
  };
  parameters p;
  explicit no_dofs(parameters q) : p(q) {}
  static no_dofs from_parameters(std::span<const double> v) { return no_dofs({v[0]}); }
  void evaluate(const pradis::local_input<no_dofs>&, pradis::local_output<no_dofs>&, pradis::element_context&) const {}
};

static_assert(pradis::check_element<no_dofs>());
