#pragma once
/// \file
/// One-step integration schemes of the Newmark family, as policies of
/// pradis::simulation: PRADIS's Stoermer scheme (SHTERM) and Newmark.
///
/// With step h, previous (u0, v0, a0) and the Newton unknown v (the velocity,
/// PRADIS's default FLAG=2):
///     a = (v - v0 - h (1 - gamma) a0) / (gamma h)
///     u = u0 + h v0 + h^2 ((1/2 - beta) a0 + beta a)
/// so du/dv = beta h / gamma, da/dv = 1 / (gamma h), and the Newton matrix is
///     J = (beta h / gamma) K + C + (1 / (gamma h)) M.
/// Stoermer is beta = 1/2, gamma = 1 (J = (h/2) K + C + (1/h) M, first order,
/// dissipative); average-acceleration Newmark is beta = 1/4, gamma = 1/2 (second
/// order, no algorithmic damping).

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <string_view>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"

namespace pradis {

/// Parameters of the Newmark scheme (default: average acceleration).
struct newmark_parameters {
  double beta = 0.25;   ///< displacement weight, 0 < beta <= 1/2
  double gamma = 0.5;   ///< velocity weight, 1/2 <= gamma <= 1
};

/// Newmark family with velocity as the Newton unknown.
class newmark {
 public:
  static constexpr std::string_view name = "NEWMARK";
  newmark() = default;
  /// Throws invalid_option unless 0 < beta <= 1/2 and 1/2 <= gamma <= 1.
  /// The scheme is unconditionally stable for linear problems when
  /// 2 beta >= gamma; with 2 beta < gamma it is only conditionally stable.
  explicit newmark(newmark_parameters p) : p_(p) {
    if (!(p.gamma >= 0.5 && p.gamma <= 1.0))
      throw error(error_code::invalid_option,
                  "NEWMARK gamma = " + std::to_string(p.gamma) + " is outside its valid range [0.5, 1]");
    if (!(p.beta > 0.0 && p.beta <= 0.5))
      throw error(error_code::invalid_option,
                  "NEWMARK beta = " + std::to_string(p.beta) + " is outside its valid range (0, 0.5]");
  }
  const newmark_parameters& parameters() const noexcept { return p_; }
  /// Jacobian coefficients for the velocity unknown.
  jacobian_coefficients coefficients(double h) const noexcept {
    return {p_.beta * h / p_.gamma, 1.0, 1.0 / (p_.gamma * h)};
  }
  /// Predictor of the velocity (PRADIS: v_p = v0 + h a0).
  double predict(double, double v0, double a0, double h) const noexcept { return v0 + h * a0; }
  /// Displacement and acceleration that follow from the velocity v.
  void complete(double u0, double v0, double a0, double h, double v, double& u, double& a) const noexcept {
    a = (v - v0 - h * (1.0 - p_.gamma) * a0) / (p_.gamma * h);
    u = u0 + h * v0 + h * h * ((0.5 - p_.beta) * a0 + p_.beta * a);
  }

 protected:
  newmark_parameters p_{};
};

/// PRADIS's Stoermer scheme (SHTERM, SCHEME=0): Newmark with beta = 1/2, gamma = 1.
///     x_i = x_{i-1} + h v_{i-1} + (h^2/2) a_i,   v_i = v_{i-1} + h a_i.
class stoermer : public newmark {
 public:
  static constexpr std::string_view name = "SHTERM";
  stoermer() { p_ = {0.5, 1.0}; }
};

/// What the simulation needs from an integration scheme.
template <class S>
concept Integrator = requires(const S s, double x, double& r) {
  { S::name } -> std::convertible_to<std::string_view>;
  { s.coefficients(x) } -> std::same_as<jacobian_coefficients>;
  { s.predict(x, x, x, x) } -> std::same_as<double>;
  s.complete(x, x, x, x, x, r, r);
};

}  // namespace pradis
