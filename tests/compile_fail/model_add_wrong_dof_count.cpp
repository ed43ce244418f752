// pradis-expect: pradis: an element must be connected to exactly EXT DOFs (its passport's EXT)
//
// Compile-fail test: model::add of a SPRING (EXT = 2) with one DOF. The typed
// add checks the number of connections at compile time.

#include "pradis/elements/mech1d/linear_spring.hpp"
#include "pradis/model/model.hpp"

int main() {
  pradis::model<pradis::elements::linear_spring> m;
  const pradis::dof x = m.add_dof("x");
  m.add<pradis::elements::linear_spring>("spring", {.k = 100.0}, x);  // needs two DOFs
}
