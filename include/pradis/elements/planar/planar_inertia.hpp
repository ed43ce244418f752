#pragma once
/// \file
/// MD: point inertia element in plane motion (translation X, Y and rotation).

#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct planar_inertia_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using planar_inertia = planar_inertia_t<>;
/// MD: point inertia in plane motion: mass m on the X and Y DOFs, moment of
/// inertia J about the centre of mass on the rotation DOF. Pure inertia (ADR=3):
/// flows (m a_x, m a_y, J eps), Jacobian dF/da = diag(m, m, J).
template <class>
struct planar_inertia_t {
  static constexpr pradis::passport passport{.name = "MD", .ext = 3, .par = 2, .adr = 3};
  static constexpr element_help help{
      .title = "point inertia in plane motion",
      .name = "Point inertia element for plane motion (mass and moment of inertia about the centre of mass)",
      .field = "mechanics",
      .dofs = "1 - translation of the centre of mass along X [m]\n"
              "2 - translation of the centre of mass along Y [m]\n"
              "3 - rotation about Z [rad]",
      .parameters = "1 - mass m [kg] (>= 0)\n"
                    "2 - moment of inertia J about the centre of mass [kg m^2] (>= 0)",
      .work = "",
      .special = "code 100 if m < 0 or J < 0"};

  struct parameters {
    double m = 0;  ///< mass [kg]
    double j = 0;  ///< moment of inertia [kg m^2]
  };
  parameters p;

  explicit planar_inertia_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {2.0, 0.1}; }
  static planar_inertia from_parameters(std::span<const double> v) { return planar_inertia({v[0], v[1]}); }

  void new_integration(element_context& ctx) const {
    if (!(p.m >= 0) || !std::isfinite(p.m)) ctx.invalid_parameter("mass m = " + to_text(p.m) + " must be finite and >= 0");
    if (!(p.j >= 0) || !std::isfinite(p.j)) ctx.invalid_parameter("moment of inertia J = " + to_text(p.j) + " must be finite and >= 0");
  }

  void evaluate(const local_input<planar_inertia>& in, local_output<planar_inertia>& out, element_context&) const {
    out.f << p.m * in.a(0), p.m * in.a(1), p.j * in.a(2);
    if (out.want_jacobian) out.M.diagonal() << p.m, p.m, p.j;
  }
};

}  // namespace pradis::elements
