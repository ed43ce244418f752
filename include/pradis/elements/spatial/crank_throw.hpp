#pragma once
/// \file
/// THROW: one crank throw of a crankshaft as a composite super-element of BEAM3 and BEAMI3 parts
/// (elements/composite.hpp): front web, crank pin in two pieces, rear web, as in examples/crankshaft.
/// docs/super-elements.md.

#include <array>
#include <cmath>
#include <numbers>
#include <string_view>
#include <tuple>

#include "pradis/elements/composite.hpp"
#include "pradis/elements/spatial/beam.hpp"
#include "pradis/elements/spatial/beam_inertia.hpp"

namespace pradis::elements {

/// The parameters of a THROW with its front web root at (x0, 0, 0) along global X: crank radius r (pin along
/// Y = r), pin from x0 to x0 + length in two pieces, webs of width b (along Z) and thickness t (along X), a
/// round pin of diameter d, steel E, G, rho. The defaults are the throw of examples/crankshaft (r = 40 mm,
/// pin 45 mm x 40 mm, webs 80 mm x 20 mm).
inline std::tuple<elastic_beam::parameters, beam_inertia::parameters, elastic_beam::parameters,
                  beam_inertia::parameters, elastic_beam::parameters, beam_inertia::parameters,
                  elastic_beam::parameters, beam_inertia::parameters>
crank_throw_parts(double x0 = 0.08, double r = 0.04, double length = 0.04, double d = 0.045, double b = 0.08,
                  double t = 0.02, double e = 2.1e11, double g = 8.1e10, double rho = 7850) {
  const double pi = std::numbers::pi;
  const double pa = pi * d * d / 4, pi_ = pi * d * d * d * d / 64;
  // Web along Y, local y = X (thickness t): Iy = t b^3/12, Iz = b t^3/12, J = b t^3/3 (1 - 0.63 t/b).
  const double wa = b * t, wy = t * b * b * b / 12, wz = b * t * t * t / 12,
               wj = b * t * t * t / 3 * (1 - 0.63 * t / b);
  const double x1 = x0 + length / 2, x2 = x0 + length;
  return {elastic_beam::parameters{e, g, wa, wy, wz, wj, x0, 0, 0, x0, r, 0, 1, 0, 0},
          beam_inertia::parameters{rho, wa, wy, wz, wy + wz, x0, 0, 0, x0, r, 0, 1, 0, 0},
          elastic_beam::parameters{e, g, pa, pi_, pi_, 2 * pi_, x0, r, 0, x1, r, 0, 0, 1, 0},
          beam_inertia::parameters{rho, pa, pi_, pi_, 2 * pi_, x0, r, 0, x1, r, 0, 0, 1, 0},
          elastic_beam::parameters{e, g, pa, pi_, pi_, 2 * pi_, x1, r, 0, x2, r, 0, 0, 1, 0},
          beam_inertia::parameters{rho, pa, pi_, pi_, 2 * pi_, x1, r, 0, x2, r, 0, 0, 1, 0},
          elastic_beam::parameters{e, g, wa, wy, wz, wj, x2, r, 0, x2, 0, 0, 1, 0, 0},
          beam_inertia::parameters{rho, wa, wy, wz, wy + wz, x2, r, 0, x2, 0, 0, 1, 0, 0}};
}

/// A node of a crank throw in the composite's local DOFs: x (y, z follow), q1 (q2, q3 follow) and the hidden
/// q4.
struct throw_node {
  int x, q1, q4;
};

/// What THROW and THROWP share: the parts' labels, help field and special text, and the example.
struct crank_throw_common {
  static constexpr std::string_view field = "mechanics, spatial motion";
  static constexpr std::array<std::string_view, 8> labels{"front web", "front web mass", "pin front", "pin front mass",
                                                          "pin rear",  "pin rear mass",  "rear web",  "rear web mass"};
  static constexpr std::string_view special =
      "an error of a part (code 100 at NEWINT, code 75 during the run) is reported "
      "with its code in the name of the element and the instance, naming the part (and for code 100 its parameter "
      "range); the inner nodes are internal DOFs with their own rotational nodes (their Lq is checked like any "
      "node's); BEAM3's and BEAMI3's special situations apply";
  /// The shape of the throw of examples/crankshaft scaled up 25 times, with a soft material as BEAM3's
  /// example (used by `pradis check` and the all-elements test: the steel throw's elastic flows, ~1e9 N at
  /// the test's random displacements, would bury its inertial flows in round-off in the finite-difference
  /// check).
  static auto example() { return crank_throw_parts(2.0, 1.0, 1.0, 1.125, 2.0, 0.5, 2e2, 80, 7.0); }
};

/// The composition of THROW: catalog name, help and the DOF layout.
///
/// Local DOFs (35): the external node A (root of the front web: x, y, z 0..2, q1..q3 3..5) and B (root of the
/// rear web: 6..8, 9..11), laid out as BEAM3's; hidden q4 of A at 12 and of B at 13; then three inner nodes,
/// each x, y, z, q1, q2, q3, q4: N1 (web/pin corner) 14..20, N2 (middle of the pin, where the connecting rod
/// sits) 21..27, N3 (pin/web corner) 28..34. The inner nodes are kept as internal DOFs (ENT = 23): not
/// condensed.
struct crank_throw_spec : crank_throw_common {
  static constexpr std::string_view name = "THROW";
  static constexpr std::string_view title = "crank throw (web, crank pin in two pieces, web) as one super-element";
  static constexpr int ext = 12;
  static constexpr int ent = 23;
  /// A, N1, N2, N3, B.
  static constexpr std::array<throw_node, 5> nodes{{{0, 3, 12}, {14, 17, 20}, {21, 24, 27}, {28, 31, 34}, {6, 9, 13}}};
};

/// The composition of THROWP: THROW with the middle of the pin external, so that a connecting rod (or a load)
/// can act on it.
///
/// Local DOFs (35): the external nodes A (0..2, q1..q3 3..5), B (6..8, 9..11) and P, the middle of the pin
/// (12..14, 15..17), laid out as BEAM3's; hidden q4 of A at 18, of B at 19, of P at 20; then the two inner
/// nodes N1 (web/pin corner) 21..27 and N3 (pin/web corner) 28..34, each x, y, z, q1, q2, q3, q4 (ENT = 17).
struct crank_throw_pin_spec : crank_throw_common {
  static constexpr std::string_view name = "THROWP";
  static constexpr std::string_view title =
      "crank throw (web, crank pin in two pieces, web) as one super-element, the middle of the pin external";
  static constexpr int ext = 18;
  static constexpr int ent = 17;
  /// A, N1, P, N3, B.
  static constexpr std::array<throw_node, 5> nodes{{{0, 3, 18}, {21, 24, 27}, {12, 15, 20}, {28, 31, 34}, {6, 9, 19}}};
};

/// The part maps of a throw whose Spec lists its nodes A, N1, N2 (P), N3, B (BEAM3 and BEAMI3 have the same
/// local DOFs: a x y z q1 q2 q3, b x y z q1 q2 q3, qa4, qb4).
namespace throw_maps {
template <class E, class Spec, int a, int b>
using beam = part<E, Spec::nodes[a].x, Spec::nodes[a].x + 1, Spec::nodes[a].x + 2, Spec::nodes[a].q1,
                  Spec::nodes[a].q1 + 1, Spec::nodes[a].q1 + 2, Spec::nodes[b].x, Spec::nodes[b].x + 1,
                  Spec::nodes[b].x + 2, Spec::nodes[b].q1, Spec::nodes[b].q1 + 1, Spec::nodes[b].q1 + 2,
                  Spec::nodes[a].q4, Spec::nodes[b].q4>;
/// The eight parts: front web A -> N1, pin front N1 -> N2, pin rear N2 -> N3, rear web N3 -> B, each BEAM3
/// then BEAMI3.
template <class Spec>
using throw_of = composite<Spec, beam<elastic_beam, Spec, 0, 1>, beam<beam_inertia, Spec, 0, 1>,
                           beam<elastic_beam, Spec, 1, 2>, beam<beam_inertia, Spec, 1, 2>,
                           beam<elastic_beam, Spec, 2, 3>, beam<beam_inertia, Spec, 2, 3>,
                           beam<elastic_beam, Spec, 3, 4>, beam<beam_inertia, Spec, 3, 4>>;
}  // namespace throw_maps

/// THROW: a crank throw as one element. External DOFs: the two ends (web roots) A and B with their rotational
/// nodes; parameters: the 8 parts' (BEAM3 15, BEAMI3 14 each) in the order front web, its mass, pin front,
/// its mass, pin rear, its mass, rear web, its mass (116 in all).
using crank_throw = throw_maps::throw_of<crank_throw_spec>;

/// THROWP: THROW with the middle of the crank pin P as a third external node (x y z q1 q2 q3 after A's and
/// B's), where a connecting rod or a load can act; the same parts and parameters (crank_throw_parts).
using crank_throw_pin = throw_maps::throw_of<crank_throw_pin_spec>;

/// The parameters of a THROW (crank_throw_parts, which documents the arguments; a THROWP takes
/// `crank_throw_pin::parameters{crank_throw_parts(...)}`).
inline crank_throw::parameters crank_throw_parameters(double x0 = 0.08, double r = 0.04, double length = 0.04,
                                                      double d = 0.045, double b = 0.08, double t = 0.02) {
  return {crank_throw_parts(x0, r, length, d, b, t)};
}

}  // namespace pradis::elements
