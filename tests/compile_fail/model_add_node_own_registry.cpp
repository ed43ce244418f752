// pradis-expect: pradis: this node kind's registry makes its nodes itself (it has no add(record))
//
// Compile-fail test: model::add_node of the rotational node kind, whose registry
// makes its nodes itself (model::add_rotation_node and the rotational slots of
// elements check the connections, code 110); it takes no bare records.

#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/model/model.hpp"

int main() {
  pradis::model<pradis::elements::point_mass> m;
  const auto d = m.add_dofs(4, "q");
  m.add_node<pradis::spatial::rotation_node_kind>({"r", {d[0].index, d[1].index, d[2].index, d[3].index}, {}, {}});
}
