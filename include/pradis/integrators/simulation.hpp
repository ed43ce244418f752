#pragma once
/// \file
/// The time-integration driver: zero step, NEWINT work per stage, implicit
/// one-step integration with Newton iterations (PRADIS convergence tests),
/// step cuts down to SMIN, element-recommended steps (STEPMD / IGNORE),
/// output sampling at OUT and run statistics.
///
/// Usage:
///     pradis::simulation sim(model, pradis::newmark{});
///     sim.on_output([&](const auto& s) { ... s.time(), s.u(d) ... });
///     sim.run({.end = 1.0, .smax = 1e-3});   // first stage (also runs the zero step)
///     sim.run({.end = 1.5});                 // second stage, NEWINT again

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <istream>
#include <ostream>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/model/model.hpp"

namespace pradis {

/// Newton options with PRADIS's names and defaults.
struct newton_options {
  double dabsu = 0.01;   ///< DABSU: absolute tolerance on the correction of the unknown (velocity), times the DOF's nominal potential (dof_scale)
  double drltu = 1e-3;   ///< DRLTU: relative tolerance on the correction
  double dabsi = 0.1;    ///< DABSI: absolute tolerance on the residual (sum of flows) per DOF, times its nominal flow (dof_scale)
  double drlti = 1e-3;   ///< DRLTI: relative tolerance on the residual, times the sum of |flows| on the DOF
  int itr = 5;           ///< ITR: maximum Newton iterations per step
  bool second = false;   ///< SECOND: force at least a second iteration
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
  double dabsx = 0.1;        ///< DABSX: absolute tolerance of the local error (velocity units), times the DOF's nominal potential
  double drltx = 1e-3;       ///< DRLTX: relative tolerance of the local error, times |v|
  bool predict = false;      ///< PREDICT: linear prediction of the acceleration in the error predictor
  double control = 0.0;      ///< CONTROL: no error-driven step reduction below this step (0: none)
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
  /// Difference (per-stage figures).
  friend run_statistics operator-(run_statistics a, const run_statistics& b) {
    a.steps -= b.steps;
    a.rejected_steps -= b.rejected_steps;
    a.newton_iterations -= b.newton_iterations;
    a.factorizations -= b.factorizations;
    a.evaluations -= b.evaluations;
    a.error_rejections -= b.error_rejections;
    return a;
  }
};

template <class Model, Integrator Scheme = newmark, class Solver = linalg::sparse_lu<linalg::automatic_ordering>>
class simulation;

/// Simulation of a model<Es...> with an integration scheme and a linear solver policy.
template <class... Es, Integrator Scheme, class Solver>
class simulation<model<Es...>, Scheme, Solver> {
 public:
  using model_type = model<Es...>;
  using observer = std::function<void(const simulation&)>;

  /// Binds the simulation to a model (which must outlive it).
  explicit simulation(model_type& m, Scheme scheme = {}) : m_(m), scheme_(scheme) {}

  /// The diagnostics log (SYSPRINT.TXT role); silent by default.
  diagnostics& log() noexcept { return log_; }
  /// Adds an observer called at t0 (after the zero step) and at every output time.
  void on_output(observer f) { observers_.push_back(std::move(f)); }
  /// Adds an observer called after every accepted step (before the output observers of
  /// that step), e.g. for a progress display. Keep it cheap: it runs once per step.
  void on_step(observer f) { step_observers_.push_back(std::move(f)); }

  /// Runs one stage up to opt.end. The first call performs the zero step.
  /// Returns the statistics of this stage. Throws pradis::error on bad options
  /// (invalid_option), model errors and run failures.
  run_statistics run(const run_options& opt) {
    validate(opt);
    const run_statistics before = stats_;
    opt_ = opt;
    if (!(opt.end > t_)) fail_option("END = " + num(opt.end) + " must be after the current time " + num(t_));
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
    while (t_ < opt.end * (1 - 1e-14) - 1e-300) {
      double target = std::min(next_out, opt.end);
      double h = h_nominal_;
      if (!opt.ignore && recommended_ < h) h = std::max(recommended_, opt.smin);
      bool clipped = false;
      const double remaining = target - t_;
      if (t_ + h >= target - 1e-9 * h) {
        h = remaining;
        clipped = true;
      } else if (remaining < 2 * h) {
        h = 0.5 * remaining;  // two equal steps rather than a full one and a sliver
      }
      if (!(t_ + h > t_)) {
        error e(error_code::step_too_small,
                "the step " + num(h) + " no longer advances the time " + num(t_) + " in double precision");
        log_.write(e);
        throw e;
      }
      const step_outcome outcome = step(h);
      if (outcome == step_outcome::error_rejected) {
        ++stats_.rejected_steps;
        ++stats_.error_rejections;
        h_nominal_ = h_error_;
        continue;
      }
      if (outcome == step_outcome::accepted) {
        for (auto& f : step_observers_) f(*this);
        if (opt.error_control)
          h_nominal_ = clipped ? std::max(h_nominal_, h_error_) : h_error_;
        else if (!clipped || h >= h_nominal_)
          grow();
        if (clipped || opt.out <= 0) {
          if (opt.out > 0) {
            ++out_index;
            next_out = t_start + static_cast<double>(out_index) * opt.out;
            if (std::abs(t_ - target) < 1e-12 * std::max(1.0, std::abs(target))) t_ = target;
          }
          notify();
        }
      } else {
        ++stats_.rejected_steps;
        h_nominal_ = h * 0.5;
        successes_ = 0;
        if (h_nominal_ < opt.smin) fail_at_smin(h);
      }
    }
    t_ = opt.end;
    return stats_ - before;
  }

  // ---- results --------------------------------------------------------------
  /// Current time.
  double time() const noexcept { return t_; }
  /// Displacement, velocity, acceleration of a DOF at the current time.
  double u(dof d) const { return s_.u(d.index); }
  double v(dof d) const { return s_.v(d.index); }
  double a(dof d) const { return s_.a(d.index); }
  /// Global state (all DOFs).
  const global_state& state() const noexcept { return s_; }
  /// Sum of flows on a DOF at the last evaluation (nonzero only on prescribed DOFs: the reaction).
  double residual(dof d) const { return asm_.residual()(d.index); }
  /// Cumulative statistics.
  const run_statistics& statistics() const noexcept { return stats_; }
  /// A statistic by its output-variable name: "NSTEP" (accepted steps), "NITER"
  /// (iterations of the last step), "STEP" (last step size), "NREJ" (rejected
  /// steps), "NFACT" (factorisations), "NITTOT" (all Newton iterations).
  double statistic(std::string_view key) const {
    if (key == "NSTEP") return static_cast<double>(stats_.steps);
    if (key == "NITER") return stats_.last_iterations;
    if (key == "STEP") return stats_.last_step;
    if (key == "NREJ") return static_cast<double>(stats_.rejected_steps);
    if (key == "NFACT") return static_cast<double>(stats_.factorizations);
    if (key == "NITTOT") return static_cast<double>(stats_.newton_iterations);
    throw error(error_code::invalid_option, "unknown statistic '" + std::string(key) +
                                                "' (known: NSTEP, NITER, STEP, NREJ, NFACT, NITTOT)");
  }
  /// The model.
  model_type& get_model() noexcept { return m_; }
  const model_type& get_model() const noexcept { return m_; }
  /// The assembler (pattern, equation numbering).
  const assembler<model_type>& get_assembler() const noexcept { return asm_; }
  /// The linear solver.
  const Solver& solver() const noexcept { return solver_; }
  /// Replaces the linear solver, e.g. by one with another ordering (the OPTIM key of the
  /// model language). If the model was already analysed, the new solver analyses its
  /// pattern at once, so the next step factorises with the new ordering.
  void set_solver(Solver solver) {
    solver_ = std::move(solver);
    if (asm_.built_for(m_)) {
      try {
        solver_.analyze(asm_.pattern());
      } catch (const error& e) {
        rethrow_singular(e);
      }
    }
  }
  /// The scheme.
  const Scheme& scheme() const noexcept { return scheme_; }
  /// Starts the scheme afresh from the current state, as at the zero step: the
  /// pseudo-acceleration of the alpha family is set to the acceleration (p = a).
  /// For a run continued with another scheme (see load_checkpoint()).
  void restart_scheme() { s_.p = s_.a; }


  // ---- checkpoint and restart --------------------------------------------------
  /// A fingerprint of the model's topology: DOF count, element types, instance
  /// names, connections, parameter counts and vector sizes (FNV-1a, 64 bit).
  std::uint64_t model_fingerprint() const {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* p, std::size_t n) {
      const auto* b = static_cast<const unsigned char*>(p);
      for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    const int nd = m_.dof_count();
    mix(&nd, sizeof nd);
    m_.for_each_instances([&](const auto& vec) {
      for (const auto& in : vec) {
        using E = std::remove_cvref_t<decltype(in.element)>;
        mix(E::passport.name.data(), E::passport.name.size());
        mix(in.name.data(), in.name.size());
        mix(in.dofs.data(), sizeof(int) * in.dofs.size());
        mix(&in.npar, sizeof in.npar);
        mix(&in.work_size, sizeof in.work_size);
        mix(&in.state_size, sizeof in.state_size);
      }
    });
    return h;
  }

  /// Writes a checkpoint: time, potentials of all DOFs, the nominal step, the
  /// statistics and every element's work and state vectors (binary, with the
  /// model fingerprint). Throws invalid_option before the zero step.
  void save_checkpoint(std::ostream& os) const {
    if (!started_) throw error(error_code::invalid_option, "no checkpoint before the first stage has run");
    os.write(checkpoint_magic, sizeof checkpoint_magic);
    put(os, model_fingerprint());
    put(os, t_);
    put(os, h_nominal_);
    put(os, static_cast<std::int64_t>(successes_));
    put(os, stats_);
    put_vec(os, s_.u);
    put_vec(os, s_.v);
    put_vec(os, s_.a);
    put_vec(os, s_.p);
    put(os, h_prev_);
    put_vec(os, a_prev_);
    put_vec(os, m_.work_pool());
    put_vec(os, m_.old_state_pool());
    put_vec(os, m_.new_state_pool());
    if (!os) throw error(error_code::io_error, "cannot write the checkpoint");
  }
  /// Restores a checkpoint written by save_checkpoint() for the same model (the
  /// parameters may differ: $REPLACE). The next run() continues from it exactly
  /// as the uninterrupted run would; the zero step is not repeated. A checkpoint
  /// of a different model, or a damaged one, is refused (io_error).
  void load_checkpoint(std::istream& is) {
    char magic[sizeof checkpoint_magic];
    is.read(magic, sizeof magic);
    if (!is || std::string_view(magic, sizeof magic) != std::string_view(checkpoint_magic, sizeof magic))
      throw error(error_code::io_error, "not a pradis checkpoint");
    std::uint64_t fp = 0;
    get(is, fp);
    if (fp != model_fingerprint())
      throw error(error_code::io_error,
                  "the checkpoint belongs to a different model (its DOFs, elements or connections differ)");
    double t = 0, h = 0;
    std::int64_t succ = 0;
    run_statistics st;
    get(is, t);
    get(is, h);
    get(is, succ);
    get(is, st);
    const int nd = m_.dof_count();
    global_state g;
    g.resize(nd);
    get_vec(is, g.u);
    get_vec(is, g.v);
    get_vec(is, g.a);
    get_vec(is, g.p);
    double hp = 0;
    get(is, hp);
    Eigen::VectorXd ap(nd);
    get_vec(is, ap);
    std::vector<double> w(m_.work_pool().size()), os(m_.old_state_pool().size()), ns(m_.new_state_pool().size());
    get_vec(is, w);
    get_vec(is, os);
    get_vec(is, ns);
    if (!is) throw error(error_code::io_error, "the checkpoint is truncated");
    detect_sources();
    s_ = g;
    build();
    t_ = t;
    h_nominal_ = h;
    h_prev_ = hp;
    a_prev_ = ap;
    successes_ = static_cast<int>(succ);
    stats_ = st;
    m_.work_pool() = std::move(w);
    m_.old_state_pool() = std::move(os);
    m_.new_state_pool() = std::move(ns);
    started_ = true;
  }

 private:
  static constexpr char checkpoint_magic[8] = {'P', 'R', 'A', 'D', 'C', 'K', '0', '1'};
  template <class T>
  static void put(std::ostream& os, const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    os.write(reinterpret_cast<const char*>(&x), sizeof x);
  }
  template <class T>
  static void get(std::istream& is, T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    is.read(reinterpret_cast<char*>(&x), sizeof x);
  }
  template <class V>
  static void put_vec(std::ostream& os, const V& v) {
    const auto n = static_cast<std::uint64_t>(v.size());
    put(os, n);
    os.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
  }
  template <class V>
  static void get_vec(std::istream& is, V& v) {
    std::uint64_t n = 0;
    get(is, n);
    if (!is || n != static_cast<std::uint64_t>(v.size()))
      throw error(error_code::io_error, "the checkpoint does not match the model's sizes");
    is.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
  }

 public:
 private:
  static std::string num(double x) {
    std::ostringstream os;
    os.precision(10);
    os << x;
    return os.str();
  }
  [[noreturn]] void fail_option(const std::string& msg) {
    error e(error_code::invalid_option, std::string(Scheme::name) + ": " + msg);
    log_.write(e);
    throw e;
  }
  void validate(const run_options& o) {
    auto bad = [](double x) { return !std::isfinite(x); };
    if (bad(o.end)) fail_option("END must be a finite number");
    if (bad(o.smax) || !(o.smax > 0)) fail_option("SMAX = " + num(o.smax) + " must be > 0");
    if (bad(o.smin) || !(o.smin > 0)) fail_option("SMIN = " + num(o.smin) + " must be > 0");
    if (o.smin > o.smax) fail_option("SMIN = " + num(o.smin) + " is above SMAX = " + num(o.smax));
    if (bad(o.out) || o.out < 0) fail_option("OUT = " + num(o.out) + " must be >= 0");
    const auto& n = o.newton;
    if (bad(n.dabsu) || n.dabsu < 0) fail_option("DABSU = " + num(n.dabsu) + " must be >= 0");
    if (bad(n.drltu) || n.drltu < 0) fail_option("DRLTU = " + num(n.drltu) + " must be >= 0");
    if (bad(n.dabsi) || n.dabsi < 0) fail_option("DABSI = " + num(n.dabsi) + " must be >= 0");
    if (bad(n.drlti) || n.drlti < 0) fail_option("DRLTI = " + num(n.drlti) + " must be >= 0");
    if (n.dabsu + n.drltu <= 0 || n.dabsi + n.drlti <= 0)
      fail_option("Newton tolerances DABSU+DRLTU and DABSI+DRLTI must not both be zero");
    if (n.itr < 1) fail_option("ITR = " + std::to_string(n.itr) + " must be >= 1");
    if (bad(o.dabsx) || o.dabsx < 0) fail_option("DABSX = " + num(o.dabsx) + " must be >= 0");
    if (bad(o.drltx) || o.drltx < 0) fail_option("DRLTX = " + num(o.drltx) + " must be >= 0");
    if (o.error_control && !(o.dabsx + o.drltx > 0))
      fail_option("error control needs DABSX + DRLTX > 0 (both are zero)");
    if (bad(o.control) || o.control < 0) fail_option("CONTROL = " + num(o.control) + " must be >= 0");
  }

  // ---- element-level phases ---------------------------------------------------
  template <class F>
  void for_each_instance(F&& f) {
    m_.for_each_instances([&](auto& vec) {
      for (auto& in : vec) f(in);
    });
  }
  element_context context_for(auto& in) {
    using E = std::remove_cvref_t<decltype(in.element)>;
    element_context ctx(E::passport.name, in.name, &log_);
    assembler<model_type>::bind(m_, in, ctx);
    ctx.time = t_;
    ctx.nstep = stats_.steps;
    return ctx;
  }

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

  void zero_step() {
    const int nd = m_.dof_count();
    s_.resize(nd);
    // The hidden q4 of every rotational node starts at 1 (identity orientation);
    // initial-rotation elements (ROT0) may set it otherwise below.
    for (const auto& node : m_.rotation_nodes()) s_.u(node.dofs[3]) = 1.0;
    std::vector<std::string> driver = detect_sources();
    new_integration();
    // Initial conditions (zero step), with conflict detection (code 90).
    std::vector<std::string> set_u(static_cast<std::size_t>(nd)), set_v(set_u);
    for_each_instance([&](auto& in) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (HasZeroStep<E>) {
        element_context ctx = context_for(in);
        ctx.newint = true;
        initial_values<element_traits<E>::n> iv;
        in.element.zero_step(iv, ctx);
        for (int k = 0; k < element_traits<E>::n; ++k) {
          const auto d = static_cast<std::size_t>(in.dofs[static_cast<std::size_t>(k)]);
          if (iv.has_displacement(k)) apply_initial(ctx, d, iv.displacement(k), s_.u, set_u, driver, "displacement");
          if (iv.has_velocity(k)) apply_initial(ctx, d, iv.velocity(k), s_.v, set_v, driver, "velocity");
        }
      }
    });
    apply_sources(t_);
    build();
    started_ = true;
    initial_acceleration();
    s_.p = s_.a;  // the pseudo-acceleration starts at the consistent acceleration
    a_prev_ = s_.a;
    h_prev_ = 0;
    // Flows and work vectors at t0 (no Jacobian needed), then accept the zero step.
    evaluate({0, 0, 0}, 0.0, false);
    recommended_ = asm_.recommended_step();
    commit();
    notify();
  }

  /// Marks the ground and the DOFs driven by kinematic sources as prescribed;
  /// two sources on one DOF (or a source on the ground) is code 90.
  std::vector<std::string> detect_sources() {
    const int nd = m_.dof_count();
    prescribed_.assign(static_cast<std::size_t>(nd), 0);
    prescribed_[0] = 1;
    std::vector<std::string> driver(static_cast<std::size_t>(nd));
    driver[0] = "the ground";
    // Sources that prescribe motion take their DOF out of the unknowns.
    for_each_instance([&](auto& in) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (PrescribesMotion<E>) {
        const auto d = static_cast<std::size_t>(in.dofs[0]);
        if (prescribed_[d]) {
          error e(error_code::conflicting_initial,
                  "DOF '" + m_.dof_name(static_cast<int>(d)) + "' is already driven by " + driver[d],
                  std::string(E::passport.name), in.name, static_cast<long>(d));
          log_.write(e);
          throw e;
        }
        prescribed_[d] = 1;
        driver[d] = std::string(E::passport.name) + " '" + in.name + "'";
      }
    });
    return driver;
  }

  void apply_initial(element_context& ctx, std::size_t d, double value, Eigen::VectorXd& target,
                     std::vector<std::string>& set_by, const std::vector<std::string>& driver,
                     const char* what) {
    if (prescribed_[d]) {
      ctx.fail(error_code::conflicting_initial, std::string("initial ") + what + " on DOF '" +
                                                    m_.dof_name(static_cast<int>(d)) + "', which is driven by " +
                                                    driver[d]);
    }
    const auto i = static_cast<Eigen::Index>(d);
    if (!set_by[d].empty() && target(i) != value)
      ctx.fail(error_code::conflicting_initial,
               std::string("initial ") + what + " " + num(value) + " on DOF '" + m_.dof_name(static_cast<int>(d)) +
                   "' conflicts with " + num(target(i)) + " set by '" + set_by[d] + "'");
    target(i) = value;
    set_by[d] = std::string(ctx.instance());
  }

  void apply_sources(double t) {
    for_each_instance([&](auto& in) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (PrescribesMotion<E>) {
        const kinematics k = in.element.motion(t);
        const auto d = static_cast<Eigen::Index>(in.dofs[0]);
        s_.u(d) = k.u;
        s_.v(d) = k.v;
        s_.a(d) = k.a;
        s_.p(d) = k.a;
      }
    });
  }

  void build() {
    if (prescribed_.size() != static_cast<std::size_t>(m_.dof_count())) {
      // DOFs were added after the zero step (internal or new): they start at rest.
      const auto old = static_cast<Eigen::Index>(prescribed_.size());
      prescribed_.resize(static_cast<std::size_t>(m_.dof_count()), 0);
      global_state g;
      g.resize(m_.dof_count());
      g.u.head(old) = s_.u;
      g.v.head(old) = s_.v;
      g.a.head(old) = s_.a;
      g.p.head(old) = s_.p;
      for (const auto& node : m_.rotation_nodes())
        if (node.dofs[3] >= old) g.u(node.dofs[3]) = 1.0;  // a new rotational node starts at the identity
      s_ = g;
    }
    asm_.build(m_, prescribed_);
    const int ne = asm_.equations();
    dv_.setZero(ne);
    rhs_.resize(static_cast<std::size_t>(ne));
    s0_ = s_;
    try {
      solver_.analyze(asm_.pattern());
    } catch (const error& e) {
      rethrow_singular(e);
    }
  }

  /// Names the DOF of a singular equation and the elements on it.
  [[noreturn]] void rethrow_singular(const error& e) {
    if (e.dof() < 0 || e.dof() >= asm_.equations()) {
      log_.write(e);
      throw e;
    }
    const int d = asm_.dof_of(static_cast<int>(e.dof()));
    std::string on;
    m_.for_each_instances([&](const auto& vec) {
      for (const auto& in : vec)
        if (std::find(in.dofs.begin(), in.dofs.end(), d) != in.dofs.end()) {
          using T = std::remove_cvref_t<decltype(in.element)>;
          if (!on.empty()) on += ", ";
          on += std::string(T::passport.name) + " '" + in.name + "'";
        }
    });
    std::string msg = e.code() == error_code::structurally_singular
                          ? "DOF '" + m_.dof_name(d) + "' has no Jacobian entry: no element acts on it"
                          : "the Newton matrix is singular at DOF '" + m_.dof_name(d) + "' (elements on it: " +
                                (on.empty() ? std::string("none") : on) +
                                "); a DOF needs stiffness, viscosity or mass, or a support";
    error out(e.code(), msg + " [t = " + num(t_) + "]", {}, {}, d);
    log_.write(out);
    throw out;
  }

  /// Consistent initial derivatives at the zero step. The unknown of each free
  /// DOF is its acceleration if it has inertia (dF/da diagonal nonzero), else its
  /// velocity if it has viscosity (a first-order DOF, e.g. the series point of a
  /// spring and a damper), else nothing (an algebraic DOF: its equation is met
  /// by Newton at the first step). One Newton step on F(u0, v0, a0, 0) = 0 with
  /// J = M (inertial columns) + C (viscous columns) + I (algebraic columns).
  /// Without it the trapezoidal u-v relation of the Newmark family would carry
  /// an inconsistent start as an undamped oscillation of v.
  void initial_acceleration() {
    using asm_t = assembler<model_type>;
    if constexpr (!asm_t::any_m && !asm_t::any_c) {
      return;
    } else {
      const int ne = asm_.equations();
      const auto& pat = asm_.pattern();
      evaluate({0, 0, 1}, 0.0, true);
      std::vector<double> mvals(asm_.values().begin(), asm_.values().end());
      std::vector<double> cvals(mvals.size(), 0.0);
      for (int i = 0; i < ne; ++i) rhs_[static_cast<std::size_t>(i)] = -asm_.residual()(asm_.dof_of(i));
      if constexpr (asm_t::any_c) {
        evaluate({0, 1, 0}, 0.0, true);
        cvals.assign(asm_.values().begin(), asm_.values().end());
      }
      std::vector<char> kind(static_cast<std::size_t>(ne), 0);  // 1 inertial, 2 viscous, 0 algebraic
      for (int i = 0; i < ne; ++i) {
        const int q = pat.find(i, i);
        if (q >= 0 && mvals[static_cast<std::size_t>(q)] != 0.0) kind[static_cast<std::size_t>(i)] = 1;
        else if (q >= 0 && cvals[static_cast<std::size_t>(q)] != 0.0) kind[static_cast<std::size_t>(i)] = 2;
      }
      // Rotational nodes: the hidden q4's unknown is its acceleration, from the norm
      // equation differentiated once more, d2(Lq)/dt2 = 0, i.e.
      // (q . q'' + |q'|^2 - (q . q')^2 / Lq^2) / Lq = 0: without it q4'' would start
      // inconsistent and the trapezoidal rule would carry the error on as an
      // undamped alternation of q'' (which enters the moments through E(q) q'').
      // q1..q3 of a node are inertial when the node's inertia block has an entry in
      // their row (their own diagonal E(q)-entry may vanish, e.g. at 180 degrees).
      for (const auto& node : m_.rotation_nodes()) {
        const int e4 = asm_.equation_of(node.dofs[3]);
        if (e4 < 0) continue;
        kind[static_cast<std::size_t>(e4)] = 1;
        for (int r = 0; r < 3; ++r) {
          const int er = asm_.equation_of(node.dofs[static_cast<std::size_t>(r)]);
          if (er < 0) continue;
          for (int c = 0; c < 4; ++c) {
            const int ec = asm_.equation_of(node.dofs[static_cast<std::size_t>(c)]);
            const int q = ec >= 0 ? pat.find(er, ec) : -1;
            if (q >= 0 && mvals[static_cast<std::size_t>(q)] != 0.0) kind[static_cast<std::size_t>(er)] = 1;
          }
        }
      }
      std::vector<double> j(mvals.size(), 0.0);
      for (int r = 0; r < ne; ++r)
        for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
          const int c = pat.col[static_cast<std::size_t>(q)];
          const auto sq = static_cast<std::size_t>(q);
          const char k = kind[static_cast<std::size_t>(c)];
          j[sq] = k == 1 ? mvals[sq] : (k == 2 ? cvals[sq] : (r == c ? 1.0 : 0.0));
        }
      for (const auto& node : m_.rotation_nodes()) {
        const int e4 = asm_.equation_of(node.dofs[3]);
        if (e4 < 0) continue;
        Eigen::Vector4d q, qd, qdd;
        for (int k = 0; k < 4; ++k) {
          const auto d = static_cast<Eigen::Index>(node.dofs[static_cast<std::size_t>(k)]);
          q(k) = s_.u(d);
          qd(k) = s_.v(d);
          qdd(k) = s_.a(d);
        }
        const double lq = q.norm(), g = q.dot(qd);
        for (int qq = pat.row_ptr[static_cast<std::size_t>(e4)]; qq < pat.row_ptr[static_cast<std::size_t>(e4) + 1]; ++qq)
          j[static_cast<std::size_t>(qq)] = 0.0;
        for (int k = 0; k < 4; ++k) {
          const int ec = asm_.equation_of(node.dofs[static_cast<std::size_t>(k)]);
          if (ec >= 0) j[static_cast<std::size_t>(pat.find(e4, ec))] = q(k) / lq;
        }
        rhs_[static_cast<std::size_t>(e4)] = -(q.dot(qdd) + qd.squaredNorm() - g * g / (lq * lq)) / lq;
      }
      try {
        solver_.factorize(j);
        ++stats_.factorizations;
        solver_.solve(rhs_);
        bool finite = true;
        for (double x : rhs_) finite = finite && std::isfinite(x);
        if (!finite) throw error(error_code::singular_matrix, "non-finite initial derivatives");
        for (int i = 0; i < ne; ++i) {
          const auto d = asm_.dof_of(i);
          const double z = rhs_[static_cast<std::size_t>(i)];
          if (kind[static_cast<std::size_t>(i)] == 1) s_.a(d) += z;
          if (kind[static_cast<std::size_t>(i)] == 2) s_.v(d) += z;
        }
      } catch (const error& e) {
        if (e.code() != error_code::singular_matrix) throw;
        std::string where =
            e.dof() >= 0 && e.dof() < ne ? " (DOF '" + m_.dof_name(asm_.dof_of(static_cast<int>(e.dof()))) + "')" : "";
        log_.write("warning: no consistent initial derivatives" + where +
                   ": the run starts with zero initial accelerations on the free DOFs");
        for (int i = 0; i < ne; ++i) s_.a(asm_.dof_of(i)) = 0;
      }
    }
  }

  /// Evaluates the model. During step k (1-based) elements see NSTEP = k; at
  /// the zero step and between steps they see the number of accepted steps.
  void evaluate(const jacobian_coefficients& c, double h, bool jac, int niter = 0, bool in_step = false) {
    call_info info{t_, h, stats_.steps + (in_step ? 1 : 0), niter, jac, &log_, opt_.newton.dabsi};
    ++stats_.evaluations;
    asm_.evaluate(m_, s_, c, info);
  }

  /// One step from t_ to t_ + h. Returns false (state restored) when Newton did
  /// not converge or an element reported a singular situation.
  step_outcome step(double h) {
    s0_ = s_;
    const double t0 = t_;
    const int ne = asm_.equations();
    const auto& nw = opt_.newton;
    t_ = t0 + h;
    apply_sources(t_);
    for (int i = 0; i < ne; ++i) {
      const auto d = asm_.dof_of(i);
      s_.v(d) = scheme_.predict(s0_.u(d), s0_.v(d), s0_.a(d), s0_.p(d), h);
      scheme_.complete(s0_.u(d), s0_.v(d), s0_.a(d), s0_.p(d), h, s_.v(d), s_.u(d), s_.a(d), s_.p(d));
    }
    const jacobian_coefficients c = scheme_.coefficients(h);
    const auto& scale = m_.scales();  // per-DOF nominal potential and flow (core/domain.hpp)
    bool correction_ok = false, roundoff = false;
    last_failure_.reset();
    try {
      for (int k = 0;; ++k) {
        evaluate(c, h, true, k, true);
        bool residual_ok = true;
        for (int i = 0; i < ne && residual_ok; ++i) {
          const auto d = asm_.dof_of(i);
          residual_ok = std::abs(asm_.residual()(d)) <=
                        nw.dabsi * scale[static_cast<std::size_t>(d)].flow + nw.drlti * asm_.abs_sum()(d);
        }
        // Converged: both PRADIS tests pass; or, after at least two corrections,
        // the last correction was at round-off level: neither the unknown nor the
        // residual can get smaller in double precision (the residual's floor is
        // about |J| eps |v| once a = (v - v0) / (gamma h)), whatever DABSU/DRLTU
        // and DABSI/DRLTI ask for.
        if (k > 0 && ((correction_ok && residual_ok) || (k >= 2 && roundoff)) && (!nw.second || k >= 2)) {
          if (opt_.error_control && !error_accepts(h)) {
            s_ = s0_;
            t_ = t0;
            return step_outcome::error_rejected;
          }
          stats_.last_iterations = k;
          stats_.last_step = h;
          ++stats_.steps;
          recommended_ = asm_.recommended_step();
          a_prev_ = s0_.a;
          h_prev_ = h;
          commit();
          return step_outcome::accepted;
        }
        if (k >= nw.itr) break;
        for (int i = 0; i < ne; ++i) rhs_[static_cast<std::size_t>(i)] = -asm_.residual()(asm_.dof_of(i));
        solver_.factorize(asm_.values());
        ++stats_.factorizations;
        solver_.solve(rhs_);
        ++stats_.newton_iterations;
        correction_ok = true;
        roundoff = true;
        bool finite = true;
        for (int i = 0; i < ne; ++i) {
          const auto d = asm_.dof_of(i);
          const double dv = rhs_[static_cast<std::size_t>(i)];
          finite = finite && std::isfinite(dv);
          s_.v(d) += dv;
          correction_ok = correction_ok && std::abs(dv) <= nw.dabsu * scale[static_cast<std::size_t>(d)].potential +
                                                               nw.drltu * std::abs(s_.v(d));
          roundoff = roundoff && std::abs(dv) <= 64 * std::numeric_limits<double>::epsilon() *
                                                     (std::abs(s_.v(d)) + std::abs(s0_.v(d)) +
                                                      h * (std::abs(s_.a(d)) + std::abs(s0_.a(d))));
          scheme_.complete(s0_.u(d), s0_.v(d), s0_.a(d), s0_.p(d), h, s_.v(d), s_.u(d), s_.a(d), s_.p(d));
        }
        if (!finite) break;
      }
    } catch (const error& e) {
      if (e.code() != error_code::singular_situation && e.code() != error_code::singular_matrix) throw;
      last_failure_ = e;
    }
    s_ = s0_;
    t_ = t0;
    return step_outcome::failed;
  }

  /// Local error test of a converged step (PRADIS's velocity-based estimate).
  /// First-order schemes (Stoermer, Newmark with gamma != 1/2): predictor
  /// v_p = v_n + h a_n (PREDICT: with a linearly extrapolated), lp = |v_p - v|/2.
  /// Second-order schemes: lp = h |beta - 1/6| |a_{n+1} - a_n|, the displacement
  /// error estimate of the Newmark family per unit step (velocity units, O(h^2)
  /// like PRADIS's). Per DOF lp <= DABSX + DRLTX |v|; r = min tolerance / lp;
  /// next step c h r (r < 1/4), c h sqrt(r) (r <= 7), c h r^(1/4), c = 0.8.
  /// Sets h_error_; returns false (redo with h_error_) when the test fails and
  /// the step is above SMIN and CONTROL; throws step_too_small when the step
  /// needed is below SMIN, naming the DOF and the time.
  bool error_accepts(double h) {
    const alpha_parameters& q = scheme_.coefficients_set();
    const bool second = std::abs(q.gamma - 0.5 - (q.alpha_f - q.alpha_m)) < 1e-12;
    double r = std::numeric_limits<double>::infinity(), worst_lp = 0, worst_tol = 0;
    int worst = -1;
    for (int i = 0; i < asm_.equations(); ++i) {
      const auto d = asm_.dof_of(i);
      double lp;
      if (second) {
        lp = h * std::abs(q.beta - 1.0 / 6.0) * std::abs(s_.a(d) - s0_.a(d));
      } else {
        double ap = s0_.a(d);
        if (opt_.predict && h_prev_ > 0 && a_prev_.size() == s0_.a.size()) ap += (s0_.a(d) - a_prev_(d)) * h / h_prev_;
        lp = 0.5 * std::abs(s0_.v(d) + h * ap - s_.v(d));
      }
      const double tol = opt_.dabsx * m_.scales()[static_cast<std::size_t>(d)].potential + opt_.drltx * std::abs(s_.v(d));
      if (lp > 0 && tol / lp < r) {
        r = tol / lp;
        worst = d;
        worst_lp = lp;
        worst_tol = tol;
      }
    }
    constexpr double c = 0.8;
    const double f = r < 0.25 ? r : (r <= 7.0 ? std::sqrt(r) : std::pow(r, 0.25));
    const double floor = std::max(opt_.smin, opt_.control);
    h_error_ = std::clamp(std::isfinite(f) ? c * h * f : opt_.smax, std::min(floor, opt_.smax), opt_.smax);
    stats_.limiting_dof = worst;
    if (r >= 1.0) return true;
    if (h <= floor * (1 + 1e-12)) {
      if (opt_.control > opt_.smin) return true;  // CONTROL: accept at the floor
      error e(error_code::step_too_small,
              "SMIN cannot reach the requested accuracy: local error " + num(worst_lp) + " above tolerance " +
                  num(worst_tol) + " on DOF '" + m_.dof_name(worst) + "' at t = " + num(t_) + " with step " + num(h),
              {}, {}, worst);
      log_.write(e);
      throw e;
    }
    return false;
  }

  [[noreturn]] void fail_at_smin(double h) {
    if (last_failure_) {
      if (last_failure_->code() == error_code::singular_matrix) rethrow_singular(*last_failure_);
      error e(last_failure_->code(),
              last_failure_->message() + " (persists at SMIN = " + num(opt_.smin) + ", t = " + num(t_) + ")",
              last_failure_->element_type(), last_failure_->instance(), last_failure_->dof());
      log_.write(e);
      throw e;
    }
    // Name the DOF with the largest residual at the last attempt.
    int worst = -1;
    double wr = -1;
    for (int i = 0; i < asm_.equations(); ++i) {
      const double r = std::abs(asm_.residual()(asm_.dof_of(i)));
      if (!(r <= wr)) {
        wr = r;
        worst = asm_.dof_of(i);
      }
    }
    error e(error_code::newton_failure,
            "Newton does not converge at SMIN: step " + num(h) + " at t = " + num(t_) +
                (worst >= 0 ? "; largest residual " + num(wr) + " on DOF '" + m_.dof_name(worst) + "'" : ""),
            {}, {}, worst);
    log_.write(e);
    throw e;
  }

  void grow() {
    if (h_nominal_ < opt_.smax && ++successes_ >= 3) {
      h_nominal_ = std::min(2 * h_nominal_, opt_.smax);
      successes_ = 0;
    }
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

  void notify() {
    for (auto& f : observers_) f(*this);
  }

  model_type& m_;
  Scheme scheme_;
  Solver solver_;
  assembler<model_type> asm_;
  diagnostics log_;
  std::vector<observer> observers_;
  std::vector<observer> step_observers_;
  global_state s_, s0_;
  std::vector<char> prescribed_;
  Eigen::VectorXd dv_;
  std::vector<double> rhs_;
  run_options opt_{};
  run_statistics stats_{};
  std::optional<error> last_failure_;
  double t_ = 0;
  double h_nominal_ = 0;
  double h_error_ = 0;
  double h_prev_ = 0;
  Eigen::VectorXd a_prev_;
  double recommended_ = std::numeric_limits<double>::infinity();
  int successes_ = 0;
  bool started_ = false;
};

/// Deduction guides: `simulation sim(model, newmark{})`.
template <class M, Integrator S>
simulation(M&, S) -> simulation<M, S>;
template <class M>
simulation(M&) -> simulation<M>;

}  // namespace pradis
