#pragma once
/// \file
/// One-step integration schemes of the Newmark / alpha family, as policies of
/// pradis::simulation: PRADIS's Stoermer scheme (SHTERM), Newmark, HHT-alpha
/// and generalized-alpha.
///
/// All are written in the form that suits an implicit system F(u, v, a, t) = 0
/// (the residual is evaluated at t_{n+1} with the true acceleration; the
/// numerical dissipation comes from a pseudo-acceleration p with p_0 = a_0):
///     (1 - alpha_m) p_{n+1} + alpha_m p_n = (1 - alpha_f) a_{n+1} + alpha_f a_n
///     u_{n+1} = u_n + h v_n + h^2 ((1/2 - beta) p_n + beta p_{n+1})
///     v_{n+1} = v_n + h ((1 - gamma) p_n + gamma p_{n+1})
/// For linear problems it has the amplification matrix of the classical
/// alpha-weighted form. With alpha_m = alpha_f = 0 it is Newmark (p = a).
///
/// The Newton unknown is the velocity v (PRADIS's default FLAG=2), so
///     du/dv = beta h / gamma,  da/dv = (1 - alpha_m) / ((1 - alpha_f) gamma h)
/// and the Newton matrix is J = cu K + C + ca M with those factors.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <concepts>
#include <string>
#include <string_view>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/concepts.hpp"

namespace pradis {

/// Parameters of the Newmark scheme (default: average acceleration).
struct newmark_parameters {
  double beta = 0.25;   ///< displacement weight, 0 < beta <= 1/2
  double gamma = 0.5;   ///< velocity weight, 1/2 <= gamma <= 1
};

/// The four parameters of the alpha family.
struct alpha_parameters {
  double alpha_m = 0, alpha_f = 0;  ///< the weights of the inertia and of the other flows at t_n
  double beta = 0.25, gamma = 0.5;   ///< the Newmark weights of the displacement and the velocity
};

/// Common implementation of the alpha family with velocity as the Newton unknown.
class alpha_scheme {
 public:
  /// The scheme's parameters.
  const alpha_parameters& coefficients_set() const noexcept { return p_; }
  /// Jacobian coefficients for the velocity unknown.
  jacobian_coefficients coefficients(double h) const noexcept {
    return {p_.beta * h / p_.gamma, 1.0, (1.0 - p_.alpha_m) / ((1.0 - p_.alpha_f) * p_.gamma * h)};
  }
  /// Predictor of the velocity (PRADIS: v_p = v0 + h a0; here with the pseudo-acceleration).
  double predict(double, double v0, double, double p0, double h) const noexcept { return v0 + h * p0; }
  /// Displacement, acceleration and pseudo-acceleration that follow from the velocity v.
  void complete(double u0, double v0, double a0, double p0, double h, double v, double& u, double& a,
                double& p) const noexcept {
    p = (v - v0 - h * (1.0 - p_.gamma) * p0) / (p_.gamma * h);
    // u = u0 + h v0 + h^2 ((1/2 - beta) p0 + beta p) with p substituted, so that
    // u follows from the velocities: through p, a stiff DOF (omega h >> 1, where
    // |p0| ~ |p| ~ omega^2 |u|) would lose u in the cancellation of p0 + p
    // (Newmark: u = u0 + h (v0 + v) / 2 exactly, whatever p0 is).
    const double r = p_.beta / p_.gamma;
    u = u0 + h * ((1.0 - r) * v0 + r * v) + h * h * (0.5 - r) * p0;
    if (p_.alpha_m == 0.0 && p_.alpha_f == 0.0)
      a = p;
    else
      a = ((1.0 - p_.alpha_m) * p + p_.alpha_m * p0 - p_.alpha_f * a0) / (1.0 - p_.alpha_f);
  }

 protected:
  alpha_parameters p_{};
};

/// Newmark family (alpha_m = alpha_f = 0).
class newmark : public alpha_scheme {
 public:
  static constexpr std::string_view name = "NEWMARK";
  newmark() = default;
  /// Throws invalid_option unless 0 < beta <= 1/2 and 1/2 <= gamma <= 1.
  /// The scheme is unconditionally stable for linear problems when
  /// 2 beta >= gamma; with 2 beta < gamma it is only conditionally stable.
  explicit newmark(newmark_parameters q) {
    if (!(q.gamma >= 0.5 && q.gamma <= 1.0))
      throw error(error_code::invalid_option,
                  "NEWMARK gamma = " + to_text(q.gamma) + " is outside its valid range [0.5, 1]");
    if (!(q.beta > 0.0 && q.beta <= 0.5))
      throw error(error_code::invalid_option,
                  "NEWMARK beta = " + to_text(q.beta) + " is outside its valid range (0, 0.5]");
    p_ = {0, 0, q.beta, q.gamma};
  }
  /// beta and gamma.
  newmark_parameters parameters() const noexcept { return {p_.beta, p_.gamma}; }
};

/// PRADIS's Stoermer scheme (SHTERM, SCHEME=0): Newmark with beta = 1/2, gamma = 1.
///     x_i = x_{i-1} + h v_{i-1} + (h^2/2) a_i,   v_i = v_{i-1} + h a_i.
class stoermer : public newmark {
 public:
  static constexpr std::string_view name = "SHTERM";
  stoermer() : newmark(newmark_parameters{0.5, 1.0}) {}
};

/// HHT-alpha (Hilber-Hughes-Taylor), alpha in [-1/3, 0]: alpha_m = 0,
/// alpha_f = -alpha, gamma = (1 - 2 alpha) / 2, beta = (1 - alpha)^2 / 4.
/// Second order; spectral radius at infinity (1 + alpha) / (1 - alpha).
class hht : public alpha_scheme {
 public:
  static constexpr std::string_view name = "HHT";
  /// Default alpha = -0.05.
  hht() : hht(-0.05) {}
  /// Throws invalid_option unless -1/3 <= alpha <= 0.
  explicit hht(double alpha) : alpha_(alpha) {
    if (!(alpha >= -1.0 / 3.0 - 1e-15 && alpha <= 0.0))
      throw error(error_code::invalid_option,
                  "HHT alpha = " + to_text(alpha) + " is outside its valid range [-1/3, 0]");
    p_ = {0.0, -alpha, (1.0 - alpha) * (1.0 - alpha) / 4.0, (1.0 - 2.0 * alpha) / 2.0};
  }
  /// The HHT parameter alpha given to the constructor.
  double alpha() const noexcept { return alpha_; }

 private:
  double alpha_;
};

/// Generalized-alpha (Chung-Hulbert) set by the spectral radius at infinity
/// rho_inf in [0, 1]: alpha_m = (2 rho - 1) / (rho + 1), alpha_f = rho / (rho + 1),
/// gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4.
class generalized_alpha : public alpha_scheme {
 public:
  static constexpr std::string_view name = "GALPHA";
  /// Default rho_inf = 0.8.
  generalized_alpha() : generalized_alpha(0.8) {}
  /// Throws invalid_option unless 0 <= rho_inf <= 1.
  explicit generalized_alpha(double rho_inf) : rho_(rho_inf) {
    if (!(rho_inf >= 0.0 && rho_inf <= 1.0))
      throw error(error_code::invalid_option,
                  "generalized-alpha rho_inf = " + to_text(rho_inf) + " is outside its valid range [0, 1]");
    const double am = (2 * rho_inf - 1) / (rho_inf + 1), af = rho_inf / (rho_inf + 1);
    p_ = {am, af, (1 - am + af) * (1 - am + af) / 4, 0.5 - am + af};
  }
  /// The spectral radius at infinity given to the constructor.
  double rho_inf() const noexcept { return rho_; }

 private:
  double rho_;
};

/// A scheme of the alpha family: the error control uses its parameters.
template <class S>
concept AlphaFamilyIntegrator = Integrator<S> && requires(const S s) {
  { s.coefficients_set() } -> std::convertible_to<alpha_parameters>;
};

/// The factor f of the shift p_n += f (a_n - a_{n-1}) of the pseudo-acceleration
/// when the step changes from h_prev to h. In the alpha form p_n approximates
/// the acceleration at t_n + (alpha_m - alpha_f) h (Arnold and Bruels, Multibody
/// System Dynamics 18 (2007) 185-202, eq. 9), so a new step size moves the time
/// p_n stands for by (alpha_m - alpha_f)(h - h_prev); with a ~ (a_n -
/// a_{n-1}) / h_prev the shift keeps the scheme second order under variable
/// steps (without it, generalized-alpha rho_inf = 0.8 under error control gained
/// energy on a linear oscillator, linearly in time). f = 0 for Newmark
/// (alpha_m = alpha_f), for schemes outside the alpha family, for the first step
/// (h_prev = 0) and for an unchanged step. A growing step shifts by at most one
/// previous step, f = (alpha_m - alpha_f) min(h - h_prev, h_prev) / h_prev: the
/// slope (a_n - a_{n-1}) / h_prev of one short step is not extrapolated over a
/// much longer one (after a contact that asked for short steps, the contact's
/// last change of acceleration, extrapolated over a step 5000 times longer,
/// changed the velocity of a free flight from 0.99 to 2.8 m/s).
template <class S>
double pseudo_acceleration_shift(const S& s, double h, double h_prev) noexcept {
  if constexpr (AlphaFamilyIntegrator<S>) {
    const alpha_parameters q = s.coefficients_set();
    if (h_prev <= 0 || h == h_prev) return 0.0;
    return (q.alpha_m - q.alpha_f) * std::min(h - h_prev, h_prev) / h_prev;
  } else {
    return 0.0;
  }
}

/// Any member of the alpha family chosen at run time: holds the four
/// parameters of the scheme it was made from (newmark, stoermer, hht,
/// generalized_alpha; implicit conversion) and computes exactly what that
/// scheme does. With it a simulation can switch scheme between stages
/// (simulation::set_scheme) without a checkpoint round trip:
///     simulation<M, alpha_family> sim(m, newmark{});
///     sim.run({.end = 1});
///     sim.set_scheme(hht(-0.1));
///     sim.run({.end = 2});
class alpha_family : public alpha_scheme {
 public:
  static constexpr std::string_view name = "ALPHA";
  /// Newmark's average acceleration.
  alpha_family() : alpha_family(newmark{}) {}
  /// The scheme with the (validated) parameters of `s`; messages carry its name.
  template <class S>
    requires std::derived_from<S, alpha_scheme>
  alpha_family(const S& s) : label_(S::name) {  // NOLINT: implicit by design
    p_ = s.coefficients_set();
  }
  /// The name of the scheme it was made from (NEWMARK, SHTERM, HHT, GALPHA).
  std::string_view label() const noexcept { return label_; }

 private:
  std::string_view label_;
};

}  // namespace pradis
