#pragma once
/// \file
/// The Element concept, element_traits, the local input/output an element
/// evaluation sees, and the element_context that carries the per-call facts of
/// the PRADIS COMMON blocks (time, step number, NEWINT, the instance name, the
/// work and state vectors, error reporting, the recommended step STEPMD).

#include <Eigen/Core>
#include <array>
#include <concepts>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include "pradis/core/diagnostics.hpp"
#include "pradis/core/error.hpp"
#include "pradis/core/passport.hpp"

namespace pradis {

namespace detail {
template <class...>
inline constexpr bool dependent_false = false;
}

/// Stand-in for a Jacobian block that the passport's ADR/IGN declares absent.
/// Using it does not compile, with one plain sentence.
struct absent_block {
  template <class... A>
  void operator()(A...) const {
    static_assert(detail::dependent_false<A...>,
                  "pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero");
  }
  template <class... A>
  void setZero(A...) const {
    static_assert(detail::dependent_false<A...>,
                  "pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero");
  }
  template <class... A>
  void diagonal(A...) const {
    static_assert(detail::dependent_false<A...>,
                  "pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero");
  }
  template <class T>
  friend void operator<<(const absent_block&, const T&) {
    static_assert(detail::dependent_false<T>,
                  "pradis: this Jacobian block is absent: the element's passport (ADR/IGN) declares it zero");
  }
  static constexpr bool present = false;
};

/// One spatial rotational node of an element: the local index of its q1 among the
/// external DOFs (q2 and q3 follow it) and the local index of its hidden q4 among
/// the internal DOFs (EXT <= q4 < EXT + ENT). A super-element (elements/composite.hpp)
/// may also declare inner nodes whose q1..q3 are internal DOFs placed before their q4:
/// the model then creates a private rotational node for them (q4 at 1, norm equation). An element with rotational nodes
/// declares `static constexpr std::array<pradis::rotation_slot, K> rotation_nodes`;
/// the model then connects the internal slot q4 to the hidden fourth potential of
/// the node whose q1, q2, q3 the element is connected to, shared by every element
/// on that node, instead of giving the element a private internal DOF.
struct rotation_slot {
  int q1 = 0;  ///< local index of q1 (external); q2 = q1 + 1, q3 = q1 + 2
  int q4 = 0;  ///< local index of the hidden q4 (internal)
  friend constexpr bool operator==(const rotation_slot&, const rotation_slot&) = default;
};

/// Whether E declares spatial rotational nodes (`E::rotation_nodes`).
template <class E>
concept HasRotationNodes = requires {
  { E::rotation_nodes.size() } -> std::convertible_to<std::size_t>;
  { E::rotation_nodes[0] } -> std::convertible_to<rotation_slot>;
};

/// The rotational nodes of E (an empty array if it declares none).
template <class E>
constexpr auto rotation_slots_of() {
  if constexpr (HasRotationNodes<E>)
    return E::rotation_nodes;
  else
    return std::array<rotation_slot, 0>{};
}

/// Whether E is inert: `static constexpr bool inert = true` states that its
/// evaluate() writes no flow and no Jacobian entry at any state and has no
/// other effect, as for an initial-condition element, which acts through
/// zero_step() alone. The assembler then skips its instances in every
/// evaluation; the all-elements test checks the claim at random states.
template <class E>
concept InertElement = requires {
  { E::inert } -> std::convertible_to<bool>;
} && E::inert;

/// Whether E's state vector is a guard only: `static constexpr bool state_is_guard = true`
/// states that OLD enters neither the flows nor the Jacobian (it may only stop a step, as a
/// singular situation), and that NEW is a function of the current potentials alone (e.g.
/// LINKX's direction, which detects a passage through zero length). NEW may then come from
/// the last Newton evaluation of an accepted step, within the Newton tolerance of the
/// converged state: the BDF driver skips its evaluation at the converged state when every
/// instance with a state vector is of such a type. The all-elements test checks the claim.
template <class E>
concept GuardStateElement = requires {
  { E::state_is_guard } -> std::convertible_to<bool>;
} && E::state_is_guard;

/// Whether E says if its flows turn with its rotational nodes: an optional
/// member `bool body_fixed_flows() const`. True states that on every rotational
/// slot the element's moments are R(q) times a function of the body angular
/// velocity and acceleration (and of t) alone, with no entry in other DOFs' rows
/// or columns that depends on the node: as for a rigid body whose centre of mass
/// is its reference point, a body-fixed torque, or an element with no flow. The
/// BDF driver then keeps the Newton matrix of a node whose every element says so
/// in the node's body frame (docs/bdf.md, "Newton"). Without the member: false.
template <class E>
concept HasBodyFixedFlows = requires(const E& e) {
  { e.body_fixed_flows() } -> std::convertible_to<bool>;
};

/// e.body_fixed_flows() if E declares it, else false.
template <class E>
bool body_fixed_flows_of(const E& e) {
  if constexpr (HasBodyFixedFlows<E>)
    return static_cast<bool>(e.body_fixed_flows());
  else
    return false;
}

/// Whether E says which of its local Jacobian entries can be nonzero for its
/// parameters: an optional member `bool jacobian_entry(int r, int c) const` (flow
/// r, DOF c, 0-based local indices). The assembler leaves the other entries out
/// of the Newton matrix's sparsity pattern and never visits them (the diagonal is
/// always kept), so that, e.g., a rigid body with its centre of mass on its
/// reference point factorises its translation apart from its rotation. The
/// claim must hold in every block (K, C, M) at every state: the finite-difference
/// checker (testing/jacobian_check.hpp) fails an entry outside it that is not
/// zero. Without the member: every entry.
template <class E>
concept HasJacobianStructure = requires(const E& e, int r, int c) {
  { e.jacobian_entry(r, c) } -> std::convertible_to<bool>;
};

/// Whether the assembler keeps the local Jacobian entry (r, c) of e: the diagonal
/// always, the others as e.jacobian_entry(r, c) says if E declares it, else all.
template <class E>
bool jacobian_entry_of(const E& e, int r, int c) {
  if constexpr (HasJacobianStructure<E>)
    return r == c || static_cast<bool>(e.jacobian_entry(r, c));
  else
    return true;
}

/// Checks the rotational-node declaration of an element with EXT = ext and ENT = ent;
/// nullptr when valid, otherwise one sentence.
template <std::size_t K>
constexpr const char* rotation_slots_problem(const std::array<rotation_slot, K>& r, int ext, int ent) noexcept {
  for (std::size_t i = 0; i < K; ++i) {
    if (r[i].q4 < ext || r[i].q4 >= ext + ent) return "a rotational node's q4 must be an internal DOF (EXT <= q4 < EXT + ENT)";
    const bool external = r[i].q1 >= 0 && r[i].q1 + 2 < ext;
    const bool inner = r[i].q1 >= ext && r[i].q1 + 2 < r[i].q4;
    if (!external && !inner)
      return "a rotational node's q1..q3 must be external DOFs (q1 + 2 < EXT), or internal DOFs before its q4 (an "
             "inner node of a super-element)";
    for (std::size_t j = 0; j < K; ++j) {
      if (j < i && r[i].q4 == r[j].q4) return "two rotational nodes share the same q4 slot";
      if (j < i && r[i].q1 < r[j].q1 + 3 && r[j].q1 < r[i].q1 + 3) return "two rotational nodes overlap in their q1..q3 slots";
      if (r[j].q4 >= r[i].q1 && r[j].q4 < r[i].q1 + 3) return "a rotational node's q4 slot lies among another node's q1..q3";
    }
  }
  return nullptr;
}

/// Reads the passport and derived compile-time facts of an element type.
/// Specialise it to adapt a third-party type whose passport lives elsewhere.
template <class E>
struct element_traits {
  /// The passport.
  static constexpr passport pass = E::passport;
  /// Local DOF count N = EXT + ENT.
  static constexpr int n = pass.dofs();
  static constexpr int ext = pass.ext;
  static constexpr int ent = pass.ent;
  static constexpr bool has_k = pass.has_k();
  static constexpr bool has_c = pass.has_c();
  static constexpr bool has_m = pass.has_m();
  /// Local vector type (fixed size, never allocates).
  using vector = Eigen::Matrix<double, n, 1>;
  /// Local square matrix type.
  using matrix = Eigen::Matrix<double, n, n, (n == 1 ? Eigen::ColMajor : Eigen::RowMajor)>;
  using k_block = std::conditional_t<has_k, matrix, absent_block>;
  using c_block = std::conditional_t<has_c, matrix, absent_block>;
  using m_block = std::conditional_t<has_m, matrix, absent_block>;
  /// The element's spatial rotational nodes (see rotation_slot); empty for most elements.
  static constexpr auto rotation_nodes = rotation_slots_of<E>();
  /// Number of spatial rotational nodes.
  static constexpr int rotations = static_cast<int>(rotation_nodes.size());
};

/// Potentials an element sees at one evaluation: displacement u, velocity v and
/// acceleration a of each local DOF (external first, then internal), and time.
/// (The manual's ADR=2/3 shorten the input arrays; here all three are passed and
/// an ADR=2 element simply does not read u: typed access replaces array shifts.)
template <class E>
struct local_input {
  using vector = typename element_traits<E>::vector;
  vector u = vector::Zero();
  vector v = vector::Zero();
  vector a = vector::Zero();
  double t = 0.0;
};

/// What an element evaluation writes: its flows f (the forces the SYSTEM applies
/// TO the element; zero with no external action) and the Jacobian blocks its
/// passport declares. Absent blocks are of type absent_block and cannot be written.
/// `want_jacobian` is false when the caller needs the flows only (the zero step,
/// the iterations on a kept Jacobian): an element may then skip its blocks. The
/// assembler hands the blocks over zeroed only when it is true (so an element may
/// add to them; a super-element does the same for its parts: clear()), and reads
/// them only then, so an element must never compute its flows from its own blocks.
template <class E>
struct local_output {
  using traits = element_traits<E>;
  typename traits::vector f = traits::vector::Zero();
  [[no_unique_address]] typename traits::k_block K{};
  [[no_unique_address]] typename traits::c_block C{};
  [[no_unique_address]] typename traits::m_block M{};
  bool want_jacobian = true;

  /// Sets the flows and every present block to zero.
  void clear() {
    f.setZero();
    if constexpr (traits::has_k) K.setZero();
    if constexpr (traits::has_c) C.setZero();
    if constexpr (traits::has_m) M.setZero();
  }
};

/// The phase of the run in which an element is called.
enum class phase { zero_step, new_integration, step };

/// Per-call facts and services for an element: the role of the PRADIS COMMON
/// blocks. The kernel fills one per call; the FD checker and tests can make
/// their own.
class element_context {
 public:
  /// A context without identity or diagnostics log (tests, tools).
  element_context() = default;
  /// A context for the element type `type` (its passport name) and instance `instance`;
  /// warnings and errors also go to `log` if given. Both views must outlive the context.
  element_context(std::string_view type, std::string_view instance, diagnostics* log = nullptr)
      : type_(type), instance_(instance), log_(log) {}

  // ---- facts of the run -------------------------------------------------
  double time = 0.0;       ///< current time (TIME)
  double step = 0.0;       ///< current step (STEP); elements must not use it for flows
  long nstep = 0;          ///< step number (NSTEP); 0 at the zero step
  int niter = 0;           ///< Newton iteration within the step (NITER)
  bool newint = false;     ///< true in the first call after a new integration stage (NEWINT)
  int npar = 0;            ///< actual parameter count (PAR(0))

  /// The instance's work vector (WRK/WRP); per instance, kept between calls.
  std::span<double> work{};
  /// The instance's state vector of the last accepted step (OLD).
  std::span<const double> old_state{};
  /// The instance's state vector being computed (NEW); copied to OLD on acceptance.
  std::span<double> new_state{};

  // ---- identity ----------------------------------------------------------
  /// The element type (passport name) that errors and warnings are reported for.
  std::string_view element_type() const noexcept { return type_; }
  /// The instance name that errors and warnings are reported for.
  std::string_view instance() const noexcept { return instance_; }
  /// Sets the type and instance of the next calls (the views must outlive their use).
  void set_identity(std::string_view type, std::string_view instance) noexcept {
    type_ = type;
    instance_ = instance;
  }
  /// Sets the diagnostics log that fail() and warn() write to (nullptr: none).
  void set_diagnostics(diagnostics* log) noexcept { log_ = log; }

  // ---- services ------------------------------------------------------------
  /// Reports an error (codes 100, 75, ...): writes it to the diagnostics log
  /// unless muted, then throws pradis::error with this element's type and instance.
  [[noreturn]] void fail(error_code code, const std::string& message) const {
    error e(code, message, std::string(type_), std::string(instance_));
    if (log_ && muted_ == 0) log_->write(e);
    throw e;
  }
  /// Shorthand for fail(error_code::invalid_parameter, message).
  [[noreturn]] void invalid_parameter(const std::string& message) const {
    fail(error_code::invalid_parameter, message);
  }
  /// Shorthand for fail(error_code::singular_situation, message): the integrator
  /// treats it as a failed step and reports it if it persists at SMIN.
  [[noreturn]] void singular(const std::string& message) const {
    fail(error_code::singular_situation, message);
  }
  /// Writes a warning line to the diagnostics log unless muted.
  void warn(std::string_view message) const {
    if (log_ && muted_ == 0)
      log_->write(std::string(type_) + " '" + std::string(instance_) + "': " + std::string(message));
  }
  /// Recommends a maximum step (STEPMD). The smallest recommendation of a step
  /// bounds the next step unless the user sets IGNORE.
  void recommend_step(double h) noexcept {
    if (h > 0 && h < recommended_step) recommended_step = h;
  }
  /// Smallest step recommended since the kernel last reset it (infinity if none).
  double recommended_step = std::numeric_limits<double>::infinity();

  /// Mutes diagnostics (the SYSPRN = 0 of a super-element calling a sub-model)
  /// while alive; errors are still thrown.
  class mute_guard {
   public:
    explicit mute_guard(element_context& c) : c_(c) { ++c_.muted_; }
    ~mute_guard() { --c_.muted_; }
    mute_guard(const mute_guard&) = delete;
    mute_guard& operator=(const mute_guard&) = delete;

   private:
    element_context& c_;
  };
  /// Whether a mute_guard is alive (diagnostics are not written).
  bool muted() const noexcept { return muted_ > 0; }

 private:
  std::string_view type_{};
  std::string_view instance_{};
  diagnostics* log_ = nullptr;
  int muted_ = 0;
};

/// Kinematics a source element prescribes on its DOF at a time.
struct kinematics {
  double u = 0, v = 0, a = 0;  ///< displacement, velocity and acceleration
};

/// Initial values an element may set at the zero step (initial-condition elements).
/// The kernel detects conflicts: setting a DOF already set to another value by a
/// different element raises code 90.
template <int N>
class initial_values {
 public:
  /// Requests the initial displacement of local DOF k.
  void set_displacement(int k, double value) { u_[k] = value; has_u_[k] = true; }
  /// Requests the initial velocity of local DOF k.
  void set_velocity(int k, double value) { v_[k] = value; has_v_[k] = true; }
  /// Whether an initial displacement of local DOF k was requested.
  bool has_displacement(int k) const { return has_u_[k]; }
  /// Whether an initial velocity of local DOF k was requested.
  bool has_velocity(int k) const { return has_v_[k]; }
  /// The requested initial displacement of local DOF k (0 if none).
  double displacement(int k) const { return u_[k]; }
  /// The requested initial velocity of local DOF k (0 if none).
  double velocity(int k) const { return v_[k]; }

 private:
  double u_[N]{};
  double v_[N]{};
  bool has_u_[N]{};
  bool has_v_[N]{};
};

// ---------------------------------------------------------------------------
// Concepts
// ---------------------------------------------------------------------------

/// A type that carries `static constexpr pradis::passport passport`.
template <class E>
concept HasPassport = requires {
  { E::passport } -> std::convertible_to<passport>;
};

/// A type that carries `static constexpr pradis::element_help help`.
template <class E>
concept HasHelp = requires {
  { E::help } -> std::convertible_to<element_help>;
};

/// Whether the passport of E is valid (usable in constant expressions).
template <class E>
inline constexpr bool valid_passport = passport_problem(E::passport) == nullptr;

/// An element type: passport, help, a `parameters` aggregate, construction from
/// that aggregate and from the flat PAR vector, and an evaluation
/// `void evaluate(const local_input<E>&, local_output<E>&, element_context&) const`.
/// Optional hooks, detected with `requires`: `new_integration(element_context&)`
/// (NEWINT work: checks, code 100, precomputation into the work vector),
/// `zero_step(initial_values<N>&, element_context&)` (initial conditions),
/// `commit(element_context&)` (after an accepted step), and
/// `kinematics motion(double t) const` for sources that prescribe their DOF.
template <class E>
concept Element = HasPassport<E> && HasHelp<E> && valid_passport<E> && std::is_class_v<typename E::parameters> &&
                  std::constructible_from<E, typename E::parameters> &&
                  requires(std::span<const double> flat) {
                    { E::from_parameters(flat) } -> std::same_as<E>;
                  } &&
                  requires(const E& e, const local_input<E>& in, local_output<E>& out, element_context& ctx) {
                    e.evaluate(in, out, ctx);
                  };

/// Whether E has the NEWINT hook.
template <class E>
concept HasNewIntegration = requires(E& e, element_context& ctx) { e.new_integration(ctx); };
/// Whether E sets initial values at the zero step.
template <class E>
concept HasZeroStep =
    requires(E& e, initial_values<element_traits<E>::n>& iv, element_context& ctx) { e.zero_step(iv, ctx); };
/// Whether E prescribes the motion of its (single) DOF: a kinematic source.
template <class E>
concept PrescribesMotion = requires(const E& e, double t) {
  { e.motion(t) } -> std::same_as<kinematics>;
};

/// Checks E step by step and stops compilation with one plain sentence at the
/// first thing that is wrong. Call as `static_assert(pradis::check_element<E>())`.
template <class E>
consteval bool check_element() {
  static_assert(HasPassport<E>,
                "pradis: an element type needs `static constexpr pradis::passport passport = {...};`");
  if constexpr (HasPassport<E>) {
    constexpr passport p = E::passport;
    static_assert(!p.name.empty(), "pradis: the element passport has no catalog name");
    static_assert(p.ext > 0, "pradis: passport EXT must be > 0 (an element needs external DOFs)");
    static_assert(p.ent >= 0, "pradis: passport ENT must be >= 0");
    static_assert(p.par >= 0, "pradis: passport PAR must be >= 0");
    static_assert(p.vpr == 0 || p.vpr == 1 || p.vpr == 11 || p.vpr == 21, "pradis: passport VPR must be 0, 1, 11 or 21");
    static_assert(p.str >= 0 && p.stp >= 0 && p.wrk >= 0 && p.wrp >= 0,
                  "pradis: passport STR, STP, WRK and WRP must be >= 0");
    static_assert(p.vpr != 0 || (p.stp == 0 && p.wrp == 0),
                  "pradis: passport STP and WRP need a variable parameter count (VPR != 0)");
    static_assert(p.adr >= 1 && p.adr <= 3, "pradis: passport ADR must be 1, 2 or 3");
    static_assert(p.ign == 0 || p.ign == 2 || p.ign == 3 || p.ign == 23, "pradis: passport IGN must be 0, 2, 3 or 23");
    static_assert(!(p.adr == 2 && (p.ign == 2 || p.ign == 23)), "pradis: passport ADR=2 allows IGN=0 or IGN=3 only");
    static_assert(!(p.adr == 3 && p.ign != 0), "pradis: passport ADR=3 allows IGN=0 only");
    if constexpr (HasRotationNodes<E>)
      static_assert(rotation_slots_problem(E::rotation_nodes, p.ext, p.ent) == nullptr,
                    "pradis: invalid rotation_nodes: q1..q3 must be external DOFs (or internal ones before q4), q4 an internal "
                    "DOF, no overlaps");
  }
  static_assert(HasHelp<E>, "pradis: an element type needs `static constexpr pradis::element_help help = {...};`");
  static_assert(requires { typename E::parameters; },
                "pradis: an element type needs a nested aggregate `parameters` (its PAR vector, typed)");
  static_assert(requires(std::span<const double> s) { E::from_parameters(s); },
                "pradis: an element type needs `static E from_parameters(std::span<const double>)` (the flat PAR vector)");
  static_assert(requires(const E& e, const local_input<E>& in, local_output<E>& out, element_context& ctx) {
                  e.evaluate(in, out, ctx);
                },
                "pradis: an element type needs `void evaluate(const local_input<E>&, local_output<E>&, "
                "element_context&) const`");
  return Element<E>;
}

}  // namespace pradis
