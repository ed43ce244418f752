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

/// The composition of THROW: catalog name, help, the DOF layout and the example.
///
/// Local DOFs (35): the external node A (root of the front web: x, y, z 0..2, q1..q3 3..5) and B (root of the
/// rear web: 6..8, 9..11), laid out as BEAM3's; hidden q4 of A at 12 and of B at 13; then three inner nodes,
/// each x, y, z, q1, q2, q3, q4: N1 (web/pin corner) 14..20, N2 (middle of the pin, where the connecting rod
/// sits) 21..27, N3 (pin/web corner) 28..34. The inner nodes are kept as internal DOFs (ENT = 23): not
/// condensed.
struct crank_throw_spec {
  static constexpr std::string_view name = "THROW";
  static constexpr std::string_view title = "crank throw (web, crank pin in two pieces, web) as one super-element";
  static constexpr std::string_view field = "mechanics, spatial motion";
  static constexpr int ext = 12;
  static constexpr int ent = 23;
  static constexpr std::array<std::string_view, 8> labels{"front web", "front web mass", "pin front", "pin front mass",
                                                          "pin rear",  "pin rear mass",  "rear web",  "rear web mass"};
  static constexpr std::string_view special =
      "an error of a part (code 100 at NEWINT, code 75 during the run) is reported "
      "with its code in the name of THROW and the instance, naming the part (and for code 100 its parameter range); "
      "the inner nodes are internal DOFs with their own rotational nodes (their Lq is checked like any node's); "
      "BEAM3's and BEAMI3's special situations apply";
  /// The shape of the throw of examples/crankshaft scaled up 25 times, with a soft material as BEAM3's
  /// example (used by `pradis check` and the all-elements test: the steel throw's elastic flows, ~1e9 N at
  /// the test's random displacements, would bury its inertial flows in round-off in the finite-difference
  /// check).
  static auto example() { return crank_throw_parts(2.0, 1.0, 1.0, 1.125, 2.0, 0.5, 2e2, 80, 7.0); }
};

/// The part maps of THROW (BEAM3 and BEAMI3 have the same local DOFs: A x y z q1 q2 q3, B x y z q1 q2 q3,
/// qA4, qB4).
namespace throw_maps {
template <class E>
using web_a = part<E, 0, 1, 2, 3, 4, 5, 14, 15, 16, 17, 18, 19, 12, 20>;
template <class E>
using pin_a = part<E, 14, 15, 16, 17, 18, 19, 21, 22, 23, 24, 25, 26, 20, 27>;
template <class E>
using pin_b = part<E, 21, 22, 23, 24, 25, 26, 28, 29, 30, 31, 32, 33, 27, 34>;
template <class E>
using web_b = part<E, 28, 29, 30, 31, 32, 33, 6, 7, 8, 9, 10, 11, 34, 13>;
}  // namespace throw_maps

/// THROW: a crank throw as one element. External DOFs: the two ends (web roots) A and B with their rotational
/// nodes; parameters: the 8 parts' (BEAM3 15, BEAMI3 14 each) in the order front web, its mass, pin front,
/// its mass, pin rear, its mass, rear web, its mass (116 in all).
using crank_throw =
    composite<crank_throw_spec, throw_maps::web_a<elastic_beam>, throw_maps::web_a<beam_inertia>,
              throw_maps::pin_a<elastic_beam>, throw_maps::pin_a<beam_inertia>, throw_maps::pin_b<elastic_beam>,
              throw_maps::pin_b<beam_inertia>, throw_maps::web_b<elastic_beam>, throw_maps::web_b<beam_inertia>>;

/// The parameters of a THROW with its front web root at (x0, 0, 0) along global X: crank radius r (pin along
/// Y = r), pin from x0 to x0 + length in two pieces, webs of width b (along Z) and thickness t (along X), a
/// round pin of diameter d, steel E, G, rho. The defaults are the throw of examples/crankshaft (r = 40 mm,
/// pin 45 mm x 40 mm, webs 80 mm x 20 mm).
inline crank_throw::parameters crank_throw_parameters(double x0 = 0.08, double r = 0.04, double length = 0.04,
                                                      double d = 0.045, double b = 0.08, double t = 0.02,
                                                      double e = 2.1e11, double g = 8.1e10, double rho = 7850) {
  const double pi = std::numbers::pi;
  const double pa = pi * d * d / 4, pi_ = pi * d * d * d * d / 64;
  // Web along Y, local y = X (thickness t): Iy = t b^3/12, Iz = b t^3/12, J = b t^3/3 (1 - 0.63 t/b).
  const double wa = b * t, wy = t * b * b * b / 12, wz = b * t * t * t / 12,
               wj = b * t * t * t / 3 * (1 - 0.63 * t / b);
  const double x1 = x0 + length / 2, x2 = x0 + length;
  return {{elastic_beam::parameters{e, g, wa, wy, wz, wj, x0, 0, 0, x0, r, 0, 1, 0, 0},
           beam_inertia::parameters{rho, wa, wy, wz, wy + wz, x0, 0, 0, x0, r, 0, 1, 0, 0},
           elastic_beam::parameters{e, g, pa, pi_, pi_, 2 * pi_, x0, r, 0, x1, r, 0, 0, 1, 0},
           beam_inertia::parameters{rho, pa, pi_, pi_, 2 * pi_, x0, r, 0, x1, r, 0, 0, 1, 0},
           elastic_beam::parameters{e, g, pa, pi_, pi_, 2 * pi_, x1, r, 0, x2, r, 0, 0, 1, 0},
           beam_inertia::parameters{rho, pa, pi_, pi_, 2 * pi_, x1, r, 0, x2, r, 0, 0, 1, 0},
           elastic_beam::parameters{e, g, wa, wy, wz, wj, x2, r, 0, x2, 0, 0, 1, 0, 0},
           beam_inertia::parameters{rho, wa, wy, wz, wy + wz, x2, r, 0, x2, 0, 0, 1, 0, 0}}};
}

/// The parameters of a THROW (crank_throw_parts, which documents the arguments).
inline crank_throw::parameters crank_throw_parameters(double x0 = 0.08, double r = 0.04, double length = 0.04,
                                                      double d = 0.045, double b = 0.08, double t = 0.02) {
  return {crank_throw_parts(x0, r, length, d, b, t)};
}

}  // namespace pradis::elements
