#pragma once
/// \file
/// A one-dimensional law y(x) given by a table of points (x_k, y_k): piecewise
/// linear or monotone cubic (PCHIP) interpolation between the points and linear
/// extrapolation beyond them, with the exact derivative dy/dx. Used by TSPRING
/// (elements/mech1d/table_spring.hpp); docs/tables.md describes the rules.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"

namespace pradis::elements {

/// How a tabular_law interpolates between its points.
enum class interpolation : int {
  linear = 0,          ///< piecewise linear: continuous value, the slope jumps at the points
  monotone_cubic = 1,  ///< Fritsch-Carlson / Fritsch-Butland PCHIP: C1, no overshoot on monotone data
};

/// Value and exact derivative of a tabular_law at one abscissa.
struct law_sample {
  double value = 0;  ///< y(x)
  double slope = 0;  ///< dy/dx(x)
};

/// A table of points (x_1, y_1), (x_2, y_2), ... with x_1 < x_2 < ... and its
/// interpolant. Construction stores the points (and, for the monotone cubic, the
/// node slopes) once; at() does not allocate.
///
/// * linear: on [x_k, x_k+1) y = y_k + s_k (x - x_k), s_k = (y_k+1 - y_k) / (x_k+1 - x_k),
///   slope s_k. At an interior point x_k the slope is that of the segment to its
///   right (the one-sided derivative; the value is continuous).
/// * monotone_cubic: the cubic Hermite interpolant with the node slopes of
///   Fritsch & Butland (1984) as used by MATLAB's pchip (Moler, Numerical
///   Computing with MATLAB, 3.4): zero at a local extremum of the data, otherwise
///   the weighted harmonic mean of the neighbouring secants; one-sided
///   three-point slopes at the ends, limited to keep the shape (Fritsch &
///   Carlson, SIAM J. Numer. Anal. 17 (1980) 238). Value and slope are continuous.
/// * Outside [x_1, x_m] both extrapolate linearly with the end slope (linear: the
///   end segment's slope; monotone cubic: the end node slope), so the slope is
///   continuous at the ends.
class tabular_law {
 public:
  tabular_law() = default;
  /// Takes the flat list x1, y1, x2, y2, ... Never throws for bad data: problem()
  /// reports it (the slopes are then not computed and at() must not be used).
  tabular_law(std::span<const double> pairs, interpolation kind) : kind_(kind), flat_(pairs.begin(), pairs.end()) {
    if (!problem().empty()) return;
    const std::size_t m = flat_.size() / 2;
    x_.resize(m);
    y_.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      x_[k] = flat_[2 * k];
      y_[k] = flat_[2 * k + 1];
    }
    secant_.resize(m - 1);
    for (std::size_t k = 0; k + 1 < m; ++k) secant_[k] = (y_[k + 1] - y_[k]) / (x_[k + 1] - x_[k]);
    node_slope_.resize(m);
    if (kind_ == interpolation::monotone_cubic) pchip_slopes();
  }

  /// Empty if the table is usable, otherwise one sentence: an odd count, fewer
  /// than 2 points, a non-finite entry, or an abscissa not above the previous one
  /// ("abscissa 3 (0.2) is not above abscissa 2 (0.3)"). Entries and points are
  /// counted from 1. `xname` and `yname` name the columns in the message.
  std::string problem(const std::string& xname = "abscissa", const std::string& yname = "ordinate") const {
    const std::size_t n = flat_.size();
    if (n % 2 != 0)
      return "the table needs pairs " + xname + ", " + yname + " (an even number of values), got " + std::to_string(n) +
             " values";
    if (n < 4) return "the table needs at least 2 points (4 values), got " + std::to_string(n / 2);
    for (std::size_t k = 0; k < n; ++k)
      if (!std::isfinite(flat_[k]))
        return "table value " + std::to_string(k + 1) + " (" + (k % 2 == 0 ? xname : yname) + " " +
               std::to_string(k / 2 + 1) + ") is not finite: " + to_text(flat_[k]);
    for (std::size_t k = 2; k < n; k += 2)
      if (!(flat_[k] > flat_[k - 2]))
        return xname + " " + std::to_string(k / 2 + 1) + " (" + to_text(flat_[k]) + ") is not above " + xname + " " +
               std::to_string(k / 2) + " (" + to_text(flat_[k - 2]) + "): the " + xname +
               "s must increase strictly";
    return {};
  }

  /// Number of points.
  std::size_t points() const noexcept { return x_.size(); }
  /// The interpolation kind.
  interpolation kind() const noexcept { return kind_; }
  /// Abscissa of point k (0-based).
  double x(std::size_t k) const { return x_[k]; }
  /// Node slope of point k (0-based) of the monotone cubic (for the linear kind: 0).
  double node_slope(std::size_t k) const { return node_slope_[k]; }
  /// Smallest distance from `xv` to a table abscissa (where the linear slope jumps).
  double distance_to_point(double xv) const noexcept {
    double d = std::abs(xv - x_[0]);
    for (double xk : x_) d = std::min(d, std::abs(xv - xk));
    return d;
  }

  /// Value and exact slope at `xv` (the table must be valid). No allocation.
  law_sample at(double xv) const noexcept {
    const std::size_t m = x_.size();
    const bool cubic = kind_ == interpolation::monotone_cubic;
    if (xv < x_[0]) {
      const double s = cubic ? node_slope_[0] : secant_[0];
      return {y_[0] + s * (xv - x_[0]), s};
    }
    if (xv >= x_[m - 1]) {
      const double s = cubic ? node_slope_[m - 1] : secant_[m - 2];
      return {y_[m - 1] + s * (xv - x_[m - 1]), s};
    }
    // Segment k with x_k <= xv < x_k+1.
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), xv) - x_.begin()) - 1;
    const double h = x_[k + 1] - x_[k], dx = xv - x_[k];
    if (!cubic) return {y_[k] + secant_[k] * dx, secant_[k]};
    // Cubic Hermite basis in t = dx / h.
    const double t = dx / h, t2 = t * t, t3 = t2 * t;
    const double m0 = node_slope_[k] * h, m1 = node_slope_[k + 1] * h;
    const double value = (2 * t3 - 3 * t2 + 1) * y_[k] + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * y_[k + 1] +
                         (t3 - t2) * m1;
    const double dvalue = (6 * t2 - 6 * t) * y_[k] + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * y_[k + 1] +
                          (3 * t2 - 2 * t) * m1;
    return {value, dvalue / h};
  }

 private:
  static double sign(double a) noexcept { return a > 0 ? 1.0 : a < 0 ? -1.0 : 0.0; }
  // Node slopes of MATLAB's pchip (Fritsch-Butland interior, shape-preserving ends).
  void pchip_slopes() {
    const std::size_t m = x_.size();
    if (m == 2) {
      node_slope_[0] = node_slope_[1] = secant_[0];
      return;
    }
    for (std::size_t k = 1; k + 1 < m; ++k) {
      const double d0 = secant_[k - 1], d1 = secant_[k];
      if (sign(d0) * sign(d1) <= 0) {
        node_slope_[k] = 0;
        continue;
      }
      const double h0 = x_[k] - x_[k - 1], h1 = x_[k + 1] - x_[k];
      const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
      node_slope_[k] = (w1 + w2) / (w1 / d0 + w2 / d1);
    }
    node_slope_[0] = end_slope(x_[1] - x_[0], x_[2] - x_[1], secant_[0], secant_[1]);
    node_slope_[m - 1] = end_slope(x_[m - 1] - x_[m - 2], x_[m - 2] - x_[m - 3], secant_[m - 2], secant_[m - 3]);
  }
  // Three-point one-sided slope at an end (h0, d0: the end segment; h1, d1: its neighbour).
  static double end_slope(double h0, double h1, double d0, double d1) {
    double s = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (sign(s) != sign(d0))
      s = 0;
    else if (sign(d0) != sign(d1) && std::abs(s) > std::abs(3 * d0))
      s = 3 * d0;
    return s;
  }

  interpolation kind_ = interpolation::linear;
  std::vector<double> flat_;        // x1, y1, x2, y2, ... as given
  std::vector<double> x_, y_;       // the points
  std::vector<double> secant_;      // (y_k+1 - y_k) / (x_k+1 - x_k)
  std::vector<double> node_slope_;  // monotone cubic: slope at each point
};

}  // namespace pradis::elements
