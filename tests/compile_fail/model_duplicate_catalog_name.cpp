// pradis-expect: pradis: two element types of a model have the same catalog name
//
// Compile-fail test: two different element types with the same catalog name
// ("MASS") in one model; add_by_name could not tell them apart.

#include "pradis/elements/library.hpp"

struct other_mass : pradis::elements::point_mass {
  using point_mass::point_mass;
  static other_mass from_parameters(std::span<const double> v) { return other_mass({v[0]}); }
  void evaluate(const pradis::local_input<other_mass>& in, pradis::local_output<other_mass>& out,
                pradis::element_context&) const {
    out.f(0) = p.m * in.a(0);
    out.M(0, 0) = p.m;
  }
};

int main() {
  pradis::model<pradis::elements::point_mass, other_mass> m;
  (void)m;
}
