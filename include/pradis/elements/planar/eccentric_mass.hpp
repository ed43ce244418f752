#pragma once
/// \file
/// MEKS: point mass with eccentricity in plane motion (manual section 3.7).

#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct eccentric_mass_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using eccentric_mass = eccentric_mass_t<>;
/// MEKS: a point mass m at distance R from the point whose DOFs are x, y and the
/// rotation theta; the radius makes the angle theta + alpha with the X axis.
/// Flows (the inertial forces, full three-block Jacobian, ADR=1 IGN=0):
///     F_x = m (a_x - R sin(phi) eps - R cos(phi) w^2)
///     F_y = m (a_y + R cos(phi) eps - R sin(phi) w^2)
///     M_z = m R^2 eps + m R (cos(phi) a_y - sin(phi) a_x),   phi = theta + alpha.
/// The manual's listing omits the second term of M_z (the moment of the
/// translational inertia forces); pradis keeps it, so that the mass matrix is
/// symmetric and the kinetic energy m |p'|^2 / 2 of the point is conserved.
template <class>
struct eccentric_mass_t {
  static constexpr pradis::passport passport{.name = "MEKS", .ext = 3, .par = 3, .adr = 1, .ign = 0};
  static constexpr element_help help{
      .title = "point mass with eccentricity in plane motion",
      .name = "Point inertia element with eccentricity",
      .field = "mechanics",
      .dofs = "1 - translation of the centre of rotation along X [m]\n"
              "2 - translation of the centre of rotation along Y [m]\n"
              "3 - rotation about Z [rad]",
      .parameters = "1 - mass m [kg] (>= 0)\n"
                    "2 - eccentricity R [m] (>= 0)\n"
                    "3 - initial angle alpha between the X axis and the radius to the mass [deg]",
      .work = "",
      .special = "code 100 if m < 0 or R < 0"};

  struct parameters {
    double m = 0;          ///< mass [kg]
    double r = 0;          ///< eccentricity [m]
    double alpha_deg = 0;  ///< initial angle [deg]
  };
  parameters p;

  explicit eccentric_mass_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.5, 0.2, 30.0}; }
  static eccentric_mass from_parameters(std::span<const double> v) { return eccentric_mass({v[0], v[1], v[2]}); }

  void new_integration(element_context& ctx) const {
    if (!(p.m >= 0) || !std::isfinite(p.m)) ctx.invalid_parameter("mass m = " + to_text(p.m) + " must be finite and >= 0");
    if (!(p.r >= 0) || !std::isfinite(p.r)) ctx.invalid_parameter("eccentricity R = " + to_text(p.r) + " must be finite and >= 0");
    if (!std::isfinite(p.alpha_deg)) ctx.invalid_parameter("angle alpha must be finite");
  }

  void evaluate(const local_input<eccentric_mass>& in, local_output<eccentric_mass>& out, element_context&) const {
    const double m = p.m, r = p.r;
    const double phi = in.u(2) + p.alpha_deg * std::numbers::pi / 180.0;
    const double w = in.v(2), eps = in.a(2), ax = in.a(0), ay = in.a(1);
    const double c = std::cos(phi), s = std::sin(phi);
    out.f(0) = m * (ax - r * s * eps - r * c * w * w);
    out.f(1) = m * (ay + r * c * eps - r * s * w * w);
    out.f(2) = m * r * r * eps + m * r * (c * ay - s * ax);
    if (!out.want_jacobian) return;
    out.K.setZero();
    out.K(0, 2) = m * (-r * c * eps + r * s * w * w);
    out.K(1, 2) = m * (-r * s * eps - r * c * w * w);
    out.K(2, 2) = m * r * (-s * ay - c * ax);
    out.C.setZero();
    out.C(0, 2) = -2.0 * m * r * c * w;
    out.C(1, 2) = -2.0 * m * r * s * w;
    out.M << m, 0, -m * r * s,  //
        0, m, m * r * c,        //
        -m * r * s, m * r * c, m * r * r;
  }
};

}  // namespace pradis::elements
