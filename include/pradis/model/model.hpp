#pragma once
/// \file
/// Models built in code and checked at compile time. A model lists the element
/// types it may hold; only those are compiled in. It owns the DOFs (DOF 0 is the
/// ground), the named element instances with their DOF connections, parameters,
/// work and state vectors, and the internal DOFs each instance needs (ENT).

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <unordered_map>
#include <vector>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/core/type_list.hpp"
#include "pradis/model/handles.hpp"
#include "pradis/model/node_connections.hpp"
#include "pradis/spatial/rotation_node_kind.hpp"

namespace pradis {

/// A model over the element types Es. Each Es must satisfy Element; listing the
/// same type twice or two types with the same catalog name does not compile.
template <class... Es>
class model {
  static consteval bool distinct_names() {
    constexpr std::string_view names[] = {Es::passport.name...};
    for (std::size_t i = 0; i < sizeof...(Es); ++i)
      for (std::size_t j = i + 1; j < sizeof...(Es); ++j)
        if (names[i] == names[j]) return false;
    return true;
  }

  static_assert(sizeof...(Es) > 0, "pradis: a model must list at least one element type");
  static_assert((check_element<Es>() && ...));
  static_assert(distinct_v<Es...>, "pradis: a model lists the same element type twice");
  static_assert(distinct_names(), "pradis: two element types of a model have the same catalog name");

 public:
  /// The element types of this model.
  using element_types = type_list<Es...>;

  /// An empty model with its ground DOF.
  model() { add_dof("ground"); }

  /// The ground DOF (index 0), fixed at zero displacement.
  static constexpr dof ground() noexcept { return dof{0}; }
  /// This model's serial number (carried by the DOFs it hands out; a copy keeps it).
  std::uint32_t serial() const noexcept { return serial_; }
  /// Whether d may be used with this model: made by it (or a copy) or from a bare index.
  bool owns(dof d) const noexcept { return d.owner == 0 || d.owner == serial_; }

  /// Adds a DOF; the name is used in messages and outputs (default "dof N"). The
  /// domain sets its nominal magnitudes (default_scale); an unspecified DOF takes the
  /// domain of the first element that declares one for it (core/domain.hpp).
  dof add_dof(std::string name = {}, domain dom = domain::unspecified) {
    const int i = static_cast<int>(dof_names_.size());
    dof_names_.push_back(name.empty() ? "dof " + std::to_string(i) : std::move(name));
    dof_domains_.push_back(dom);
    dof_scales_.push_back(default_scale(dom));
    scale_fixed_.push_back(0);
    domain_by_.emplace_back();
    return dof{i, serial_};
  }
  /// Adds `count` DOFs and returns them.
  std::vector<dof> add_dofs(int count, const std::string& prefix = {}) {
    std::vector<dof> out;
    out.reserve(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k)
      out.push_back(add_dof(prefix.empty() ? std::string{} : prefix + std::to_string(k + 1)));
    return out;
  }
  /// Number of DOFs including the ground and the internal DOFs.
  int dof_count() const noexcept { return static_cast<int>(dof_names_.size()); }
  /// Name of a DOF.
  const std::string& dof_name(int i) const { return dof_names_.at(static_cast<std::size_t>(i)); }
  /// Physical domain of a DOF (unspecified until an element or add_dof declares one).
  domain dof_domain(dof d) const { return dof_domains_.at(checked_dof(d, "dof_domain")); }
  /// Nominal magnitudes of a DOF, which scale the absolute tolerances (core/domain.hpp).
  const dof_scale& scale(dof d) const { return dof_scales_.at(checked_dof(d, "scale")); }
  /// Nominal magnitudes of all DOFs, indexed by DOF (what the integrator reads).
  const std::vector<dof_scale>& scales() const noexcept { return dof_scales_; }
  /// Sets the nominal magnitudes of a DOF (e.g. a hydraulic line whose flows are
  /// litres per hour). They then stay as set, whatever domain elements declare. Both
  /// must be finite and > 0 (else invalid_option).
  void set_scale(dof d, dof_scale s) {
    const std::size_t i = checked_dof(d, "set_scale");
    if (!s.valid())
      throw error(error_code::invalid_option, "nominal potential and flow of DOF '" + dof_names_[i] +
                                                  "' must be finite and > 0");
    dof_scales_[i] = s;
    scale_fixed_[i] = 1;
  }

  /// The node kinds of a model (core/node_kind.hpp): the rotational node
  /// (spatial/rotation_node_kind.hpp), then those its element types declare
  /// (E::node_kinds), each once.
  using node_kinds =
      unique_t<concat_t<type_list<spatial::rotation_node_kind>, typename node_kinds_of<Es>::type...>>;
  static_assert([]<class... Ks>(type_list<Ks...>) { return (NodeKind<Ks> && ...); }(node_kinds{}),
                "pradis: an element type declares a node kind that does not satisfy NodeKind (core/node_kind.hpp)");
  /// The nodes of kind K.
  template <NodeKind K>
  const std::vector<typename K::record>& nodes() const {
    return std::get<typename K::registry>(registries_).records();
  }
  /// Adds a node of kind K (a kind that an element type of the model declares) whose
  /// registry takes records (`registry.add(record)`). Every DOF of the record must exist
  /// in this model and appear once in the record (the ground excepted), and a hidden
  /// one (K::hidden) must be neither the ground nor the hidden DOF of another node, of
  /// any kind (its row carries one node's equation): else code 110, and the model is
  /// unchanged.
  template <NodeKind K>
  void add_node(typename K::record r) {
    static_assert(contains_in<K>(node_kinds{}), "pradis: no element type of this model declares this node kind");
    static_assert(requires(typename K::registry& g) { g.add(std::move(r)); },
                  "pradis: this node kind's registry makes its nodes itself (it has no add(record))");
    detail::check_node_connections<K>(
        r, dof_count(), [&](int d) -> const std::string& { return dof_name(d); }, [&] { return hidden_dofs(true); });
    std::get<typename K::registry>(registries_).add(std::move(r));
    ++version_;
  }
  /// Calls f(std::type_identity<K>{}, nodes<K>()) for every node kind K of the model.
  template <class F>
  void for_each_node_kind(F&& f) const {
    [&]<class... Ks>(type_list<Ks...>) { (f(std::type_identity<Ks>{}, nodes<Ks>()), ...); }(node_kinds{});
  }

  /// Sets the hidden DOFs of every node (K::hidden) whose index is `from` or more to
  /// their start potentials (K::start) in u, a vector over all DOFs.
  void start_hidden_dofs(Eigen::VectorXd& u, int from = 0) const {
    for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      for (const auto& node : nodes)
        for (std::size_t k = 0; k < static_cast<std::size_t>(K::size); ++k)
          if (K::hidden[k] && node.dofs[k] >= from) u(static_cast<Eigen::Index>(node.dofs[k])) = K::start[k];
    });
  }
  /// Per DOF: whether it is a hidden DOF of a node (K::hidden), with `slaved` also
  /// whether it is a slaved DOF of a node (K::slaved; core/node_kind.hpp).
  std::vector<char> hidden_dofs(bool slaved = false) const {
    std::vector<char> h(static_cast<std::size_t>(dof_count()), 0);
    for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
      for (const auto& node : nodes)
        for (std::size_t k = 0; k < static_cast<std::size_t>(K::size); ++k)
          if (slaved ? owned_dof<K>(static_cast<int>(k)) : K::hidden[k]) h[static_cast<std::size_t>(node.dofs[k])] = 1;
    });
    return h;
  }

  /// Adds a spatial rotational node with three new external DOFs `<name>.q1`,
  /// `<name>.q2`, `<name>.q3` and the hidden `<name>.q4` (initialised to 1 at the zero step).
  rotation_node add_rotation_node(std::string name = {}) {
    if (name.empty()) name = "rotation node " + std::to_string(rotation_nodes().size() + 1);
    const dof a = add_dof(name + ".q1"), b = add_dof(name + ".q2"), c = add_dof(name + ".q3");
    return add_rotation_node(std::move(name), a, b, c);
  }
  /// Declares the existing DOFs q1, q2, q3 a spatial rotational node and adds its hidden
  /// q4. A component given as the ground is fixed (PRADIS: connecting an angular DOF to
  /// node 0). A DOF that already belongs to a rotational node is code 110.
  rotation_node add_rotation_node(std::string name, dof q1, dof q2, dof q3) {
    for (const dof d : {q1, q2, q3}) checked_dof(d, "add_rotation_node");
    return rotation_node_handle(rotations().add(std::move(name), {q1.index, q2.index, q3.index}, dof_count(),
                                                new_dof_index(), dof_namer()));
  }
  /// The rotational nodes of the model (explicit ones and those created by elements).
  const std::vector<rotation_node_record>& rotation_nodes() const noexcept {
    return std::get<spatial::rotation_node_registry>(registries_).records();
  }
  /// Handle of rotational node i.
  rotation_node rotation_node_handle(int i) const {
    const auto& r = rotation_nodes().at(static_cast<std::size_t>(i));
    return rotation_node{dof{r.dofs[0], serial_}, dof{r.dofs[1], serial_}, dof{r.dofs[2], serial_},
                         dof{r.dofs[3], serial_}, i};
  }
  /// The rotational node whose external DOF q1, q2 or q3 is `d` (not the ground), if any.
  std::optional<rotation_node> find_rotation_node(dof d) const {
    const int i = std::get<spatial::rotation_node_registry>(registries_).node_of(d.index);
    if (i < 0) return std::nullopt;
    return rotation_node_handle(i);
  }
  /// The rotational node of slot k (0-based, in E::rotation_nodes order) of an instance.
  template <class E>
  rotation_node rotation_node_of(element_ref<E> r, int k = 0) const {
    const auto slot = element_traits<E>::rotation_nodes.at(static_cast<std::size_t>(k));
    const int q4 = instance(r).dofs[static_cast<std::size_t>(slot.q4)];
    for (std::size_t i = 0; i < rotation_nodes().size(); ++i)
      if (rotation_nodes()[i].dofs[3] == q4) return rotation_node_handle(static_cast<int>(i));
    throw error(error_code::invalid_model, "no rotational node on this slot");
  }

  /// Places an element of type E with typed parameters, connected to exactly
  /// EXT DOFs (another count does not compile). Each argument is a `dof` or a
  /// `rotation_node`, which stands for its three external DOFs q1, q2, q3.
  /// Internal DOFs are added automatically; an internal slot that is the hidden q4
  /// of a rotational node (E::rotation_nodes) is connected to the node's shared q4.
  template <class E, class... D>
    requires((std::same_as<D, dof> || std::same_as<D, rotation_node>) && ...)
  element_ref<E> add(std::string name, typename E::parameters p, D... d) {
    static_assert(contains_v<E, Es...>, "pradis: this element type is not listed in the model's element types");
    static_assert(((std::same_as<D, dof> ? 1 : 3) + ... + 0) == element_traits<E>::ext,
                  "pradis: an element must be connected to exactly EXT DOFs (its passport's EXT)");
    std::array<dof, element_traits<E>::ext> ds{};
    std::size_t at = 0;
    const auto put = [&](const auto& x) {
      if constexpr (std::same_as<std::remove_cvref_t<decltype(x)>, dof>) {
        ds[at++] = x;
      } else {
        ds[at++] = x.q1;
        ds[at++] = x.q2;
        ds[at++] = x.q3;
      }
    };
    (put(d), ...);
    E e(p);
    int npar = E::passport.par;
    if constexpr (requires { e.parameter_count(); }) npar = e.parameter_count();
    return place<E>(std::move(name), std::move(e), ds, npar);
  }

  /// Places an element of type E from the flat PAR vector, as the model language
  /// does; DOF and parameter counts are checked at run time (codes 110 and 101).
  template <class E>
  element_ref<E> add_flat(std::string name, std::span<const dof> d, std::span<const double> par) {
    static_assert(contains_v<E, Es...>, "pradis: this element type is not listed in the model's element types");
    constexpr passport p = E::passport;
    if (static_cast<int>(d.size()) != p.ext)
      throw error(error_code::invalid_model,
                  "element needs " + std::to_string(p.ext) + " DOFs (EXT), got " + std::to_string(d.size()),
                  std::string(p.name), name);
    check_parameter_count<E>(name, static_cast<int>(par.size()));
    for (double x : par)
      if (!std::isfinite(x))
        throw error(error_code::invalid_parameter, "parameter list contains a non-finite number", std::string(p.name),
                    name);
    return place<E>(std::move(name), E::from_parameters(par), d, static_cast<int>(par.size()));
  }

  /// Places an element by its catalog name (e.g. "LINKD"), as the model language
  /// does. Throws invalid_model for an unknown name.
  instance_location add_by_name(std::string_view catalog_name, std::string name, std::span<const dof> d,
                                std::span<const double> par) {
    std::optional<instance_location> loc;
    for_each_type([&]<class E>(std::type_identity<E>) {
      if (!loc && E::passport.name == catalog_name)
        loc = instance_location{index_of<E, Es...>(), add_flat<E>(std::move(name), d, par).index};
    });
    if (!loc) throw error(error_code::invalid_model, "unknown element type '" + std::string(catalog_name) + "'", {}, name);
    return *loc;
  }

  /// Checks a parameter count against the passport's PAR/VPR rules (code 101).
  template <class E>
  static void check_parameter_count(const std::string& name, int npar) {
    constexpr passport p = E::passport;
    if (!p.parameter_count_ok(npar))
      throw error(error_code::parameter_count,
                  "got " + std::to_string(npar) + " parameters, the passport asks for " +
                      std::string(p.parameter_rule()) + " = " + std::to_string(p.par),
                  std::string(p.name), name);
  }

  /// Calls f(std::type_identity<E>{}) for every element type E of the model.
  template <class F>
  static void for_each_type(F&& f) {
    (f(std::type_identity<Es>{}), ...);
  }

  /// The instances of type E.
  template <class E>
  std::vector<element_instance<E>>& instances() {
    return std::get<std::vector<element_instance<E>>>(instances_);
  }
  template <class E>
  const std::vector<element_instance<E>>& instances() const {
    return std::get<std::vector<element_instance<E>>>(instances_);
  }
  /// Calls f(instances<E>()) for every type E.
  template <class F>
  void for_each_instances(F&& f) {
    std::apply([&](auto&... v) { (f(v), ...); }, instances_);
  }
  template <class F>
  void for_each_instances(F&& f) const {
    std::apply([&](const auto&... v) { (f(v), ...); }, instances_);
  }

  /// The element object behind a handle (to read or replace its parameters).
  template <class E>
  E& element(element_ref<E> r) {
    return instances<E>().at(static_cast<std::size_t>(r.index)).element;
  }
  /// The instance record behind a handle.
  template <class E>
  const element_instance<E>& instance(element_ref<E> r) const {
    return instances<E>().at(static_cast<std::size_t>(r.index));
  }
  /// The global DOF of local DOF k (external first, then internal) of an instance.
  template <class E>
  dof dof_of(element_ref<E> r, int k) const {
    return dof{instance(r).dofs.at(static_cast<std::size_t>(k)), serial_};
  }

  /// Finds an instance by name.
  std::optional<instance_location> find(std::string_view name) const {
    auto it = by_name_.find(std::string(name));
    if (it == by_name_.end()) return std::nullopt;
    return it->second;
  }
  /// Catalog name of the type of an instance.
  std::string_view type_name(const instance_location& loc) const {
    std::string_view out;
    std::size_t i = 0;
    ((i++ == loc.type ? (out = Es::passport.name, 0) : 0), ...);
    return out;
  }

  /// Work vector of an instance (the user's W:Name(k) is work(...)[k-1]).
  template <class E>
  std::span<double> work(element_ref<E> r) {
    const auto& in = instance(r);
    return {work_.data() + in.work_offset, in.work_size};
  }
  /// Work vector of an instance by name (throws invalid_model if unknown).
  std::span<const double> work(std::string_view name) const {
    auto loc = find(name);
    if (!loc) throw error(error_code::invalid_model, "no element instance named '" + std::string(name) + "'");
    std::span<const double> out;
    std::size_t i = 0;
    (
        [&] {
          if (i++ == loc->type) {
            const auto& in = instances<Es>()[static_cast<std::size_t>(loc->index)];
            out = {work_.data() + in.work_offset, in.work_size};
          }
        }(),
        ...);
    return out;
  }
  /// The flat work pool (all instances).
  std::vector<double>& work_pool() noexcept { return work_; }
  /// The OLD (accepted) state pool and the NEW (being computed) state pool.
  std::vector<double>& old_state_pool() noexcept { return old_state_; }
  std::vector<double>& new_state_pool() noexcept { return new_state_; }
  /// Total number of element instances.
  std::size_t element_count() const noexcept { return by_name_.size(); }
  /// A counter that changes whenever DOFs or elements are added (topology changes)
  /// or structure_changed() is called.
  std::size_t topology_version() const noexcept { return version_ + dof_names_.size(); }
  /// Tells the drivers to rebuild the Newton matrix's pattern before their next
  /// run: call it after changing an element's parameters in place (instances()),
  /// since an element may declare a Jacobian structure that depends on them
  /// (core/element.hpp, HasJacobianStructure).
  void structure_changed() noexcept { ++version_; }

 private:
  template <class E, std::size_t K>
  element_ref<E> place_impl(std::string name, E e, std::span<const dof, K> d, int npar) {
    constexpr passport p = E::passport;
    if (name.empty()) name = std::string(p.name) + "#" + std::to_string(by_name_.size() + 1);
    if (by_name_.count(name))
      throw error(error_code::invalid_model, "an element named '" + name + "' already exists", std::string(p.name),
                  name);
    element_instance<E> in{std::move(e), name, {}, npar, 0, 0, 0, 0};
    for (std::size_t k = 0; k < d.size(); ++k) {
      if (d[k].index < 0 || d[k].index >= dof_count() || !owns(d[k]))
        throw error(error_code::invalid_model,
                    "DOF " + std::to_string(d[k].index) +
                        (owns(d[k]) ? " does not exist in this model" : " belongs to another model") + " (connection " +
                        std::to_string(k + 1) + ")",
                    std::string(p.name), name);
      in.dofs[k] = d[k].index;
    }
    check_domains<E>(in.dofs, name);
    constexpr auto slots = element_traits<E>::rotation_nodes;
    for (int k = 0; k < p.ent; ++k) {
      int hidden = -1;
      for (const rotation_slot& sl : slots)
        if (sl.q4 == p.ext + k) {
          const auto q1 = static_cast<std::size_t>(sl.q1);
          const std::array<int, 3> t{in.dofs[q1], in.dofs[q1 + 1], in.dofs[q1 + 2]};
          const int node = rotations().resolve(t, p.name, name, dof_count(), new_dof_index(), dof_namer());
          hidden = rotation_nodes()[static_cast<std::size_t>(node)].dofs[3];
        }
      in.dofs[static_cast<std::size_t>(p.ext + k)] =
          hidden >= 0 ? hidden : add_dof(name + ".internal" + std::to_string(k + 1)).index;
    }
    in.work_offset = work_.size();
    in.work_size = static_cast<std::size_t>(p.work_size(npar));
    work_.resize(work_.size() + in.work_size, 0.0);
    in.state_offset = old_state_.size();
    in.state_size = static_cast<std::size_t>(p.state_size(npar));
    old_state_.resize(old_state_.size() + in.state_size, 0.0);
    new_state_.resize(old_state_.size(), 0.0);
    apply_domains<E>(in.dofs, name);
    auto& v = instances<E>();
    v.push_back(std::move(in));
    const int idx = static_cast<int>(v.size()) - 1;
    by_name_.emplace(name, instance_location{index_of<E, Es...>(), idx});
    ++version_;
    return element_ref<E>{idx};
  }
  template <class E, std::size_t K>
  element_ref<E> place(std::string name, E e, const std::array<dof, K>& d, int npar) {
    return place_impl<E, K>(std::move(name), std::move(e), std::span<const dof, K>(d), npar);
  }
  template <class E>
  element_ref<E> place(std::string name, E e, std::span<const dof> d, int npar) {
    return place_impl<E, std::dynamic_extent>(std::move(name), std::move(e), d, npar);
  }

  std::size_t checked_dof(dof d, const char* what) const {
    if (d.index < 0 || d.index >= dof_count() || !owns(d))
      throw error(error_code::invalid_model, std::string(what) + ": DOF " + std::to_string(d.index) +
                                                 (owns(d) ? " does not exist in this model" : " belongs to another model"));
    return static_cast<std::size_t>(d.index);
  }
  /// A DOF of one domain connected to an element slot of another is code 110.
  template <class E, std::size_t N>
  void check_domains(const std::array<int, N>& dofs, const std::string& name) const {
    for (int k = 0; k < E::passport.ext; ++k) {
      const auto d = static_cast<std::size_t>(dofs[static_cast<std::size_t>(k)]);
      const domain want = declared_domain<E>(k), have = dof_domains_[d];
      if (d == 0 || want == domain::unspecified || have == domain::unspecified || have == want) continue;
      throw error(error_code::invalid_model,
                  "DOF '" + dof_names_[d] + "' is " + std::string(to_string(have)) +
                      (domain_by_[d].empty() ? std::string() : " (set by " + domain_by_[d] + ")") + ", but connection " +
                      std::to_string(k + 1) + " of this element is " + std::string(to_string(want)),
                  std::string(E::passport.name), name);
    }
  }
  template <class E, std::size_t N>
  void apply_domains(const std::array<int, N>& dofs, const std::string& name) {
    for (std::size_t k = 0; k < N; ++k) {
      const auto d = static_cast<std::size_t>(dofs[k]);
      const domain want = declared_domain<E>(static_cast<int>(k));
      if (d == 0 || want == domain::unspecified || dof_domains_[d] != domain::unspecified) continue;
      dof_domains_[d] = want;
      domain_by_[d] = std::string(E::passport.name) + " '" + name + "'";
      if (!scale_fixed_[d]) dof_scales_[d] = default_scale(want);
    }
  }

  spatial::rotation_node_registry& rotations() { return std::get<spatial::rotation_node_registry>(registries_); }
  /// For the registries: adds a DOF by name and returns its index.
  auto new_dof_index() {
    return [this](std::string n) { return add_dof(std::move(n)).index; };
  }
  /// For the registries: the name of DOF d.
  auto dof_namer() const {
    return [this](int d) { return dof_name(d); };
  }

  template <class K, class... Ks>
  static constexpr bool contains_in(type_list<Ks...>) {
    return contains_v<K, Ks...>;
  }
  /// One registry per node kind (core/node_kind.hpp), in node_kinds order.
  node_registries_t<node_kinds> registries_;
  std::vector<std::string> dof_names_;
  std::vector<domain> dof_domains_;
  std::vector<dof_scale> dof_scales_;
  std::vector<char> scale_fixed_;         // 1: set by set_scale, kept whatever elements declare
  std::vector<std::string> domain_by_;    // the element that set the DOF's domain (messages)
  std::tuple<std::vector<element_instance<Es>>...> instances_;
  std::unordered_map<std::string, instance_location> by_name_;
  std::vector<double> work_, old_state_, new_state_;
  std::size_t version_ = 0;
  std::uint32_t serial_ = detail::next_model_serial();
};

/// A model over the types of a type_list: model_of<type_list<A, B>> is model<A, B>.
template <class L>
using model_of = apply_t<model, L>;

}  // namespace pradis
