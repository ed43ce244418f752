#pragma once
/// \file
/// The numerical core of pradis::bdf_simulation: the history of the
/// variable-order (1..5), variable-step BDF method in the fixed-leading-
/// coefficient form with modified divided differences, its predictor, local
/// error estimates and the order and step selection. Model-free: it works on
/// a vector y of N components (the driver stacks the displacements and the
/// velocities of the free DOFs) and their weights 1 / tolerance.
///
/// Method (Brenan, Campbell, Petzold, Numerical Solution of Initial-Value
/// Problems in Differential-Algebraic Equations, SIAM 1996, chapter 5 (DASSL);
/// Hindmarsh et al., SUNDIALS: Suite of nonlinear and differential/algebraic
/// equation solvers, ACM TOMS 31 (2005) 363-396, section 2 (IDA)), with h the
/// step to t_{n+1}, k the order and, as in IDA, psi_{i-1} = t_{n+1} - t_{n+1-i}
/// (i = 1..k+1), alpha_i = h / psi_i,
/// beta_i = prod_{j<i} psi_j(new) / psi_j(old), sigma_i = i! prod alpha_j,
/// gamma_i = gamma_{i-1} + alpha_{i-1} / h. The history phi_j (j = 0..k+1) holds
/// the modified divided differences of y; the predictor is
///     y_p = sum_{j=0..k} phi*_j,   y'_p = sum_{j=1..k} gamma_j phi*_j,
/// (phi*_j = beta_j phi_j), and the corrector satisfies
///     y'_{n+1} = y'_p + c (y_{n+1} - y_p),  c = -alpha_s / h,  alpha_s = -sum_{j=1..k} 1/j.
/// With e = y_{n+1} - y_p the local error estimate of order k is
/// C_k |e| with C_k = max(|alpha_k + alpha_s - alpha_0|, alpha_k), alpha_0 = -sum_{j<k} alpha_j,
/// and the errors at orders k-1, k-2, k+1 come from sigma_{k-1} |phi_k + e|,
/// sigma_{k-2} |phi_{k-1} + phi_k + e| and |e - phi_{k+1}| / (k + 2) (IDA,
/// section 2.1; the order and step rules below are IDA's).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

#include "pradis/integrators/bdf/options.hpp"

namespace pradis::bdf_detail {

/// Weighted root-mean-square norm sqrt(sum (x_i w_i)^2 / N) (IDA's WRMS norm).
inline double wrms(const Eigen::VectorXd& x, const Eigen::VectorXd& w) {
  const Eigen::Index n = x.size();
  if (n == 0) return 0;
  double s = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = x[i] * w[i];
    s += t * t;
  }
  return std::sqrt(s / static_cast<double>(n));
}

/// The local error estimates of a converged step (IDA's IDATestError).
struct error_estimate {
  bool passed = true;  ///< C_k |e| <= 1 (the weights are 1 / tolerance)
  double err_k = 0;    ///< sigma_k |e|: the error at the current order
  double err_km1 = 0;  ///< at order k - 1 (k > 1)
  int knew = 1;        ///< the order to use if the step is redone
};

/// The BDF history and coefficients; see the file comment.
class history {
 public:
  static constexpr int kmax = bdf_highest_order;

  /// Starts at order 1 from y and y' with the first step h (phi_0 = y, phi_1 = h y').
  void start(const Eigen::VectorXd& y, const Eigen::VectorXd& yp, double h) {
    phi_.setZero(y.size(), kmax + 2);
    phi_.col(0) = y;
    phi_.col(1) = h * yp;
    k_ = 1;
    kused_ = 0;
    hused_ = 0;
    h_ = h;
    psi_.fill(0);
    psi_[0] = h;
    cj_ = cjlast_ = 1 / h;
    phase_ = 0;
    ns_ = 0;
    steps_ = 0;
    hold_ = false;
  }

  /// The current order and step (the next step to try).
  int order() const noexcept { return k_; }
  double step() const noexcept { return h_; }
  /// Sets the step of the next attempt (clipped to an output time or SMAX).
  void set_step(double h) noexcept { h_ = h; }
  /// Leading coefficient c of the corrector y' = y'_p + c (y - y_p) and its previous value.
  double c() const noexcept { return cj_; }
  double c_last() const noexcept { return cjlast_; }
  /// Accepted steps since start().
  long steps() const noexcept { return steps_; }
  /// The current value y_n (phi_0).
  auto current() const { return phi_.col(0); }
  /// The start phase (raise the order and double the step after every step) is over.
  bool started() const noexcept { return phase_ == 1; }

  /// Coefficients of the step h from t_n at order k (IDA's IDASetCoeffs); scales
  /// phi to phi*. Undo with restore() if the step is not accepted.
  void set_coefficients() {
    if (h_ != hused_ || k_ != kused_) ns_ = 0;
    ns_ = std::min(ns_ + 1, kused_ + 2);
    if (k_ + 1 >= ns_) {
      beta_[0] = alpha_[0] = sigma_[0] = 1;
      gamma_[0] = 0;
      double temp1 = h_;
      for (int i = 1; i <= k_; ++i) {
        const double temp2 = psi_[i - 1];
        psi_[i - 1] = temp1;
        beta_[i] = beta_[i - 1] * psi_[i - 1] / temp2;
        temp1 = temp2 + h_;
        alpha_[i] = h_ / temp1;
        sigma_[i] = i * sigma_[i - 1] * alpha_[i];
        gamma_[i] = gamma_[i - 1] + alpha_[i - 1] / h_;
      }
      psi_[k_] = temp1;
    }
    double alphas = 0, alpha0 = 0;
    for (int i = 0; i < k_; ++i) {
      alphas -= 1.0 / (i + 1);
      alpha0 -= alpha_[i];
    }
    cjlast_ = cj_;
    cj_ = -alphas / h_;
    ck_ = std::max(std::abs(alpha_[k_] + alphas - alpha0), alpha_[k_]);
    for (int i = ns_; i <= k_; ++i) phi_.col(i) *= beta_[i];
  }

  /// The predictor y_p and y'_p of the step (after set_coefficients()).
  void predict(Eigen::VectorXd& y, Eigen::VectorXd& yp) const {
    // Row by row, the sums in registers (the same order as y = phi_0 + phi_1 + ...).
    const Eigen::Index n = phi_.rows();
    y.resize(n);
    yp.resize(n);
    const double* const p0 = phi_.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      const double* q = p0 + i;
      double a = *q, b = 0;
      for (int j = 1; j <= k_; ++j) {
        q += n;
        a += *q;
        b += gamma_[static_cast<std::size_t>(j)] * *q;
      }
      y[i] = a;
      yp[i] = b;
    }
  }

  /// The step about to be attempted (after set_coefficients()) is one whose
  /// correction enters the test for raising the order in complete() with
  /// error control: the order has been kept for k + 2 steps of this size, and
  /// it is below max_order (and not fixed).
  bool raise_test_due(int max_order, bool fixed) const noexcept {
    return phase_ == 1 && !fixed && k_ < max_order && k_ + 1 < ns_ && k_ == kused_;
  }

  /// Scales row r of the history (component r of y and of its differences) by f:
  /// the history of the motion with that component scaled, for a model invariant
  /// under the scaling (rotations.hpp).
  void scale_row(int r, double f) { phi_.row(r) *= f; }

  /// Undoes set_coefficients() after a failed or rejected attempt (IDARestore).
  void restore() {
    for (int j = 1; j <= k_; ++j) psi_[j - 1] = psi_[j] - h_;
    for (int j = ns_; j <= k_; ++j) phi_.col(j) /= beta_[j];
  }

  /// The local error test of a converged step with correction e = y - y_p and
  /// weights w (IDATestError). fixed: never propose a lower order.
  error_estimate test_error(const Eigen::VectorXd& e, const Eigen::VectorXd& w, bool fixed) {
    error_estimate r;
    const double enorm_k = wrms(e, w);
    r.err_k = sigma_[k_] * enorm_k;
    const double terr_k = (k_ + 1) * r.err_k;
    r.knew = k_;
    if (k_ > 1) {
      // |phi_k + e| and |phi_k + phi_{k-1} + e| in one pass (wrms of each).
      const Eigen::Index n = e.size();
      const double* const pk = phi_.data() + k_ * n;
      const double* const pkm1 = pk - n;
      double s1 = 0, s2 = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double d1 = pk[i] + e[i], d2 = d1 + pkm1[i];
        s1 += (d1 * w[i]) * (d1 * w[i]);
        s2 += (d2 * w[i]) * (d2 * w[i]);
      }
      const double nn = n > 0 ? static_cast<double>(n) : 1.0;
      r.err_km1 = sigma_[k_ - 1] * std::sqrt(s1 / nn);
      const double terr_km1 = k_ * r.err_km1;
      if (k_ > 2) {
        const double terr_km2 = (k_ - 1) * sigma_[k_ - 2] * std::sqrt(s2 / nn);
        if (std::max(terr_km1, terr_km2) <= terr_k) r.knew = k_ - 1;
      } else if (terr_km1 <= 0.5 * terr_k) {
        r.knew = k_ - 1;
      }
    }
    if (fixed) r.knew = k_;
    r.passed = ck_ * enorm_k <= 1;
    last_ = r;
    return r;
  }

  /// After restore(): the step and order for the redo of a step that failed the
  /// error test for the nef-th time in a row (IDA: order knew and
  /// h * clamp(0.9 (2 err_k + 1e-4)^(-1/(k+1)), 1/4, 0.9) at the first failure,
  /// knew and h / 4 at the second, order 1 and h / 4 after that). The step
  /// after the accepted redo is at most the redo's (complete(); CVODE's rule
  /// after a failure): the doubling that IDA's rule would allow there tends to
  /// fail again where a stiff, excited mode sets the step, and the steps then
  /// alternate between failing and passing (docs/bdf.md, "Error control and
  /// tolerances": "Stiff, excited modes: the crankshaft").
  void on_error_failure(int nef, bool fixed) {
    phase_ = 1;
    hold_ = true;
    double rr = 0.25;
    if (nef == 1) {
      k_ = last_.knew;
      rr = std::clamp(0.9 * std::pow(2 * last_.err_k + 1e-4, -1.0 / (k_ + 1)), 0.25, 0.9);
    } else if (nef == 2) {
      k_ = last_.knew;
    } else if (!fixed) {
      k_ = 1;
    }
    h_ *= rr;
  }

  /// After restore(): the step of the redo of a step whose corrector failed (h / 4).
  void on_convergence_failure() { h_ *= 0.25; }

  /// Accepts the step with correction e (IDACompleteStep): updates the history
  /// and chooses the next order and step. control: the order and step follow
  /// the error estimates (IDA's rules, step at most hmax); otherwise the order
  /// rises by one per step up to max_order and the step is left to the caller.
  void complete(const Eigen::VectorXd& e, const Eigen::VectorXd& w, int max_order, bool fixed, bool control,
                double hmax) {
    ++steps_;
    const int kdiff = k_ - kused_;
    kused_ = k_;
    hused_ = h_;
    if (!control) {
      if (k_ < max_order) ++k_;
    } else {
      if (last_.knew == k_ - 1 || k_ >= max_order) phase_ = 1;
      if (phase_ == 0) {
        if (steps_ > 1) {
          ++k_;
          h_ = std::min(2 * h_, hmax);
        }
      } else {
        choose_order_and_step(e, w, max_order, fixed, kdiff, hmax);
      }
      if (hold_) h_ = std::min(h_, hused_);  // no growth on the step after an error-test failure
    }
    hold_ = false;
    if (kused_ < kmax) phi_.col(kused_ + 1) = e;
    phi_.col(kused_) += e;
    for (int j = kused_ - 1; j >= 0; --j) phi_.col(j) += phi_.col(j + 1);
  }

 private:
  enum class action { lower, maintain, raise };

  void choose_order_and_step(const Eigen::VectorXd& e, const Eigen::VectorXd& w, int max_order, bool fixed,
                             int kdiff, double hmax) {
    action act = action::maintain;
    double err_kp1 = 0;
    if (fixed) {
      act = action::maintain;
    } else if (last_.knew == k_ - 1) {
      act = action::lower;
    } else if (k_ >= max_order || k_ + 1 >= ns_ || kdiff == 1) {
      act = action::maintain;
    } else {
      const Eigen::Index n = e.size();
      const double* const pkp1 = phi_.data() + (k_ + 1) * n;
      double s2 = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double d = (e[i] - pkp1[i]) * w[i];
        s2 += d * d;
      }
      err_kp1 = (n > 0 ? std::sqrt(s2 / static_cast<double>(n)) : 0.0) / (k_ + 2);
      const double terr_k = (k_ + 1) * last_.err_k, terr_kp1 = (k_ + 2) * err_kp1;
      if (k_ == 1) {
        act = terr_kp1 >= 0.5 * terr_k ? action::maintain : action::raise;
      } else {
        const double terr_km1 = k_ * last_.err_km1;
        act = terr_km1 <= std::min(terr_k, terr_kp1) ? action::lower
              : terr_kp1 >= terr_k                   ? action::maintain
                                                     : action::raise;
      }
    }
    double err_new = last_.err_k;
    if (act == action::raise) {
      ++k_;
      err_new = err_kp1;
    } else if (act == action::lower) {
      --k_;
      err_new = last_.err_km1;
    }
    // h_new / h from the error estimate: doubled if it allows 2, kept if in
    // (1, 2), else reduced to h * clamp(rr, 1/2, 0.9).
    // rr = x^(-1/(k+1)), x = 2 err + 1e-4: rr >= 2 when x <= 2^-(k+1), rr <= 1 when
    // x >= 1 (the pow only then, for the reduction).
    const double x = 2 * err_new + 1e-4;
    if (x <= std::ldexp(1.0, -(k_ + 1)))
      h_ = std::min(2 * h_, hmax);
    else if (x >= 1)
      h_ *= std::clamp(std::pow(x, -1.0 / (k_ + 1)), 0.5, 0.9);
    h_ = std::min(h_, hmax);
  }

  Eigen::MatrixXd phi_;
  std::array<double, kmax + 2> psi_{}, alpha_{}, beta_{}, sigma_{}, gamma_{};
  double h_ = 0, hused_ = 0, cj_ = 0, cjlast_ = 0, ck_ = 0;
  bool hold_ = false;  // the step just accepted redid an error-test failure: the next may not grow
  int k_ = 1, kused_ = 0, ns_ = 0, phase_ = 0;
  long steps_ = 0;
  error_estimate last_{};
};

}  // namespace pradis::bdf_detail
