// pradis-expect: pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero
//
// Compile-fail test: a pure stiffness element (ADR=1, IGN=23) calls setZero()
// on its absent acceleration block.

#include <span>

#include "pradis/core/element.hpp"

struct stiff {
  static constexpr pradis::passport passport{.name = "STF", .ext = 1, .par = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "t", .name = "t", .field = "tests", .dofs = "1",
                                             .parameters = "1", .work = "", .special = "none"};
  struct parameters {
    double k = 0;
  };
  parameters p;
  explicit stiff(parameters q) : p(q) {}
  static stiff from_parameters(std::span<const double> v) { return stiff({v[0]}); }
  void evaluate(const pradis::local_input<stiff>& in, pradis::local_output<stiff>& out,
                pradis::element_context&) const {
    out.f(0) = p.k * in.u(0);
    out.K(0, 0) = p.k;
    out.M.setZero();
  }
};

int main() { static_assert(pradis::check_element<stiff>()); }
