#pragma once
/// \file
/// DAMPER: linear viscous damper between two DOFs.

#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct linear_damper_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using linear_damper = linear_damper_t<>;
/// DAMPER: linear damper between DOFs 1 and 2: flows c (v1 - v2), c (v2 - v1).
/// Pure viscosity (ADR=2, IGN=3): only the velocity block exists.
template <class>
struct linear_damper_t {
  static constexpr pradis::passport passport{.name = "DAMPER", .ext = 2, .par = 1, .wrk = 1, .adr = 2, .ign = 3};
  static constexpr element_help help{.title = "linear viscous damper between two DOFs",
                                     .name = "Linear viscous element between two DOFs",
                                     .field = "mechanics",
                                     .dofs = "1 - displacement of end 1 [m]\n2 - displacement of end 2 [m]",
                                     .parameters = "1 - damping coefficient c [N s/m] (>= 0)",
                                     .work = "1 - damper force c (v2 - v1) [N]",
                                     .special = "code 100 if c < 0"};
  struct parameters {
    double c = 0;  ///< damping coefficient [N s/m]
  };
  parameters p;
  explicit linear_damper_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {3.0}; }
  static linear_damper from_parameters(std::span<const double> v) { return linear_damper({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping coefficient c = " + to_text(p.c) + " must be finite and >= 0");
  }
  void evaluate(const local_input<linear_damper>& in, local_output<linear_damper>& out, element_context& ctx) const {
    const double f = p.c * (in.v(0) - in.v(1));
    out.f << f, -f;
    ctx.work[0] = -f;
    if (out.want_jacobian) out.C << p.c, -p.c, -p.c, p.c;
  }
};

}  // namespace pradis::elements
