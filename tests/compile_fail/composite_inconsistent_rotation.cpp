// pradis-expect: pradis: a composite's parts map a rotational node
// inconsistently
//
// Compile-fail test: two BEAM3 parts put their end A (q1..q3) on the same
// composite DOFs 3..5 but its hidden q4 on different internal DOFs (12 and 13):
// one node cannot have two q4 (docs/super-elements.md). Everything else is
// correct.

#include <array>
#include <string_view>

#include "pradis/elements/composite.hpp"
#include "pradis/elements/spatial/beam.hpp"

struct spec {
  static constexpr std::string_view name = "BAD";
  static constexpr std::string_view title = "two beams that disagree about a node's q4";
  static constexpr int ext = 18, ent = 4;
};
using bad =
    pradis::composite<spec, pradis::part<pradis::elements::elastic_beam, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 18, 19>,
                      pradis::part<pradis::elements::elastic_beam, 0, 1, 2, 3, 4, 5, 12, 13, 14, 15, 16, 17, 20, 21>>;

static_assert(pradis::check_element<bad>());
