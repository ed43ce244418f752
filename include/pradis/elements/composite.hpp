#pragma once
/// \file
/// Composite super-elements: an element type made of existing element types (its parts), each connected
/// to some of the composite's local DOFs, usable like any element. The passport is derived from the parts at
/// compile time; evaluation calls every part with its gathered input, with diagnostics muted (the PRADIS
/// super-element's SYSPRN = 0), and scatters its flows and blocks into the composite's. Internal DOFs (ENT)
/// are kept, not condensed. docs/super-elements.md.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/elements/composite_detail.hpp"

namespace pradis {

/// A super-element made of the parts Ps (each a `part<E, map...>`). Spec gives `static constexpr
/// std::string_view name` (catalog name), `title` (help title), `int ext`, `int ent` (the composite's
/// external and internal DOF counts) and optionally `std::array<std::string_view, sizeof...(Ps)> labels`
/// (part names for messages and help), `field`, `special`, and `static example()` returning the tuple of the
/// parts' typed parameters.
///
/// Derived passport: PAR = the parts' PAR in part order (the flat vector is their concatenation; parts with a
/// variable count are refused), STR = the sum, WRK = the sum plus 1 + parts statistics entries (evaluations,
/// errors per part), the blocks K, C, M present in any part. rotation_nodes = the parts' rotational slots
/// mapped to the composite, deduplicated; a node whose q1..q3 are internal is an inner node, which the model
/// gives its own hidden q4 and norm equation.
template <class Spec, class... Ps>
struct composite {
  static_assert(sizeof...(Ps) > 0, "pradis: a composite needs at least one part");
  static_assert((check_element<typename Ps::element>() && ...));
  static_assert(((Ps::element::passport.vpr == 0) && ...),
                "pradis: a composite's parts must have a fixed parameter count (VPR = 0): the flat parameter vector "
                "is split by the parts' PAR");
  static_assert(!(PrescribesMotion<typename Ps::element> || ...),
                "pradis: a kinematic source cannot be a part of a composite (the kernel prescribes only whole "
                "elements' DOFs)");
  static_assert(composite_detail::map_problem<Ps...>(Spec::ext, Spec::ent) == nullptr,
                "pradis: invalid part map: a composite DOF outside 0 .. EXT + ENT - 1, two local DOFs of one part "
                "on the same composite DOF, or a composite DOF connected to no part");

  /// Number of parts.
  static constexpr int part_count = static_cast<int>(sizeof...(Ps));

 private:
  static constexpr composite_detail::sums sums_ = composite_detail::sum_of<Ps...>();
  static constexpr std::array<int, 2> adr_ign_ = composite_detail::adr_ign(sums_.k, sums_.c, sums_.m);
  static constexpr composite_detail::rotation_table rot_ = composite_detail::rotation_table_of<Ps...>();
  static_assert(rot_.problem == nullptr,
                "pradis: a composite's parts map a rotational node inconsistently: q1, q2, q3 "
                "must go to consecutive composite DOFs and every part must use the same q4");

 public:
  /// Offsets of each part's parameters, state and work in the composite's vectors.
  static constexpr auto par_offset =
      composite_detail::offsets(std::array<int, sizeof...(Ps)>{Ps::element::passport.par...});
  static constexpr auto str_offset =
      composite_detail::offsets(std::array<int, sizeof...(Ps)>{Ps::element::passport.str...});
  static constexpr auto wrk_offset =
      composite_detail::offsets(std::array<int, sizeof...(Ps)>{Ps::element::passport.wrk...});
  /// Index of the statistics in the work vector: W(stats + 1) = evaluations, then one error count per part.
  static constexpr int stats = sums_.wrk;

  static constexpr pradis::passport passport{.name = Spec::name,
                                             .ext = Spec::ext,
                                             .ent = Spec::ent,
                                             .par = sums_.par,
                                             .str = sums_.str,
                                             .wrk = sums_.wrk + 1 + part_count,
                                             .adr = adr_ign_[0],
                                             .ign = adr_ign_[1]};
  /// The physical domain of each local DOF, as the parts declare it.
  static constexpr auto domains = [] {
    constexpr composite_detail::domain_table t = composite_detail::domain_table_of<Ps...>();
    static_assert(!t.conflict, "pradis: two parts of a composite declare different physical domains on one DOF");
    std::array<domain, static_cast<std::size_t>(Spec::ext + Spec::ent)> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = t.dom[i];
    return a;
  }();
  /// The parts' rotational nodes in the composite's local DOFs.
  static constexpr auto rotation_nodes = [] {
    std::array<rotation_slot, static_cast<std::size_t>(rot_.count)> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = rot_.slots[i];
    return a;
  }();
  /// The node kinds the parts' element types declare (core/node_kind.hpp), each once: a model
  /// that lists the composite has them as if it listed the parts' types.
  using node_kinds = unique_t<concat_t<type_list<>, typename node_kinds_of<typename Ps::element>::type...>>;

 private:
  struct params_f {
    constexpr composite_detail::text operator()() const { return composite_detail::parameter_text<Spec, Ps...>(); }
  };
  struct dofs_f {
    constexpr composite_detail::text operator()() const { return composite_detail::dof_text<Spec, Ps...>(Spec::ext); }
  };
  struct work_f {
    constexpr composite_detail::text operator()() const { return composite_detail::work_text<Spec, Ps...>(); }
  };
  struct name_f {
    constexpr composite_detail::text operator()() const { return composite_detail::name_text<Ps...>(); }
  };
  static constexpr std::string_view field_() {
    if constexpr (requires { Spec::field; })
      return Spec::field;
    else
      return std::tuple_element_t<0, std::tuple<typename Ps::element...>>::help.field;
  }
  static constexpr std::string_view special_() {
    if constexpr (requires { Spec::special; })
      return Spec::special;
    else
      return "an error of a part (code 100 at NEWINT, code 75 during the run, ...) is reported with its code in the "
             "name "
             "of the super-element and instance, naming the part; the parts' own special situations apply";
  }

 public:
  static constexpr element_help help{.title = Spec::title,
                                     .name = composite_detail::text_storage<name_f>::view,
                                     .field = field_(),
                                     .dofs = composite_detail::text_storage<dofs_f>::view,
                                     .parameters = composite_detail::text_storage<params_f>::view,
                                     .work = composite_detail::text_storage<work_f>::view,
                                     .special = special_()};

  /// Typed parameters: one aggregate per part, in part order.
  struct parameters {
    std::tuple<typename Ps::element::parameters...> parts;
  };

  explicit composite(parameters q) : composite(q, std::index_sequence_for<Ps...>{}) {}
  /// From the flat PAR vector: the parts' vectors one after the other.
  static composite from_parameters(std::span<const double> v) { return composite(v, std::index_sequence_for<Ps...>{}); }
  /// Example parameters: the spec's, else the parts' examples.
  static parameters example() requires(requires { Spec::example(); } || (requires { Ps::element::example(); } && ...)) {
    if constexpr (requires { Spec::example(); })
      return parameters{Spec::example()};
    else
      return parameters{{Ps::element::example()...}};
  }

  /// Draws every part that has a draw hook (io/model_scene.hpp), its local DOFs
  /// mapped into the composite's: a THROW shows its four beams. Parts without
  /// one draw nothing.
  template <class Drawer>
  void draw(Drawer& d) const {
    for_parts([&]<std::size_t I, class P>() {
      if constexpr (requires(const typename P::element& e, composite_detail::part_drawer<Drawer, P>& pd) {
                      e.draw(pd);
                    }) {
        composite_detail::part_drawer<Drawer, P> pd{d};
        std::get<I>(parts_).draw(pd);
      }
    });
  }

  /// Part I's element object.
  template <std::size_t I>
  const auto& get() const noexcept {
    return std::get<I>(parts_);
  }
  /// "part i 'NAME' (label)" for messages.
  template <std::size_t I>
  static std::string part_name() {
    using P = std::tuple_element_t<I, std::tuple<Ps...>>;
    std::string s = "part " + std::to_string(I + 1) + " '" + std::string(P::element::passport.name) + "'";
    if constexpr (requires { Spec::labels; }) s += " (" + std::string(Spec::labels[I]) + ")";
    return s;
  }

  /// NEWINT of every part (muted); a part's error is re-thrown naming the part and its PAR range.
  void new_integration(element_context& ctx) {
    for_parts([&]<std::size_t I, class P>() {
      if constexpr (HasNewIntegration<typename P::element>) {
        guarded<I, P>(ctx, [&](element_context& c) { std::get<I>(parts_).new_integration(c); });
      }
    });
  }

  /// Every part's flows and blocks, gathered and scattered through its map.
  void evaluate(const local_input<composite>& in, local_output<composite>& out, element_context& ctx) const {
    if (static_cast<int>(ctx.work.size()) > stats) ctx.work[static_cast<std::size_t>(stats)] += 1;
    if (out.want_jacobian)
      out.clear();
    else
      out.f.setZero();
    for_parts([&]<std::size_t I, class P>() {
      using E = typename P::element;
      using pt = element_traits<E>;
      constexpr auto& mp = P::map;
      local_input<E> li;
      for (int k = 0; k < pt::n; ++k) {
        const int m = mp[static_cast<std::size_t>(k)];
        li.u(k) = in.u(m);
        li.v(k) = in.v(m);
        li.a(k) = in.a(m);
      }
      li.t = in.t;
      local_output<E> lo;
      lo.want_jacobian = out.want_jacobian;
      if (lo.want_jacobian) lo.clear();  // a part gets its blocks zeroed, as from the assembler
      guarded<I, P>(ctx, [&](element_context& c) { std::get<I>(parts_).evaluate(li, lo, c); });
      for (int r = 0; r < pt::n; ++r) out.f(mp[static_cast<std::size_t>(r)]) += lo.f(r);
      if (!out.want_jacobian) return;
      for (int r = 0; r < pt::n; ++r) {
        const int mr = mp[static_cast<std::size_t>(r)];
        for (int q = 0; q < pt::n; ++q) {
          const int mq = mp[static_cast<std::size_t>(q)];
          if constexpr (pt::has_k) out.K(mr, mq) += lo.K(r, q);
          if constexpr (pt::has_c) out.C(mr, mq) += lo.C(r, q);
          if constexpr (pt::has_m) out.M(mr, mq) += lo.M(r, q);
        }
      }
    });
  }

  /// Initial values the parts request, merged; two parts requesting different values for one DOF is code 90.
  void zero_step(initial_values<Spec::ext + Spec::ent>& iv,
                 element_context& ctx) requires(HasZeroStep<typename Ps::element> || ...) {
    std::array<int, static_cast<std::size_t>(element_traits<composite>::n)> by_u{}, by_v{};
    by_u.fill(-1);
    by_v.fill(-1);
    for_parts([&]<std::size_t I, class P>() {
      using E = typename P::element;
      if constexpr (HasZeroStep<E>) {
        initial_values<element_traits<E>::n> piv;
        guarded<I, P>(ctx, [&](element_context& c) { std::get<I>(parts_).zero_step(piv, c); });
        for (int k = 0; k < element_traits<E>::n; ++k) {
          const int m = P::map[static_cast<std::size_t>(k)];
          const auto mm = static_cast<std::size_t>(m);
          if (piv.has_displacement(k)) {
            if (by_u[mm] >= 0 && iv.displacement(m) != piv.displacement(k))
              ctx.fail(error_code::conflicting_initial, conflict_text<I>("displacement", by_u[mm], m));
            iv.set_displacement(m, piv.displacement(k));
            by_u[mm] = static_cast<int>(I);
          }
          if (piv.has_velocity(k)) {
            if (by_v[mm] >= 0 && iv.velocity(m) != piv.velocity(k))
              ctx.fail(error_code::conflicting_initial, conflict_text<I>("velocity", by_v[mm], m));
            iv.set_velocity(m, piv.velocity(k));
            by_v[mm] = static_cast<int>(I);
          }
        }
      }
    });
  }

  /// After an accepted step: the parts' commit hooks.
  void commit(element_context& ctx) requires(composite_detail::has_commit<typename Ps::element> || ...) {
    for_parts([&]<std::size_t I, class P>() {
      if constexpr (composite_detail::has_commit<typename P::element>)
        guarded<I, P>(ctx, [&](element_context& c) { std::get<I>(parts_).commit(c); });
    });
  }

  /// States every part with an admissibility test admits.
  bool admissible(const local_input<composite>& in) const
      requires(composite_detail::has_admissible<typename Ps::element> || ...) {
    bool ok = true;
    for_parts([&]<std::size_t I, class P>() {
      using E = typename P::element;
      if constexpr (composite_detail::has_admissible<E>) {
        local_input<E> li;
        for (int k = 0; k < element_traits<E>::n; ++k) {
          const int m = P::map[static_cast<std::size_t>(k)];
          li.u(k) = in.u(m);
          li.v(k) = in.v(m);
          li.a(k) = in.a(m);
        }
        li.t = in.t;
        ok = ok && std::get<I>(parts_).admissible(li);
      }
    });
    return ok;
  }

 private:
  std::tuple<typename Ps::element...> parts_;

  template <std::size_t... I>
  composite(const parameters& q, std::index_sequence<I...>) : parts_(typename Ps::element(std::get<I>(q.parts))...) {}
  template <std::size_t... I>
  composite(std::span<const double> v, std::index_sequence<I...>)
      : parts_(Ps::element::from_parameters(v.subspan(static_cast<std::size_t>(par_offset[I]),
                                                      static_cast<std::size_t>(Ps::element::passport.par)))...) {}

  template <class F>
  static void for_parts(F&& f) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (f.template operator()<I, std::tuple_element_t<I, std::tuple<Ps...>>>(), ...);
    }
    (std::index_sequence_for<Ps...>{});
  }

  template <std::size_t I>
  static std::string conflict_text(const char* what, int other, int dof) {
    return part_name<I>() + " requests an initial " + what + " of local DOF " + std::to_string(dof + 1) +
           " different from the one " +
           (other == static_cast<int>(I) ? std::string("it") : "part " + std::to_string(other + 1)) + " requested";
  }

  /// The context as part I sees it for the duration of one call: its slices of the work and state vectors,
  /// its PAR count, its catalog name, diagnostics muted. Restored on every exit.
  class part_scope {
   public:
    template <class E>
    part_scope(element_context& c, std::size_t w0, std::size_t s0, std::type_identity<E>)
        : c_(c),
          work_(c.work),
          old_(c.old_state),
          new_(c.new_state),
          npar_(c.npar),
          type_(c.element_type()),
          guard_(c) {
      constexpr pradis::passport p = E::passport;
      c.work = c.work.size() >= w0 + static_cast<std::size_t>(p.wrk)
                   ? c.work.subspan(w0, static_cast<std::size_t>(p.wrk))
                   : std::span<double>{};
      c.old_state = c.old_state.size() >= s0 + static_cast<std::size_t>(p.str)
                        ? c.old_state.subspan(s0, static_cast<std::size_t>(p.str))
                        : std::span<const double>{};
      c.new_state = c.new_state.size() >= s0 + static_cast<std::size_t>(p.str)
                        ? c.new_state.subspan(s0, static_cast<std::size_t>(p.str))
                        : std::span<double>{};
      c.npar = p.par;
      c.set_identity(p.name, c.instance());
    }
    ~part_scope() {
      c_.work = work_;
      c_.old_state = old_;
      c_.new_state = new_;
      c_.npar = npar_;
      c_.set_identity(type_, c_.instance());
    }
    part_scope(const part_scope&) = delete;
    part_scope& operator=(const part_scope&) = delete;

   private:
    element_context& c_;
    std::span<double> work_;
    std::span<const double> old_;
    std::span<double> new_;
    int npar_;
    std::string_view type_;
    element_context::mute_guard guard_;
  };

  /// Runs f(ctx) as part I; a pradis::error it throws is counted and re-thrown, with its code, in the
  /// composite's name (written to the diagnostics log once, unmuted).
  template <std::size_t I, class P, class F>
  static void guarded(element_context& ctx, F&& f) {
    using E = typename P::element;
    bool failed = false;
    error_code code{};
    std::string message;
    try {
      part_scope scope(ctx, static_cast<std::size_t>(wrk_offset[I]), static_cast<std::size_t>(str_offset[I]),
                       std::type_identity<E>{});
      f(ctx);
    } catch (const error& e) {
      code = e.code();
      failed = true;
      message = e.message();
    }
    if (!failed) return;
    const std::size_t at = static_cast<std::size_t>(stats + 1) + I;
    if (ctx.work.size() > at) ctx.work[at] += 1;
    std::string where = part_name<I>();
    if (E::passport.par > 0 && code == error_code::invalid_parameter)
      where += ", parameters " + std::to_string(par_offset[I] + 1) + ".." + std::to_string(par_offset[I + 1]) + " of " +
               std::string(Spec::name);
    ctx.fail(code, where + ": " + message);
  }
};

}  // namespace pradis
