#pragma once
/// \file
/// A periodic cubic spline y(x) through the points (x_1, y_1) ... (x_m, y_m) with
/// y_m = y_1 and period x_m - x_1: value, slope and curvature are continuous
/// everywhere, also across the period. Used by the cam (CAM, cam.hpp), whose
/// follower acceleration follows the curvature of the lift.

#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"

namespace pradis::elements {

/// Value and exact first and second derivatives of a periodic_spline.
struct spline_sample {
  double value = 0;      ///< y(x)
  double slope = 0;      ///< dy/dx
  double curvature = 0;  ///< d^2y/dx^2
};

/// The periodic cubic spline (C2) through a table of points. On [x_k, x_k+1]
/// with h = x_k+1 - x_k, t = x - x_k and the second derivatives M_k at the points:
///
///     y = M_k (x_k+1 - x)^3 / 6h + M_k+1 t^3 / 6h + (y_k / h - M_k h / 6)(x_k+1 - x)
///         + (y_k+1 / h - M_k+1 h / 6) t
///
/// where the M_k solve the cyclic tridiagonal system
/// h_k-1 M_k-1 + 2 (h_k-1 + h_k) M_k + h_k M_k+1 = 6 (d_k - d_k-1), d_k the
/// secants, with M_m = M_1 (de Boor, A Practical Guide to Splines, 1978, IV).
/// Abscissae outside [x_1, x_m) are reduced into the period first.
class periodic_spline {
 public:
  /// Takes the flat list x1, y1, x2, y2, ...; never throws for bad data:
  /// problem() reports it (the second derivatives are then not computed).
  explicit periodic_spline(std::span<const double> pairs) {
    if (pairs.size() % 2 != 0) return;
    for (std::size_t i = 0; i + 1 < pairs.size(); i += 2) {
      x_.push_back(pairs[i]);
      y_.push_back(pairs[i + 1]);
    }
    if (problem("x", "y").empty()) solve();
  }

  /// Empty if the table is usable, otherwise one sentence: an odd count, fewer
  /// than 4 points, a non-finite entry, an abscissa not above the previous one,
  /// or a last value that differs from the first (the period must close).
  std::string problem(const std::string& xname, const std::string& yname) const {
    if (x_.size() < 4) return "the table needs at least 4 points (" + xname + ", " + yname + " pairs), got " +
                              std::to_string(x_.size());
    for (std::size_t k = 0; k < x_.size(); ++k) {
      if (!std::isfinite(x_[k]) || !std::isfinite(y_[k]))
        return "point " + std::to_string(k + 1) + " is not finite";
      if (k > 0 && !(x_[k] > x_[k - 1]))
        return xname + " " + std::to_string(k + 1) + " (" + to_text(x_[k]) + ") is not above " + xname + " " +
               std::to_string(k) + " (" + to_text(x_[k - 1]) + ")";
    }
    const double scale = std::max(1.0, std::abs(y_.front()));
    if (std::abs(y_.back() - y_.front()) > 1e-12 * scale)
      return "the last " + yname + " (" + to_text(y_.back()) + ") must equal the first (" + to_text(y_.front()) +
             "): the table spans one period";
    return {};
  }
  /// The period x_m - x_1.
  double period() const noexcept { return x_.back() - x_.front(); }

  /// Value, slope and curvature at `xv` (the table must be valid). No allocation.
  spline_sample at(double xv) const noexcept {
    const double p = period();
    double r = std::fmod(xv - x_.front(), p);
    if (r < 0) r += p;
    const double xr = x_.front() + r;
    std::size_t k = 0;
    {
      std::size_t lo = 0, hi = x_.size() - 1;  // x_[lo] <= xr < x_[hi]
      while (hi - lo > 1) {
        const std::size_t mid = (lo + hi) / 2;
        (x_[mid] <= xr ? lo : hi) = mid;
      }
      k = lo;
    }
    const double h = x_[k + 1] - x_[k], a = x_[k + 1] - xr, t = xr - x_[k];
    const double m0 = m_[k], m1 = m_[k + 1];
    spline_sample s;
    s.value = m0 * a * a * a / (6 * h) + m1 * t * t * t / (6 * h) + (y_[k] / h - m0 * h / 6) * a +
              (y_[k + 1] / h - m1 * h / 6) * t;
    s.slope = -m0 * a * a / (2 * h) + m1 * t * t / (2 * h) + (y_[k + 1] - y_[k]) / h - (m1 - m0) * h / 6;
    s.curvature = (m0 * a + m1 * t) / h;
    return s;
  }

 private:
  // Cyclic tridiagonal solve (Sherman-Morrison on the Thomas algorithm) for M_0..M_n-1,
  // n = m - 1 unknowns; M_n = M_0.
  void solve() {
    const std::size_t n = x_.size() - 1;
    std::vector<double> h(n), d(n), a(n), b(n), c(n), r(n);
    for (std::size_t k = 0; k < n; ++k) {
      h[k] = x_[k + 1] - x_[k];
      d[k] = (y_[k + 1] - y_[k]) / h[k];
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t km = (k + n - 1) % n;
      a[k] = h[km];             // coefficient of M_k-1
      b[k] = 2 * (h[km] + h[k]);
      c[k] = h[k];              // coefficient of M_k+1
      r[k] = 6 * (d[k] - d[km]);
    }
    // Corner entries: row 0 has a[0] at column n-1, row n-1 has c[n-1] at column 0.
    const double alpha = c[n - 1], beta = a[0], gamma = -b[0];
    std::vector<double> bb = b;
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    std::vector<double> u(n, 0.0), z, xsol;
    u[0] = gamma;
    u[n - 1] = alpha;
    xsol = thomas(a, bb, c, r);
    z = thomas(a, bb, c, u);
    const double fact = (xsol[0] + beta * xsol[n - 1] / gamma) / (1 + z[0] + beta * z[n - 1] / gamma);
    m_.assign(n + 1, 0.0);
    for (std::size_t k = 0; k < n; ++k) m_[k] = xsol[k] - fact * z[k];
    m_[n] = m_[0];
  }
  static std::vector<double> thomas(const std::vector<double>& a, const std::vector<double>& b,
                                    const std::vector<double>& c, const std::vector<double>& r) {
    const std::size_t n = b.size();
    std::vector<double> cp(n), dp(n), x(n);
    cp[0] = c[0] / b[0];
    dp[0] = r[0] / b[0];
    for (std::size_t i = 1; i < n; ++i) {
      const double m = b[i] - a[i] * cp[i - 1];
      cp[i] = c[i] / m;
      dp[i] = (r[i] - a[i] * dp[i - 1]) / m;
    }
    x[n - 1] = dp[n - 1];
    for (std::size_t i = n - 1; i-- > 0;) x[i] = dp[i] - cp[i] * x[i + 1];
    return x;
  }

  std::vector<double> x_, y_, m_;
};

}  // namespace pradis::elements
