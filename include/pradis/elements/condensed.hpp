#pragma once
/// \file
/// Condensed super-elements: a composite whose internal DOFs are eliminated inside the element by nonlinear
/// static condensation, so that the model sees only its external DOFs (and the hidden q4 slots of its external
/// rotational nodes). Every call solves the internal equations F_I(u_R, u_I) = 0 for u_I by Newton iterations on the
/// parts and returns the condensed flows and the Schur-complement Jacobian. The condensed DOFs must be quasi-static: no
/// part may put mass or damping on them. docs/super-elements.md.

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "pradis/core/element.hpp"
#include "pradis/elements/composite.hpp"

namespace pradis {

namespace condensed_detail {

/// Which DOFs of the underlying composite are kept (its external DOFs and the hidden q4 slots of its external
/// rotational nodes, in increasing order) and which are condensed (the other internal DOFs, the q1..q4 of inner
/// rotational nodes included); `pos[k]` is composite DOF k's index among the kept or among the condensed ones. `inner`
/// lists, per inner rotational node (q1..q3 internal), the composite DOFs of its q1, q2, q3, q4.
struct layout {
  std::array<int, 512> kept{}, cond{}, pos{};
  std::array<std::array<int, 4>, 64> inner{};
  int nr = 0, ni = 0, n_inner = 0, n_outer = 0;
};

template <class Full>
constexpr layout layout_of(int ext) {
  layout l;
  std::array<bool, 512> q4{};
  for (const rotation_slot& s : Full::rotation_nodes) {
    if (s.q1 >= ext)
      l.inner[static_cast<std::size_t>(l.n_inner++)] = {s.q1, s.q1 + 1, s.q1 + 2, s.q4};
    else {
      q4[static_cast<std::size_t>(s.q4)] = true;
      ++l.n_outer;
    }
  }
  for (int k = 0; k < element_traits<Full>::n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (k < ext || q4[kk]) {
      l.pos[kk] = l.nr;
      l.kept[static_cast<std::size_t>(l.nr++)] = k;
    } else {
      l.pos[kk] = l.ni;
      l.cond[static_cast<std::size_t>(l.ni++)] = k;
    }
  }
  return l;
}

}  // namespace condensed_detail

/// A super-element made of the parts Ps (each a `part<E, map...>`, as for `composite`) whose internal DOFs are
/// condensed: Spec is the one of `composite<Spec, Ps...>` (name, title, ext, ent: the DOFs of the parts' assembly;
/// optionally labels, field, special, example()). The condensed element has EXT = Spec::ext external DOFs and keeps as
/// internal DOFs only the hidden q4 slots of its external rotational nodes.
///
/// Each evaluation solves F_I(u_R, u_I, t) = 0 for the condensed DOFs u_I by Newton iterations, starting from their
/// values at the last accepted step (the state vector; zero at the start), until the correction is below 1e-10 of the
/// largest displacement; it returns f_R - K_RI K_II^-1 f_I and the blocks K_RR - K_RI K_II^-1 K_IR, C_RR - K_RI K_II^-1
/// C_IR, M_RR - K_RI K_II^-1 M_IR. For linear parts this is Guyan (static) condensation. Requirements, checked: a
/// stiffness block (K) and, at run time, no mass or damping on a condensed DOF (code 100). An inner rotational node
/// (q1..q3 internal) is condensed with its hidden q4: the element adds the node's norm equation |q| = 1 on the q4 row
/// (norm_rows) and starts the node at the identity. The parts' admissibility tests (which states the Jacobian checks may
/// use) are applied at the condensed state (admissible()).
template <class Spec, class... Ps>
struct condensed {
  /// The composite the condensation works on (its DOFs: Spec::ext external, Spec::ent internal).
  using full_type = composite<Spec, Ps...>;
  using full_traits = element_traits<full_type>;

 private:
  static constexpr condensed_detail::layout lay_ = condensed_detail::layout_of<full_type>(Spec::ext);
  static_assert(lay_.ni > 0,
                "pradis: a condensed composite needs internal DOFs to condense (ENT beyond the hidden q4 slots); with "
                "none, use pradis::composite");
  static_assert(full_traits::has_k, "pradis: a condensed composite needs a stiffness block (K) in some part");

 public:
  /// Number of kept DOFs (EXT + kept q4 slots) and of condensed DOFs.
  static constexpr int kept_count = lay_.nr;
  static constexpr int condensed_count = lay_.ni;
  /// The composite DOF of each kept and each condensed DOF.
  static constexpr auto kept_dofs = [] {
    std::array<int, static_cast<std::size_t>(lay_.nr)> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = lay_.kept[i];
    return a;
  }();
  static constexpr auto condensed_dofs = [] {
    std::array<int, static_cast<std::size_t>(lay_.ni)> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = lay_.cond[i];
    return a;
  }();
  /// Newton iterations allowed per call; the correction test, relative to the largest displacement.
  static constexpr int max_iterations = 30;
  static constexpr double tolerance = 1e-10;
  /// Halvings of a Newton step allowed in its line search.
  static constexpr int max_halvings = 10;
  /// Index in the state vector of the first condensed displacement (after the parts' states), and in the work vector of
  /// W(iterations of the last call), then W(iterations in all).
  static constexpr int state_at = full_type::passport.str;
  static constexpr int work_at = full_type::passport.wrk;

  static constexpr pradis::passport passport{.name = Spec::name,
                                             .ext = Spec::ext,
                                             .ent = lay_.nr - Spec::ext,
                                             .par = full_type::passport.par,
                                             .str = full_type::passport.str + lay_.ni,
                                             .wrk = full_type::passport.wrk + 2,
                                             .adr = full_type::passport.adr,
                                             .ign = full_type::passport.ign};
  /// The domains of the kept DOFs.
  static constexpr auto domains = [] {
    std::array<domain, static_cast<std::size_t>(lay_.nr)> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = full_type::domains[static_cast<std::size_t>(lay_.kept[i])];
    return a;
  }();
  /// The external rotational nodes, their q4 slots renumbered among the kept DOFs (inner nodes are condensed).
  static constexpr auto rotation_nodes = [] {
    std::array<rotation_slot, static_cast<std::size_t>(lay_.n_outer)> a{};
    std::size_t n = 0;
    for (const rotation_slot& s : full_type::rotation_nodes)
      if (s.q1 < Spec::ext) a[n++] = {s.q1, lay_.pos[static_cast<std::size_t>(s.q4)]};
    return a;
  }();
  /// Number of inner rotational nodes (q1..q3 internal), condensed with their q4.
  static constexpr int inner_rotation_nodes = lay_.n_inner;
  /// The node kinds the parts declare (composite::node_kinds). Their nodes are added to the
  /// model (model::add_node) on its DOFs, which the condensed DOFs are not.
  using node_kinds = typename full_type::node_kinds;

 private:
  struct name_f {
    constexpr composite_detail::text operator()() const {
      // Built from the parts' texts again, not from full_type::help: reading a text_storage array in a constant
      // expression is refused by GCC under -fsanitize=address,undefined (its null-pointer check).
      return "Condensed s" + composite_detail::name_text<Ps...>().substr(1) +
             " Internal DOFs eliminated by static condensation: " + composite_detail::number(lay_.ni) + ".";
    }
  };
  struct work_f {
    constexpr composite_detail::text operator()() const {
      const int k = full_type::passport.wrk;
      return composite_detail::work_text<Spec, Ps...>() + "\n" + composite_detail::number(k + 1) +
             " - Newton iterations on the condensed DOFs in the last call [-]\n" + composite_detail::number(k + 2) +
             " - Newton iterations on the condensed DOFs in all calls [-]";
    }
  };
  static constexpr std::string_view special_() {
    if constexpr (requires { Spec::special; })
      return Spec::special;
    else
      return "a condensed DOF with mass or damping from a part is code 100 (keep it with a composite); a singular "
             "stiffness of the condensed DOFs, or no convergence of their Newton iterations in 30 steps, is code 75 "
             "(the step is cut); an error of a part is reported with its code, naming the part";
  }

 public:
  static constexpr element_help help{.title = Spec::title,
                                     .name = composite_detail::text_storage<name_f>::view,
                                     .field = full_type::help.field,
                                     .dofs = full_type::help.dofs,
                                     .parameters = full_type::help.parameters,
                                     .work = composite_detail::text_storage<work_f>::view,
                                     .special = special_()};

  /// Typed parameters: those of the composite (one aggregate per part).
  using parameters = typename full_type::parameters;

  explicit condensed(parameters q) : full_(std::move(q)) {}
  /// Condenses the internal DOFs of a composite object.
  explicit condensed(full_type f) : full_(std::move(f)) {}
  static condensed from_parameters(std::span<const double> v) { return condensed(full_type::from_parameters(v)); }
  static parameters example() requires(requires { full_type::example(); }) { return full_type::example(); }

  /// The composite whose internal DOFs are condensed.
  const full_type& full() const noexcept { return full_; }

  /// NEWINT of every part.
  void new_integration(element_context& ctx) { full_.new_integration(ctx); }

  /// The condensed flows and blocks (see the type's description).
  void evaluate(const local_input<condensed>& in, local_output<condensed>& out, element_context& ctx) const {
    local_input<full_type> fin = full_input(in);
    // The start: the condensed DOFs of the last accepted step, so that a call is a function of its input and the
    // accepted state alone (not of the calls before it in the step).
    const bool stored = ctx.new_state.size() >= static_cast<std::size_t>(state_at + ni) &&
                        ctx.old_state.size() >= static_cast<std::size_t>(state_at + ni);
    for (int j = 0; j < ni; ++j) fin.u(cond(j)) = stored ? ctx.old_state[static_cast<std::size_t>(state_at + j)] : 0.0;
    local_output<full_type> fo;
    Eigen::PartialPivLU<mat_ii> lu;
    vec_i du = vec_i::Zero();
    const int it = condense(fin, fo, lu, du, ctx);
    if (stored)
      for (int j = 0; j < ni; ++j) ctx.new_state[static_cast<std::size_t>(state_at + j)] = fin.u(cond(j));
    if (ctx.work.size() >= static_cast<std::size_t>(work_at + 2)) {
      ctx.work[static_cast<std::size_t>(work_at)] = it;
      ctx.work[static_cast<std::size_t>(work_at + 1)] += it;
    }
    // The last evaluation was at u_I - du: its flows corrected to first order (f_R + K_RI du; f_I + K_II du = 0).
    for (int r = 0; r < nr; ++r) {
      double f = fo.f(kept(r));
      for (int j = 0; j < ni; ++j) f += fo.K(kept(r), cond(j)) * du(j);
      out.f(r) = f;
    }
    if (!out.want_jacobian) return;
    mat_ri k_ri;
    for (int r = 0; r < nr; ++r)
      for (int j = 0; j < ni; ++j) k_ri(r, j) = fo.K(kept(r), cond(j));
    if constexpr (full_traits::has_k) schur(fo.K, k_ri, lu, out.K);
    if constexpr (full_traits::has_c) schur(fo.C, k_ri, lu, out.C);
    if constexpr (full_traits::has_m) schur(fo.M, k_ri, lu, out.M);
  }

  /// States the parts' admissibility tests admit (which states the Jacobian checks may use), tested at the condensed
  /// state: the condensation is solved from the start a model's first call uses (the condensed DOFs at zero, inner
  /// rotational nodes at the identity). A state at which it fails (singular, not converging, a part's error) or needs
  /// more than a third of the iterations allowed is not admissible: far from that start the damped iterations' path
  /// is sensitive (measured on BEAM3C at the all-elements test's random states: every state that converged within 10
  /// iterations passed the finite-difference check; from 11 on, some neighbouring states did not converge in 30).
  bool admissible(const local_input<condensed>& in) const requires(composite_detail::has_admissible<full_type>) {
    local_input<full_type> fin = full_input(in);
    for (int j = 0; j < ni; ++j) fin.u(cond(j)) = 0.0;
    std::vector<double> work(static_cast<std::size_t>(full_type::passport.wrk), 0.0),
        old_state(static_cast<std::size_t>(full_type::passport.str), 0.0), new_state(old_state);
    element_context ctx(Spec::name, "admissibility test");
    ctx.work = work;
    ctx.old_state = old_state;
    ctx.new_state = new_state;
    ctx.npar = passport.par;
    local_output<full_type> fo;
    Eigen::PartialPivLU<mat_ii> lu;
    vec_i du = vec_i::Zero();
    try {
      if (condense(fin, fo, lu, du, ctx) > max_iterations / 3) return false;
    } catch (const error&) {
      return false;
    }
    return full_.admissible(fin);
  }

  /// Initial values the parts request on kept DOFs; a request on a condensed DOF, which the condensation computes, is
  /// code 90.
  void zero_step(initial_values<lay_.nr>& iv,
                 element_context& ctx) requires(HasZeroStep<full_type>) {
    initial_values<full_traits::n> fiv;
    full_.zero_step(fiv, ctx);
    for (int r = 0; r < nr; ++r) {
      if (fiv.has_displacement(kept(r))) iv.set_displacement(r, fiv.displacement(kept(r)));
      if (fiv.has_velocity(kept(r))) iv.set_velocity(r, fiv.velocity(kept(r)));
    }
    for (int j = 0; j < ni; ++j)
      if (fiv.has_displacement(cond(j)) || fiv.has_velocity(cond(j)))
        ctx.fail(error_code::conflicting_initial, "a part requests an initial value of internal DOF " +
                                                      std::to_string(cond(j) + 1) +
                                                      ", which is condensed: static condensation computes it");
  }

  /// After an accepted step: the parts' commit hooks.
  void commit(element_context& ctx) requires(composite_detail::has_commit<full_type>) { full_.commit(ctx); }

 private:
  static constexpr int nr = lay_.nr;
  static constexpr int ni = lay_.ni;
  using mat_ii = Eigen::Matrix<double, ni, ni>;
  using vec_i = Eigen::Matrix<double, ni, 1>;
  using mat_ri = Eigen::Matrix<double, nr, ni>;
  static constexpr int kept(int r) { return lay_.kept[static_cast<std::size_t>(r)]; }
  static constexpr int cond(int j) { return lay_.cond[static_cast<std::size_t>(j)]; }
  /// The composite's input with the kept DOFs from `in` (the condensed ones still to be set).
  static local_input<full_type> full_input(const local_input<condensed>& in) {
    local_input<full_type> fin;
    for (int r = 0; r < nr; ++r) {
      const int k = kept(r);
      fin.u(k) = in.u(r);
      fin.v(k) = in.v(r);
      fin.a(k) = in.a(r);
    }
    fin.t = in.t;
    return fin;
  }

  /// Newton iterations on the condensed DOFs of fin (started from their values there) until F_I = 0: fo holds the
  /// composite's flows and blocks at the last evaluation, which was at fin's condensed DOFs minus du; lu is K_II's
  /// factorisation there. Returns the number of Newton iterations (line-search trials not counted).
  ///
  /// Each Newton step du is damped by backtracking (halving it up to `max_halvings` times) until the natural
  /// monotonicity test passes: the simplified Newton correction at the trial, K_II^-1 F_I with the factorisation of the
  /// step's start, is shorter than (1 - lambda / 4) |du|. Unlike |F_I|, this test does not depend on the units or
  /// scales of the residual's rows (forces, moments, the norm rows). A trial state at which a part reports a singular
  /// situation (code 75) fails the test. Near the root the full step passes at once, so the line search costs one
  /// back-substitution there; far from it (the external nodes moved far since the last accepted step) it keeps the
  /// iterates from diverging.
  /// Eigen's estimate of the reciprocal condition number of lu, out of line: inlined into the element's
  /// callers, GCC 12 (-O2) took the estimator's sign vector (ConditionEstimator.h, old_sign_vector, which
  /// Eigen assigns before it reads it) for uninitialised (-Wmaybe-uninitialized, in bench_kernel.cpp).
  [[gnu::noinline]] static double reciprocal_condition(const Eigen::PartialPivLU<mat_ii>& lu) { return lu.rcond(); }
  int condense(local_input<full_type>& fin, local_output<full_type>& fo, Eigen::PartialPivLU<mat_ii>& lu, vec_i& du,
               element_context& ctx) const {
    start_inner_nodes(fin);
    fo.want_jacobian = true;
    mat_ii kii;
    vec_i ri;
    residual(fin, fo, ri, kii, ctx);
    int it = 1;
    for (;;) {
      lu.compute(kii);
      const double rc = reciprocal_condition(lu);
      if (!(rc > 1e-14))
        ctx.singular("the stiffness of the condensed DOFs is singular (reciprocal condition number " +
                     std::to_string(rc) + "): an internal DOF is held by no stiffness in this state");
      du = -lu.solve(ri);
      double scale = 0;
      for (int k = 0; k < full_traits::n; ++k) scale = std::max(scale, std::abs(fin.u(k)));
      const double step = du.cwiseAbs().maxCoeff();
      if (step <= tolerance * std::max(scale, 1e-8)) {
        for (int j = 0; j < ni; ++j) fin.u(cond(j)) += du(j);
        return it;
      }
      if (it >= max_iterations || !std::isfinite(step))
        ctx.singular("the condensed DOFs did not converge in " + std::to_string(max_iterations) +
                     " Newton iterations (last correction " + std::to_string(step) + ")");
      ++it;
      const double dn = du.norm();
      vec_i base;
      for (int j = 0; j < ni; ++j) base(j) = fin.u(cond(j));
      double lambda = 1;
      for (int h = 0;; ++h) {
        for (int j = 0; j < ni; ++j) fin.u(cond(j)) = base(j) + lambda * du(j);
        bool singular = false;
        try {
          residual(fin, fo, ri, kii, ctx);
        } catch (const error& e) {
          if (e.code() != error_code::singular_situation || h >= max_halvings) throw;
          singular = true;
        }
        // Natural monotonicity: the simplified Newton correction at the trial (with the base point's K_II)
        // shorter than the step's correction.
        if (!singular && (lu.solve(ri).norm() <= (1 - lambda / 4) * dn || h >= max_halvings)) break;
        lambda /= 2;
      }
    }
  }

  /// The residual F_I and the block K_II (with the inner nodes' norm rows) at fin; code 100 for mass or damping on a
  /// condensed DOF, code 150 for a non-finite flow or stiffness.
  void residual(const local_input<full_type>& fin, local_output<full_type>& fo, vec_i& ri, mat_ii& kii,
                element_context& ctx) const {
    full_.evaluate(fin, fo, ctx);
    check_quasi_static(fo, ctx);
    for (int i = 0; i < ni; ++i) {
      ri(i) = fo.f(cond(i));
      for (int j = 0; j < ni; ++j) kii(i, j) = fo.K(cond(i), cond(j));
    }
    norm_rows(fin, ri, kii);
    if (!ri.allFinite() || !kii.allFinite())
      ctx.fail(error_code::non_finite, "a part returned a non-finite flow or stiffness on a condensed DOF");
  }

  /// The condensed index of component c (0..3 for q1..q4) of inner rotational node n.
  static constexpr int inner(int n, int c) {
    return lay_.pos[static_cast<std::size_t>(lay_.inner[static_cast<std::size_t>(n)][static_cast<std::size_t>(c)])];
  }

  /// An inner rotational node without a stored orientation (the first call; the state vector starts at zero) starts
  /// at the identity, q = (0, 0, 0, 1), as the model starts its nodes.
  static void start_inner_nodes(local_input<full_type>& fin) {
    for (int n = 0; n < lay_.n_inner; ++n) {
      double lq2 = 0;
      for (int c = 0; c < 4; ++c) lq2 += fin.u(cond(inner(n, c))) * fin.u(cond(inner(n, c)));
      if (lq2 < 0.25)
        for (int c = 0; c < 4; ++c) fin.u(cond(inner(n, c))) = c == 3 ? 1.0 : 0.0;
    }
  }

  /// The norm equation of each inner rotational node, on its q4 row (on which the parts put no flow): s (Lq - 1) = 0,
  /// Lq = |q|, with the row s q^T / Lq. It is the static counterpart of the model's Mu d(Lq)/dt = 0 and removes the
  /// direction along q, in which the parts' flows do not change, from K_II. Scaling a condensed row changes neither the
  /// root nor the Schur complements (the row has no kept columns); s, the largest stiffness on the node's q1..q3
  /// rows, keeps K_II's conditioning.
  static void norm_rows(const local_input<full_type>& fin, vec_i& ri, mat_ii& kii) {
    for (int n = 0; n < lay_.n_inner; ++n) {
      Eigen::Vector4d q;
      for (int c = 0; c < 4; ++c) q(c) = fin.u(cond(inner(n, c)));
      const double lq = q.norm();
      double s = 1;
      for (int c = 0; c < 3; ++c)
        for (int j = 0; j < ni; ++j) s = std::max(s, std::abs(kii(inner(n, c), j)));
      const int row = inner(n, 3);
      ri(row) = s * (lq - 1);
      for (int j = 0; j < ni; ++j) kii(row, j) = 0;
      if (lq > 0)
        for (int c = 0; c < 4; ++c) kii(row, inner(n, c)) = s * q(c) / lq;
    }
  }

  full_type full_;

  /// B_RR - K_RI K_II^-1 B_IR into the condensed block.
  template <class Full, class Out>
  static void schur(const Full& b, const mat_ri& k_ri, const Eigen::PartialPivLU<mat_ii>& lu, Out& o) {
    Eigen::Matrix<double, ni, nr> b_ir;
    for (int j = 0; j < ni; ++j)
      for (int r = 0; r < nr; ++r) b_ir(j, r) = b(cond(j), kept(r));
    const Eigen::Matrix<double, ni, nr> x = lu.solve(b_ir);
    for (int r = 0; r < nr; ++r)
      for (int q = 0; q < nr; ++q) o(r, q) = b(kept(r), kept(q)) - k_ri.row(r).dot(x.col(q));
  }

  /// Code 100 if a part puts mass or damping on a condensed DOF (a column of C or M).
  static void check_quasi_static(const local_output<full_type>& fo, element_context& ctx) {
    for (int j = 0; j < ni; ++j)
      for (int k = 0; k < full_traits::n; ++k) {
        const char* what = nullptr;
        if constexpr (full_traits::has_m)
          if (fo.M(k, cond(j)) != 0.0) what = "mass (dF/da)";
        if constexpr (full_traits::has_c)
          if (!what && fo.C(k, cond(j)) != 0.0) what = "damping (dF/dv)";
        if (what)
          ctx.invalid_parameter("internal DOF " + std::to_string(cond(j) + 1) + " (on " + part_on(cond(j)) +
                                ") carries " + what +
                                ": a condensed DOF must be quasi-static; keep it with pradis::composite or move the "
                                "mass to an external DOF");
      }
  }

  /// The first part connected to composite DOF m, for messages.
  static std::string part_on(int m) {
    std::string s;
    int i = 0;
    (
        [&] {
          for (int k : Ps::map)
            if (k == m && s.empty()) s = composite_detail::part_name<Spec, Ps>(i).str();
          ++i;
        }(),
        ...);
    return s;
  }
};

}  // namespace pradis
