#pragma once
/// \file
/// What both drivers (simulation, bdf_simulation) watch over the accepted steps of a
/// stage: the stage's largest accepted step, the crawl warning and the step budget
/// (run_options::max_steps, the language's NSTEPMAX).
///
/// A run crawls when a singular state of the model holds its step far below the steps
/// the stage has taken, with no error raised: each step passes, but the stage's end
/// recedes by millions of steps. An example: a massless DOF held only by a LINKD link,
/// whose force on it vanishes on the branch where the link has its free length, made
/// SHTERM take steps of about 4e-8 s after steps of 1e-4 s (20 s of CPU for 0.24 s of
/// a 1 s stage). The crawl warning names the time, the step and what sets it (an
/// element's recommended step, the DOF whose local error, or failed steps); NSTEPMAX
/// ends such a stage with code 142. A stage held at SMIN from its start (an element
/// recommending a step below SMIN, such as a source of 1e30 Hz) has no larger step to
/// fall from; it crawls too when a window's mean step is below twice SMIN while SMAX is at
/// least 1 / crawl_drop times SMIN.

#include <cmath>
#include <string>

#include "pradis/core/error.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis {

/// The crawl warning is written when crawl_steps accepted steps in a row advanced the time by
/// less than crawl_drop times as much as as many steps of the stage's largest accepted step
/// would: their mean step is below crawl_drop of the largest. (The mean, not each step: a step
/// that Newton failures cut and that then grows again saws up and down while it crawls.)
inline constexpr long crawl_steps = 10000;
/// See crawl_steps. A window also crawls when its mean step is below twice SMIN while
/// SMIN <= crawl_drop SMAX: the step is held at SMIN, whatever the stage's largest.
inline constexpr double crawl_drop = 1e-3;
/// A stage whose END lies more than this many steps of SMAX ahead gets a note at its start:
/// it is long whatever its steps, and no crawl (which compares steps) will be reported.
inline constexpr double long_stage_steps = 1e8;

namespace detail {

/// The error (code 142) for a stage that used up NSTEPMAX = max_steps accepted steps at time t
/// before `end`; `steps` (may be empty) describes its steps.
inline error step_budget_error(long max_steps, double t, double end, const std::string& steps) {
  return error(error_code::step_budget, "the stage used up its NSTEPMAX = " + std::to_string(max_steps) +
                                            " accepted steps at t = " + num(t) + ", before END = " + num(end) +
                                            (steps.empty() ? std::string() : " (" + steps + ")") +
                                            "; the results up to t stand");
}

/// At the start of a stage from t to `end` with SMAX = h_max and NSTEPMAX = max_steps (0:
/// none): the warning when the stage needs more steps of SMAX than max_steps allows, else the
/// note when it needs more than long_stage_steps; empty otherwise.
inline std::string stage_start_text(double t, double end, double h_max, long max_steps) {
  if (!(h_max > 0)) return {};
  const double fewest = std::ceil((end - t) / h_max * (1 - 1e-12));
  const bool over_budget = max_steps > 0 && fewest > static_cast<double>(max_steps);
  if (!over_budget && !(fewest > long_stage_steps)) return {};  // the usual stage: no text, no allocation
  const std::string need = "needs at least " + num(fewest) + " steps to END = " + num(end) + " (from t = " + num(t) +
                           " in steps of at most SMAX = " + num(h_max) + ")";
  if (over_budget)
    return "warning: the stage " + need + ", more than its NSTEPMAX = " + std::to_string(max_steps) +
           ": it will end with code 142 before END";
  return "note: the stage " + need + "; a larger SMAX or a nearer END shortens it, NSTEPMAX " +
         "(run_options::max_steps) ends a stage after that many steps";
}

/// The accepted steps of one stage: its largest step, its windows of crawl_steps steps
/// and the stage's step count against run_options::max_steps.
class step_watch {
 public:
  /// Starts a stage whose steps lie in [h_min, h_max] (SMIN, SMAX; 0, 0: the floor
  /// criterion of crawl_drop is not applied).
  void start_stage(double h_min = 0, double h_max = 0) noexcept {
    *this = step_watch{};
    h_min_ = h_min;
    h_max_ = h_max;
  }

  /// Records an accepted step of size h that ended at time t.
  void accepted(double h, double t) noexcept {
    ++steps_;
    if (h > largest_) largest_ = h;
    if (window_ == 0) t_window_ = t - h;
    if (++window_ == crawl_steps) {
      const double span = t - t_window_, n = static_cast<double>(crawl_steps);
      if (!crawled_ && span < crawl_drop * n * largest_) {
        crawled_ = true;
      } else if (!crawled_ && h_min_ > 0 && h_min_ <= crawl_drop * h_max_ && span < 2 * n * h_min_) {
        crawled_ = at_floor_ = true;
      }
      window_ = 0;
    }
  }

  /// The largest step accepted in this stage (0 before the first).
  double largest() const noexcept { return largest_; }
  /// Steps accepted in this stage.
  long steps() const noexcept { return steps_; }

  /// True once per stage: after the first window of crawl_steps steps that crawled.
  bool crawl_to_report() noexcept {
    if (warned_ || !crawled_) return false;
    warned_ = true;
    return true;
  }

  /// The crawl warning at time t, last step h, stage end `end`; `why` says what set the
  /// step (an element's recommendation, the DOF whose local error; empty when unknown).
  std::string crawl_text(double t, double h, double end, const std::string& why) const {
    const double more = h > 0 ? std::round((end - t) / h) : 0;
    const std::string held = at_floor_ ? " accepted steps were held at SMIN = " + num(h_min_) +
                                             " (on average below twice it; SMAX = " + num(h_max_) + ")"
                                       : " accepted steps were on average below " + num(crawl_drop) +
                                             " of the stage's largest step " + num(largest_);
    return "warning: the run crawls: the last " + std::to_string(crawl_steps) + held + " (now h = " + num(h) +
           " at t = " + num(t) + "; at this step the stage needs about " + num(more) + " more steps to END = " +
           num(end) + ")" +
           (why.empty() ? std::string() : "; " + why) +
           (at_floor_ ? ". An element that recommends a step below SMIN (a source of too high a frequency, a "
                        "contact too stiff) or steps that keep failing above it usually cause this"
                      : ". A singular state of the model usually causes this (a massless DOF whose force vanishes, a "
                        "switch that chatters)") +
           "; NSTEPMAX (run_options::max_steps) ends a stage after that many steps";
  }

  /// Whether the stage has used up its budget of `max_steps` accepted steps (0: none).
  bool budget_spent(long max_steps) const noexcept { return max_steps > 0 && steps_ >= max_steps; }

  /// The error for a stage that used up NSTEPMAX = max_steps steps at time t before `end`,
  /// with the last step h.
  error budget_error(long max_steps, double t, double h, double end) const {
    return step_budget_error(max_steps, t, end, "last step " + num(h) + ", the stage's largest " + num(largest_));
  }

 private:
  double largest_ = 0;
  double h_min_ = 0, h_max_ = 0;  // the stage's SMIN and SMAX (start_stage)
  long steps_ = 0;
  double t_window_ = 0;  // the time at the start of the current window of crawl_steps steps
  long window_ = 0;      // steps in it so far
  bool crawled_ = false, warned_ = false;
  bool at_floor_ = false;  // the window that crawled was held at SMIN (not below the largest step)
};

}  // namespace detail
}  // namespace pradis
