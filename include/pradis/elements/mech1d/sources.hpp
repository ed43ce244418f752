#pragma once
/// \file
/// XSRC and VSRC: kinematic sources that prescribe the motion of one DOF.
///
/// A kinematic source takes its DOF out of the unknowns: the kernel sets the
/// DOF's u, v, a from motion(t) at every step, drops its balance equation, and
/// writes the force the source applies to the DOF (the reaction) into W(1).
/// This is exact (no penalty stiffness) and keeps the Newton matrix regular.

#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

namespace detail {
inline void check_harmonic(element_context& ctx, double a, double f, double ph, double c) {
  if (!std::isfinite(a) || !std::isfinite(ph) || !std::isfinite(c))
    ctx.invalid_parameter("amplitude, phase and constant part must be finite");
  if (!(f >= 0) || !std::isfinite(f))
    ctx.invalid_parameter("frequency f = " + to_text(f) + " must be finite and >= 0");
}
}  // namespace detail

template <class = void>
struct displacement_source_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using displacement_source = displacement_source_t<>;
/// XSRC: displacement source u(t) = U0 + A sin(2 pi f t + phase).
template <class>
struct displacement_source_t {
  static constexpr pradis::passport passport{.name = "XSRC", .ext = 1, .par = 4, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "displacement source on one DOF",
      .name = "Kinematic source prescribing u(t) = U0 + A sin(2 pi f t + phase)",
      .field = "mechanics",
      .dofs = "1 - the driven DOF",
      .parameters = "1 - amplitude A [m]\n2 - frequency f [Hz] (>= 0)\n3 - phase [deg]\n4 - constant part U0 [m]",
      .work = "1 - force the source applies to the DOF (reaction) [N]",
      .special = "code 100 if f < 0 or a parameter is not finite; code 90 if the DOF is the ground, is driven by "
                 "another source, or has an initial condition"};
  struct parameters {
    double amplitude = 0, frequency = 0, phase_deg = 0, offset = 0;
  };
  parameters p;
  explicit displacement_source_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.1, 2.0, 30.0, 0.5}; }
  static displacement_source from_parameters(std::span<const double> v) {
    return displacement_source({v[0], v[1], v[2], v[3]});
  }
  void new_integration(element_context& ctx) const {
    detail::check_harmonic(ctx, p.amplitude, p.frequency, p.phase_deg, p.offset);
  }
  /// The prescribed kinematics.
  kinematics motion(double t) const {
    const double w = 2 * std::numbers::pi * p.frequency, x = w * t + p.phase_deg * std::numbers::pi / 180;
    return {p.offset + p.amplitude * std::sin(x), p.amplitude * w * std::cos(x), -p.amplitude * w * w * std::sin(x)};
  }
  void evaluate(const local_input<displacement_source>&, local_output<displacement_source>& out,
                element_context& ctx) const {
    if (p.frequency > 0) ctx.recommend_step(1.0 / (20.0 * p.frequency));
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

template <class = void>
struct velocity_source_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using velocity_source = velocity_source_t<>;
/// VSRC: velocity source v(t) = V0 + A sin(2 pi f t + phase), with u(0) = 0 and
/// u(t) the exact integral V0 t - A (cos(2 pi f t + phase) - cos(phase)) / (2 pi f).
template <class>
struct velocity_source_t {
  static constexpr pradis::passport passport{.name = "VSRC", .ext = 1, .par = 4, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "velocity source on one DOF",
      .name = "Kinematic source prescribing v(t) = V0 + A sin(2 pi f t + phase), u(0) = 0",
      .field = "mechanics",
      .dofs = "1 - the driven DOF",
      .parameters = "1 - amplitude A [m/s]\n2 - frequency f [Hz] (>= 0)\n3 - phase [deg]\n4 - constant part V0 [m/s]",
      .work = "1 - force the source applies to the DOF (reaction) [N]",
      .special = "code 100 if f < 0 or a parameter is not finite; code 90 if the DOF is the ground, is driven by "
                 "another source, or has an initial condition"};
  struct parameters {
    double amplitude = 0, frequency = 0, phase_deg = 0, offset = 0;
  };
  parameters p;
  explicit velocity_source_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.2, 1.0, 0.0, 0.3}; }
  static velocity_source from_parameters(std::span<const double> v) {
    return velocity_source({v[0], v[1], v[2], v[3]});
  }
  void new_integration(element_context& ctx) const {
    detail::check_harmonic(ctx, p.amplitude, p.frequency, p.phase_deg, p.offset);
  }
  kinematics motion(double t) const {
    const double ph = p.phase_deg * std::numbers::pi / 180;
    const double w = 2 * std::numbers::pi * p.frequency, x = w * t + ph;
    const double u = p.offset * t + (w > 0 ? -p.amplitude * (std::cos(x) - std::cos(ph)) / w : p.amplitude * std::sin(ph) * t);
    return {u, p.offset + p.amplitude * std::sin(x), p.amplitude * w * std::cos(x)};
  }
  void evaluate(const local_input<velocity_source>&, local_output<velocity_source>& out, element_context& ctx) const {
    if (p.frequency > 0) ctx.recommend_step(1.0 / (20.0 * p.frequency));
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

}  // namespace pradis::elements
