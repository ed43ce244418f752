#pragma once
/// \file
/// FRICT: dry friction between two DOFs (Coulomb with a Stribeck curve and
/// viscous friction) with a stick state; docs/friction.md.

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct friction_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using friction = friction_t<>;
/// FRICT: friction between DOFs 1 and 2 with relative displacement d = u2 - u1
/// and relative velocity v = v2 - v1. F is the friction force, positive when it
/// opposes a positive v (as a damper's c v); flows -F, F.
///
/// Sliding (direction s = +-1, kept in the state vector):
///   F = s (Fc + (Fs - Fc) exp(-(v / vs)^2)) + b v.
/// Sticking (anchor d0 in the state vector): a stiff spring-damper anchored at
/// the stick position, F = ks (d - d0) + cs v, so a stuck contact does not creep.
///
/// Mode changes (the state vector STR = 3: mode, direction, anchor; the kernel
/// copies NEW to OLD only when a step is accepted, so every Newton iterate of a
/// step starts from the same accepted mode):
///  - stuck -> sliding within the step: when the stick force reaches |F| > Fs and
///    the contact moves in the direction of that force (s = sign F, s v > 0), the
///    sliding law with s is used at this iterate (the breakaway force is Fs on
///    both sides of the switch, up to the small Stribeck and viscous terms);
///  - sliding -> stuck at the end of an accepted step whose relative velocity
///    fell below the threshold or reversed (s v <= vth); anchor: the d of that step.
/// STEPMD: while sliding and decelerating (s a < 0) the element recommends the
/// step s v / |a| that brings the relative velocity to zero, so a velocity
/// reversal falls at a step end rather than within a step.
/// Normal force: give Fs = mu_s N and Fc = mu_k N (forces, not coefficients).
template <class>
struct friction_t {
  static constexpr pradis::passport passport{
      .name = "FRICT", .ext = 2, .par = 7, .str = 3, .wrk = 3, .adr = 1, .ign = 3};
  static constexpr std::array<pradis::domain, 2> domains{pradis::domain::mechanical, pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "dry friction (Coulomb + Stribeck + viscous) with sticking between two DOFs",
      .name = "Friction between two DOFs: sliding F = s (Fc + (Fs - Fc) exp(-(v/vs)^2)) + b v, sticking on a "
              "stiff anchored spring ks (d - d0) + cs v, d = u2 - u1, v = v2 - v1",
      .field = "mechanics",
      .dofs = "1 - displacement of body 1 [m] (or rotation [rad])\n"
              "2 - displacement of body 2 [m] (or rotation [rad])",
      .parameters = "1 - static (breakaway) friction force Fs = mu_s N [N] (>= 0)\n"
                    "2 - kinetic (Coulomb) friction force Fc = mu_k N [N] (0 <= Fc <= Fs)\n"
                    "3 - Stribeck velocity vs [m/s] (> 0)\n"
                    "4 - viscous friction coefficient b [N s/m] (>= 0)\n"
                    "5 - stick stiffness ks [N/m] (> 0)\n"
                    "6 - stick damping cs [N s/m] (>= 0)\n"
                    "7 - stick velocity threshold vth [m/s] (> 0)",
      .work = "1 - friction force F [N], positive when it opposes a positive v2 - v1\n"
              "2 - relative velocity v = v2 - v1 [m/s]\n"
              "3 - stick flag: 1 stuck, 0 sliding",
      .special = "code 100 if Fs < 0, Fc < 0, Fc > Fs, vs <= 0, b < 0, ks <= 0, cs < 0, vth <= 0 or a parameter "
                 "is not finite. State vector (STR = 3): mode (1 stuck, 2 sliding), sliding direction, stick "
                 "anchor. Breakaway within the step when the stick force exceeds Fs; sticking after an accepted "
                 "step whose relative velocity fell below vth or reversed. Recommends the step s v / |a| while "
                 "sliding and decelerating (a velocity reversal at a step end). docs/friction.md"};
  /// Typed parameters, in PAR order.
  struct parameters {
    double fs = 0;         ///< static friction force Fs [N]
    double fc = 0;         ///< kinetic (Coulomb) friction force Fc [N]
    double vs = 1e-3;      ///< Stribeck velocity [m/s]
    double b = 0;          ///< viscous friction coefficient [N s/m]
    double ks = 1e7;       ///< stick stiffness [N/m]
    double cs = 0;         ///< stick damping [N s/m]
    double vth = 1e-6;     ///< stick velocity threshold [m/s]
  };
  parameters p;
  explicit friction_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {10.0, 8.0, 0.5, 0.3, 1e5, 10.0, 1e-3}; }
  static friction from_parameters(std::span<const double> v) {
    return friction({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
  }

  /// Modes kept in NEW/OLD(1); 0 is the zeroed state before the first evaluation.
  static constexpr double stuck = 1, sliding = 2;

  void new_integration(element_context& ctx) const {
    const auto check = [&](double x, const char* what, bool positive) {
      if (!std::isfinite(x) || (positive ? !(x > 0) : !(x >= 0)))
        ctx.invalid_parameter(std::string(what) + " = " + to_text(x) + " must be finite and " +
                              (positive ? "> 0" : ">= 0"));
    };
    check(p.fs, "static friction force Fs", false);
    check(p.fc, "kinetic friction force Fc", false);
    if (p.fc > p.fs)
      ctx.invalid_parameter("kinetic friction force Fc = " + to_text(p.fc) + " must not exceed the static friction "
                            "force Fs = " + to_text(p.fs));
    check(p.vs, "Stribeck velocity vs", true);
    check(p.b, "viscous friction coefficient b", false);
    check(p.ks, "stick stiffness ks", true);
    check(p.cs, "stick damping cs", false);
    check(p.vth, "stick velocity threshold vth", true);
  }

  /// The sliding friction force in direction s at relative velocity v and dF/dv.
  std::array<double, 2> sliding_force(double s, double v) const {
    const double x = v / p.vs, e = std::exp(-x * x);
    return {s * (p.fc + (p.fs - p.fc) * e) + p.b * v, -2.0 * s * (p.fs - p.fc) * e * x / p.vs + p.b};
  }

  void evaluate(const local_input<friction>& in, local_output<friction>& out, element_context& ctx) const {
    const double d = in.u(1) - in.u(0), v = in.v(1) - in.v(0);
    const bool has_state = ctx.old_state.size() == 3 && ctx.new_state.size() == 3;
    double mode = has_state ? ctx.old_state[0] : 0.0;
    double dir = has_state ? ctx.old_state[1] : 0.0;
    double anchor = has_state ? ctx.old_state[2] : d;
    bool follow = false;  // the anchor follows d (no accepted state yet): no stiffness
    if (mode != stuck && mode != sliding) {
      // First evaluation (zero step) or no state: sliding if moving, else stuck where it is.
      follow = true;
      anchor = d;
      if (std::abs(v) > p.vth) {
        mode = sliding;
        dir = v > 0 ? 1.0 : -1.0;
      } else {
        mode = stuck;
      }
    }
    double force = 0, kk = 0, cc = 0;
    bool stick = false;
    double next_mode = mode, next_anchor = 0;
    if (mode == stuck) {
      const double fst = p.ks * (d - anchor) + p.cs * v;
      const double s = fst > 0 ? 1.0 : -1.0;
      if (std::abs(fst) > p.fs && s * v > 0) {  // breakaway at this iterate
        const auto [f, dfdv] = sliding_force(s, v);
        force = f;
        cc = dfdv;
        dir = s;
        next_mode = sliding;
      } else {
        force = fst;
        kk = follow ? 0.0 : p.ks;
        cc = p.cs;
        stick = true;
        next_anchor = anchor;
      }
    } else {
      const auto [f, dfdv] = sliding_force(dir, v);
      force = f;
      cc = dfdv;
      // Velocity fell below the threshold or reversed: stuck from the next step on.
      if (dir * v <= p.vth) {
        next_mode = stuck;
        next_anchor = d;
      } else if (dir * in.a(1) - dir * in.a(0) < 0) {
        ctx.recommend_step(dir * v / std::abs(in.a(1) - in.a(0)));
      }
    }
    if (has_state) {
      ctx.new_state[0] = next_mode;
      ctx.new_state[1] = next_mode == sliding ? dir : 0.0;
      ctx.new_state[2] = next_anchor;
    }
    out.f << -force, force;
    ctx.work[0] = force;
    ctx.work[1] = v;
    ctx.work[2] = stick ? 1.0 : 0.0;
    if (!out.want_jacobian) return;
    out.K << kk, -kk, -kk, kk;
    out.C << cc, -cc, -cc, cc;
  }

  /// The all-elements check (no accepted state: stuck with the anchor at d if
  /// |v| <= vth, else sliding with s = sign v) stays 1e-4 away from the switch |v| = vth.
  bool admissible(const local_input<friction>& in) const {
    return std::abs(std::abs(in.v(1) - in.v(0)) - p.vth) > 1e-4;
  }
};

}  // namespace pradis::elements
