#pragma once
/// \file
/// D and SW: a smooth diode and a time-switched resistance, both pure viscosity
/// blocks (their current depends on the node voltages v and on time only).

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct diode_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using diode = diode_t<>;
/// D: diode from node 1 (anode) to node 2 (cathode), vd = v1 - v2. Shockley's law
/// i = Is (exp(vd / (n Vt)) - 1) up to the limiting voltage Vmax, continued above it
/// by its tangent at Vmax (so exp never overflows and Newton cannot be thrown to
/// huge currents by one large iterate), plus a parallel minimum conductance Gmin
/// (keeps a reverse-biased diode's node from floating):
///     vd <= Vmax:  i = Is (exp(vd/(n Vt)) - 1) + Gmin vd
///     vd >  Vmax:  i = Is (exp(Vmax/(n Vt)) (1 + (vd - Vmax)/(n Vt)) - 1) + Gmin vd
/// The current and its derivative are continuous at Vmax (the curve is C1).
template <class>
struct diode_t {
  static constexpr pradis::passport passport{.name = "D", .ext = 2, .par = 5, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::electric, domain::electric};
  static constexpr element_help help{
      .title = "diode (Shockley, linearly continued above a limiting voltage)",
      .name = "Semiconductor diode: i = Is (exp(vd/(n Vt)) - 1) + Gmin vd, tangent continuation above Vmax",
      .field = "electric circuits",
      .dofs = "1 - anode [V]\n2 - cathode [V]",
      .parameters = "1 - saturation current Is [A] (> 0)\n2 - emission coefficient n (> 0)\n"
                    "3 - thermal voltage Vt [V] (> 0; 0.025852 at 300 K)\n"
                    "4 - limiting voltage Vmax [V] (> 0, Vmax/(n Vt) <= 200)\n"
                    "5 - minimum parallel conductance Gmin [S] (>= 0)",
      .work = "1 - current i from anode to cathode [A]\n2 - voltage vd = v1 - v2 [V]",
      .special = "code 100 if a parameter is outside its range or not finite. Above Vmax the characteristic is "
                 "the tangent of the exponential at Vmax: choose Vmax above the forward voltages of the circuit. Newton "
                 "descends the exponential by about n Vt per iteration: a diode node without capacitance may need "
                 "more iterations than ITR = 5 from a far start"};
  struct parameters {
    double is = 1e-14;     ///< saturation current [A]
    double n = 1;          ///< emission coefficient
    double vt = 0.025852;  ///< thermal voltage [V]
    double vmax = 0.9;     ///< limiting voltage [V]
    double gmin = 1e-12;   ///< minimum conductance [S]
  };
  parameters p;
  explicit diode_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1e-9, 1.5, 0.025852, 0.7, 1e-6}; }
  static diode from_parameters(std::span<const double> v) { return diode({v[0], v[1], v[2], v[3], v[4]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.is > 0) || !std::isfinite(p.is)) ctx.invalid_parameter("saturation current Is = " + to_text(p.is) + " must be finite and > 0");
    if (!(p.n > 0) || !std::isfinite(p.n)) ctx.invalid_parameter("emission coefficient n = " + to_text(p.n) + " must be finite and > 0");
    if (!(p.vt > 0) || !std::isfinite(p.vt)) ctx.invalid_parameter("thermal voltage Vt = " + to_text(p.vt) + " must be finite and > 0");
    if (!(p.vmax > 0) || !(p.vmax / (p.n * p.vt) <= max_exponent))
      ctx.invalid_parameter("limiting voltage Vmax = " + to_text(p.vmax) + " must be > 0 with Vmax/(n Vt) <= 200");
    if (!(p.gmin >= 0) || !std::isfinite(p.gmin)) ctx.invalid_parameter("minimum conductance Gmin = " + to_text(p.gmin) + " must be finite and >= 0");
  }
  /// Current i(vd) and conductance di/dvd.
  void characteristic(double vd, double& i, double& g) const {
    const double nvt = p.n * p.vt;
    if (vd <= p.vmax) {
      const double e = std::exp(vd / nvt);
      i = p.is * (e - 1.0) + p.gmin * vd;
      g = p.is * e / nvt + p.gmin;
    } else {
      const double em = std::exp(p.vmax / nvt);
      i = p.is * (em * (1.0 + (vd - p.vmax) / nvt) - 1.0) + p.gmin * vd;
      g = p.is * em / nvt + p.gmin;
    }
  }
  void evaluate(const local_input<diode>& in, local_output<diode>& out, element_context& ctx) const {
    const double vd = in.v(0) - in.v(1);
    double i = 0, g = 0;
    characteristic(vd, i, g);
    out.f << i, -i;
    ctx.work[0] = i;
    ctx.work[1] = vd;
    if (out.want_jacobian) out.C << g, -g, -g, g;
  }
  /// Largest admissible Vmax / (n Vt).
  static constexpr double max_exponent = 200;
};

template <class = void>
struct time_switch_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using time_switch = time_switch_t<>;
/// SW: time-switched resistance between nodes 1 and 2: R1 before t1, R2 from t1 + tau
/// to t2, R1 again from t2 + tau, with smooth transitions of length tau. The
/// resistance moves geometrically, R = R1^(1-s) R2^s, with the C1 ramp
/// s(t) = S((t - t1)/tau) - S((t - t2)/tau), S(x) = 3x^2 - 2x^3 on [0, 1] (0 before,
/// 1 after). A closing switch has R1 large and R2 small, an opening one the reverse.
template <class>
struct time_switch_t {
  static constexpr pradis::passport passport{.name = "SW", .ext = 2, .par = 5, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::electric, domain::electric};
  static constexpr element_help help{
      .title = "resistance switched at given times",
      .name = "Switch: resistance R1 before t1 and after t2 + tau, R2 between, smooth transitions of length tau",
      .field = "electric circuits",
      .dofs = "1 - node 1 [V]\n2 - node 2 [V]",
      .parameters = "1 - resistance R1 outside [t1, t2] [Ohm] (> 0; off: large)\n"
                    "2 - resistance R2 inside [t1 + tau, t2] [Ohm] (> 0; on: small)\n3 - switching time t1 [s]\n"
                    "4 - switching-back time t2 [s] (>= t1 + tau)\n5 - transition time tau [s] (> 0)",
      .work = "1 - current from node 1 to node 2 [A]\n2 - current resistance R(t) [Ohm]",
      .special = "code 100 if a resistance or tau is not > 0, t2 < t1 + tau, or a parameter is not finite; "
                 "recommends steps that land on t1 and t2 and resolve each transition with 10 steps"};
  struct parameters {
    double r1 = 1e9;   ///< resistance outside the switched interval [Ohm]
    double r2 = 1e-3;  ///< resistance inside [Ohm]
    double t1 = 0;     ///< switching time [s]
    double t2 = 1;     ///< switching-back time [s]
    double tau = 1e-6; ///< transition time [s]
  };
  parameters p;
  explicit time_switch_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {100.0, 0.5, 0.6, 1.4, 0.3}; }
  static time_switch from_parameters(std::span<const double> v) { return time_switch({v[0], v[1], v[2], v[3], v[4]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.r1 > 0) || !std::isfinite(p.r1)) ctx.invalid_parameter("resistance R1 = " + to_text(p.r1) + " must be finite and > 0");
    if (!(p.r2 > 0) || !std::isfinite(p.r2)) ctx.invalid_parameter("resistance R2 = " + to_text(p.r2) + " must be finite and > 0");
    if (!(p.tau > 0) || !std::isfinite(p.tau)) ctx.invalid_parameter("transition time tau = " + to_text(p.tau) + " must be finite and > 0");
    if (!std::isfinite(p.t1) || !std::isfinite(p.t2) || !(p.t2 >= p.t1 + p.tau))
      ctx.invalid_parameter("switching times t1 = " + to_text(p.t1) + ", t2 = " + to_text(p.t2) +
                            " must be finite with t2 >= t1 + tau");
  }
  /// The on-fraction s(t) in [0, 1].
  double fraction(double t) const { return ramp((t - p.t1) / p.tau) - ramp((t - p.t2) / p.tau); }
  /// R(t) = R1^(1-s) R2^s.
  double resistance(double t) const {
    const double s = fraction(t);
    return std::exp((1.0 - s) * std::log(p.r1) + s * std::log(p.r2));
  }
  void evaluate(const local_input<time_switch>& in, local_output<time_switch>& out, element_context& ctx) const {
    const double r = resistance(in.t), g = 1.0 / r, i = g * (in.v(0) - in.v(1));
    out.f << i, -i;
    ctx.work[0] = i;
    ctx.work[1] = r;
    for (const double te : {p.t1, p.t2}) {
      if (in.t < te) ctx.recommend_step(std::max(te - in.t, 0.1 * p.tau));
      else if (in.t < te + p.tau) ctx.recommend_step(0.1 * p.tau);
    }
    if (out.want_jacobian) out.C << g, -g, -g, g;
  }

 private:
  static double ramp(double x) { return x <= 0 ? 0.0 : (x >= 1 ? 1.0 : x * x * (3.0 - 2.0 * x)); }
};

}  // namespace pradis::elements
