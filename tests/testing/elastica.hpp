#pragma once
// The elastica of a cantilever under a dead tip load, the reference of the large-deflection tests of BEAM3C
// (tests/elements/test_condensed_beam.cpp, tests/lang/test_large_deflection_model.cpp).

#include <array>
#include <cmath>

namespace pradis_test {

/// The tip (x, y) / L of an inextensible Euler-Bernoulli cantilever of length L along X, clamped at x = 0, under a
/// dead load P along Y at its tip, alpha = P L^2 / (E I). The elastica: theta'' = -alpha cos(theta) in s / L,
/// theta(0) = 0 and theta'(1) = 0 (the moment E I theta' = P (x_tip - x) vanishes at the tip); solved by shooting on
/// theta'(0) with classical Runge-Kutta (4000 steps, bisection to 1e-14: the tip to about 1e-12).
/// Bisshopp and Drucker, Q. Appl. Math. 3 (1945) 272, tabulate it; at alpha = 1 the tip is at x = 0.9436 L,
/// y = 0.3017 L (checked in the tests).
inline std::array<double, 2> elastica_tip(double alpha) {
  const auto shoot = [&](double c, std::array<double, 2>& tip) {
    constexpr int n = 4000;
    const double h = 1.0 / n;
    double th = 0, w = c, x = 0, y = 0;
    const auto f = [&](double t, double ww) {
      return std::array<double, 4>{ww, -alpha * std::cos(t), std::cos(t), std::sin(t)};
    };
    for (int i = 0; i < n; ++i) {
      const auto k1 = f(th, w);
      const auto k2 = f(th + h / 2 * k1[0], w + h / 2 * k1[1]);
      const auto k3 = f(th + h / 2 * k2[0], w + h / 2 * k2[1]);
      const auto k4 = f(th + h * k3[0], w + h * k3[1]);
      th += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
      w += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
      x += h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2]);
      y += h / 6 * (k1[3] + 2 * k2[3] + 2 * k3[3] + k4[3]);
    }
    tip = {x, y};
    return w;  // theta'(1)
  };
  // theta'(1) < 0 at theta'(0) = 0 and > 0 at theta'(0) = alpha (the root curvature of the load's moment arm L).
  double lo = 0, hi = alpha;
  std::array<double, 2> tip{};
  while (hi - lo > 1e-14) {
    const double c = (lo + hi) / 2;
    (shoot(c, tip) > 0 ? hi : lo) = c;
  }
  shoot((lo + hi) / 2, tip);
  return tip;
}

}  // namespace pradis_test
