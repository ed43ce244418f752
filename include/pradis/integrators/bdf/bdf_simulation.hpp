#pragma once
/// \file
/// pradis::bdf_simulation: a variable-order (1..5), variable-step BDF driver
/// with local error control for the nodal form F(u, v, a, t) = 0, next to the
/// one-step driver pradis::simulation (docs/bdf.md).
///
/// Formulation. The same BDF formula is applied to u and to v, i.e. to the
/// first-order system u' = v, F(u, v, v', t) = 0 (history.hpp has the method).
/// With the predictors u_p, u'_p, v_p, v'_p and the leading coefficient c of the
/// step, the corrector is u' = u'_p + c (u - u_p), a = v' = v'_p + c (v - v_p);
/// u' = v is met exactly by
///     u = u_p + (v - u'_p) / c,   a = v'_p + c (v - v_p),
/// so Newton solves F for the velocities v of the free DOFs, as in
/// pradis::simulation, with du/dv = 1/c, da/dv = c: the Newton matrix is
/// J = (1/c) K + C + c M, assembled by the same assembler.
///
/// Error control, step and order follow IDA's rules: a weighted RMS norm over the
/// displacements and velocities of the free DOFs with per-DOF weights (set_weights();
/// index-3 multipliers and slaved DOFs left out; index-3 constraints in the stabilised
/// index-2 form, constraints.hpp). Newton is IDA's modified Newton with the Jacobian and
/// its factorisation kept across iterations and steps (corrector.hpp); PRADIS's
/// DABSU/DRLTU/DABSI/DRLTI and newton_options::method are not used. A rotational node
/// whose quaternion norm drifted is scaled back to Lq = 1 with its history (rotations.hpp).
/// docs/bdf.md ("Error control and tolerances", "Newton", "Options") has the rules in full.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/integrators/bdf/constraints.hpp"
#include "pradis/integrators/bdf/corrector.hpp"
#include "pradis/integrators/bdf/history.hpp"
#include "pradis/integrators/bdf/options.hpp"
#include "pradis/integrators/bdf/rotations.hpp"
#include "pradis/integrators/checkpoint.hpp"
#include "pradis/integrators/concepts.hpp"
#include "pradis/integrators/driver_core.hpp"
#include "pradis/integrators/failures.hpp"
#include "pradis/integrators/initialisation.hpp"
#include "pradis/integrators/options.hpp"
#include "pradis/integrators/precision.hpp"
#include "pradis/integrators/step_control.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/model/model.hpp"

namespace pradis {

template <class Model, LinearSolver Solver = linalg::sparse_lu<linalg::automatic_ordering>>
class bdf_simulation;

/// Variable-order, variable-step BDF simulation of a model<Es...> with a linear
/// solver policy (see the file comment and docs/bdf.md). Usage as pradis::simulation:
///     pradis::bdf_simulation sim(model, {.max_order = 5});
///     sim.on_output([&](const auto& s) { ... s.time(), s.u(d) ... });
///     sim.run({.end = 1.0, .smax = 0.1, .error_control = true, .drltx = 1e-6});
template <class... Es, LinearSolver Solver>
class bdf_simulation<model<Es...>, Solver> : private detail::driver_core<model<Es...>> {
  using core = detail::driver_core<model<Es...>>;
  using core::asm_, core::index3_, core::log_, core::m_, core::opt_, core::prescribed_, core::recommended_, core::rhs_, core::s0_,
      core::s_, core::started_, core::stats_, core::t_, core::last_failure_, core::watch_;
  using core::bad_dof, core::checked, core::commit, core::context_for, core::evaluate, core::for_each_instance,
      core::new_integration, core::raise, core::start_watch, core::watch_accepted;

 public:
  // The results and the log (driver_core.hpp).
  using core::a, core::get_assembler, core::get_model, core::log, core::model_fingerprint, core::residual, core::state,
      core::statistics, core::time, core::u, core::v;
  /// The model type the driver runs.
  using model_type = model<Es...>;
  /// A callback at output times or steps (on_output, on_step).
  using observer = std::function<void(const bdf_simulation&)>;
  /// The method's name in messages.
  static constexpr std::string_view name = "BDF";

  /// Binds the simulation to a model (which must outlive it). Throws
  /// invalid_option for bad options (check_bdf_options).
  explicit bdf_simulation(model_type& m, bdf_options o = {}) : core(m), bopt_(o) {
    if (auto msg = check_bdf_options(o)) throw error(error_code::invalid_option, "BDF: " + *msg);
  }

  /// Adds an observer called at t0 (after the zero step) and at every output time.
  void on_output(observer f) { observers_.push_back(std::move(f)); }
  /// Adds an observer called after every accepted step (before the output observers of that step).
  void on_step(observer f) { step_observers_.push_back(std::move(f)); }

  /// Runs one stage up to opt.end (the first call performs the zero step, with
  /// consistent initial derivatives as pradis::simulation). Every stage starts
  /// the BDF history afresh at order 1 from the current u, v, a. With
  /// opt.error_control the step and order are error-controlled (DRLTX, DABSX);
  /// without it the stage starts with a step of SMIN, doubles it after every
  /// step up to SMAX and raises the order by one per step up to max_order.
  /// Returns the statistics of this stage; throws pradis::error on bad options
  /// (invalid_option), model errors and run failures.
  run_statistics run(const run_options& opt) {
    if (auto msg = check_options(opt)) fail_option(*msg);
    if (!(effective_dabsx(opt) + opt.drltx > 0))
      fail_option("DABSX + DRLTX must be > 0 (they weight the Newton and the error tests)");
    if (!(opt.end > t_)) fail_option("END = " + num(opt.end) + " must be after the current time " + num(t_));
    if (opt.predict)
      fail_option("PREDICT does not apply: the BDF predictor is the interpolating polynomial of the last k + 1 steps");
    const run_statistics before = stats_;
    opt_ = opt;
    newton_.valid = false;
    if (!started_) {
      zero_step();
    } else {
      if (!asm_.built_for(m_)) build();
      new_integration();
      evaluate({0, 0, 0}, 0.0, false);
      recommended_ = asm_.recommended_step();
    }
    start_history();
    start_watch();
    const double t_start = t_;
    long out_index = 1;
    double next_out = opt.out > 0 ? t_start + opt.out : opt.end;
    while (t_ < opt.end * (1 - 1e-14) - 1e-300) {
      const double target = std::min(next_out, opt.end);
      bool clipped = false;
      const double wanted = hist_.step();
      const double h = choose_step(t_, target, wanted, recommended_, opt, clipped);
      // An element holds the step below what the error allows (a switch in its transition, a
      // contact, a friction reversal): its blocks change fast, so the kept Newton matrix is
      // refreshed (docs/bdf.md, "Newton": a stale one let a switched node drift unseen).
      if (!opt.ignore && recommended_ < wanted) newton_.valid = false;
      if (!(t_ + h > t_))
        raise(error(error_code::step_too_small,
                    "the step " + num(h) + " no longer advances the time " + num(t_) + " in double precision"));
      hist_.set_step(h);
      if (!attempt()) continue;
      if (clipped) hist_.set_step(std::max(hist_.step(), std::min(wanted, opt.smax)));
      for (auto& f : step_observers_) f(*this);
      if (clipped || opt.out <= 0) {
        if (opt.out > 0) {
          ++out_index;
          next_out = t_start + static_cast<double>(out_index) * opt.out;
          if (std::abs(t_ - target) < 1e-12 * std::max(1.0, std::abs(target))) t_ = target;
        }
        notify();
      }
      watch_accepted(h);
    }
    t_ = opt.end;
    return stats_ - before;
  }

  // ---- results (see also driver_core.hpp: time, u, v, a, state, residual, statistics) -----
  /// The order of the next step.
  int order() const noexcept { return hist_.order(); }
  /// A statistic by name: those of pradis::simulation::statistic() ("NSTEP",
  /// "NITER", "STEP", "NREJ", "NFACT", "NITTOT", "NJAC", "NEVAL") and "ORDER",
  /// the order of the next step.
  double statistic(std::string_view key) const {
    if (key == "ORDER") return hist_.order();
    return statistic_by_name(stats_, key, "ORDER");
  }
  /// The BDF options.
  const bdf_options& options() const noexcept { return bopt_; }
  /// The linear solver.
  const Solver& solver() const noexcept { return solver_; }
  /// Replaces the linear solver (e.g. another ordering) for the following steps;
  /// the pattern is analysed again.
  void set_solver(Solver s) {
    solver_ = std::move(s);
    newton_.valid = false;
    if (started_) build();
  }

  // ---- checkpoint and restart --------------------------------------------------
  /// Writes a checkpoint in the format of pradis::simulation (checkpoint.hpp):
  /// time, potentials (the pseudo-acceleration is the acceleration), the next
  /// step, the statistics and every element's work and state vectors. Either
  /// driver can continue from it: BDF starts every stage afresh at order 1 from
  /// the state anyway, and an alpha scheme starts with p = a. Throws
  /// invalid_option before the zero step.
  void save_checkpoint(std::ostream& os) const { write_checkpoint(os, model_fingerprint(), checkpoint()); }
  /// The fields save_checkpoint() writes, in memory. Throws invalid_option before the zero step.
  checkpoint_data checkpoint() const {
    if (!started_) throw error(error_code::invalid_option, "no checkpoint before the first stage has run");
    return {t_, std::max(hist_.step(), 0.0), stats_.last_step, 0, stats_, s_, s_.a, m_.work_pool(),
            m_.old_state_pool(), m_.new_state_pool(), this->dof_classes()};
  }
  /// Continues from another driver `d` of the same model (simulation or bdf_simulation) as load_checkpoint() of its
  /// checkpoint would, not serialised; the next run() starts at order 1. Throws as simulation::continue_from().
  template <CheckpointSource Driver>
  void continue_from(const Driver& d) {
    restore(this->handover_from(d));
  }
  /// Restores a checkpoint of the same model written by either driver (see
  /// save_checkpoint()); the next run() starts its BDF history at order 1 from
  /// it. A checkpoint of another model or format, or a damaged one, is refused
  /// with io_error and the simulation is unchanged.
  void load_checkpoint(std::istream& is) {
    restore(this->read_own_checkpoint(is));
  }

 private:
  /// Takes over checked checkpoint data (load_checkpoint(), continue_from()).
  void restore(checkpoint_data c) {
    detail::detect_sources(m_, prescribed_, log_);
    s_ = std::move(c.state);
    s_.p = s_.a;
    build();
    this->take_over(c);
  }

  static std::string num(double x) { return detail::num(x); }

  [[noreturn]] void fail_option(const std::string& msg) { raise(error(error_code::invalid_option, "BDF: " + msg)); }

  // ---- element-level phases (driver_core.hpp, shared with pradis::simulation) ---
  /// The zero step: prescribed DOFs, initial conditions, consistent initial
  /// derivatives (initialisation.hpp), flows at t0.
  void zero_step() {
    this->start_zero_step(solver_, [&] { build(); });
    if (std::find(index3_.begin(), index3_.end(), char{1}) != index3_.end()) {
      const auto driven = bdf_detail::driven_constraint(m_, index3_, prescribed_);
      if (driven) log_.write(detail::bdf_driven_constraint_note(driven->first, driven->second));
      if (driven || !bopt_.stabilised_index2) log_.write(std::string(detail::bdf_index3_warning));
    }
    newton_.valid = false;  // the solver holds the factorisation of the initial-derivative matrix
    this->finish_zero_step();
    notify();
  }
  /// (Re)builds the equations and analyses the pattern.
  void build() {
    this->rebuild_equations();
    newton_.valid = false;
    try {
      solver_.analyze(asm_.pattern());
    } catch (const error& e) {
      raise(detail::singular_error(m_, asm_, e, t_));
    }
  }
  void notify() {
    for (auto& f : observers_) f(*this);
  }

  // ---- the BDF steps --------------------------------------------------------
  /// The error weights 1 / (DRLTX |x| + DABSX s) of the displacements and
  /// velocities of the free DOFs at the current state; zero for the multipliers
  /// of index-3 constraints and for slaved DOFs (driver_core::error_skip(); core/node_kind.hpp:
  /// functions of their node's other DOFs), which the error and
  /// corrector tests leave out. In the plain index-3 form (no stabilisation)
  /// the velocities of the DOFs an index-3 constraint acts on (the columns of
  /// its row, index2_) are index-2 components: their weights are multiplied by
  /// min(1, h / 1 s), h the step, in the Newton and the error test alike, as
  /// the code RADAU5 divides the tolerances of index-2 components by h (Hairer
  /// and Wanner, Solving ODEs II, 2nd ed. 1996; radau5.f, routine RADCOR). Any
  /// step of that form projects the incoming velocity onto the hidden
  /// constraint G v = 0, so their unscaled error does not shrink with h and
  /// small steps were rejected as often as large ones. The stabilised form
  /// meets G v = 0 itself and tests them unscaled.
  void set_weights(double h) {
    const int ne = asm_.equations();
    const double dabsx = effective_dabsx(opt_);
    const double hv = stab_.rows.empty() ? std::min(1.0, h) : 1.0;
    w_.resize(2 * ne);
    for (int i = 0; i < ne; ++i) {
      const auto d = asm_.dof_of(i);
      const double s = m_.scales()[static_cast<std::size_t>(d)].potential;
      const auto& sk = this->error_skip();
      const auto& uv = this->unused_velocity();
      const bool skip = static_cast<std::size_t>(d) < sk.size() && sk[static_cast<std::size_t>(d)];
      const bool skip_v = skip || (static_cast<std::size_t>(d) < uv.size() && uv[static_cast<std::size_t>(d)]);
      const bool index2 = static_cast<std::size_t>(i) < index2_.size() && index2_[static_cast<std::size_t>(i)];
      w_(i) = skip ? 0.0 : 1 / (opt_.drltx * std::abs(s_.u(d)) + dabsx * s);
      w_(ne + i) = skip_v ? 0.0 : (index2 ? hv : 1.0) / (opt_.drltx * std::abs(s_.v(d)) + dabsx * s);
    }
    rates_.weights(s_, ne, opt_.drltx, dabsx, m_.scales(), index2_, hv, w_);
  }
  /// Starts the history at order 1 from the current state, with IDA's first
  /// step (error control) or SMIN.
  void start_history() {
    const int ne = asm_.equations();
    Eigen::VectorXd y(2 * ne), yp(2 * ne);
    for (int i = 0; i < ne; ++i) {
      const auto d = asm_.dof_of(i);
      y(i) = s_.u(d);
      y(ne + i) = s_.v(d);
      yp(i) = s_.v(d);
      yp(ne + i) = s_.a(d);
    }
    converged_state_evaluation_ = this->states_need_converged_evaluation();
    const std::vector<char> slaved = detail::slaved_dofs(m_);
    any_slaved_ = std::find(slaved.begin(), slaved.end(), char{1}) != slaved.end();
    rates_.build(m_.rotation_nodes(), asm_, bopt_.rotation_rates);
    turned_.build(m_, asm_, bopt_.rotated_jacobian, bopt_.body_frame);
    rates_.rates(s_, ne, y, &yp);
    bdf_detail::mark_constraints(
        asm_, index3_, bopt_.stabilised_index2 && !bdf_detail::driven_constraint(m_, index3_, prescribed_), index2_,
        stab_);
    constraint_types_ = bdf_detail::constraint_types(m_, index3_);
    asm_.restrict_partial_rows(stab_.rows);  // G is read on the constraint rows alone
    // J again from the kept element blocks when only c moved (bdf_options::reform_jacobian): without
    // index-3 constraints, where every free rotational node is turned in its body frame (or there is none).
    const auto free_nodes = static_cast<int>(bdf_detail::free_rotation_nodes(m_.rotation_nodes(), asm_).size());
    asm_.keep_blocks(bopt_.reform_jacobian && std::find(index3_.begin(), index3_.end(), char{1}) == index3_.end() &&
                     rates_.empty() && turned_.body_frame_nodes() == free_nodes);
    double h = opt_.smin;
    set_weights(opt_.error_control ? 0.001 * (opt_.end - t_) : h);
    if (opt_.error_control) {
      h = bopt_.initial_step;
      if (h <= 0) {
        h = 0.001 * (opt_.end - t_);
        const double ypnorm = bdf_detail::wrms(yp, w_);
        if (ypnorm > 0.5 / h) h = 0.5 / ypnorm;
      }
      h = std::clamp(std::max(h, opt_.control), opt_.smin, opt_.smax);  // CONTROL: no first step below it
    }
    hist_.start(y, yp, h);
    nef_ = ncf_ = 0;
  }
  /// One attempt of the step hist_.step() at order hist_.order(). Returns true
  /// when accepted; otherwise the state is restored and the history holds the
  /// step and order of the redo.
  bool attempt() {
    s0_ = s_;
    const double t0 = t_;
    set_weights(hist_.step());
    hist_.set_coefficients();
    const double h = hist_.step(), c = hist_.c();
    t_ = t0 + h;
    detail::apply_sources(m_, s_, t_);
    hist_.predict(y_p_, yp_p_);
    const long iter0 = stats_.newton_iterations;
    const bool raise_test = opt_.error_control && hist_.raise_test_due(bopt_.max_order, bopt_.fixed_order);
    const bool ok = bdf_detail::correct(
        asm_, solver_, s_, y_p_, yp_p_, c, hist_.c_last(), w_, opt_.newton,
        raise_test ? bopt_.raise_test_tolerance : bopt_.newton_tolerance, bopt_.coefficient_change,
        bopt_.turn_refresh, newton_, rhs_, dy_, stats_, last_failure_, stab_.rows.empty() ? nullptr : &stab_,
        rates_.empty() ? nullptr : &rates_, turned_.empty() ? nullptr : &turned_, any_slaved_,
        [&](global_state& s, std::vector<double>* rhs, double scale) {
          detail::project_slaved(m_, s, log_, rhs, scale, [&](int d) { return asm_.equation_of(d); });
        },
        [&](const jacobian_coefficients& jc, bool jac, bool rows, int k) {
          evaluate(jc, h, jac, k, true, rows ? &constraint_types_ : nullptr);
        });
    const int ne = asm_.equations();
    if (ok) {
      if (auto e = detail::non_finite_state(m_, asm_, s_, t_, h)) raise(*e);
      e_.resize(2 * ne);
      for (int i = 0; i < ne; ++i) {
        const auto d = asm_.dof_of(i);
        e_(i) = s_.u(d) - y_p_(i);
        e_(ne + i) = s_.v(d) - y_p_(ne + i);
      }
      rates_.errors(s_, ne, y_p_, e_);
    }
    if (!ok) {
      undo(t0);
      ++stats_.rejected_steps;
      ++ncf_;
      hist_.on_convergence_failure();
      if (hist_.step() < opt_.smin * (1 - 1e-12)) {
        if (last_failure_ && last_failure_->code() == error_code::singular_matrix)
          raise(detail::singular_error(m_, asm_, *last_failure_, t_));
        raise(detail::smin_error(m_, asm_, last_failure_, opt_.smin, t_, h));
      }
      return false;
    }
    if (opt_.error_control) {
      const bdf_detail::error_estimate est = hist_.test_error(e_, w_, bopt_.fixed_order);
      // CONTROL: a step at or below it is accepted whatever its error (as in pradis::simulation).
      const bool at_control = opt_.control > opt_.smin && h <= opt_.control * (1 + 1e-12);
      if (!est.passed && !at_control) {
        const int worst = worst_dof();
        undo(t0);
        ++stats_.rejected_steps;
        ++stats_.error_rejections;
        stats_.limiting_dof = worst;
        ++nef_;
        hist_.on_error_failure(nef_, bopt_.fixed_order);
        if (opt_.control > opt_.smin && hist_.step() < opt_.control) hist_.set_step(opt_.control);
        if (hist_.step() < opt_.smin * (1 - 1e-12)) {
          if (h > opt_.smin * (1 + 1e-12)) {
            hist_.set_step(opt_.smin);
          } else {
            raise(error(error_code::step_too_small,
                        "SMIN cannot reach the requested accuracy: the local error of DOF '" +
                            (worst >= 0 ? m_.dof_name(worst) : std::string("?")) + "' is above its tolerance at t = " + num(t_) + " with step " + num(h) + " (order " +
                            std::to_string(hist_.order()) + ")",
                        {}, {}, worst));
          }
        }
        return false;
      }
    }
    nef_ = ncf_ = 0;
    // Element states are committed at the converged state (the last Newton evaluation was at
    // the iterate before the last correction), unless all are guards (GuardStateElement).
    if (converged_state_evaluation_) evaluate({0, 0, 0}, h, false, 0, true);
    hist_.complete(e_, w_, bopt_.max_order, bopt_.fixed_order, opt_.error_control, opt_.smax);
    if (bdf_detail::renormalise_rotation_nodes(m_.rotation_nodes(), asm_, s_, hist_, bopt_.lq_renormalise, rates_) > 0)
      newton_.valid = false;  // dF/dq scales with the node
    if (opt_.error_control && hist_.step() < opt_.control) hist_.set_step(std::min(opt_.control, opt_.smax));
    if (!opt_.error_control) {
      // The start without error control: the step grows from SMIN to SMAX by a
      // factor the variable-step method of the current order stays stable with
      // (a run of doublings at order 5 is not; factors found on the oscillator
      // of tests/integrators/test_bdf.cpp, with a margin).
      constexpr double growth[] = {2.0, 2.0, 1.5, 1.25, 1.1};
      hist_.set_step(std::min(growth[hist_.order() - 1] * h, opt_.smax));
    }
    s_.p = s_.a;
    ++stats_.steps;
    stats_.last_step = h;
    stats_.last_iterations = static_cast<int>(stats_.newton_iterations - iter0);
    recommended_ = asm_.recommended_step();
    commit();
    return true;
  }
  void undo(double t0) {
    s_ = s0_;
    t_ = t0;
    hist_.restore();
  }
  /// The DOF with the largest weighted local error (for messages).
  int worst_dof() const {
    const int ne = asm_.equations();
    int worst = -1;
    double we = -1;
    for (int i = 0; i < 2 * ne; ++i) {
      const double x = std::abs(e_(i) * w_(i));
      if (x > we) {
        we = x;
        worst = asm_.dof_of(i % ne);
      }
    }
    return worst;
  }

  bdf_options bopt_;
  Solver solver_;
  bdf_detail::history hist_;
  std::vector<observer> observers_;
  std::vector<observer> step_observers_;
  Eigen::VectorXd y_p_, yp_p_, w_, e_, dy_;
  bdf_detail::newton_memory newton_;  // the kept factorisation, its c and Newton's rate estimate
  std::vector<char> index2_;  // by equation: a DOF of an index-3 constraint's row (mark_constraints)
  bool any_slaved_ = false;  // some DOF is slaved (set by start_history; bdf_detail::correct projects them)
  bdf_detail::rotated_jacobian turned_;    // the kept Newton matrix turned with the rotational nodes
  bdf_detail::rate_form rates_;            // rotational nodes whose velocity rows hold (w, r) (rate_form.hpp)
  bdf_detail::index2_stabilisation stab_;  // the stabilised index-2 form (empty: none, or the plain index-3 form)
  std::vector<char> constraint_types_;     // per element type: owns an index-3 multiplier (bdf_detail::constraint_types)
  int nef_ = 0, ncf_ = 0;
  bool converged_state_evaluation_ = true;  // evaluate after an accepted step to commit the states
};

/// Deduction guides: `bdf_simulation sim(model)`, `bdf_simulation sim(model, bdf_options{...})`.
template <class M>
bdf_simulation(M&) -> bdf_simulation<M>;
template <class M>
bdf_simulation(M&, bdf_options) -> bdf_simulation<M>;

}  // namespace pradis
