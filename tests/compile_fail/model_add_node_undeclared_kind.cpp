// pradis-expect: pradis: no element type of this model declares this node kind
//
// Compile-fail test: model::add_node of a node kind (core/node_kind.hpp) that no
// element type of the model declares (E::node_kinds): a model holds only the node
// kinds its element types bring, besides the rotational node.

#include "../../examples/pi_control/integral_node.hpp"  // a kind written outside the library
#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/model/model.hpp"

int main() {
  pradis::model<pradis::elements::point_mass> m;
  const pradis::dof x = m.add_dof("x"), h = m.add_dof("h");
  m.add_node<pradis_examples::integral_node>({{x.index, h.index}});  // no element type declares it
}
