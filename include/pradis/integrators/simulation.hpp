#pragma once
/// \file
/// The time-integration driver: zero step, NEWINT work per stage, implicit
/// one-step integration with Newton iterations (PRADIS convergence tests),
/// step cuts down to SMIN, element-recommended steps (STEPMD / IGNORE),
/// output sampling at OUT, checkpoints and run statistics.
///
/// Usage:
///     pradis::simulation sim(model, pradis::newmark{});
///     sim.on_output([&](const auto& s) { ... s.time(), s.u(d) ... });
///     sim.run({.end = 1.0, .smax = 1e-3});   // first stage (also runs the zero step)
///     sim.run({.end = 1.5});                 // second stage, NEWINT again
///
/// The parts: options.hpp (options, statistics), concepts.hpp (Integrator,
/// LinearSolver), newmark.hpp (the alpha family), newton.hpp (full and
/// modified Newton), step_control.hpp (error test, step rules),
/// initialisation.hpp (zero step), checkpoint.hpp (the checkpoint format),
/// failures.hpp (the messages of run failures), driver_core.hpp (the state and
/// element-level phases shared with bdf_simulation).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <istream>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/integrators/checkpoint.hpp"
#include "pradis/integrators/concepts.hpp"
#include "pradis/integrators/driver_core.hpp"
#include "pradis/integrators/failures.hpp"
#include "pradis/integrators/initialisation.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/newton.hpp"
#include "pradis/integrators/options.hpp"
#include "pradis/integrators/precision.hpp"
#include "pradis/integrators/step_control.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/model/model.hpp"

namespace pradis {

template <class Model, Integrator Scheme = newmark, LinearSolver Solver = linalg::sparse_lu<linalg::automatic_ordering>>
class simulation;

/// Simulation of a model<Es...> with an integration scheme and a linear solver policy.
template <class... Es, Integrator Scheme, LinearSolver Solver>
class simulation<model<Es...>, Scheme, Solver> : private detail::driver_core<model<Es...>> {
  using core = detail::driver_core<model<Es...>>;
  using core::asm_, core::index3_, core::massless_count_, core::massless_dof_, core::log_, core::m_, core::opt_,
      core::prescribed_, core::recommended_, core::rhs_, core::s0_, core::s_, core::started_, core::stats_, core::t_,
      core::last_failure_, core::watch_;
  using core::bad_dof, core::checked, core::commit, core::context_for, core::evaluate, core::for_each_instance,
      core::new_integration, core::raise, core::start_watch, core::watch_accepted;

 public:
  // The results and the log (driver_core.hpp).
  using core::a, core::get_assembler, core::get_model, core::log, core::model_fingerprint, core::residual, core::state,
      core::statistics, core::time, core::u, core::v;
  /// The model type the simulation runs.
  using model_type = model<Es...>;
  /// A callback at output times or steps (on_output, on_step).
  using observer = std::function<void(const simulation&)>;

  /// Binds the simulation to a model (which must outlive it).
  explicit simulation(model_type& m, Scheme scheme = {}) : core(m), scheme_(scheme) {}

  /// Adds an observer called at t0 (after the zero step) and at every output time.
  void on_output(observer f) { observers_.push_back(std::move(f)); }
  /// Adds an observer called after every accepted step (before the output observers of
  /// that step), e.g. for a progress display. Keep it cheap: it runs once per step.
  void on_step(observer f) { step_observers_.push_back(std::move(f)); }

  /// Runs one stage up to opt.end. The first call performs the zero step.
  /// Returns the statistics of this stage. Throws pradis::error on bad options
  /// (invalid_option), model errors and run failures.
  run_statistics run(const run_options& opt) {
    if (auto msg = check_options(opt)) fail_option(*msg);
    const run_statistics before = stats_;
    opt_ = opt;
    if (!(opt.end > t_)) fail_option("END = " + num(opt.end) + " must be after the current time " + num(t_));
    newton_.invalidate();  // every stage starts with a fresh Jacobian
    precision_warned_ = false;
    start_watch();
    if (!started_) {
      zero_step();
    } else {
      if (!asm_.built_for(m_)) build();
      new_integration();
      // Refresh flows, work vectors and the recommended step (STEPMD) with the
      // stage's parameters, so the first step of the stage respects them.
      evaluate({0, 0, 0}, 0.0, false);
      recommended_ = asm_.recommended_step();
    }
    const double t_start = t_;
    long out_index = 1;
    double next_out = opt.out > 0 ? t_start + opt.out : opt.end;
    if (h_nominal_ <= 0 || h_nominal_ > opt.smax) h_nominal_ = opt.smax;
    if (opt.error_control && stats_.steps == 0) h_nominal_ = opt.smin;  // PRADIS: start with steps of SMIN
    long controlled_steps = 0, steps_at_smax = 0;  // error control: did the tolerance ever limit the step?
    long cut_in_stage = 0;                         // failed steps (Newton, singular situations) of this stage
    while (t_ < opt.end * (1 - 1e-14) - 1e-300) {
      const double target = std::min(next_out, opt.end);
      bool clipped = false;
      const double h = choose_step(t_, target, h_nominal_, recommended_, opt, clipped);
      if (!(t_ + h > t_))
        raise(error(error_code::step_too_small,
                    "the step " + num(h) + " no longer advances the time " + num(t_) + " in double precision"));
      const step_outcome outcome = step(h);
      if (outcome == step_outcome::error_rejected) {
        ++stats_.rejected_steps;
        ++stats_.error_rejections;
        h_nominal_ = h_error_;
        continue;
      }
      if (outcome == step_outcome::accepted) {
        for (auto& f : step_observers_) f(*this);
        if (opt.error_control) {
          ++controlled_steps;
          if (h >= opt.smax * (1 - 1e-12)) ++steps_at_smax;
          h_nominal_ = clipped ? std::max(h_nominal_, h_error_) : h_error_;
        }
        else if (!clipped || h >= h_nominal_)
          grow_nominal_step(h_nominal_, successes_, opt_.smax);
        if (clipped || opt.out <= 0) {
          if (opt.out > 0) {
            ++out_index;
            next_out = t_start + static_cast<double>(out_index) * opt.out;
            if (std::abs(t_ - target) < 1e-12 * std::max(1.0, std::abs(target))) t_ = target;
          }
          notify();
        }
        watch_accepted(h);
      } else {
        ++stats_.rejected_steps;
        if (++cut_in_stage == detail::undamped_massless_cuts && massless_count_ > 0 && detail::undamped(scheme_))
          log_.write(detail::undamped_massless_warning(scheme_label(), cut_in_stage, massless_count_,
                                                       m_.dof_name(massless_dof_)));
        h_nominal_ = h * 0.5;
        successes_ = 0;
        if (h_nominal_ < opt.smin) fail_at_smin(h);
      }
    }
    t_ = opt.end;
    if (controlled_steps >= 10 && steps_at_smax >= 0.9 * static_cast<double>(controlled_steps))
      log_.write(detail::smax_warning_text(steps_at_smax, controlled_steps, opt));
    if (newton_.has_multipliers() && detail::undamped(scheme_))
      log_.write(detail::undamped_constraint_note(scheme_label()));
    return stats_ - before;
  }

  // ---- results (see also driver_core.hpp: time, u, v, a, state, residual, statistics) -----
  /// A statistic by its output-variable name: "NSTEP" (accepted steps), "NITER"
  /// (iterations of the last step), "STEP" (last step size), "NREJ" (rejected
  /// steps), "NFACT" (factorisations), "NITTOT" (all Newton iterations),
  /// "NJAC" (evaluations with the Jacobian), "NEVAL" (all model evaluations).
  double statistic(std::string_view key) const { return statistic_by_name(stats_, key); }
  /// The linear solver.
  const Solver& solver() const noexcept { return newton_.linear_solver(); }
  /// Replaces the linear solver, e.g. by one with another ordering (the OPTIM key of the
  /// model language). If the model was already analysed, the new solver analyses its
  /// pattern at once, so the next step factorises with the new ordering.
  void set_solver(Solver solver) {
    newton_.linear_solver() = std::move(solver);
    newton_.invalidate();
    if (asm_.built_for(m_)) analyze();
  }
  /// The scheme.
  const Scheme& scheme() const noexcept { return scheme_; }
  /// Replaces the scheme for the following stages (e.g. simulation<M, alpha_family>
  /// switching from newmark to hht). restart = true starts the new scheme afresh
  /// from the current state (restart_scheme()), as a run continued from a
  /// checkpoint with another scheme does; false keeps the pseudo-acceleration.
  void set_scheme(Scheme scheme, bool restart = true) {
    scheme_ = std::move(scheme);
    newton_.invalidate();
    if (restart && started_) restart_scheme();
  }
  /// Starts the scheme afresh from the current state, as at the zero step: the
  /// pseudo-acceleration of the alpha family is set to the acceleration (p = a).
  /// For a run continued with another scheme (see load_checkpoint()).
  void restart_scheme() { s_.p = s_.a; }

  // ---- checkpoint and restart --------------------------------------------------

  /// Writes a checkpoint (format: checkpoint.hpp): time, potentials of all DOFs,
  /// the step-size state, the statistics and every element's work and state
  /// vectors, with the model fingerprint. Throws invalid_option before the zero step.
  void save_checkpoint(std::ostream& os) const { write_checkpoint(os, model_fingerprint(), checkpoint()); }
  /// The fields save_checkpoint() writes, in memory. Throws invalid_option before the zero step.
  checkpoint_data checkpoint() const {
    if (!started_) throw error(error_code::invalid_option, "no checkpoint before the first stage has run");
    return {t_, h_nominal_, h_prev_, successes_, stats_, s_, a_prev_, m_.work_pool(), m_.old_state_pool(),
            m_.new_state_pool(), this->dof_classes()};
  }
  /// Continues from the state of another driver `d` of the same model: a
  /// pradis::simulation of any scheme or solver, or a pradis::bdf_simulation.
  /// The same as load_checkpoint() of d's checkpoint, without writing or
  /// reading one (no serialisation). From another scheme, call restart_scheme()
  /// after it, as after a checkpoint. Throws invalid_option if d has not run a
  /// stage or its model differs (fingerprint or sizes); this one is unchanged then.
  template <CheckpointSource Driver>
  void continue_from(const Driver& d) {
    restore(this->handover_from(d));
  }
  /// Restores a checkpoint written by save_checkpoint() for the same model (the
  /// parameters may differ: $REPLACE). The next run() continues from it exactly
  /// as the uninterrupted run would; the zero step is not repeated. A checkpoint
  /// of a different model, of another format version, or a damaged one (wrong
  /// checksum, truncated, values out of range: "checkpoint damaged") is refused
  /// with io_error; the simulation is unchanged then.
  void load_checkpoint(std::istream& is) {
    restore(this->read_own_checkpoint(is));
  }

 private:
  /// Takes over checked checkpoint data (load_checkpoint(), continue_from()).
  void restore(checkpoint_data c) {
    detail::detect_sources(m_, prescribed_, log_);
    s_ = std::move(c.state);
    build();
    h_nominal_ = c.h_nominal;
    h_prev_ = c.h_previous;
    a_prev_ = std::move(c.a_previous);
    p_start_.resize(s_.p.size());
    successes_ = c.successes;
    this->take_over(c);
  }

  static std::string num(double x) { return detail::num(x); }

  std::string_view scheme_label() const {
    if constexpr (requires { scheme_.label(); })
      return scheme_.label();
    else
      return Scheme::name;
  }
  [[noreturn]] void fail_option(const std::string& msg) {
    raise(error(error_code::invalid_option, std::string(scheme_label()) + ": " + msg));
  }

  void zero_step() {
    this->start_zero_step(newton_.linear_solver(), [&] { build(); });
    newton_.invalidate();  // the solver holds the factorisation of the initial-derivative matrix
    a_prev_ = s_.a;
    p_start_.resize(s_.p.size());  // sized here, so that the steps never allocate it
    h_prev_ = 0;
    this->finish_zero_step();
    notify();
  }

  void build() {
    this->rebuild_equations();
    newton_.invalidate();
    analyze();
  }
  void analyze() {
    try {
      newton_.linear_solver().analyze(asm_.pattern());
    } catch (const error& e) {
      rethrow_singular(e);
    }
  }

  /// Names the DOF of a singular equation and the elements on it.
  [[noreturn]] void rethrow_singular(const error& e) { raise(detail::singular_error(m_, asm_, e, t_)); }

  /// One step from t_ to t_ + h: predictor, Newton, local error test (with
  /// error control), commit. On failure or rejection the state is restored.
  step_outcome step(double h) {
    s0_ = s_;
    const double shift = pseudo_acceleration_shift(scheme_, h, h_prev_);  // newmark.hpp
    if (shift != 0) {
      p_start_ = s_.p;  // restored if the step is not accepted
      for (int i = 0; i < asm_.equations(); ++i) {
        const auto d = asm_.dof_of(i);
        s0_.p(d) += shift * (s0_.a(d) - a_prev_(d));
      }
    }
    const double t0 = t_;
    t_ = t0 + h;
    detail::apply_sources(m_, s_, t_);
    for (int i = 0; i < asm_.equations(); ++i) {
      const auto d = asm_.dof_of(i);
      s_.v(d) = scheme_.predict(s0_.u(d), s0_.v(d), s0_.a(d), s0_.p(d), h);
      scheme_.complete(s0_.u(d), s0_.v(d), s0_.a(d), s0_.p(d), h, s_.v(d), s_.u(d), s_.a(d), s_.p(d));
    }
    const jacobian_coefficients c = scheme_.coefficients(h);
    last_failure_.reset();
    const newton_result r = newton_.solve(asm_, scheme_, s_, s0_, h, c, opt_.newton, m_.scales(), rhs_, stats_,
                                          [&](bool jac, int k) { evaluate(c, h, jac, k, true); });
    if (r.converged) {
      check_finite(h);
      if (opt_.error_control && !error_accepts(h)) {
        s_ = s0_;
        if (shift != 0) s_.p = p_start_;
        t_ = t0;
        return step_outcome::error_rejected;
      }
      stats_.last_iterations = r.iterations;
      stats_.last_step = h;
      ++stats_.steps;
      recommended_ = asm_.recommended_step();
      a_prev_ = s0_.a;
      h_prev_ = h;
      commit();
      if (!precision_warned_)  // once per stage (precision.hpp)
        if (auto l = detail::displacement_precision_loss(scheme_, asm_, s_, s0_, h, opt_, m_.scales())) {
          log_.write(detail::precision_warning_text(*l, m_.dof_name(l->dof), t_, h));
          precision_warned_ = true;
        }
      return step_outcome::accepted;
    }
    last_failure_ = r.failure;
    s_ = s0_;
    if (shift != 0) s_.p = p_start_;
    t_ = t0;
    return step_outcome::failed;
  }

  /// A converged state must be finite: u, v and a of every free DOF (an
  /// overflow, e.g. of u on a first-order DOF, whose flows stay finite).
  void check_finite(double h) {
    if (auto e = detail::non_finite_state(m_, asm_, s_, t_, h)) raise(*e);
  }

  /// The local error test (step_control.hpp). Sets h_error_; returns false
  /// (redo with h_error_) when the test fails and the step is above SMIN and
  /// CONTROL; throws step_too_small when the step needed is below SMIN, naming
  /// the DOF and the time.
  bool error_accepts(double h) {
    const error_test e =
        local_error_test(scheme_, asm_, s_, s0_, a_prev_, h_prev_, h, opt_, m_.scales(), this->error_skip(),
                         this->constrained(), h >= roundoff_floor_drop * watch_.largest());
    h_error_ = e.h_next;
    stats_.limiting_dof = e.worst;
    if (e.passed) {
      // After the run's first error rejection the step grows by at most max_step_growth per step.
      if (stats_.error_rejections > 0) h_error_ = std::min(h_error_, max_step_growth * h);
      return true;
    }
    const double floor = std::max(opt_.smin, opt_.control);
    if (h <= floor * (1 + 1e-12)) {
      if (opt_.control > opt_.smin) return true;  // CONTROL: accept at the floor
      raise(error(error_code::step_too_small,
                  "SMIN cannot reach the requested accuracy: local error " + num(e.worst_error) +
                      " above tolerance " + num(e.worst_tolerance) + " on DOF '" + m_.dof_name(e.worst) +
                      "' at t = " + num(t_) + " with step " + num(h) +
                      (newton_.has_multipliers() && detail::undamped(scheme_)
                           ? " (the model has constraint multipliers and " + std::string(scheme_label()) +
                                 " does not damp their alternation, which the error estimate sees: use HHT or GALPHA)"
                           : std::string()),
                  {}, {}, e.worst));
    }
    return false;
  }

  [[noreturn]] void fail_at_smin(double h) {
    if (last_failure_ && last_failure_->code() == error_code::singular_matrix) rethrow_singular(*last_failure_);
    raise(detail::smin_error(m_, asm_, last_failure_, opt_.smin, t_, h));
  }

  void notify() {
    for (auto& f : observers_) f(*this);
  }

  Scheme scheme_;
  newton_solver<Solver> newton_;
  bool precision_warned_ = false;  // a loss-of-precision warning was written in this stage
  std::vector<observer> observers_;
  std::vector<observer> step_observers_;
  double h_nominal_ = 0;
  double h_error_ = 0;
  double h_prev_ = 0;
  Eigen::VectorXd a_prev_;
  Eigen::VectorXd p_start_;  // p at the step's start before pseudo_acceleration_shift
  int successes_ = 0;
};

/// Deduction guides: `simulation sim(model, newmark{})`.
template <class M, Integrator S>
simulation(M&, S) -> simulation<M, S>;
template <class M>
simulation(M&) -> simulation<M>;

}  // namespace pradis
