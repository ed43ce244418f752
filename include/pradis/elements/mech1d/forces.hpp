#pragma once
/// \file
/// F and FSIN: force sources on one DOF.

#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct constant_force_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using constant_force = constant_force_t<>;
/// F: constant force P applied to a DOF (positive along the DOF). Its flow, the
/// force the system applies to the source, is -P. Its (zero) stiffness block is
/// declared because a passport cannot declare no block at all.
template <class>
struct constant_force_t {
  static constexpr pradis::passport passport{.name = "F", .ext = 1, .par = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "constant force on one DOF",
                                     .name = "Source of constant force (or moment)",
                                     .field = "mechanics",
                                     .dofs = "1 - the DOF the force acts on",
                                     .parameters = "1 - force P [N] (or moment [N m]), positive along the DOF",
                                     .work = "",
                                     .special = "code 100 if P is not finite"};
  struct parameters {
    double force = 0;  ///< P [N]
  };
  parameters p;
  explicit constant_force_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {10.0}; }
  static constant_force from_parameters(std::span<const double> v) { return constant_force({v[0]}); }
  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.force)) ctx.invalid_parameter("force P must be finite");
  }
  void evaluate(const local_input<constant_force>&, local_output<constant_force>& out, element_context&) const {
    out.f(0) = -p.force;
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

template <class = void>
struct sine_force_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using sine_force = sine_force_t<>;
/// FSIN: harmonic force P(t) = P0 + A sin(2 pi f t + phase) on a DOF.
template <class>
struct sine_force_t {
  static constexpr pradis::passport passport{.name = "FSIN", .ext = 1, .par = 4, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "harmonic force on one DOF",
      .name = "Source of harmonic force P0 + A sin(2 pi f t + phase)",
      .field = "mechanics",
      .dofs = "1 - the DOF the force acts on",
      .parameters = "1 - amplitude A [N]\n2 - frequency f [Hz] (>= 0)\n3 - phase [deg]\n4 - constant part P0 [N]",
      .work = "1 - current force P(t) [N]",
      .special = "code 100 if f < 0 or a parameter is not finite; recommends a step of at most 1/(20 f)"};
  struct parameters {
    double amplitude = 0;  ///< A [N]
    double frequency = 0;  ///< f [Hz]
    double phase_deg = 0;  ///< phase [deg]
    double offset = 0;     ///< P0 [N]
  };
  parameters p;
  explicit sine_force_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {5.0, 2.0, 30.0, 1.0}; }
  static sine_force from_parameters(std::span<const double> v) { return sine_force({v[0], v[1], v[2], v[3]}); }
  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.amplitude) || !std::isfinite(p.phase_deg) || !std::isfinite(p.offset))
      ctx.invalid_parameter("amplitude, phase and constant part must be finite");
    if (!(p.frequency >= 0) || !std::isfinite(p.frequency))
      ctx.invalid_parameter("frequency f = " + to_text(p.frequency) + " must be finite and >= 0");
  }
  /// P(t).
  double force(double t) const {
    return p.offset + p.amplitude * std::sin(2 * std::numbers::pi * p.frequency * t + p.phase_deg * std::numbers::pi / 180);
  }
  void evaluate(const local_input<sine_force>& in, local_output<sine_force>& out, element_context& ctx) const {
    const double f = force(in.t);
    out.f(0) = -f;
    ctx.work[0] = f;
    if (p.frequency > 0) ctx.recommend_step(1.0 / (20.0 * p.frequency));
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

}  // namespace pradis::elements
