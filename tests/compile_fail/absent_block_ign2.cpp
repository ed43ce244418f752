// pradis-expect: pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero
//
// Compile-fail test: the passport says ADR=1, IGN=2 (stiffness and inertia, no
// velocity block), but evaluate writes the velocity block out.C. In pradis an
// absent block has the type pradis::absent_block and cannot be written.

#include <span>

#include "pradis/core/element.hpp"

struct damper_in_disguise {
  static constexpr pradis::passport passport{.name = "DISG", .ext = 1, .par = 1, .adr = 1, .ign = 2};
  static constexpr pradis::element_help help{.title = "damper with IGN=2",
                                             .name = "Viscous element whose passport denies its velocity block",
                                             .field = "tests",
                                             .dofs = "1 - displacement [m]",
                                             .parameters = "1 - damping coefficient [N s/m]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double c = 0;
  };
  parameters p;
  explicit damper_in_disguise(parameters q) : p(q) {}
  static damper_in_disguise from_parameters(std::span<const double> v) { return damper_in_disguise({v[0]}); }
  void evaluate(const pradis::local_input<damper_in_disguise>& in, pradis::local_output<damper_in_disguise>& out,
                pradis::element_context&) const {
    out.f(0) = p.c * in.v(0);
    out.C(0, 0) = p.c;  // the velocity block does not exist for IGN=2
  }
};

static_assert(pradis::check_element<damper_in_disguise>());
