// pradis-expect: pradis: a condensed composite cannot condense an inner rotational node
//
// Compile-fail test: two BEAM3 in a line, A (DOFs 0..5) to an inner node N (12..17, q4 at 20) to B (6..11):
// N's q1..q3 are internal, and its hidden q4 needs the norm equation the model adds, which a condensation
// inside the element cannot give (docs/super-elements.md). The same parts form a valid pradis::composite.

#include <string_view>

#include "pradis/elements/condensed.hpp"
#include "pradis/elements/spatial/beam.hpp"

struct spec {
  static constexpr std::string_view name = "BAD";
  static constexpr std::string_view title = "two beams with the node between them condensed";
  static constexpr int ext = 12, ent = 9;
};
using beam = pradis::elements::elastic_beam;
using kept = pradis::composite<spec, pradis::part<beam, 0, 1, 2, 3, 4, 5, 12, 13, 14, 15, 16, 17, 18, 20>,
                               pradis::part<beam, 12, 13, 14, 15, 16, 17, 6, 7, 8, 9, 10, 11, 20, 19>>;
static_assert(pradis::check_element<kept>());
using bad = pradis::condensed<spec, pradis::part<beam, 0, 1, 2, 3, 4, 5, 12, 13, 14, 15, 16, 17, 18, 20>,
                              pradis::part<beam, 12, 13, 14, 15, 16, 17, 6, 7, 8, 9, 10, 11, 20, 19>>;

static_assert(pradis::check_element<bad>());
