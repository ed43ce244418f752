#pragma once
/// \file
/// Nodal assembly. The sparsity pattern of the Newton matrix is built once per
/// topology from the connectivity and the blocks each passport declares, with a
/// scatter map from every local Jacobian entry to its slot in the global sparse
/// array: numeric assembly does no searching and never allocates.
///
/// Per Newton iteration J = cu * dF/du + cv * dF/dv + ca * dF/da, with the
/// integrator's coefficients. Blocks an element type does not declare are never
/// computed nor added: a scene without viscous elements never touches a C block.

#include <Eigen/Core>
#include <algorithm>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "pradis/assembly/assembly_state.hpp"
#include "pradis/assembly/slaved_rows.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/linalg/sparsity.hpp"
#include "pradis/model/model.hpp"

namespace pradis {

template <class Model>
class assembler;

/// Assembler of a model<Es...>.
template <class... Es>
class assembler<model<Es...>> {
 public:
  using model_type = model<Es...>;

  /// Whether any element type of the model declares a velocity block.
  static constexpr bool any_c = (element_traits<Es>::has_c || ...);
  /// Whether any element type of the model declares an acceleration block.
  static constexpr bool any_m = (element_traits<Es>::has_m || ...);
  /// Whether any element type of the model declares a displacement block.
  static constexpr bool any_k = (element_traits<Es>::has_k || ...);

  /// Builds the equation numbering, the pattern and the scatter maps.
  /// `prescribed[d]` is true for DOFs whose motion is known (ground, sources);
  /// they get no equation.
  void build(const model_type& m, const std::vector<char>& prescribed) {
    const int nd = m.dof_count();
    eq_of_dof_.assign(static_cast<std::size_t>(nd), -1);
    dof_of_eq_.clear();
    for (int d = 0; d < nd; ++d)
      if (!prescribed[static_cast<std::size_t>(d)]) {
        eq_of_dof_[static_cast<std::size_t>(d)] = static_cast<int>(dof_of_eq_.size());
        dof_of_eq_.push_back(d);
      }
    const int ne = static_cast<int>(dof_of_eq_.size());
    std::vector<std::pair<int, int>> entries;
    // Every local entry an element may fill (jacobian_entry_of: all, unless the
    // element declares its structure).
    m.for_each_instances([&](const auto& vec) {
      for (const auto& in : vec) {
        const int n = static_cast<int>(in.dofs.size());
        for (int r = 0; r < n; ++r)
          for (int c = 0; c < n; ++c) {
            const int er = eq_of_dof_[static_cast<std::size_t>(in.dofs[static_cast<std::size_t>(r)])];
            const int ec = eq_of_dof_[static_cast<std::size_t>(in.dofs[static_cast<std::size_t>(c)])];
            if (er >= 0 && ec >= 0 && jacobian_entry_of(in.element, r, c)) entries.emplace_back(er, ec);
          }
      }
    });
    // Nodes (core/node_kind.hpp): the block of a node's DOFs, in which its own equation
    // fills the rows K::rows.
    m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      for (const auto& node : nodes)
        for (int r : node.dofs)
          for (int c : node.dofs) {
            const int er = eq_of_dof_[static_cast<std::size_t>(r)], ec = eq_of_dof_[static_cast<std::size_t>(c)];
            if (er >= 0 && ec >= 0) entries.emplace_back(er, ec);
          }
    });
    const auto eq_of = [&](int d) { return eq_of_dof_[static_cast<std::size_t>(d)]; };
    m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      if constexpr (SlavingNodeKind<K>)
        detail::slaved_table<K>::add_entries(
            nodes, eq_of, [&](int d) -> const std::string& { return m.dof_name(d); }, entries);
    });
    pattern_ = linalg::sparsity_pattern::from_entries(ne, entries);
    m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      if constexpr (SlavingNodeKind<K>) std::get<detail::slaved_table<K>>(slaved_).build(nodes, eq_of, pattern_);
    });
    m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      constexpr int n = K::size;
      auto& slots = std::get<node_slot_table<K>>(node_slots_).slots;
      slots.assign(nodes.size() * static_cast<std::size_t>(n * n), -1);
      for (std::size_t i = 0; i < nodes.size(); ++i)
        for (int r = 0; r < n; ++r) {
          const int er = eq_of_dof_[static_cast<std::size_t>(nodes[i].dofs[static_cast<std::size_t>(r)])];
          for (int c = 0; c < n; ++c) {
            const int ec = eq_of_dof_[static_cast<std::size_t>(nodes[i].dofs[static_cast<std::size_t>(c)])];
            if (K::rows[static_cast<std::size_t>(r)] && er >= 0 && ec >= 0)
              slots[i * n * n + static_cast<std::size_t>(r * n + c)] = pattern_.find(er, ec);
          }
        }
    });
    // Scatter maps: per instance, the local entries (r, c) whose row and column
    // both have an equation, with their slots (entries on ground or prescribed
    // DOFs are not listed, so numeric assembly does not visit them).
    std::apply(
        [&](auto&... maps) {
          (
              [&](auto& map) {
                using E = typename std::remove_cvref_t<decltype(map)>::element_type;
                constexpr int n = element_traits<E>::n;
                const auto& vec = m.template instances<E>();
                map.first.assign(vec.size() + 1, 0);
                map.entries.clear();
                for (std::size_t i = 0; i < vec.size(); ++i) {
                  for (int r = 0; r < n; ++r)
                    for (int c = 0; c < n; ++c) {
                      const int er = eq_of_dof_[static_cast<std::size_t>(vec[i].dofs[static_cast<std::size_t>(r)])];
                      const int ec = eq_of_dof_[static_cast<std::size_t>(vec[i].dofs[static_cast<std::size_t>(c)])];
                      if (er >= 0 && ec >= 0 && jacobian_entry_of(vec[i].element, r, c))
                        map.entries.push_back({storage_index<E>(r, c), pattern_.find(er, ec)});
                    }
                  map.first[i + 1] = static_cast<int>(map.entries.size());
                }
              }(maps),
              ...);
        },
        maps_);
    values_.assign(static_cast<std::size_t>(pattern_.nnz()), 0.0);
    if (keep_blocks_) resize_blocks();
    ++blocks_version_;
    residual_.setZero(nd);
    abs_sum_.setZero(nd);
    partial_rows_ = false;
    // The element types with instances, in the model's order: evaluate() visits only these, so the types a model
    // lists but does not use (most of library_model's in a small scene) cost nothing per evaluation.
    active_types_.clear();
    (
        [&] {
          if constexpr (!InertElement<Es>)
            if (!m.template instances<Es>().empty()) active_types_.push_back(&assembler::evaluate_active<Es>);
        }(),
        ...);
    built_version_ = m.topology_version();
  }

  /// Restricts the partial Jacobians (call_info::jacobian_types without want_jacobian)
  /// to the entries on the equations `eqs`: only those rows of values() are then
  /// assembled (the BDF driver reads G on its constraint rows alone). Empty: all rows.
  /// build() lifts the restriction. Allocates; call it after build(), not per step.
  void restrict_partial_rows(const std::vector<int>& eqs) {
    partial_rows_ = !eqs.empty();
    std::vector<char> keep(static_cast<std::size_t>(pattern_.n), 0);
    for (const int e : eqs) keep.at(static_cast<std::size_t>(e)) = 1;
    std::vector<int> row_of(static_cast<std::size_t>(pattern_.nnz()));
    const auto& rp = pattern_.row_ptr;
    for (int r = 0; r < pattern_.n; ++r)
      for (int q = rp[static_cast<std::size_t>(r)]; q < rp[static_cast<std::size_t>(r) + 1]; ++q)
        row_of[static_cast<std::size_t>(q)] = r;
    (
        [&] {
          const auto& src = std::get<index_of<Es, Es...>()>(maps_);
          auto& dst = std::get<index_of<Es, Es...>()>(partial_maps_);
          dst.first.assign(src.first.size(), 0);
          dst.entries.clear();
          for (std::size_t i = 0; i + 1 < src.first.size(); ++i) {
            for (int k = src.first[i]; k < src.first[i + 1]; ++k) {
              const scatter_entry& e = src.entries[static_cast<std::size_t>(k)];
              if (keep[static_cast<std::size_t>(row_of[static_cast<std::size_t>(e.slot)])]) dst.entries.push_back(e);
            }
            dst.first[i + 1] = static_cast<int>(dst.entries.size());
          }
        }(),
        ...);
  }

  /// Whether build() was run for the model's current topology.
  bool built_for(const model_type& m) const noexcept { return built_version_ == m.topology_version(); }

  /// Evaluates every element at the global state `s`: sums the flows into the
  /// residual (all DOFs) and |flows| into abs_sum (for DRLTI), and, if
  /// info.want_jacobian, assembles J = cu K + cv C + ca M into values() (with
  /// info.jacobian_types instead, the part of J from those element types, on the
  /// rows of restrict_partial_rows() if it was called).
  /// Never allocates. Element errors propagate as pradis::error; a non-finite
  /// flow or Jacobian entry raises error_code::non_finite naming the instance.
  void evaluate(model_type& m, const global_state& s, const jacobian_coefficients& c, const call_info& info) {
    residual_.setZero();
    abs_sum_.setZero();
    if (info.want_jacobian || info.jacobian_types) {
      std::fill(values_.begin(), values_.end(), 0.0);
      ++blocks_version_;  // the blocks kept (keep_blocks) are those of this evaluation, or none
      if (keep_blocks_ && info.want_jacobian)
        for (auto* b : {&k_values_, &c_values_, &m_values_}) std::fill(b->begin(), b->end(), 0.0);
    }
    element_context ctx;
    ctx.set_diagnostics(info.log);
    ctx.time = info.time;
    ctx.step = info.step;
    ctx.nstep = info.nstep;
    ctx.niter = info.niter;
    const bool partial = partial_rows_ && !info.want_jacobian && info.jacobian_types;
    for (const type_evaluation f : active_types_) (this->*f)(m, s, c, info, ctx, partial);
    m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      if constexpr (SlavingNodeKind<K>) carry_slaved<K>(m, nodes, s, c, info, ctx);
    });
    m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      evaluate_nodes<K>(m, nodes, std::get<node_slot_table<K>>(node_slots_).slots, s, c, info, ctx);
    });
    recommended_step_ = ctx.recommended_step;
  }

  /// Evaluates one element instance alone (used for reactions and by tools).
  template <class E>
  void evaluate_instance(model_type& m, int index, const global_state& s, double t, local_output<E>& out,
                         diagnostics* log = nullptr) {
    auto& in = m.template instances<E>()[static_cast<std::size_t>(index)];
    local_input<E> li;
    gather(in, s, li);
    li.t = t;
    element_context ctx(E::passport.name, in.name, log);
    bind(m, in, ctx);
    ctx.time = t;
    out.clear();
    in.element.evaluate(li, out, ctx);
  }

  /// Number of equations (free DOFs).
  int equations() const noexcept { return static_cast<int>(dof_of_eq_.size()); }
  /// Equation of a DOF, or -1 for ground/prescribed DOFs.
  int equation_of(int dof) const noexcept { return eq_of_dof_[static_cast<std::size_t>(dof)]; }
  /// DOF of an equation.
  int dof_of(int eq) const noexcept { return dof_of_eq_[static_cast<std::size_t>(eq)]; }
  /// Sparsity pattern of the Newton matrix (equations only).
  const linalg::sparsity_pattern& pattern() const noexcept { return pattern_; }
  /// Assembled Newton-matrix values in the pattern's CSR order.
  std::span<const double> values() const noexcept { return values_; }

  /// Keeps the element blocks K, C and M of every full Jacobian evaluation apart
  /// (in the pattern's order), so that reform() can make J for other
  /// coefficients without evaluating the elements again. Off by default (three
  /// more sums per assembled entry).
  void keep_blocks(bool on) {
    keep_blocks_ = on;
    if (on) resize_blocks();
    ++blocks_version_;
  }
  /// Whether keep_blocks is on.
  bool keeps_blocks() const noexcept { return keep_blocks_; }
  /// Changes with every evaluation that assembles a Jacobian (and with build()):
  /// the blocks kept are those of the evaluation that set the current value,
  /// if it was a full one with keep_blocks on.
  std::size_t blocks_version() const noexcept { return blocks_version_; }
  /// values() := cu K + cv C + ca M from the blocks kept (keep_blocks): the Newton
  /// matrix of the last full Jacobian evaluation's state for other coefficients.
  /// Never allocates.
  void reform(const jacobian_coefficients& c) {
    for (std::size_t i = 0; i < values_.size(); ++i)
      values_[i] = c.cu * k_values_[i] + c.cv * c_values_[i] + c.ca * m_values_[i];
  }
  /// Sum of flows per DOF (all DOFs).
  const Eigen::VectorXd& residual() const noexcept { return residual_; }
  /// Sum of |flows| per DOF (all DOFs).
  const Eigen::VectorXd& abs_sum() const noexcept { return abs_sum_; }
  /// Smallest step recommended by an element in the last evaluate() (STEPMD), or infinity.
  double recommended_step() const noexcept { return recommended_step_; }
  /// The element flows of the slaved rows of the nodes of slaving kind K at the last evaluate(),
  /// K::size per node in the model's order (slaved_table::flows; empty before build).
  template <class K>
  std::span<const double> slaved_flows() const noexcept {
    return std::get<detail::slaved_table<K>>(slaved_).flows;
  }

  /// Binds an instance's work and state vectors into a context.
  template <class E>
  static void bind(model_type& m, element_instance<E>& in, element_context& ctx) {
    ctx.work = std::span<double>(m.work_pool().data() + in.work_offset, in.work_size);
    ctx.old_state = std::span<const double>(m.old_state_pool().data() + in.state_offset, in.state_size);
    ctx.new_state = std::span<double>(m.new_state_pool().data() + in.state_offset, in.state_size);
    ctx.npar = in.npar;
  }
  /// Copies the global potentials of an instance's DOFs into a local input.
  template <class E>
  static void gather(const element_instance<E>& in, const global_state& s, local_input<E>& li) {
    for (int k = 0; k < element_traits<E>::n; ++k) {
      const auto d = static_cast<Eigen::Index>(in.dofs[static_cast<std::size_t>(k)]);
      li.u(k) = s.u(d);
      li.v(k) = s.v(d);
      li.a(k) = s.a(d);
    }
  }

 private:
  /// Where the local Jacobian entry (r, c) lies in the storage of E's n x n blocks.
  template <class E>
  static constexpr int storage_index(int r, int c) {
    constexpr int n = element_traits<E>::n;
    return element_traits<E>::matrix::IsRowMajor ? r * n + c : c * n + r;
  }
  /// One local Jacobian entry of an instance that is assembled: its place in
  /// the storage of the local blocks (storage_index) and its slot.
  struct scatter_entry {
    int local;
    int slot;
  };
  template <class E>
  struct scatter_map {
    using element_type = E;
    std::vector<int> first;                // instance i's entries: [first[i], first[i + 1])
    std::vector<scatter_entry> entries;
  };

  /// evaluate_type for the element type E (one with instances) with its scatter map, the partial one
  /// (restrict_partial_rows) if `partial`.
  template <class E>
  void evaluate_active(model_type& m, const global_state& s, const jacobian_coefficients& c, const call_info& info,
                       element_context& ctx, bool partial) {
    constexpr std::size_t i = index_of<E, Es...>();
    evaluate_type<E>(m, s, c, info, ctx, partial ? std::get<i>(partial_maps_) : std::get<i>(maps_), i);
  }
  /// Evaluates the instances of E and assembles them (evaluate()).
  template <class E>
  void evaluate_type(model_type& m, const global_state& s, const jacobian_coefficients& c, const call_info& info,
                     element_context& ctx, const scatter_map<E>& map, std::size_t type_index) {
    using tr = element_traits<E>;
    constexpr int n = tr::n;
    if constexpr (InertElement<E>) return;  // no flow, no Jacobian entry (core/element.hpp)
    auto& vec = m.template instances<E>();
    if (vec.empty()) return;  // most of library_model's types in a small model: no set-up for them
    local_input<E> li;
    local_output<E> out;
    li.t = info.time;
    const bool jac = info.want_jacobian || (info.jacobian_types && type_index < info.jacobian_types->size() &&
                                            (*info.jacobian_types)[type_index]);
    out.want_jacobian = jac;
    for (std::size_t i = 0; i < vec.size(); ++i) {
      auto& in = vec[i];
      gather(in, s, li);
      ctx.set_identity(E::passport.name, in.name);
      bind(m, in, ctx);
      if (jac)
        out.clear();
      else
        out.f.setZero();  // the blocks are not read: an element may leave them as they are
      in.element.evaluate(li, out, ctx);
      if (!out.f.allFinite()) ctx.fail(error_code::non_finite, "a flow is NaN or infinite");
      for (int k = 0; k < n; ++k) {
        const auto d = static_cast<Eigen::Index>(in.dofs[static_cast<std::size_t>(k)]);
        residual_(d) += out.f(k);
        abs_sum_(d) += std::abs(out.f(k));
      }
      if (!jac) continue;
      // Only the entries assembled are checked: x is NaN or infinite if one of
      // its terms is (0 * inf is NaN), and the block is named afterwards.
      const scatter_entry* const b = map.entries.data() + map.first[i];
      const scatter_entry* const e = map.entries.data() + map.first[i + 1];
      double check = 0;
      const bool keep = keep_blocks_ && info.want_jacobian;
      for (const scatter_entry* p = b; p != e; ++p) {
        const auto j = static_cast<Eigen::Index>(p->local);
        const auto slot = static_cast<std::size_t>(p->slot);
        double x = 0;
        if constexpr (tr::has_k) x += c.cu * out.K.data()[j];
        if constexpr (tr::has_c) x += c.cv * out.C.data()[j];
        if constexpr (tr::has_m) x += c.ca * out.M.data()[j];
        check += x * 0.0;
        values_[slot] += x;
        if (keep) {
          if constexpr (tr::has_k) k_values_[slot] += out.K.data()[j];
          if constexpr (tr::has_c) c_values_[slot] += out.C.data()[j];
          if constexpr (tr::has_m) m_values_[slot] += out.M.data()[j];
        }
      }
      if (check != 0.0) {  // NaN: some entry was not finite
        if constexpr (tr::has_k)
          if (!out.K.allFinite()) ctx.fail(error_code::non_finite, "a Jacobian entry dF/du is NaN or infinite");
        if constexpr (tr::has_c)
          if (!out.C.allFinite()) ctx.fail(error_code::non_finite, "a Jacobian entry dF/dv is NaN or infinite");
        if constexpr (tr::has_m)
          if (!out.M.allFinite()) ctx.fail(error_code::non_finite, "a Jacobian entry dF/da is NaN or infinite");
        ctx.fail(error_code::non_finite, "a Jacobian entry is NaN or infinite");
      }
    }
  }

  /// The own equations of the nodes of kind K (core/node_kind.hpp), once per node:
  /// flows in the rows K::rows and, with info.want_jacobian, their entries
  /// cu dF/du + cv dF/dv in the node's columns (`slots`: per node, n x n slots,
  /// row-major, -1 where absent). A flow or an assembled entry that is NaN or
  /// infinite is code 150 in the name of the node (K::label and the DOF of its first
  /// row). Never allocates.
  template <class K>
  void evaluate_nodes(const model_type& m, const std::vector<typename K::record>& nodes,
                      const std::vector<int>& slots, const global_state& s, const jacobian_coefficients& c,
                      const call_info& info, element_context& ctx) {
    constexpr int n = K::size;
    node_values<n> x;
    node_flows<n> out;
    const node_call call{info.dabsi, info.want_jacobian};
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const auto& dofs = nodes[i].dofs;
      gather_node<n>(dofs, s, x);
      K::evaluate(nodes[i], x, call, out, ctx);
      double check = 0;  // NaN if a flow or an entry is not finite (0 * inf is NaN)
      for (int r = 0; r < n; ++r) {
        if (!K::rows[static_cast<std::size_t>(r)]) continue;
        const auto d = static_cast<Eigen::Index>(dofs[static_cast<std::size_t>(r)]);
        residual_(d) += out.f(r);
        abs_sum_(d) += std::abs(out.f(r));
        check += out.f(r) * 0.0;
        if (!info.want_jacobian) continue;
        const int* slot = slots.data() + i * n * n + static_cast<std::size_t>(r * n);
        for (int k = 0; k < n; ++k) {
          if (slot[k] < 0) continue;
          const auto q = static_cast<std::size_t>(slot[k]);
          const double e = c.cu * out.K(r, k) + c.cv * out.C(r, k);
          check += e * 0.0;
          values_[q] += e;
          if (keep_blocks_) {
            k_values_[q] += out.K(r, k);
            c_values_[q] += out.C(r, k);
          }
        }
      }
      if (check != 0.0) node_not_finite<K>(m, nodes[i], out, ctx);
    }
  }
  /// The rows of the slaved DOFs of the nodes of kind K carried to their nodes' other rows
  /// (assembly/slaved_rows.hpp); the Jacobian's only with a full one (info.want_jacobian).
  template <class K>
  void carry_slaved(const model_type& m, const std::vector<typename K::record>& nodes, const global_state& s,
                    const jacobian_coefficients& c, const call_info& info, element_context& ctx) {
    const bool keep = keep_blocks_ && info.want_jacobian;
    std::vector<double>* kept[3] = {keep ? &k_values_ : nullptr, keep ? &c_values_ : nullptr,
                                    keep ? &m_values_ : nullptr};
    detail::carry_slaved_rows<K>(m, nodes, std::get<detail::slaved_table<K>>(slaved_), s, c.cu, info.want_jacobian,
                                 residual_, abs_sum_, values_, kept, ctx);
  }
  /// Code 150 for a node whose flows or Jacobian entries are not finite.
  template <class K>
  [[noreturn]] static void node_not_finite(const model_type& m, const typename K::record& node,
                                           const node_flows<K::size>& out, element_context& ctx) {
    int first = 0;
    while (first + 1 < K::size && !K::rows[static_cast<std::size_t>(first)]) ++first;
    const std::string& dof = m.dof_name(node.dofs[static_cast<std::size_t>(first)]);
    ctx.set_identity(K::label, dof);
    bool flows = true;
    for (int r = 0; r < K::size; ++r)
      if (K::rows[static_cast<std::size_t>(r)]) flows = flows && std::isfinite(out.f(r));
    ctx.fail(error_code::non_finite, std::string(K::label) + " node of DOF '" + dof + "': " +
                                         (flows ? "a Jacobian entry of its equation is NaN or infinite"
                                                : "a flow of its equation is NaN or infinite"));
  }

  using node_kinds = typename model_type::node_kinds;
  /// Per node kind: the slots of its nodes' rows (evaluate_nodes).
  template <class K>
  struct node_slot_table {
    std::vector<int> slots;
  };
  /// std::tuple<T<K>...> over the model's node kinds.
  template <template <class> class T, class L>
  struct per_kind;
  template <template <class> class T, class... Ks>
  struct per_kind<T, type_list<Ks...>> {
    using type = std::tuple<T<Ks>...>;
  };
  typename per_kind<node_slot_table, node_kinds>::type node_slots_;
  typename per_kind<detail::slaved_table, node_kinds>::type slaved_;  // used for slaving kinds only
  std::vector<int> eq_of_dof_, dof_of_eq_;
  linalg::sparsity_pattern pattern_;
  std::tuple<scatter_map<Es>...> maps_;
  std::tuple<scatter_map<Es>...> partial_maps_;  // maps_ on the rows of restrict_partial_rows()
  /// evaluate_active<E> of the element types with instances (build()).
  using type_evaluation = void (assembler::*)(model_type&, const global_state&, const jacobian_coefficients&,
                                              const call_info&, element_context&, bool);
  std::vector<type_evaluation> active_types_;
  bool partial_rows_ = false;
  void resize_blocks() {
    for (auto* b : {&k_values_, &c_values_, &m_values_}) b->assign(values_.size(), 0.0);
  }
  std::vector<double> values_;
  bool keep_blocks_ = false;
  std::vector<double> k_values_, c_values_, m_values_;  // keep_blocks: K, C, M of the last full evaluation
  std::size_t blocks_version_ = 0;
  Eigen::VectorXd residual_, abs_sum_;
  double recommended_step_ = 0;
  std::size_t built_version_ = static_cast<std::size_t>(-1);
};

}  // namespace pradis
