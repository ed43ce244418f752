#pragma once
/// \file
/// Time functions of the electric and pneumatic sources: a constant, a sine and a
/// table of (t, y) pairs with linear interpolation. Each gives its value, its time
/// derivative and its exact integral from t = 0 (the integral is the u of a source
/// that prescribes a potential: the flux linkage of a voltage source).

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/core/element.hpp"

namespace pradis::elements {

/// Value y(t), derivative y'(t) and integral of y from 0 to t of a waveform.
struct wave_sample {
  double value = 0;     ///< y(t)
  double slope = 0;     ///< y'(t)
  double integral = 0;  ///< integral of y from 0 to t
};

/// Constant waveform y(t) = Y0 (one parameter).
struct constant_wave {
  static constexpr int par = 1, vpr = 0;
  /// The parameter.
  struct parameters {
    double value = 0;  ///< Y0
  };
  static parameters from(std::span<const double> v) { return {v[0]}; }
  static int count(const parameters&) { return par; }
  /// Code 100 unless Y0 is finite; `what` names the quantity ("current I0 [A]").
  static void check(const parameters& p, element_context& ctx, std::string_view what) {
    if (!std::isfinite(p.value)) ctx.invalid_parameter(std::string(what) + " must be finite");
  }
  static wave_sample at(const parameters& p, double t) { return {p.value, 0.0, p.value * t}; }
  /// Largest step that resolves the waveform (none).
  static double resolving_step(const parameters&) { return std::numeric_limits<double>::infinity(); }
};

/// Harmonic waveform y(t) = Y0 + A sin(2 pi f t + phase) (four parameters:
/// A, f [Hz], phase [deg], Y0).
struct sine_wave {
  static constexpr int par = 4, vpr = 0;
  /// The parameters, in PAR order.
  struct parameters {
    double amplitude = 0;  ///< A
    double frequency = 0;  ///< f [Hz] (>= 0)
    double phase_deg = 0;  ///< phase [deg]
    double offset = 0;     ///< Y0
  };
  static parameters from(std::span<const double> v) { return {v[0], v[1], v[2], v[3]}; }
  static int count(const parameters&) { return par; }
  /// Code 100 for a negative or non-finite frequency or a non-finite amplitude, phase or offset.
  static void check(const parameters& p, element_context& ctx, std::string_view what) {
    if (!std::isfinite(p.amplitude) || !std::isfinite(p.phase_deg) || !std::isfinite(p.offset))
      ctx.invalid_parameter("amplitude, phase and constant part of the " + std::string(what) + " must be finite");
    if (!(p.frequency >= 0) || !std::isfinite(p.frequency))
      ctx.invalid_parameter("frequency f = " + to_text(p.frequency) + " must be finite and >= 0");
  }
  static wave_sample at(const parameters& p, double t) {
    const double ph = p.phase_deg * std::numbers::pi / 180, w = 2 * std::numbers::pi * p.frequency, x = w * t + ph;
    const double integral =
        p.offset * t + (w > 0 ? -p.amplitude * (std::cos(x) - std::cos(ph)) / w : p.amplitude * std::sin(ph) * t);
    return {p.offset + p.amplitude * std::sin(x), p.amplitude * w * std::cos(x), integral};
  }
  /// 1 / (20 f): twenty steps per period.
  static double resolving_step(const parameters& p) {
    return p.frequency > 0 ? 1.0 / (20.0 * p.frequency) : std::numeric_limits<double>::infinity();
  }
};

/// Table waveform: pairs (t1, y1), (t2, y2), ... with t1 < t2 < ..., linear
/// interpolation between them, y1 before t1 and the last y after the last t
/// (an even number of parameters, at least 4: VPR = 21).
struct table_wave {
  static constexpr int par = 4, vpr = 21;
  /// The parameters: t1, y1, t2, y2, ... (allocated once, at construction).
  struct parameters {
    std::vector<double> pairs{};  ///< t1, y1, t2, y2, ...
  };
  static parameters from(std::span<const double> v) { return {std::vector<double>(v.begin(), v.end())}; }
  static int count(const parameters& p) { return static_cast<int>(p.pairs.size()); }
  /// Code 100 unless there is an even number (>= 4) of finite values with strictly increasing times.
  static void check(const parameters& p, element_context& ctx, std::string_view what) {
    const std::size_t n = p.pairs.size();
    if (n < 4 || n % 2 != 0)
      ctx.invalid_parameter("the table of the " + std::string(what) + " needs an even number (at least 4) of values "
                            "t1, y1, t2, y2, ..., got " + std::to_string(n));
    for (std::size_t k = 0; k < n; ++k)
      if (!std::isfinite(p.pairs[k]))
        ctx.invalid_parameter("table value " + std::to_string(k + 1) + " of the " + std::string(what) + " must be finite");
    for (std::size_t k = 2; k < n; k += 2)
      if (!(p.pairs[k] > p.pairs[k - 2]))
        ctx.invalid_parameter("the table times must increase strictly: time t" + std::to_string(k / 2 + 1) + " = " +
                              to_text(p.pairs[k]) + " is not after t" + std::to_string(k / 2) + " = " +
                              to_text(p.pairs[k - 2]));
  }
  static wave_sample at(const parameters& p, double t) {
    const double v = value_slope(p, t, nullptr);
    double s = 0;
    value_slope(p, t, &s);
    return {v, s, antiderivative(p, t) - antiderivative(p, 0.0)};
  }
  /// No bound: the step control resolves the kinks.
  static double resolving_step(const parameters&) { return std::numeric_limits<double>::infinity(); }

 private:
  static double value_slope(const parameters& p, double t, double* slope) {
    const std::size_t m = p.pairs.size() / 2;
    const auto tt = [&](std::size_t k) { return p.pairs[2 * k]; };
    const auto yy = [&](std::size_t k) { return p.pairs[2 * k + 1]; };
    if (slope) *slope = 0;
    if (t < tt(0)) return yy(0);
    if (t >= tt(m - 1)) return yy(m - 1);
    std::size_t k = 0;
    while (t >= tt(k + 1)) ++k;
    const double s = (yy(k + 1) - yy(k)) / (tt(k + 1) - tt(k));
    if (slope) *slope = s;
    return yy(k) + s * (t - tt(k));
  }
  // G(t) with G(t1) = 0 and G' = y.
  static double antiderivative(const parameters& p, double t) {
    const std::size_t m = p.pairs.size() / 2;
    const auto tt = [&](std::size_t k) { return p.pairs[2 * k]; };
    const auto yy = [&](std::size_t k) { return p.pairs[2 * k + 1]; };
    if (t <= tt(0)) return yy(0) * (t - tt(0));
    double g = 0;
    for (std::size_t k = 0; k + 1 < m; ++k) {
      const double h = tt(k + 1) - tt(k);
      if (t < tt(k + 1)) {
        const double s = t - tt(k);
        return g + yy(k) * s + 0.5 * (yy(k + 1) - yy(k)) / h * s * s;
      }
      g += 0.5 * (yy(k) + yy(k + 1)) * h;
    }
    return g + yy(m - 1) * (t - tt(m - 1));
  }
};

}  // namespace pradis::elements
