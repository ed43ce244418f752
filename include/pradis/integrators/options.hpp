#pragma once
/// \file
/// Options and statistics of a simulation: the Newton tolerances (PRADIS's
/// names and defaults), the options of one stage (run_options), the outcome
/// of one attempted step and the cumulative run statistics.

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "pradis/core/error.hpp"

namespace pradis {

/// How Newton treats the Jacobian within and across steps.
enum class newton_method {
  /// Modified Newton: the Jacobian and its factorisation are kept across
  /// iterations and steps and refreshed when convergence slows down, when the
  /// step's Jacobian coefficients change beyond newton_options::coefficient_change,
  /// at the start of every stage, and before a step is cut for a Newton failure.
  modified,
  /// Full Newton: a fresh Jacobian and factorisation at every iteration.
  full,
};

/// Newton options with PRADIS's names and defaults.
struct newton_options {
  double dabsu = 0.01;   ///< DABSU: absolute tolerance on the correction of the unknown (velocity), times the DOF's nominal potential (dof_scale)
  double drltu = 1e-3;   ///< DRLTU: relative tolerance on the correction
  double dabsi = 0.1;    ///< DABSI: absolute tolerance on the residual (sum of flows) per DOF, times its nominal flow (dof_scale)
  double drlti = 1e-3;   ///< DRLTI: relative tolerance on the residual, times the sum of |flows| on the DOF
  int itr = 5;           ///< ITR: maximum Newton iterations per step
  bool second = false;   ///< SECOND: force at least a second iteration
  /// Full Newton (the default: modified Newton's results differ within the
  /// Newton tolerances, and some of the accuracy tests ask for more) or
  /// modified Newton (Jacobian reuse, fewer factorisations and Jacobians).
  newton_method method = newton_method::full;
  /// Modified Newton: refresh the Jacobian when the convergence rate estimated
  /// from successive corrections, (|d_m| / |d_1|)^(1/(m-1)), exceeds this
  /// (SUNDIALS IDA uses 0.9), or when the corrections at that rate would not
  /// pass the correction test within ITR iterations.
  double max_rate = 0.9;
  /// Modified Newton: refresh the Jacobian when the coefficient of the inertia
  /// block (ca ~ 1/h) changed by more than this fraction since the last
  /// factorisation (IDA's XRATE = 0.25: ratios outside [0.6, 1/0.6]).
  double coefficient_change = 0.25;
};

/// Options of one call of an integration program (one stage of a run).
struct run_options {
  double end = 1.0;          ///< END: time at which the stage stops
  double out = 0.0;          ///< OUT: output interval (0: output after every step)
  double smax = 0.01;        ///< SMAX: maximum (and nominal) step
  double smin = 1e-11;       ///< SMIN: minimum step; below it the run fails
  bool ignore = false;       ///< IGNORE: ignore steps recommended by elements (STEPMD)
  newton_options newton{};   ///< Newton tolerances
  /// Error-controlled step size. false: every step is SMAX (cut only when Newton
  /// fails). true: PRADIS's velocity-based local error estimate and three-branch
  /// step rule; the first stage starts with steps of SMIN and grows.
  bool error_control = false;
  /// DABSX: absolute tolerance of the local error (velocity units), times the DOF's
  /// nominal potential. Unset (the default): DABSX = DRLTX, so that the relative
  /// tolerance alone sets the accuracy on a model whose velocities are O(1) in their
  /// nominal units. (PRADIS's fixed default 0.1 made DRLTX below ~1e-3 irrelevant there;
  /// set `.dabsx = 0.1` for PRADIS's behaviour.)
  std::optional<double> dabsx{};
  double drltx = 1e-3;       ///< DRLTX: relative tolerance of the local error, times |v|
  bool predict = false;      ///< PREDICT: linear prediction of the acceleration in the error predictor
  /// Second-order schemes: estimate a_{n+1} - a_n by the two-step difference
  /// (a_{n+1} - a_{n-1}) h / (h + h_prev), which filters the ringing of stiff modes the
  /// step does not resolve (step_control.hpp). false: PRADIS's one-step difference.
  bool two_step_estimate = true;
  double control = 0.0;      ///< CONTROL: no error-driven step reduction below this step (0: none)
  /// NSTEPMAX: the most steps the stage may accept (0: no limit). A stage that reaches it
  /// before END ends with error code 142 (step_budget), its results up to there kept: a
  /// bound on a run that crawls (step_watch.hpp).
  long max_steps = 0;
  /// At the stage's start, the warning when it needs more steps of SMAX to END than
  /// max_steps allows and the note when it needs more than 1e8 (detail::stage_start_text,
  /// step_watch.hpp).
  /// false: not written; a caller that runs one stage as several calls (the language's
  /// SAVE pieces) writes them once for the whole stage.
  bool start_notes = true;
};

/// What one attempted step ended in.
enum class step_outcome { accepted, failed, error_rejected };

/// Run statistics, cumulative over the stages of a simulation.
struct run_statistics {
  long steps = 0;              ///< accepted steps
  long rejected_steps = 0;     ///< steps cut (Newton failure, singular situation)
  long newton_iterations = 0;  ///< linear solves in Newton iterations
  long factorizations = 0;     ///< numeric factorisations
  long evaluations = 0;        ///< full model evaluations
  int last_iterations = 0;     ///< Newton iterations of the last accepted step
  double last_step = 0;        ///< size of the last accepted step
  long error_rejections = 0;   ///< steps redone because the local error exceeded the tolerance
  int limiting_dof = -1;       ///< DOF whose local error set the last step (error control), or -1
  long jacobian_evaluations = 0;  ///< model evaluations that assembled the Jacobian (the others: flows only)
  long jacobian_retries = 0;      ///< modified Newton: step attempts redone with a fresh Jacobian after a failure
  /// Difference (per-stage figures).
  friend run_statistics operator-(run_statistics a, const run_statistics& b) {
    a.steps -= b.steps;
    a.rejected_steps -= b.rejected_steps;
    a.newton_iterations -= b.newton_iterations;
    a.factorizations -= b.factorizations;
    a.evaluations -= b.evaluations;
    a.error_rejections -= b.error_rejections;
    a.jacobian_evaluations -= b.jacobian_evaluations;
    a.jacobian_retries -= b.jacobian_retries;
    return a;
  }
};

/// A statistic by its output-variable name: "NSTEP" (accepted steps), "NITER"
/// (iterations of the last step), "STEP" (last step size), "NREJ" (rejected
/// steps), "NFACT" (factorisations), "NITTOT" (all Newton iterations),
/// "NJAC" (evaluations with the Jacobian), "NEVAL" (all model evaluations).
/// Throws invalid_option for another name (`more`: further names the caller
/// knows, for the message).
inline double statistic_by_name(const run_statistics& s, std::string_view key, std::string_view more = {}) {
  if (key == "NSTEP") return static_cast<double>(s.steps);
  if (key == "NITER") return s.last_iterations;
  if (key == "STEP") return s.last_step;
  if (key == "NREJ") return static_cast<double>(s.rejected_steps);
  if (key == "NFACT") return static_cast<double>(s.factorizations);
  if (key == "NITTOT") return static_cast<double>(s.newton_iterations);
  if (key == "NJAC") return static_cast<double>(s.jacobian_evaluations);
  if (key == "NEVAL") return static_cast<double>(s.evaluations);
  throw error(error_code::invalid_option, "unknown statistic '" + std::string(key) +
                                              "' (known: NSTEP, NITER, STEP, NREJ, NFACT, NITTOT, NJAC, NEVAL" +
                                              (more.empty() ? std::string() : ", " + std::string(more)) + ")");
}

namespace detail {
inline std::string num(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}
}  // namespace detail

/// The DABSX a stage uses: the one set, else DRLTX (see run_options::dabsx).
inline double effective_dabsx(const run_options& o) noexcept { return o.dabsx.value_or(o.drltx); }

/// Checks a stage's options; returns the message of the first invalid one
/// (the simulation throws it as invalid_option, prefixed by the scheme name).
inline std::optional<std::string> check_options(const run_options& o) {
  using detail::num;
  auto bad = [](double x) { return !std::isfinite(x); };
  if (bad(o.end)) return "END must be a finite number";
  if (bad(o.smax) || !(o.smax > 0)) return "SMAX = " + num(o.smax) + " must be > 0";
  if (bad(o.smin) || !(o.smin > 0)) return "SMIN = " + num(o.smin) + " must be > 0";
  if (o.smin > o.smax) return "SMIN = " + num(o.smin) + " is above SMAX = " + num(o.smax);
  if (bad(o.out) || o.out < 0) return "OUT = " + num(o.out) + " must be >= 0";
  const auto& n = o.newton;
  if (bad(n.dabsu) || n.dabsu < 0) return "DABSU = " + num(n.dabsu) + " must be >= 0";
  if (bad(n.drltu) || n.drltu < 0) return "DRLTU = " + num(n.drltu) + " must be >= 0";
  if (bad(n.dabsi) || n.dabsi < 0) return "DABSI = " + num(n.dabsi) + " must be >= 0";
  if (bad(n.drlti) || n.drlti < 0) return "DRLTI = " + num(n.drlti) + " must be >= 0";
  if (n.dabsu + n.drltu <= 0) return "the Newton tolerances DABSU and DRLTU must not both be zero";
  if (n.dabsi + n.drlti <= 0) return "the Newton tolerances DABSI and DRLTI must not both be zero";
  if (n.itr < 1) return "ITR = " + std::to_string(n.itr) + " must be >= 1";
  if (bad(n.max_rate) || !(n.max_rate > 0 && n.max_rate < 1))
    return "the Newton rate limit " + num(n.max_rate) + " must be in (0, 1)";
  if (bad(n.coefficient_change) || n.coefficient_change < 0)
    return "the Jacobian coefficient change " + num(n.coefficient_change) + " must be >= 0";
  if (o.dabsx && (bad(*o.dabsx) || *o.dabsx < 0)) return "DABSX = " + num(*o.dabsx) + " must be >= 0";
  if (bad(o.drltx) || o.drltx < 0) return "DRLTX = " + num(o.drltx) + " must be >= 0";
  if (o.error_control && !(effective_dabsx(o) + o.drltx > 0))
    return "error control needs DABSX + DRLTX > 0 (both are zero)";
  if (bad(o.control) || o.control < 0) return "CONTROL = " + num(o.control) + " must be >= 0";
  if (o.max_steps < 0) return "NSTEPMAX = " + std::to_string(o.max_steps) + " must be >= 0 (0: no limit)";
  return std::nullopt;
}

}  // namespace pradis
