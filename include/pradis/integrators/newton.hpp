#pragma once
/// \file
/// The Newton solver of one implicit step: PRADIS's convergence tests (DABSU,
/// DRLTU on the correction of the velocity, DABSI, DRLTI on the residual, per
/// DOF scaled by its nominal potential and flow), full or modified Newton.
///
/// Modified Newton (newton_method::modified; the default is full Newton) keeps the Jacobian
/// J = cu K + cv C + ca M and its factorisation across iterations and steps, as
/// SUNDIALS IDA does (Hindmarsh et al., ACM TOMS 31 (2005), section 2.1):
/// - iterations with a kept factorisation evaluate the flows only (the
///   assembly's want_jacobian = false, cheaper);
/// - from successive corrections d_1, ..., d_m (weighted max norm, 1 = the
///   correction test) it estimates the rate R = (|d_m| / |d_1|)^(1/(m-1)); the
///   Jacobian is refreshed at the current iterate when R > max_rate or when
///   |d_m| R^(ITR - k) > 1 (the test would not pass within ITR iterations);
///   a correction with a kept Jacobian passes the correction test only if
///   |d| max(1, 10 R / (1 - R)) does: the error left by a linearly converging
///   iteration, about R / (1 - R) |d|, is below a tenth of the tolerance (R of
///   the last step for the first correction, else 1/2);
/// - it is refreshed when the coefficients changed beyond coefficient_change
///   (a new step size or scheme), at the start of each stage and after the
///   model was (re)built;
/// - a step that fails with a kept Jacobian is retried once from its predictor
///   with a fresh one before the driver cuts the step.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/domain.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/concepts.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis {

/// The result of Newton on one step.
struct newton_result {
  bool converged = false;        ///< the corrector met its tolerances
  int iterations = 0;            ///< corrections of the (last) attempt
  std::optional<error> failure;  ///< a singular situation or matrix that ended the attempt
};

/// Newton iterations of one step with a linear solver policy; owns the solver
/// and remembers its factorisation across steps (modified Newton).
template <LinearSolver Solver>
class newton_solver {
 public:
  /// The linear solver.
  Solver& linear_solver() noexcept { return solver_; }
  const Solver& linear_solver() const noexcept { return solver_; }
  /// Forgets the factorisation: the next iteration evaluates and factorises J.
  void invalidate() noexcept { valid_ = false; }
  /// Whether the last Jacobian had equations with a zero diagonal (Lagrange
  /// multipliers, currents of ideal voltage sources).
  bool has_multipliers() const noexcept {
    for (char c : multiplier_)
      if (c) return true;
    return false;
  }
  /// Whether a factorisation is kept for the next step.
  bool has_factorization() const noexcept { return valid_; }

  /// Solves F(u(v), v, a(v), t) = 0 for the velocities of the equations of
  /// `as`, starting from the predictor in s (s0: the state at the step's
  /// start). `evaluate(bool want_jacobian, int iteration)` evaluates the model
  /// at s into `as`. On failure s holds the last iterate (the driver restores).
  template <class Assembler, Integrator Scheme, class Evaluate>
  newton_result solve(Assembler& as, const Scheme& scheme, global_state& s, const global_state& s0, double h,
                      const jacobian_coefficients& c, const newton_options& nw, const std::vector<dof_scale>& scale,
                      std::vector<double>& rhs, run_statistics& stats, Evaluate&& evaluate) {
    const bool full = nw.method == newton_method::full;
    bool refresh = full || !valid_ || coefficients_changed(c, nw.coefficient_change);
    if (full) return iterate(as, scheme, s, s0, h, c, nw, scale, rhs, stats, evaluate, refresh);
    predictor_ = s;
    for (;;) {
      const bool kept = !refresh;
      newton_result r = iterate(as, scheme, s, s0, h, c, nw, scale, rhs, stats, evaluate, refresh);
      if (r.converged || !kept || (r.failure && r.failure->code() == error_code::singular_situation)) return r;
      s = predictor_;  // retry with a fresh Jacobian before the step is cut
      ++stats.jacobian_retries;
      refresh = true;
    }
  }

 private:
  bool coefficients_changed(const jacobian_coefficients& c, double x) const noexcept {
    if (!(x < 1)) return false;
    const double lo = (1 - x) / (1 + x), hi = 1 / lo;
    auto off = [&](double now, double then) {
      if (now == then) return false;
      if (then == 0 || now == 0) return true;
      const double r = now / then;
      return !(r >= lo && r <= hi);
    };
    return off(c.cu, jac_c_.cu) || off(c.cv, jac_c_.cv) || off(c.ca, jac_c_.ca);
  }

  template <class Assembler, class Scheme, class Evaluate>
  newton_result iterate(Assembler& as, const Scheme& scheme, global_state& s, const global_state& s0, double h,
                        const jacobian_coefficients& c, const newton_options& nw, const std::vector<dof_scale>& scale,
                        std::vector<double>& rhs, run_statistics& stats, Evaluate& evaluate, bool refresh) {
    const bool full = nw.method == newton_method::full;
    const int ne = as.equations();
    bool correction_ok = false, roundoff = false;
    // Stalled: the last two corrections both passed the correction test and the
    // last did not shrink to below half of the one before (weighted max norm).
    bool stalled = false, prev_correction_ok = false;
    double prev_wnorm = -1;
    double first_norm = 0, rate = -1;  // modified Newton: norm of the first correction with this J, rate estimate
    int with_this_j = 0;               // corrections made with the current factorisation
    newton_result out;
    try {
      for (int k = 0;; ++k) {
        const bool jac = full || refresh;
        evaluate(jac, k);
        bool residual_ok = true;
        for (int i = 0; i < ne && residual_ok; ++i) {
          const auto d = as.dof_of(i);
          residual_ok = std::abs(as.residual()(d)) <=
                        nw.dabsi * scale[static_cast<std::size_t>(d)].flow + nw.drlti * as.abs_sum()(d);
        }
        // Converged: both PRADIS tests pass; or, after at least two corrections,
        // the last correction was at round-off level: neither the unknown nor the
        // residual can get smaller in double precision (the residual's floor is
        // about |J| eps (|v| + |u| / cu) once a = (v - v0) / (gamma h)), whatever
        // DABSU/DRLTU and DABSI/DRLTI ask for.
        // Also converged: the unknowns passed the correction test twice and the
        // corrections stalled: the residual left is what no correction within
        // the tolerance removes (round-off of positions X0 + u, which the
        // element sees but u does not show, times a stiffness of 1e12).
        if (k > 0 && ((correction_ok && residual_ok) || (k >= 2 && roundoff) || (k >= 3 && stalled)) &&
            (!nw.second || k >= 2)) {
          out.converged = true;
          out.iterations = k;
          return out;
        }
        if (k >= nw.itr) break;
        for (int i = 0; i < ne; ++i) rhs[static_cast<std::size_t>(i)] = -as.residual()(as.dof_of(i));
        if (jac) {
          mark_multipliers(as);
          valid_ = false;
          solver_.factorize(as.values());
          ++stats.factorizations;
          valid_ = true;
          jac_c_ = c;
          refresh = false;
          with_this_j = 0;
          rate = -1;
          last_rate_ = -1;
        }
        solver_.solve(rhs);
        ++stats.newton_iterations;
        double factor = 1;  // full Newton: the last correction measures the error
        double norm = 0;
        if (!full) {
          for (int i = 0; i < ne; ++i) {
            if (multiplier_[static_cast<std::size_t>(i)]) continue;
            const auto d = as.dof_of(i);
            const double dv = rhs[static_cast<std::size_t>(i)];
            const double w =
                nw.dabsu * scale[static_cast<std::size_t>(d)].potential + nw.drltu * std::abs(s.v(d) + dv);
            const double e = w > 0 ? std::abs(dv) / w : (dv == 0 ? 0.0 : std::numeric_limits<double>::infinity());
            norm = std::max(norm, e);
          }
          if (with_this_j == 0) {
            first_norm = norm;
          } else if (first_norm > 0) {
            rate = std::pow(norm / first_norm, 1.0 / with_this_j);
            last_rate_ = rate;
          }
          ++with_this_j;
          // A correction with a kept Jacobian: the error left is about
          // R / (1 - R) |d| (linear convergence); it must be below a tenth of
          // the tolerance (R unknown: the rate of the last step, else 1/2). A
          // correction with a Jacobian fresh at this iterate is a Newton step
          // and is tested as under full Newton.
          if (!jac) {
            const double r = rate >= 0 ? rate : (last_rate_ >= 0 ? last_rate_ : 0.5);
            factor = r < 1 ? std::max(1.0, 10 * r / (1 - r)) : std::numeric_limits<double>::infinity();
          }
        }
        correction_ok = true;
        roundoff = true;
        bool finite = true;
        double wnorm = 0;
        for (int i = 0; i < ne; ++i) {
          const auto d = as.dof_of(i);
          const double dv = rhs[static_cast<std::size_t>(i)];
          finite = finite && std::isfinite(dv);
          s.v(d) += dv;
          scheme.complete(s0.u(d), s0.v(d), s0.a(d), s0.p(d), h, s.v(d), s.u(d), s.a(d), s.p(d));
          if (multiplier_[static_cast<std::size_t>(i)]) continue;  // judged through the residuals it balances
          const double tol = nw.dabsu * scale[static_cast<std::size_t>(d)].potential + nw.drltu * std::abs(s.v(d));
          correction_ok = correction_ok && factor * std::abs(dv) <= tol;
          wnorm = std::max(wnorm, tol > 0 ? std::abs(dv) / tol : (dv == 0 ? 0.0 : 1e300));
          // The round-off of v includes that of u seen through du/dv = cu: a
          // stiff element (k = 1e12) turns eps |u| into a force k eps |u| that
          // no velocity correction below eps |u| / cu can remove.
          roundoff = roundoff && std::abs(dv) <= 64 * std::numeric_limits<double>::epsilon() *
                                                     (std::abs(s.v(d)) + std::abs(s0.v(d)) +
                                                      h * (std::abs(s.a(d)) + std::abs(s0.a(d))) +
                                                      (c.cu > 0 ? (std::abs(s.u(d)) + std::abs(s0.u(d))) / c.cu : 0.0));
        }
        if (!finite) break;
        stalled = correction_ok && prev_correction_ok && prev_wnorm >= 0 && wnorm > 0.5 * prev_wnorm;
        prev_correction_ok = correction_ok;
        prev_wnorm = wnorm;
        // Modified Newton: slow convergence, or a rate at which the correction
        // test would not pass within ITR iterations: a fresh J at this iterate.
        if (!full && rate >= 0 && !correction_ok &&
            (rate > nw.max_rate || norm * std::pow(rate, nw.itr - k - 1) > 1))
          refresh = true;
      }
    } catch (const error& e) {
      if (e.code() != error_code::singular_situation && e.code() != error_code::singular_matrix) throw;
      out.failure = e;
    }
    return out;
  }

  /// Marks the equations whose diagonal of J is structurally or numerically zero:
  /// Lagrange multipliers and the currents of ideal voltage sources (their rows
  /// are constraints). Their corrections are not tested against DABSU/DRLTU: in
  /// an index-3 constraint the multiplier is determined only to about
  /// eps |u| m / h^2 (a round-off of the positions is an acceleration (4 / h^2)
  /// eps |u|), far above DRLTU |N| at small steps, so the test could never pass.
  /// They are judged through the residuals they enter (the force balance of the
  /// DOFs they act on, DABSI/DRLTI) and the constraint rows themselves, and the
  /// corrections of every other unknown.
  template <class Assembler>
  void mark_multipliers(const Assembler& as) {
    const auto& pat = as.pattern();
    const auto vals = as.values();
    multiplier_.assign(static_cast<std::size_t>(as.equations()), 0);
    for (int i = 0; i < as.equations(); ++i) {
      const int q = pat.find(i, i);
      multiplier_[static_cast<std::size_t>(i)] = q < 0 || vals[static_cast<std::size_t>(q)] == 0.0;
    }
  }

  Solver solver_;
  std::vector<char> multiplier_;  // per equation: a zero diagonal (mark_multipliers)
  bool valid_ = false;
  jacobian_coefficients jac_c_{};
  double last_rate_ = -1;  // the last rate estimate with the kept Jacobian (-1: none)
  global_state predictor_;
};

}  // namespace pradis
