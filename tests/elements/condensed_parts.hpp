#pragma once
// Condensed super-elements shared by tests/elements/test_condensed.cpp and the no-allocation test
// (tests/core/test_no_allocation.cpp): springs in series, a star of LINKD, a BEAM3 with springs beside it, two BEAM3
// with the node between them (an inner rotational node) condensed.

#include <array>
#include <string_view>
#include <tuple>
#include <vector>

#include "pradis/elements/condensed.hpp"
#include "pradis/elements/library.hpp"

namespace pradis_condensed_tests {

using namespace pradis;
using namespace pradis::elements;

/// Two springs in series, the point between them internal (composite DOF 3).
struct series_spec {
  static constexpr std::string_view name = "SPRING2C";
  static constexpr std::string_view title = "two linear springs in series, the middle point condensed";
  static constexpr int ext = 2, ent = 1;
  static constexpr std::array<std::string_view, 2> labels{"left spring", "right spring"};
};
using series_kept = composite<series_spec, part<linear_spring, 0, 2>, part<linear_spring, 2, 1>>;
using series = condensed<series_spec, part<linear_spring, 0, 2>, part<linear_spring, 2, 1>>;

/// Three LINKD from the external points P1, P2, P3 (DOFs 1..6) to the internal centre C (DOFs 7, 8): a geometrically
/// nonlinear star whose centre is condensed.
struct star_spec {
  static constexpr std::string_view name = "STAR3";
  static constexpr std::string_view title = "three elastic links meeting at a condensed centre";
  static constexpr int ext = 6, ent = 2;
  static std::tuple<planar_link::parameters, planar_link::parameters, planar_link::parameters> example() {
    return {{0, 0, 1, 0.7, 1e3}, {2, 0, 1, 0.7, 2e3}, {1, 2, 1, 0.7, 1.5e3}};
  }
};
struct star_kept_spec : star_spec {
  static constexpr std::string_view name = "STAR3K";
};
using star_kept = composite<star_kept_spec, part<planar_link, 0, 1, 6, 7>, part<planar_link, 2, 3, 6, 7>,
                            part<planar_link, 4, 5, 6, 7>>;
using star =
    condensed<star_spec, part<planar_link, 0, 1, 6, 7>, part<planar_link, 2, 3, 6, 7>, part<planar_link, 4, 5, 6, 7>>;

/// A BEAM3 between the external spatial nodes A (DOFs 1..6) and B (7..12) and, beside it, two springs in series from
/// A's x to B's x through the condensed DOF 16; 13 and 14 are the hidden q4 of A and B, which stay (the condensed
/// element's two internal DOFs).
struct beam_spec {
  static constexpr std::string_view name = "BEAMS2C";
  static constexpr std::string_view title = "a beam with two springs in series beside it";
  static constexpr int ext = 12, ent = 3;
  static std::tuple<elastic_beam::parameters, linear_spring::parameters, linear_spring::parameters> example() {
    return {elastic_beam::example(), {4e2}, {6e2}};
  }
};
using beam_parts_kept = composite<beam_spec, part<elastic_beam, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13>,
                                  part<linear_spring, 0, 14>, part<linear_spring, 14, 6>>;
using beam_parts = condensed<beam_spec, part<elastic_beam, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13>,
                             part<linear_spring, 0, 14>, part<linear_spring, 14, 6>>;
/// The same beam with the two springs replaced by one of their series stiffness.
struct beam1_spec {
  static constexpr std::string_view name = "BEAMS1";
  static constexpr std::string_view title = "a beam with one spring beside it";
  static constexpr int ext = 12, ent = 2;
};
using beam_one_spring =
    composite<beam1_spec, part<elastic_beam, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13>, part<linear_spring, 0, 6>>;


/// A cantilever of two BEAM3 from the external node A (DOFs 1..6, hidden q4 at 19) through the inner node N (DOFs 13..18,
/// q4 at 21) to the external node B (7..12, q4 at 20), 1 m along X, section as in tests/spatial/test_beam.cpp: the
/// condensed type condenses N with its q1..q4 (an inner rotational node).
struct beam2_spec {
  static constexpr std::string_view name = "BEAM2C";
  static constexpr std::string_view title = "two beams in a line, the node between them condensed";
  static constexpr int ext = 12, ent = 9;
  static constexpr std::array<std::string_view, 2> labels{"first half", "second half"};
  static elastic_beam::parameters half(double xa, double xb) {
    return {1e4, 4e3, 0.03, 1e-4, 2e-4, 1.5e-4, xa, 0, 0, xb, 0, 0, 0, 1, 0};
  }
  static std::tuple<elastic_beam::parameters, elastic_beam::parameters> example() {
    return {half(0, 0.5), half(0.5, 1.0)};
  }
};
struct beam2_kept_spec : beam2_spec {
  static constexpr std::string_view name = "BEAM2K";
};
using beam2_first = part<elastic_beam, 0, 1, 2, 3, 4, 5, 12, 13, 14, 15, 16, 17, 18, 20>;
using beam2_second = part<elastic_beam, 12, 13, 14, 15, 16, 17, 6, 7, 8, 9, 10, 11, 20, 19>;
using beam2_kept = composite<beam2_kept_spec, beam2_first, beam2_second>;
using beam2 = condensed<beam2_spec, beam2_first, beam2_second>;

/// A context with its own work and state vectors for an element of type E (for calling it outside a model).
template <class E>
struct cond_context {
  std::vector<double> work = std::vector<double>(static_cast<std::size_t>(E::passport.wrk), 0.0);
  std::vector<double> old_s = std::vector<double>(static_cast<std::size_t>(E::passport.str), 0.0);
  std::vector<double> new_s = std::vector<double>(static_cast<std::size_t>(E::passport.str), 0.0);
  element_context ctx;
  explicit cond_context(std::string_view name) : ctx(E::passport.name, name) {
    ctx.work = work;
    ctx.old_state = old_s;
    ctx.new_state = new_s;
    ctx.npar = E::passport.par;
  }
  /// The step is accepted: the new state becomes the old (the spans stay valid: same sizes).
  void accept() { old_s = new_s; }
};

}  // namespace pradis_condensed_tests
