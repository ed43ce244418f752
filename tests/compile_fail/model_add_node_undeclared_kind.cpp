// pradis-expect: pradis: no element type of this model declares this node kind
//
// Compile-fail test: model::add_node of a node kind (core/node_kind.hpp) that no
// element type of the model declares (E::node_kinds): a model holds only the node
// kinds its element types bring, besides the rotational node.

#include <Eigen/Core>
#include <array>
#include <string_view>
#include <vector>

#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/model/model.hpp"

struct tagged_record {
  std::array<int, 2> dofs{};
};
struct tagged_registry {
  std::vector<tagged_record> nodes;
  const std::vector<tagged_record>& records() const noexcept { return nodes; }
  void add(tagged_record r) { nodes.push_back(r); }
};
struct tagged_kind {
  using record = tagged_record;
  using registry = tagged_registry;
  static constexpr int size = 2;
  static constexpr std::string_view label = "TAGGED";
  static constexpr std::array<bool, 2> hidden{false, true}, rows{false, true};
  static constexpr std::array<double, 2> start{0, 0};
  static constexpr bool inertial_block = false;
  static void evaluate(const record&, const pradis::node_values<2>&, const pradis::node_call&,
                       pradis::node_flows<2>& out, pradis::element_context&) {
    out.f(1) = 0;
  }
  static void zero_step_row(const pradis::node_values<2>&, int, Eigen::Vector2d& row, double& rhs) {
    row << 0, 1;
    rhs = 0;
  }
};

int main() {
  pradis::model<pradis::elements::point_mass> m;
  const pradis::dof x = m.add_dof("x"), h = m.add_dof("h");
  m.add_node<tagged_kind>({{x.index, h.index}});  // no element type declares tagged_kind
}
