#pragma once
// An independent solution of a planar chain of n point masses m on massless rigid
// links of length l, the first hinged at the origin, released horizontally from
// rest under gravity -Y: Lagrange's equations in the absolute link angles theta_j,
//
//   sum_k c_jk [cos(theta_j - theta_k) theta_k'' + sin(theta_j - theta_k) theta_k'^2]
//       = -(g / l) cos(theta_j) (n - j),   c_jk = n - max(j, k)   (0-based j, k),
//
// integrated with the classical Runge-Kutta method (global error ~h^4). Used by
// tests/elements/test_rigid_link.cpp and bench/bench_joints.cpp as the reference
// for chains built of LINKX (exact) or LINKD (penalty) links.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace pradis_reference {

/// Angles theta_j and rates theta_j' of the chain's links.
struct chain_state {
  Eigen::VectorXd th, om;
};

/// theta'' from Lagrange's equations (a dense solve).
inline Eigen::VectorXd chain_acceleration(const Eigen::VectorXd& th, const Eigen::VectorXd& om, double l, double g) {
  const int n = static_cast<int>(th.size());
  Eigen::MatrixXd a(n, n);
  Eigen::VectorXd b(n);
  for (int j = 0; j < n; ++j) {
    b(j) = -(g / l) * std::cos(th(j)) * (n - j);
    for (int k = 0; k < n; ++k) {
      const double c = n - std::max(j, k);
      a(j, k) = c * std::cos(th(j) - th(k));
      b(j) -= c * std::sin(th(j) - th(k)) * om(k) * om(k);
    }
  }
  return a.partialPivLu().solve(b);
}

/// The state at t_end after `steps` RK4 steps from the horizontal at rest.
inline chain_state chain_reference(int n, double l, double g, double t_end, int steps) {
  chain_state s{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  const double h = t_end / steps;
  for (int i = 0; i < steps; ++i) {
    const Eigen::VectorXd k1t = s.om, k1o = chain_acceleration(s.th, s.om, l, g);
    const Eigen::VectorXd k2t = s.om + 0.5 * h * k1o, k2o = chain_acceleration(s.th + 0.5 * h * k1t, k2t, l, g);
    const Eigen::VectorXd k3t = s.om + 0.5 * h * k2o, k3o = chain_acceleration(s.th + 0.5 * h * k2t, k3t, l, g);
    const Eigen::VectorXd k4t = s.om + h * k3o, k4o = chain_acceleration(s.th + h * k3t, k4t, l, g);
    s.th += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    s.om += h / 6 * (k1o + 2 * k2o + 2 * k3o + k4o);
  }
  return s;
}

/// Tip position (x, y) of the chain state.
inline Eigen::Vector2d chain_tip(const chain_state& s, double l) {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (int j = 0; j < s.th.size(); ++j) p += l * Eigen::Vector2d(std::cos(s.th(j)), std::sin(s.th(j)));
  return p;
}

}  // namespace pradis_reference
