// pradis-expect: pradis: invalid part map
//
// Compile-fail test: a composite with ENT = 2 whose parts use only one internal
// DOF: the other would be an equation with no entry (docs/super-elements.md).

#include <string_view>

#include "pradis/elements/composite.hpp"
#include "pradis/elements/mech1d/linear_spring.hpp"

struct spec {
  static constexpr std::string_view name = "BAD";
  static constexpr std::string_view title = "two springs and a DOF nobody uses";
  static constexpr int ext = 2, ent = 2;
};
using bad = pradis::composite<spec, pradis::part<pradis::elements::linear_spring, 0, 2>,
                              pradis::part<pradis::elements::linear_spring, 2, 1>>;

static_assert(pradis::check_element<bad>());
