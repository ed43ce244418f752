#pragma once
/// \file
/// LINKD: ideal elastic axial link for plane motion (the manual's worked example, section 3.6).

#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct planar_link_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using planar_link = planar_link_t<>;
/// LINKD: linear elastic link between two points A and B moving in a plane,
/// working in tension and compression. Flows (forces the system applies to the
/// link): F_A = -k (L - L0) e, F_B = -F_A, with e = (B - A) / L.
template <class>
struct planar_link_t {
  static constexpr pradis::passport passport{
      .name = "LINKD", .ext = 4, .par = 5, .str = 2, .wrk = 3, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "ideal elastic axial link for plane motion",
      .name = "Ideal elastic element for plane motion, working in tension and compression",
      .field = "mechanics",
      .dofs = "1 - translation of point A along X [m]\n"
              "2 - translation of point A along Y [m]\n"
              "3 - translation of point B along X [m]\n"
              "4 - translation of point B along Y [m]",
      .parameters = "1 - initial abscissa of point A [m]\n"
                    "2 - initial ordinate of point A [m]\n"
                    "3 - initial abscissa of point B [m]\n"
                    "4 - initial ordinate of point B [m] (A and B must not coincide)\n"
                    "5 - stiffness k [N/m] (>= 0)",
      .work = "1 - initial length L0 [m]\n"
              "2 - current length L [m]\n"
              "3 - axial force k (L - L0) [N], positive in tension",
      .special = "code 100 if A and B coincide initially, k < 0 or a parameter is not finite; code 75 if the "
                 "current length becomes close to zero during the run, or the link's direction reverses within one "
                 "step (it passed through zero length); treated as a failed step, reported if it persists at SMIN. "
                 "The state vector (STR = 2) holds the direction of the last accepted step"};

  /// The state (the direction at the last accepted step) only guards the next step.
  static constexpr bool state_is_guard = true;
  /// Typed parameters, in PAR order.
  struct parameters {
    double xa0 = 0, ya0 = 0, xb0 = 1, yb0 = 0;  ///< initial coordinates of A and B [m]
    double k = 0;                               ///< stiffness [N/m]
  };
  parameters p;

  explicit planar_link_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.0, 0.0, 1.0, 0.5, 5e3}; }
  static planar_link from_parameters(std::span<const double> v) { return planar_link({v[0], v[1], v[2], v[3], v[4]}); }

  /// NEWINT: parameter checks and the initial length into W(1).
  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.xa0) || !std::isfinite(p.ya0) || !std::isfinite(p.xb0) || !std::isfinite(p.yb0))
      ctx.invalid_parameter("the coordinates of A and B must be finite");
    const double l0 = std::hypot(p.xb0 - p.xa0, p.yb0 - p.ya0);
    if (!(l0 > min_length)) ctx.invalid_parameter("points A and B coincide: the initial length is zero");
    if (!(p.k >= 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and >= 0");
    ctx.work[0] = l0;
  }

  void evaluate(const local_input<planar_link>& in, local_output<planar_link>& out, element_context& ctx) const {
    const double l0 = ctx.work[0];
    const double dx = (p.xb0 + in.u(2)) - (p.xa0 + in.u(0));
    const double dy = (p.yb0 + in.u(3)) - (p.ya0 + in.u(1));
    const double l = std::hypot(dx, dy);
    if (!(l > min_length * std::max(1.0, l0))) ctx.singular("the length of the link has become close to zero");
    const double c = dx / l, s = dy / l, du = l - l0;
    // The state vector keeps the direction of the last accepted step: a reversed
    // direction means the link passed through zero length within the step (a
    // step cut resolves a mere fast rotation; a real passage persists to SMIN).
    if (ctx.old_state.size() == 2 && ctx.new_state.size() == 2) {
      const double oc = ctx.old_state[0], os = ctx.old_state[1];
      if ((oc != 0.0 || os != 0.0) && c * oc + s * os < 0.0)
        ctx.singular("the link passed through zero length (its direction reversed within one step); its length "
                     "became close to zero");
      ctx.new_state[0] = c;
      ctx.new_state[1] = s;
    }
    out.f(0) = -p.k * du * c;
    out.f(1) = -p.k * du * s;
    out.f(2) = -out.f(0);
    out.f(3) = -out.f(1);
    ctx.work[1] = l;
    ctx.work[2] = p.k * du;
    if (!out.want_jacobian) return;
    // Manual section 3.6.3: dF1/dX1 = k (1 - L0/L sin^2), dF1/dX2 = k L0/L sin cos, dF2/dX2 = k (1 - L0/L cos^2).
    const double r = l0 / l;
    const double kxx = p.k * (1.0 - r * s * s), kxy = p.k * r * s * c, kyy = p.k * (1.0 - r * c * c);
    out.K << kxx, kxy, -kxx, -kxy,  //
        kxy, kyy, -kxy, -kyy,       //
        -kxx, -kxy, kxx, kxy,       //
        -kxy, -kyy, kxy, kyy;
  }

  /// Whether a state is admissible for checks (the link keeps at least 10% of its initial length).
  bool admissible(const local_input<planar_link>& in) const {
    const double dx = (p.xb0 + in.u(2)) - (p.xa0 + in.u(0)), dy = (p.yb0 + in.u(3)) - (p.ya0 + in.u(1));
    return std::hypot(dx, dy) > 0.1 * std::hypot(p.xb0 - p.xa0, p.yb0 - p.ya0);
  }

  /// Lengths below this (relative to L0, absolute below 1 m) count as zero.
  static constexpr double min_length = 1e-12;
};

}  // namespace pradis::elements
