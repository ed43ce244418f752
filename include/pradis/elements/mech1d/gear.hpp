#pragma once
/// \file
/// GEAR: gear pair with a ratio, backlash and mesh stiffness and damping between
/// two rotation DOFs; docs/friction.md.

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct gear_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using gear = gear_t<>;
/// GEAR: gear pair between shaft 1 (rotation phi1) and shaft 2 (phi2) with the
/// signed ratio r: the ideal mesh keeps phi2 = r phi1 (r < 0 for an external
/// pair, which reverses the sense of rotation). The mesh gap, in shaft-2 radians,
/// is g = phi2 - r phi1. Inside the backlash |g| <= b nothing is transmitted;
/// outside it the teeth are a spring-damper:
///   T = k (g - b sign g) + c g'   for |g| > b,   T = 0 otherwise.
/// T is the mesh torque on shaft 2 (the flows are those of the energy
/// k (|g| - b)^2 / 2 and of the dissipation c g'^2 / 2 in g): flow on shaft 2 is T,
/// flow on shaft 1 is -r T, so the torques are in the ratio r and the mesh power
/// T (phi2' - r phi1') is what the spring stores and the damper dissipates.
/// Jacobian: K = k [r^2 -r; -r 1], C = c [r^2 -r; -r 1] in contact, 0 in the gap.
template <class>
struct gear_t {
  static constexpr pradis::passport passport{.name = "GEAR", .ext = 2, .par = 4, .wrk = 3, .adr = 1, .ign = 3};
  static constexpr std::array<pradis::domain, 2> domains{pradis::domain::mechanical, pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "gear pair with ratio and backlash between two rotation DOFs",
      .name = "Gear pair: gap g = phi2 - r phi1, torque T = k (g -+ b) + c g' outside the backlash |g| <= b, 0 "
              "inside; torque on shaft 1 = -r T",
      .field = "mechanics",
      .dofs = "1 - rotation of shaft 1 [rad]\n2 - rotation of shaft 2 [rad]",
      .parameters = "1 - signed ratio r = phi2 / phi1 of the ideal mesh (!= 0; < 0 for an external pair)\n"
                    "2 - half backlash b [rad of shaft 2] (>= 0; the dead zone is |g| <= b)\n"
                    "3 - mesh stiffness k [N m/rad] (>= 0)\n"
                    "4 - mesh damping c [N m s/rad] (>= 0)",
      .work = "1 - mesh torque on shaft 2 T [N m] (on shaft 1: -r T)\n"
              "2 - mesh gap g = phi2 - r phi1 [rad]\n"
              "3 - contact flag: 1 g > b, -1 g < -b, 0 inside the backlash",
      .special = "code 100 if r = 0, b < 0, k < 0, c < 0 or a parameter is not finite. The damping acts only in "
                 "contact (a Kelvin-Voigt tooth contact: it may pull briefly while the teeth separate). "
                 "docs/friction.md"};
  /// Typed parameters, in PAR order.
  struct parameters {
    double ratio = 1;      ///< signed ratio r
    double backlash = 0;   ///< half backlash b [rad]
    double k = 0;          ///< mesh stiffness [N m/rad]
    double c = 0;          ///< mesh damping [N m s/rad]
  };
  parameters p;
  explicit gear_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {-2.5, 0.05, 1e4, 5.0}; }
  static gear from_parameters(std::span<const double> v) { return gear({v[0], v[1], v[2], v[3]}); }

  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.ratio) || p.ratio == 0)
      ctx.invalid_parameter("ratio r = " + to_text(p.ratio) + " must be finite and nonzero");
    if (!std::isfinite(p.backlash) || !(p.backlash >= 0))
      ctx.invalid_parameter("backlash b = " + to_text(p.backlash) + " must be finite and >= 0");
    if (!std::isfinite(p.k) || !(p.k >= 0))
      ctx.invalid_parameter("mesh stiffness k = " + to_text(p.k) + " must be finite and >= 0");
    if (!std::isfinite(p.c) || !(p.c >= 0))
      ctx.invalid_parameter("mesh damping c = " + to_text(p.c) + " must be finite and >= 0");
  }

  /// The mesh gap g = phi2 - r phi1.
  double gap(double phi1, double phi2) const { return phi2 - p.ratio * phi1; }

  void evaluate(const local_input<gear>& in, local_output<gear>& out, element_context& ctx) const {
    const double r = p.ratio, g = gap(in.u(0), in.u(1)), gd = gap(in.v(0), in.v(1));
    const double side = g > p.backlash ? 1.0 : (g < -p.backlash ? -1.0 : 0.0);
    const double torque = side == 0 ? 0.0 : p.k * (g - side * p.backlash) + p.c * gd;
    out.f << -r * torque, torque;
    ctx.work[0] = torque;
    ctx.work[1] = g;
    ctx.work[2] = side;
    if (!out.want_jacobian) return;
    const double k = side == 0 ? 0.0 : p.k, c = side == 0 ? 0.0 : p.c;
    out.K << k * r * r, -k * r, -k * r, k;
    out.C << c * r * r, -c * r, -c * r, c;
  }

  /// Finite-difference checks stay 1e-3 rad away from the backlash edges |g| = b.
  bool admissible(const local_input<gear>& in) const {
    return std::abs(std::abs(gap(in.u(0), in.u(1))) - p.backlash) > 1e-3;
  }
};

}  // namespace pradis::elements
