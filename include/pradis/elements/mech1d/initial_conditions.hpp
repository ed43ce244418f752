#pragma once
/// \file
/// X0 and V0: initial displacement and initial velocity of a DOF (zero step only).

#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct initial_displacement_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using initial_displacement = initial_displacement_t<>;
/// X0: sets the initial displacement of a DOF at the zero step. Produces no flow.
/// A different value already set on the DOF by another element is code 90;
/// changing the value in a later stage ($REPLACE) is code 100.
template <class>
struct initial_displacement_t {
  static constexpr pradis::passport passport{.name = "X0", .ext = 1, .par = 1, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "initial displacement of a DOF",
      .name = "Initial-condition element: displacement at t = 0",
      .field = "mechanics",
      .dofs = "1 - the DOF",
      .parameters = "1 - initial displacement u0 [m]",
      .work = "1 - the value applied at the zero step [m]",
      .special = "code 90 if another element set a different initial displacement on the DOF, or the DOF is "
                 "driven by a source or is the ground; code 100 if u0 is changed after the zero step"};
  struct parameters {
    double u0 = 0;
  };
  parameters p;
  explicit initial_displacement_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.25}; }
  static initial_displacement from_parameters(std::span<const double> v) { return initial_displacement({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.u0)) ctx.invalid_parameter("initial displacement must be finite");
    if (ctx.nstep > 0 && ctx.work[0] != p.u0)
      ctx.invalid_parameter("the initial displacement cannot be changed after the zero step");
  }
  void zero_step(initial_values<1>& iv, element_context& ctx) const {
    iv.set_displacement(0, p.u0);
    ctx.work[0] = p.u0;
  }
  /// No flow and no Jacobian entry: the assembler skips it (core/element.hpp, InertElement).
  static constexpr bool inert = true;
  void evaluate(const local_input<initial_displacement>&, local_output<initial_displacement>& out,
                element_context&) const {
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

template <class = void>
struct initial_velocity_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using initial_velocity = initial_velocity_t<>;
/// V0: sets the initial velocity of a DOF at the zero step. Produces no flow.
template <class>
struct initial_velocity_t {
  static constexpr pradis::passport passport{.name = "V0", .ext = 1, .par = 1, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "initial velocity of a DOF",
      .name = "Initial-condition element: velocity at t = 0",
      .field = "mechanics",
      .dofs = "1 - the DOF",
      .parameters = "1 - initial velocity v0 [m/s]",
      .work = "1 - the value applied at the zero step [m/s]",
      .special = "code 90 if another element set a different initial velocity on the DOF, or the DOF is driven "
                 "by a source or is the ground; code 100 if v0 is changed after the zero step"};
  struct parameters {
    double v0 = 0;
  };
  parameters p;
  explicit initial_velocity_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.5}; }
  static initial_velocity from_parameters(std::span<const double> v) { return initial_velocity({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.v0)) ctx.invalid_parameter("initial velocity must be finite");
    if (ctx.nstep > 0 && ctx.work[0] != p.v0)
      ctx.invalid_parameter("the initial velocity cannot be changed after the zero step");
  }
  void zero_step(initial_values<1>& iv, element_context& ctx) const {
    iv.set_velocity(0, p.v0);
    ctx.work[0] = p.v0;
  }
  /// No flow and no Jacobian entry: the assembler skips it (core/element.hpp, InertElement).
  static constexpr bool inert = true;
  void evaluate(const local_input<initial_velocity>&, local_output<initial_velocity>& out, element_context&) const {
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

}  // namespace pradis::elements
