#pragma once
/// \file
/// What the two time-integration drivers share: the one-step `simulation`
/// (simulation.hpp) and the multistep `bdf_simulation` (bdf/bdf_simulation.hpp).
/// driver_core<Model> holds the model, the assembler, the diagnostics log, the
/// global state and the run statistics, and carries out the element-level
/// phases the same way for both: NEWINT work, model evaluation, the commit of an
/// accepted step, the (re)build of the equations when DOFs were added, and the
/// zero step (initial conditions, prescribed motions, consistent initial
/// derivatives, initialisation.hpp). Each driver adds its own scheme, Newton
/// solver and step control.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <istream>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/checkpoint.hpp"
#include "pradis/integrators/failures.hpp"
#include "pradis/integrators/initialisation.hpp"
#include "pradis/integrators/options.hpp"
#include "pradis/integrators/step_watch.hpp"

namespace pradis::detail {

/// The DOF classes of driver_core::dof_classes() (a checkpoint field).
inline constexpr double dof_class_massless = 1;
/// Massless, but its velocity is an unknown of its own, not the derivative of a displacement that its equation
/// fixes: a velocity-level multiplier (kinds 4 and 5 of initial_derivatives, such as a source current), a node
/// whose potential a floating source fixes (kinds 4 and 6), or a node's DOF (a massless rotational node's
/// q1..q3, which its norm equation reads through q').
inline constexpr double dof_class_massless_velocity_unknown = 2;
inline constexpr double dof_class_index3 = 3;

/// The state and element-level phases shared by the drivers (see the file comment).
template <class Model>
class driver_core {
 protected:
  explicit driver_core(Model& m) : m_(m) {}

  // ---- results: public in both drivers (their `using core::...` declarations) ----
  /// The diagnostics log (SYSPRINT.TXT role); silent by default.
  diagnostics& log() noexcept { return log_; }
  /// Current time.
  double time() const noexcept { return t_; }
  /// Displacement of a DOF at the current time. Throws invalid_model for a DOF outside the model (index out of
  /// range, or a DOF handed out by another model) or before the first stage.
  double u(dof d) const { return s_.u(checked(d)); }
  /// Velocity of a DOF at the current time (throws as u()).
  double v(dof d) const { return s_.v(checked(d)); }
  /// Acceleration of a DOF at the current time (throws as u()).
  double a(dof d) const { return s_.a(checked(d)); }
  /// Global state (all DOFs).
  const global_state& state() const noexcept { return s_; }
  /// Sum of flows on a DOF at the last evaluation (nonzero only on prescribed DOFs: the reaction; throws as u()).
  double residual(dof d) const {
    const Eigen::Index i = checked(d);
    if (i >= asm_.residual().size()) bad_dof(d);
    return asm_.residual()(i);
  }
  /// Cumulative statistics (steps, rejected steps and error rejections, Newton iterations, evaluations, Jacobian
  /// evaluations, factorisations; run_statistics).
  const run_statistics& statistics() const noexcept { return stats_; }
  /// The model.
  Model& get_model() noexcept { return m_; }
  /// The model (const).
  const Model& get_model() const noexcept { return m_; }
  /// The assembler (pattern, equation numbering).
  const assembler<Model>& get_assembler() const noexcept { return asm_; }
  /// A fingerprint of the model's topology (see pradis::model_fingerprint); checkpoints carry it.
  std::uint64_t model_fingerprint() const { return pradis::model_fingerprint(m_); }

  // ---- element-level phases --------------------------------------------------

  /// Calls f(instance) for every element instance of the model.
  template <class F>
  void for_each_instance(F&& f) {
    m_.for_each_instances([&](auto& vec) {
      for (auto& in : vec) f(in);
    });
  }
  /// The element context of an instance at the current time and step count.
  element_context context_for(auto& in) {
    using E = std::remove_cvref_t<decltype(in.element)>;
    element_context ctx(E::passport.name, in.name, &log_);
    assembler<Model>::bind(m_, in, ctx);
    ctx.time = t_;
    ctx.nstep = stats_.steps;
    return ctx;
  }
  /// Whether committing the element states of an accepted step needs an evaluation at the
  /// converged state: some instance has a state vector and its type is not a GuardStateElement.
  bool states_need_converged_evaluation() {
    bool need = false;
    for_each_instance([&](auto& in) {
      if constexpr (!GuardStateElement<std::remove_cvref_t<decltype(in.element)>>) need = need || in.state_size > 0;
    });
    return need;
  }
  /// NEWINT work of every element (parameter checks, work vectors).
  void new_integration() {
    for_each_instance([&](auto& in) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (HasNewIntegration<E>) {
        element_context ctx = context_for(in);
        ctx.newint = true;
        in.element.new_integration(ctx);
      }
    });
    recommended_ = std::numeric_limits<double>::infinity();
  }
  /// Evaluates the model. During step k (1-based) elements see NSTEP = k; at
  /// the zero step and between steps they see the number of accepted steps.
  void evaluate(const jacobian_coefficients& c, double h, bool jac, int niter = 0, bool in_step = false,
                const std::vector<char>* jacobian_types = nullptr) {
    call_info info{t_, h, stats_.steps + (in_step ? 1 : 0), niter, jac, &log_, opt_.newton.dabsi, jacobian_types};
    ++stats_.evaluations;
    if (jac) ++stats_.jacobian_evaluations;
    asm_.evaluate(m_, s_, c, info);
  }
  /// The zero step's evaluation at the time t_ + dt with the kinematic sources at that time
  /// (they overwrite u, v, a, p of their DOFs; the caller restores them); t_ is kept.
  void evaluate_at(double dt, const jacobian_coefficients& c, bool jac) {
    if (dt == 0.0) return evaluate(c, 0.0, jac);
    const double t0 = t_;
    struct restore_time {
      double& t;
      double t0;
      ~restore_time() { t = t0; }
    } keep{t_, t0};
    t_ = t0 + dt;
    apply_sources(m_, s_, t_);
    evaluate(c, 0.0, jac);
  }
  /// Accepts the step: NEW state to OLD, element commit hooks, source reactions.
  void commit() {
    m_.old_state_pool() = m_.new_state_pool();
    for_each_instance([&](auto& in) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (requires(E& e, element_context& c) { e.commit(c); }) {
        element_context ctx = context_for(in);
        in.element.commit(ctx);
      }
      if constexpr (PrescribesMotion<E>) {
        // W(1) of a source: the force it applies to its DOF (the reaction).
        if (in.work_size > 0) m_.work_pool()[in.work_offset] = asm_.residual()(in.dofs[0]);
      }
    });
  }
  /// (Re)builds the equations and the pattern; DOFs added since the start (new
  /// internal or user DOFs) start at rest, the hidden DOFs of a new node at their start
  /// values (core/node_kind.hpp; a new rotational node at the identity).
  /// The driver then analyses the pattern with its solver.
  void rebuild_equations() {
    if (prescribed_.size() != static_cast<std::size_t>(m_.dof_count())) {
      const auto old = static_cast<Eigen::Index>(prescribed_.size());
      prescribed_.resize(static_cast<std::size_t>(m_.dof_count()), 0);
      global_state g;
      g.resize(m_.dof_count());
      g.u.head(old) = s_.u;
      g.v.head(old) = s_.v;
      g.a.head(old) = s_.a;
      g.p.head(old) = s_.p;
      m_.start_hidden_dofs(g.u, static_cast<int>(old));
      s_ = g;
    }
    asm_.build(m_, prescribed_);
    rhs_.resize(static_cast<std::size_t>(asm_.equations()));
    s0_ = s_;
  }
  /// The zero step up to the consistent initial derivatives: the hidden DOFs of
  /// the nodes at their start values (the rotational nodes' q4 at 1), NEWINT, initial conditions and prescribed
  /// motions, build() (the driver's: rebuild_equations and its analysis),
  /// initial derivatives with `solver` (which then holds their factorisation),
  /// and the log's note on initial conditions a massless DOF loses. The driver
  /// then resets its own history and calls finish_zero_step().
  template <class Solver, class Build>
  void start_zero_step(Solver& solver, Build&& build) {
    s_.resize(m_.dof_count());
    m_.start_hidden_dofs(s_.u);
    const std::vector<std::string> driver = detect_sources(m_, prescribed_, log_);
    new_integration();
    const auto [set_u, set_v] =
        apply_initial_conditions(m_, s_, prescribed_, driver, [&](auto& in) { return context_for(in); });
    apply_sources(m_, s_, t_);
    build();
    started_ = true;
    hidden_dof_velocities(m_, asm_, s_, opt_.newton.dabsi, log_, set_v);
    slaved_dof_start(m_, asm_, s_, opt_.newton.dabsi, log_, set_u, set_v);
    const std::vector<char> kind = initial_derivatives(
        m_, asm_, solver, s_, rhs_, stats_, log_, opt_.newton.dabsi,
        [&](const jacobian_coefficients& c, bool jac, double dt = 0.0) { evaluate_at(dt, c, jac); });
    warn_lost_initial_conditions(m_, asm_, kind, set_u, set_v, log_);
    std::vector<double> classes(static_cast<std::size_t>(m_.dof_count()), 0.0);
    const std::vector<char> hidden = m_.hidden_dofs(true);  // a node's hidden or slaved DOF: not counted as massless
    // The DOFs of the nodes (core/node_kind.hpp): their node's equations may read their velocities where the zero
    // step's M and C do not show it (the rotational norm equation reads q' through q, zero at the identity).
    std::vector<char> node_dof(classes.size(), 0);
    m_.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      for (const auto& node : nodes)
        for (std::size_t k = 0; k < static_cast<std::size_t>(K::size); ++k)
          if (node.dofs[k] >= 0 && static_cast<std::size_t>(node.dofs[k]) < node_dof.size())
            node_dof[static_cast<std::size_t>(node.dofs[k])] = 1;
    });
    for (int i = 0; i < static_cast<int>(kind.size()); ++i) {
      const auto d = static_cast<std::size_t>(asm_.dof_of(i));
      if (kind[static_cast<std::size_t>(i)] == 3) classes[d] = dof_class_index3;
      const char k = kind[static_cast<std::size_t>(i)];
      // Kinds 4, 5: a source current, whose value is its v; 6: a node whose velocity a source fixes. Kind 0: an
      // algebraic DOF, whose displacement its equation fixes (its velocity is that displacement's derivative,
      // even where another equation reads it), unless it is a node's DOF.
      if ((k == 0 || k >= 4) && !hidden[d])
        classes[d] = k >= 4 || node_dof[d] ? dof_class_massless_velocity_unknown : dof_class_massless;
    }
    set_dof_classes(classes);
  }
  /// The DOF classes of the zero step, per DOF: dof_class_index3 (the multiplier of an index-3 constraint),
  /// dof_class_massless (an equation with neither mass nor viscosity; a node's hidden DOF not counted),
  /// dof_class_massless_velocity_unknown (such an equation whose DOF's velocity is an unknown of its own: a
  /// source current) or 0.
  /// Checkpoints keep them, so that a restored run leaves the same DOFs out of its error tests and warns as the
  /// first run.
  std::vector<double> dof_classes() const {
    std::vector<double> c(static_cast<std::size_t>(m_.dof_count()), 0.0);
    for (std::size_t d = 0; d < c.size() && d < index3_.size(); ++d)
      if (index3_[d]) c[d] = dof_class_index3;
    for (std::size_t d = 0; d < c.size() && d < massless_.size(); ++d)
      if (massless_[d]) c[d] = velocity_unknown_[d] ? dof_class_massless_velocity_unknown : dof_class_massless;
    return c;
  }
  /// Per DOF: left out of the local error tests: the index-3 multipliers (index3_) and the
  /// slaved DOFs of the nodes (core/node_kind.hpp: functions of their node's other DOFs).
  const std::vector<char>& error_skip() const noexcept { return error_skip_; }
  /// Per DOF: held by an index-3 constraint (a column of a constraint's row), or massless (neither mass nor
  /// viscosity): Newton puts its position on the constraint or on its equation to round-off, which the local
  /// error test of the one-step schemes counts (step_control.hpp). A mass on a spring to a massless node held by
  /// a second spring, started with the node on its equation (algebraic_start.hpp), had NEWMARK's estimate of
  /// the node's round-off, about eps |u| / h, hold the first steps near SMIN until code 141 at t = 2.7e-9.
  const std::vector<char>& constrained() const noexcept { return constrained_; }
  /// Per DOF: massless with a displacement that its equation fixes (dof_class_massless, not
  /// dof_class_massless_velocity_unknown), and not a column of an index-3 constraint's row. BDF leaves these
  /// velocities out of its Newton and error norms, as IDA does with every derivative: Newton puts the position on
  /// its equation to round-off d, about eps |u|, and the velocity, the position's BDF derivative, then carries
  /// about c d = d / h, which at the first steps (h ~ 1e-11 s) outweighed any tolerance
  /// (bdf_simulation::set_weights). The position keeps its weight, and where another equation reads the
  /// velocity, that equation's own DOFs are tested.
  const std::vector<char>& unused_velocity() const noexcept { return unused_velocity_; }
  /// Sets index3_, the massless DOFs and their count from classes as dof_classes() gives them.
  void set_dof_classes(const std::vector<double>& classes) {
    index3_.assign(classes.size(), 0);
    massless_.assign(classes.size(), 0);
    velocity_unknown_.assign(classes.size(), 0);
    massless_count_ = 0;
    massless_dof_ = -1;
    error_skip_ = slaved_dofs(m_);
    error_skip_.resize(classes.size(), 0);
    for (std::size_t d = 0; d < classes.size(); ++d) {
      if (classes[d] == dof_class_index3) index3_[d] = error_skip_[d] = 1;
      if (classes[d] == dof_class_massless || classes[d] == dof_class_massless_velocity_unknown) {
        massless_[d] = 1;
        velocity_unknown_[d] = classes[d] == dof_class_massless_velocity_unknown;
        if (massless_count_++ == 0) massless_dof_ = static_cast<int>(d);
      }
    }
    constrained_ = massless_;
    unused_velocity_ = massless_;
    for (std::size_t d = 0; d < classes.size(); ++d)
      if (velocity_unknown_[d]) unused_velocity_[d] = 0;
    const auto& pat = asm_.pattern();
    for (std::size_t d = 0; d < classes.size(); ++d) {
      const int r = index3_[d] ? asm_.equation_of(static_cast<int>(d)) : -1;
      if (r < 0) continue;
      for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
        const auto c = static_cast<std::size_t>(asm_.dof_of(pat.col[static_cast<std::size_t>(q)]));
        constrained_[c] = 1;
        unused_velocity_[c] = 0;
      }
    }
  }
  /// The end of the zero step: the pseudo-acceleration starts at the consistent
  /// acceleration; flows and work vectors at t0 (no Jacobian); the zero step
  /// is accepted.
  void finish_zero_step() {
    s_.p = s_.a;
    evaluate({0, 0, 0}, 0.0, false);
    recommended_ = asm_.recommended_step();
    commit();
  }
  /// The index of a DOF of this model for reading the state; throws
  /// invalid_model for a DOF outside the model (index out of range, or handed
  /// out by another model) or before the first stage.
  Eigen::Index checked(dof d) const {
    if (d.index < 0 || d.index >= s_.u.size() || !m_.owns(d)) bad_dof(d);
    return d.index;
  }
  [[noreturn]] void bad_dof(dof d) const {
    throw error(error_code::invalid_model,
                "DOF index " + std::to_string(d.index) +
                    (!m_.owns(d) ? " belongs to another model than this simulation's"
                     : started_  ? " is not a DOF of this model (it has " + std::to_string(s_.u.size()) + " DOFs)"
                                 : " asked for before the first stage has run"),
                {}, {}, d.index);
  }
  /// The checkpoint data of driver d, checked to fit this model (check_handover): what continue_from() takes over.
  template <CheckpointSource Driver>
  checkpoint_data handover_from(const Driver& d) const {
    checkpoint_data c = d.checkpoint();
    check_handover(c, d.model_fingerprint(), pradis::model_fingerprint(m_), m_.dof_count(), m_.work_pool().size(),
                   m_.old_state_pool().size(), m_.new_state_pool().size());
    return c;
  }
  /// A checkpoint read from `is` and checked to fit this model (read_checkpoint): what load_checkpoint() of
  /// both drivers takes over.
  checkpoint_data read_own_checkpoint(std::istream& is) const {
    return read_checkpoint(is, pradis::model_fingerprint(m_), m_.dof_count(), m_.work_pool().size(),
                           m_.old_state_pool().size(), m_.new_state_pool().size());
  }
  /// Takes over the fields of checked checkpoint data that both drivers keep alike (time, statistics, the
  /// elements' work and state vectors, the DOF classes) and marks the driver started. The state itself comes
  /// first, in the driver's restore(), since its build() reads it.
  void take_over(checkpoint_data& c) {
    t_ = c.time;
    stats_ = c.stats;
    m_.work_pool() = std::move(c.work);
    m_.old_state_pool() = std::move(c.old_state);
    m_.new_state_pool() = std::move(c.new_state);
    set_dof_classes(c.dof_classes);
    started_ = true;
  }
  /// Starts the step watch of the stage opt_ (step_watch.hpp) at the current time, and writes its
  /// note on a long stage or its warning on a step budget too small for END (unless
  /// run_options::start_notes is false).
  void start_watch() {
    watch_.start_stage(opt_.smin, opt_.smax);
    if (!opt_.start_notes) return;
    const std::string text = stage_start_text(t_, opt_.end, opt_.smax, opt_.max_steps);
    if (!text.empty()) log_.write(text);
  }
  /// After an accepted step of size h and its outputs: the crawl warning, once per stage,
  /// and the step budget (step_watch.hpp). Throws step_budget when the stage used up
  /// NSTEPMAX accepted steps before END.
  void watch_accepted(double h) {
    watch_.accepted(h, t_);
    if (watch_.crawl_to_report()) {
      std::string why;
      if (!opt_.ignore && recommended_ <= h * (1 + 1e-9))
        why = "an element's recommended step (STEPMD) " + num(recommended_) + " sets the step";
      else if (opt_.error_control && stats_.limiting_dof >= 0)
        why = "the local error of DOF '" + m_.dof_name(stats_.limiting_dof) + "' sets the step";
      else if (stats_.rejected_steps > 0)
        why = "failed steps (Newton, singular situations) cut the step: " + std::to_string(stats_.rejected_steps) +
              " so far in the run";
      log_.write(watch_.crawl_text(t_, h, opt_.end, why));
    }
    if (watch_.budget_spent(opt_.max_steps) && t_ < opt_.end * (1 - 1e-14) - 1e-300)
      raise(watch_.budget_error(opt_.max_steps, t_, h, opt_.end));
  }
  /// Writes the error to the log and throws it.
  [[noreturn]] void raise(const error& e) {
    log_.write(e);
    throw e;
  }

  Model& m_;
  assembler<Model> asm_;
  diagnostics log_;
  global_state s_, s0_;
  std::vector<char> prescribed_;
  /// Per DOF: the multiplier of an index-3 constraint (found at the zero step,
  /// mark_index3_multipliers). The local error tests leave these out, as is
  /// necessary for index-3 multipliers (they are determined by the positions,
  /// not by an integrated derivative; Hairer and Wanner, Solving ODEs II, VII.3).
  std::vector<char> index3_;
  std::vector<char> error_skip_;  // index3_ and the slaved DOFs (error_skip())
  std::vector<char> constrained_;  // the massless DOFs and the columns of the index-3 constraints' rows (constrained())
  std::vector<char> unused_velocity_;  // unused_velocity()
  std::vector<char> velocity_unknown_;  // the massless DOFs of class dof_class_massless_velocity_unknown
  /// Equations with neither mass nor viscosity (algebraic, found at the zero step; index-3 multipliers and the
  /// nodes' hidden DOFs, such as the rotational q4, not counted), and the first one's DOF (-1 if none): the
  /// undamped-scheme warning of simulation::run names it.
  std::vector<char> massless_;
  int massless_count_ = 0;
  int massless_dof_ = -1;
  std::vector<double> rhs_;
  run_options opt_{};
  run_statistics stats_{};
  std::optional<error> last_failure_;
  double t_ = 0;
  double recommended_ = std::numeric_limits<double>::infinity();
  bool started_ = false;
  step_watch watch_;  // the stage's accepted steps (watch_accepted)
};

}  // namespace pradis::detail
