#pragma once
/// \file
/// SPRING: linear spring between two DOFs.

#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct linear_spring_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using linear_spring = linear_spring_t<>;
/// SPRING: linear spring between DOFs 1 and 2 (connect DOF 2 to the ground for a
/// spring to a fixed point): flows k (u1 - u2), k (u2 - u1). Pure stiffness (ADR=1, IGN=23).
template <class>
struct linear_spring_t {
  static constexpr pradis::passport passport{.name = "SPRING", .ext = 2, .par = 1, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "linear spring between two DOFs",
                                     .name = "Linear elastic element between two DOFs",
                                     .field = "mechanics",
                                     .dofs = "1 - displacement of end 1 [m]\n2 - displacement of end 2 [m]",
                                     .parameters = "1 - stiffness k [N/m] (>= 0)",
                                     .work = "1 - spring force k (u2 - u1) [N], positive in tension",
                                     .special = "code 100 if k < 0"};
  struct parameters {
    double k = 0;  ///< stiffness [N/m]
  };
  parameters p;
  explicit linear_spring_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {100.0}; }
  static linear_spring from_parameters(std::span<const double> v) { return linear_spring({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.k >= 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and >= 0");
  }
  void evaluate(const local_input<linear_spring>& in, local_output<linear_spring>& out, element_context& ctx) const {
    const double f = p.k * (in.u(0) - in.u(1));
    out.f << f, -f;
    ctx.work[0] = -f;
    if (out.want_jacobian) out.K << p.k, -p.k, -p.k, p.k;
  }
};

}  // namespace pradis::elements
