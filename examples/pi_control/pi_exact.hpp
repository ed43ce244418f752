#pragma once
// The exact solution of the PI-controlled oscillator of examples/pi_control:
//     m x'' + c x' + (k + Kp) x + Ki h = F0,   h' = x,   x(0) = x'(0) = h(0) = 0,
// as z(t) = exp(A t) z(0) with z = (x, x', h, 1) (the constant force as the fourth state),
// exp by scaling and squaring of its Taylor series (the norm scaled below 1/2, 24 terms).

#include <Eigen/Core>
#include <cmath>

namespace pradis_examples {

/// The plant and the controller.
struct pi_plant {
  double m = 1;      ///< mass [kg]
  double c = 10;     ///< damping [N s/m]
  double k = 100;    ///< spring [N/m]
  double kp = 300;   ///< proportional gain [N/m]
  double ki = 1000;  ///< integral gain [N/(m s)]
  double f0 = 10;    ///< disturbance from t = 0 [N]
};

/// exp(M) of a 4 x 4 matrix.
inline Eigen::Matrix4d expm4(const Eigen::Matrix4d& a) {
  const double norm = a.cwiseAbs().rowwise().sum().maxCoeff();
  int s = 0;
  while (std::ldexp(norm, -s) > 0.5) ++s;
  const Eigen::Matrix4d b = a * std::ldexp(1.0, -s);
  Eigen::Matrix4d e = Eigen::Matrix4d::Identity(), term = Eigen::Matrix4d::Identity();
  for (int n = 1; n <= 24; ++n) {
    term = term * b / n;
    e += term;
  }
  for (int i = 0; i < s; ++i) e = e * e;
  return e;
}

/// z(t) = (x, x', h, 1) of the exact solution.
inline Eigen::Vector4d pi_exact(const pi_plant& p, double t) {
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a(0, 1) = 1;
  a(1, 0) = -(p.k + p.kp) / p.m;
  a(1, 1) = -p.c / p.m;
  a(1, 2) = -p.ki / p.m;
  a(1, 3) = p.f0 / p.m;
  a(2, 0) = 1;
  return expm4(a * t) * Eigen::Vector4d(0, 0, 0, 1);
}

}  // namespace pradis_examples
