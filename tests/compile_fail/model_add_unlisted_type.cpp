// pradis-expect: pradis: this element type is not listed in the model's element types
//
// Compile-fail test: model::add of an element type the model does not list.
// Only the listed types are compiled into a model.

#include "pradis/elements/mech1d/linear_spring.hpp"
#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/model/model.hpp"

int main() {
  pradis::model<pradis::elements::point_mass> m;
  const pradis::dof x = m.add_dof("x");
  m.add<pradis::elements::point_mass>("mass", {.m = 1.0}, x);
  m.add<pradis::elements::linear_spring>("spring", {.k = 100.0}, x, m.ground());  // SPRING is not listed
}
