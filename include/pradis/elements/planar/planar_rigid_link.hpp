#pragma once
/// \file
/// LINKX: exact rigid link for plane motion, the constraint |B - A| = L0 with its
/// axial force as a Lagrange multiplier (PRADIS's "additional equation of
/// connection"), instead of LINKD's penalty spring.

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct planar_rigid_link_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using planar_rigid_link = planar_rigid_link_t<>;
/// LINKX: rigid massless link between two points A and B moving in a plane. The
/// axial force N (positive in tension) is an internal DOF: its velocity-level
/// unknown v_N = N, the Newton unknown like every velocity. Flows:
///
///     F_A = -N e,  F_B = N e,  e = (B - A) / L,
///     F_N = L - L0                      (the constraint row, zero when met)
///
/// so the Newton matrix gains the rows and columns of a saddle point,
///
///     [ K_geo du/dv + C + M da/dv   G^T ]      G = dL/du = [-e^T, e^T],
///     [ G du/dv                       0 ],     K_geo = N/L (I - e e^T) blocks,
///
/// whose zero diagonal the sparse LU eliminates after the neighbouring rows
/// (delayed elimination). The constraint is enforced on positions (index 3), so
/// the length stays L0 to the Newton tolerance at every step, without drift;
/// the multiplier oscillates under undamped NEWMARK at large steps: use HHT or
/// generalized-alpha for models with many links (docs/joints.md).
template <class>
struct planar_rigid_link_t {
  static constexpr pradis::passport passport{
      .name = "LINKX", .ext = 4, .ent = 1, .par = 4, .str = 2, .wrk = 3, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact rigid link for plane motion (constraint with a Lagrange multiplier)",
      .name = "Rigid massless link of constant length between two points in plane motion; the axial force is an "
              "internal unknown",
      .field = "mechanics",
      .dofs = "1 - translation of point A along X [m]\n"
              "2 - translation of point A along Y [m]\n"
              "3 - translation of point B along X [m]\n"
              "4 - translation of point B along Y [m]",
      .parameters = "1 - initial abscissa of point A [m]\n"
                    "2 - initial ordinate of point A [m]\n"
                    "3 - initial abscissa of point B [m]\n"
                    "4 - initial ordinate of point B [m] (A and B must not coincide; the initial distance is the "
                    "link's length L0)",
      .work = "1 - length L0 [m]\n"
              "2 - current length L [m] (L - L0 is the constraint's residual)\n"
              "3 - axial force N [N], positive in tension (the reaction of the constraint)",
      .special = "Internal DOF 1: the axial force N [N], positive in tension (its velocity-level unknown); "
                 "code 100 if A and B coincide initially or a coordinate is not finite; code 75 if the current "
                 "length becomes close to zero or the link's direction reverses within one step. The constraint "
                 "row has a zero diagonal (no inertia, no stiffness of its own); the model's points must carry "
                 "mass or other constraints so that the saddle-point matrix is regular. Use HHT or "
                 "generalized-alpha (numerical damping) for long runs: under NEWMARK the axial force may ring. "
                 "The state vector (STR = 2) holds the direction of the last accepted step"};
  /// The state (the direction at the last accepted step) only guards the next step.
  static constexpr bool state_is_guard = true;
  /// The internal DOF (the axial force) belongs to the mechanical domain.
  static constexpr std::array<domain, 5> domains{domain::mechanical, domain::mechanical, domain::mechanical,
                                                 domain::mechanical, domain::mechanical};

  /// Typed parameters, in PAR order.
  struct parameters {
    double xa0 = 0, ya0 = 0, xb0 = 1, yb0 = 0;  ///< initial coordinates of A and B [m]
  };
  parameters p;

  explicit planar_rigid_link_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.0, 0.0, 1.0, 0.5}; }
  static planar_rigid_link from_parameters(std::span<const double> v) {
    return planar_rigid_link({v[0], v[1], v[2], v[3]});
  }

  /// NEWINT: parameter checks and the length into W(1).
  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.xa0) || !std::isfinite(p.ya0) || !std::isfinite(p.xb0) || !std::isfinite(p.yb0))
      ctx.invalid_parameter("the coordinates of A and B must be finite");
    const double l0 = std::hypot(p.xb0 - p.xa0, p.yb0 - p.ya0);
    if (!(l0 > min_length)) ctx.invalid_parameter("points A and B coincide: the link's length is zero");
    ctx.work[0] = l0;
  }

  void evaluate(const local_input<planar_rigid_link>& in, local_output<planar_rigid_link>& out,
                element_context& ctx) const {
    const double l0 = ctx.work[0];
    const double dx = (p.xb0 + in.u(2)) - (p.xa0 + in.u(0));
    const double dy = (p.yb0 + in.u(3)) - (p.ya0 + in.u(1));
    const double l = std::sqrt(dx * dx + dy * dy);  // sqrt, not the slower hypot: l is checked below
    if (!(l > min_length * std::max(1.0, l0))) ctx.singular("the length of the link has become close to zero");
    const double c = dx / l, s = dy / l, n = in.v(4);
    if (ctx.old_state.size() == 2 && ctx.new_state.size() == 2) {
      const double oc = ctx.old_state[0], os = ctx.old_state[1];
      if ((oc != 0.0 || os != 0.0) && c * oc + s * os < 0.0)
        ctx.singular("the link passed through zero length (its direction reversed within one step)");
      ctx.new_state[0] = c;
      ctx.new_state[1] = s;
    }
    out.f(0) = -n * c;
    out.f(1) = -n * s;
    out.f(2) = n * c;
    out.f(3) = n * s;
    out.f(4) = l - l0;
    ctx.work[1] = l;
    ctx.work[2] = n;
    if (!out.want_jacobian) return;
    // Geometric stiffness of the force N e at fixed N: d(N e)/dB = N/L (I - e e^T).
    const double g = n / l;
    const double kxx = g * s * s, kxy = -g * s * c, kyy = g * c * c;
    out.K.setZero();
    out.K.template topLeftCorner<4, 4>() << kxx, kxy, -kxx, -kxy,  //
        kxy, kyy, -kxy, -kyy,                                       //
        -kxx, -kxy, kxx, kxy,                                       //
        -kxy, -kyy, kxy, kyy;
    // The constraint row: dL/du.
    out.K.row(4) << -c, -s, c, s, 0.0;
    // The multiplier's column: dF/dN = G^T.
    out.C.setZero();
    out.C.col(4) << -c, -s, c, s, 0.0;
  }

  /// Whether a state is admissible for checks (the link keeps at least 10% of its length).
  bool admissible(const local_input<planar_rigid_link>& in) const {
    const double dx = (p.xb0 + in.u(2)) - (p.xa0 + in.u(0)), dy = (p.yb0 + in.u(3)) - (p.ya0 + in.u(1));
    return std::hypot(dx, dy) > 0.1 * std::hypot(p.xb0 - p.xa0, p.yb0 - p.ya0);
  }

  /// Lengths below this (relative to L0, absolute below 1 m) count as zero.
  static constexpr double min_length = 1e-12;
};

}  // namespace pradis::elements
