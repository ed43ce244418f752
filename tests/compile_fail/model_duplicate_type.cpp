// pradis-expect: pradis: a model lists the same element type twice
//
// Compile-fail test: a model whose list of element types names one type twice.

#include "pradis/elements/mech1d/linear_spring.hpp"
#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/model/model.hpp"

int main() {
  pradis::model<pradis::elements::point_mass, pradis::elements::linear_spring, pradis::elements::point_mass> m;
  (void)m.add_dof("x");
}
