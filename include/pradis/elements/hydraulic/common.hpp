#pragma once
/// \file
/// Shared pieces of the hydraulic element library (docs/domains.md): the
/// regularised square root of the turbulent orifice law, the C1 ramp and clamp
/// of valve openings, and parameter checks.
///
/// Conventions of every hydraulic element: a hydraulic DOF's velocity-level
/// unknown v is the (gauge) pressure p [Pa], u its time integral [Pa s], a = dp/dt;
/// its flow is the volume flow [m^3/s] the element takes from the node (positive
/// into the element). The tank is the ground DOF (p = 0).

#include <cmath>
#include <string>

#include "pradis/core/element.hpp"

namespace pradis::elements::hydraulic_detail {

/// Regularised signed square root, the value and its first derivative:
///   r(x) = x / (x^2 + d^2)^(1/4),
///   r'(x) = (x^2 / 2 + d^2) / (x^2 + d^2)^(5/4)  (> 0: monotone),
/// with r'(0) = 1 / sqrt(d) finite. For |x| >> d, r(x) = sign(x) sqrt(|x|) (1 + d^2 / x^2)^(-1/4),
/// so the relative deviation from the signed root is below d^2 / (4 x^2).
/// (The idea of Modelica.Fluid.Utilities.regRoot; derivation in docs/domains.md.)
struct reg_root {
  double value = 0, slope = 0;
  reg_root(double x, double d) {
    const double s = x * x + d * d;
    const double q = std::sqrt(std::sqrt(s));  // s^(1/4)
    value = x / q;
    slope = (0.5 * x * x + d * d) / (s * q);
  }
};

/// C1 ramp: 0 for s <= -w, (s + w)^2 / (4 w) for |s| < w, s for s >= w; value, slope and
/// curvature (1 / (2 w) inside the corner, else 0).
struct ramp {
  double value = 0, slope = 0, curvature = 0;
  ramp(double s, double w) {
    if (s <= -w) return;
    if (s >= w) {
      value = s;
      slope = 1;
      return;
    }
    value = (s + w) * (s + w) / (4 * w);
    slope = (s + w) / (2 * w);
    curvature = 1 / (2 * w);
  }
};

/// C1 clamp of s to [0, 1] with rounded corners inside the interval (0 < w < 1/4); value and slope:
///   c(s) = (ramp(s - w) - ramp(s - 1 + w)) / (1 - 2 w),
/// exactly 0 for s <= 0, exactly 1 for s >= 1, c(1/2) = 1/2, linear with slope 1 / (1 - 2 w)
/// on [2 w, 1 - 2 w].
struct clamp01 {
  double value = 0, slope = 0;
  clamp01(double s, double w) {
    if (s <= 0) return;
    if (s >= 1) {
      value = 1;
      return;
    }
    const ramp a(s - w, w), b(s - 1 + w, w);
    value = (a.value - b.value) / (1 - 2 * w);
    slope = (a.slope - b.slope) / (1 - 2 * w);
  }
};

/// Width of the rounded corners of valve opening characteristics (fraction of the full stroke or band).
inline constexpr double opening_corner = 0.02;

/// Code 100 unless x is finite and > 0.
inline void require_positive(element_context& ctx, const char* what, double x) {
  if (!(x > 0) || !std::isfinite(x)) ctx.invalid_parameter(std::string(what) + " = " + to_text(x) + " must be finite and > 0");
}
/// Code 100 unless x is finite and >= 0.
inline void require_nonnegative(element_context& ctx, const char* what, double x) {
  if (!(x >= 0) || !std::isfinite(x))
    ctx.invalid_parameter(std::string(what) + " = " + to_text(x) + " must be finite and >= 0");
}
/// Code 100 unless x is finite.
inline void require_finite(element_context& ctx, const char* what, double x) {
  if (!std::isfinite(x)) ctx.invalid_parameter(std::string(what) + " = " + to_text(x) + " must be finite");
}

}  // namespace pradis::elements::hydraulic_detail
