#pragma once
/// \file
/// MASS: point mass on one translational DOF (or a rotary inertia on an angle DOF).

#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct point_mass_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using point_mass = point_mass_t<>;
/// MASS: inertia m on one DOF; flow m a (ADR=3: pure inertia, standing with one "foot" on the ground).
template <class>
struct point_mass_t {
  static constexpr pradis::passport passport{.name = "MASS", .ext = 1, .par = 1, .adr = 3};
  static constexpr element_help help{.title = "point mass on one DOF",
                                     .name = "Point inertia element for one translational or rotational DOF",
                                     .field = "mechanics (any domain: capacitance-like element)",
                                     .dofs = "1 - displacement [m] (or angle [rad])",
                                     .parameters = "1 - mass m [kg] (or moment of inertia [kg m^2]) (>= 0)",
                                     .work = "",
                                     .special = "code 100 if m < 0"};
  struct parameters {
    double m = 0;  ///< mass [kg]
  };
  parameters p;
  explicit point_mass_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {2.0}; }
  static point_mass from_parameters(std::span<const double> v) { return point_mass({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.m >= 0) || !std::isfinite(p.m)) ctx.invalid_parameter("mass m = " + to_text(p.m) + " must be finite and >= 0");
  }
  void evaluate(const local_input<point_mass>& in, local_output<point_mass>& out, element_context&) const {
    out.f(0) = p.m * in.a(0);
    if (out.want_jacobian) out.M(0, 0) = p.m;
  }
};

}  // namespace pradis::elements
