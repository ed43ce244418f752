#pragma once
/// \file
/// The first half of a session (session.hpp): turns the $DATA, $FRAGMENT,
/// #STRUCTURE and #OUTPUT of an ast::program into a library_model (every element
/// type of the built-in library) and its output columns, with `file:line:column`
/// messages for everything wrong.

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/lang/ast.hpp"
#include "pradis/lang/catalog.hpp"
#include "pradis/lang/parser.hpp"
#include "pradis/lang/run_types.hpp"
#include "pradis/spatial/node_state.hpp"

namespace pradis::lang {

/// Builds the model and the outputs of a model file (the base of session).
class model_builder {
 public:
  /// Largest number of element instances a model file may create.
  static constexpr std::size_t max_elements = 200000;
  /// Largest number of fragment instances, of outputs and of values in one list.
  static constexpr std::size_t max_instances = 200000, max_outputs = 10000, max_list = 100000;

  /// Builds the model and its outputs. Throws lang_error.
  explicit model_builder(ast::program prog) : prog_(std::move(prog)), model_(std::make_unique<library_model>()) {
    build_data();
    build_structure();
    build_outputs();
  }
  model_builder(const model_builder&) = delete;
  model_builder& operator=(const model_builder&) = delete;

  /// The model (every library element type).
  library_model& model() noexcept { return *model_; }
  /// The outputs, in #OUTPUT order.
  const std::vector<output_column>& outputs() const noexcept { return outputs_; }
  /// The model DOF of a node number of the file (throws std::out_of_range if the node is not used).
  int dof_of_node(int node) const { return node_dof_.at(node); }
  /// The current value of a $DATA name.
  const std::vector<double>& data(const std::string& name) const { return data_.at(name).values; }

 protected:
  struct data_entry {
    std::vector<double> values;
    location loc;
  };
  struct element_record {
    std::string name;
    location loc;
    std::vector<ast::item> params;
    std::vector<double> values;
  };

  [[noreturn]] static void fail(const location& l, const std::string& msg) { throw lang_error(l, msg); }
  static std::string num(double x) {
    std::ostringstream os;
    os.precision(10);
    os << x;
    return os.str();
  }

  // ---- $DATA ----------------------------------------------------------------------
  std::vector<std::string> data_names() const {
    std::vector<std::string> v;
    for (const auto& [k, e] : data_) v.push_back(k);
    return v;
  }
  const data_entry& lookup(const ast::item& it) const {
    auto f = data_.find(it.text);
    if (f == data_.end()) fail(it.loc, "undefined $DATA name '" + it.text + "'" + did_you_mean(it.text, data_names()));
    return f->second;
  }
  /// Expands numbers and $DATA names (lists in place) into values.
  std::vector<double> expand(const std::vector<ast::item>& items, const char* where) const {
    std::vector<double> out;
    for (const auto& it : items) {
      if (it.what == ast::item::kind::number) {
        out.push_back(it.number);
      } else if (it.what == ast::item::kind::name) {
        const auto& v = lookup(it).values;
        if (out.size() + v.size() > max_list)
          fail(it.loc, "the list grows beyond " + std::to_string(max_list) + " values");
        for (double x : v) out.push_back(it.negate ? -x : x);
      } else {
        fail(it.loc, std::string("only numbers and $DATA names are allowed in ") + where);
      }
    }
    return out;
  }
  /// One number from a single item (a number or a scalar $DATA name).
  double scalar(const ast::item& it, const std::string& what) const {
    if (it.what == ast::item::kind::number) return it.number;
    if (it.what != ast::item::kind::name) fail(it.loc, what + " must be a number or a $DATA name");
    const auto& v = lookup(it).values;
    if (v.size() != 1)
      fail(it.loc, what + " needs one value; '" + it.text + "' is a list of " + std::to_string(v.size()));
    return it.negate ? -v[0] : v[0];
  }
  int whole(const ast::item& it, const std::string& what, int lo, int hi) const {
    const double x = scalar(it, what);
    if (!(x >= lo && x <= hi) || x != std::floor(x))
      fail(it.loc, what + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                       ", got " + num(x));
    return static_cast<int>(x);
  }

  void build_data() {
    for (const auto& d : prog_.data) {
      if (auto f = data_.find(d.name); f != data_.end())
        fail(d.loc, "$DATA name '" + d.name + "' is already defined at " + f->second.loc.str());
      auto v = expand(d.values, "$DATA");
      data_.emplace(d.name, data_entry{std::move(v), d.loc});
    }
  }

  // ---- $FRAGMENT / #STRUCTURE ----------------------------------------------------------
  /// How the nodes of a fragment being instantiated map to model DOFs.
  struct scope {
    std::string prefix;                            ///< instance-name prefix ("" for the main model)
    const std::map<int, int>* external = nullptr;  ///< fragment node -> model DOF (sub-structures)
    std::map<int, int> internal;                   ///< fragment-internal nodes -> model DOF
    std::vector<std::string> stack;                ///< fragments being instantiated (cycle check)
  };

  int node_dof(scope& sc, int node) {
    if (node == 0) return 0;
    if (!sc.external) {
      auto [it, fresh] = node_dof_.emplace(node, 0);
      if (fresh) it->second = model_->add_dof("node " + std::to_string(node)).index;
      return it->second;
    }
    if (auto e = sc.external->find(node); e != sc.external->end()) return e->second;
    auto [it, fresh] = sc.internal.emplace(node, 0);
    if (fresh) it->second = model_->add_dof(sc.prefix + "node " + std::to_string(node)).index;
    return it->second;
  }

  std::vector<int> node_list(const std::vector<ast::item>& items) const {
    std::vector<int> out;
    for (const auto& it : items) {
      if (it.what != ast::item::kind::number && it.what != ast::item::kind::name)
        fail(it.loc, "a node must be a whole number >= 0 (0 is the ground)");
      if (it.what == ast::item::kind::name && !data_.count(it.text))
        fail(it.loc, "a node must be a whole number >= 0, and '" + it.text + "' is not a $DATA name either" +
                         did_you_mean(it.text, data_names()));
      out.push_back(whole(it, "a node", 0, 1000000000));
    }
    return out;
  }

  const ast::fragment* find_fragment(const std::string& name) const {
    for (const auto& f : prog_.fragments)
      if (f.name == name) return &f;
    return nullptr;
  }

  void build_structure() {
    const ast::fragment* main = nullptr;
    for (const auto& f : prog_.fragments) {
      if (!f.name.empty()) {
        for (const auto& g : prog_.fragments)
          if (&g != &f && g.name == f.name) fail(g.loc, "$FRAGMENT " + f.name + " is defined twice");
        if (f.name == "" || find_element_passport(f.name))
          fail(f.loc, "fragment name " + f.name + " is the name of a library element");
        if (find_program(node_programs(), f.name))
          fail(f.loc, "fragment name " + f.name + " is the name of a node program (`pradis help " + f.name + "`)");
        continue;
      }
      if (main)
        fail(f.loc, "a second unnamed $FRAGMENT: the model has exactly one (name sub-structures: $FRAGMENT NAME)");
      main = &f;
    }
    if (!main) fail(prog_.end, "missing section $FRAGMENT (the model: $FRAGMENT with #STRUCTURE)");
    main_ = main;
    scope sc;
    instantiate(*main, sc);
    if (model_->element_count() == 0) fail(main->loc, "the model has no elements (#STRUCTURE is empty)");
  }

  static std::optional<passport> find_element_passport(const std::string& name) {
    std::optional<passport> p;
    library_model::for_each_type([&]<class E>(std::type_identity<E>) {
      if (E::passport.name == name) p = E::passport;
    });
    return p;
  }

  void instantiate(const ast::fragment& f, scope& sc) {
    for (const auto& c : f.structure) {
      if (auto p = find_element_passport(c.program)) {
        add_element(c, *p, sc);
      } else if (c.program == "PIVOT") {
        add_pivot(c, sc);
      } else if (const ast::fragment* sub = find_fragment(c.program); sub && !c.program.empty()) {
        add_instance(c, *sub, sc);
      } else {
        std::vector<std::string> cands = element_names();
        cands.emplace_back("PIVOT");
        for (const auto& g : prog_.fragments)
          if (!g.name.empty()) cands.push_back(g.name);
        std::string hint;
        if (find_program(output_programs(), c.program))
          hint = " ('" + c.program + "' is an output program: use it under #OUTPUT)";
        else if (find_program(integration_programs(), c.program))
          hint = " ('" + c.program + "' is an integration program: use it under $RUN)";
        else
          hint = did_you_mean(c.program, cands);
        fail(c.program_loc, "unknown element model '" + c.program + "'" + hint + "; `pradis list` shows the catalog");
      }
    }
  }

  void add_element(const ast::call& c, const passport& p, scope& sc) {
    const std::string model_name(p.name);
    if (model_->element_count() >= max_elements)
      fail(c.loc, "the model has more than " + std::to_string(max_elements) +
                      " elements (do nested fragment instances multiply?)");
    if (c.args.size() != 2)
      fail(c.args_loc,
           "an element needs (nodes; parameters): '" + model_name + "' " +
               (c.args.size() < 2 ? "has no ';' between its nodes and its parameters" : "has more than one ';'"));
    const std::vector<int> nodes = node_list(c.args[0]);
    if (static_cast<int>(nodes.size()) != p.ext)
      fail(c.args.front().empty() ? c.args_loc : c.args[0].front().loc,
           "'" + model_name + "' needs " + std::to_string(p.ext) + " node" + (p.ext == 1 ? "" : "s") +
               " (EXT = " + std::to_string(p.ext) + "), got " + std::to_string(nodes.size()));
    std::vector<double> par = expand(c.args[1], "an element's parameter list");
    const int npar = static_cast<int>(par.size());
    if (!p.parameter_count_ok(npar))
      fail(c.args[1].empty() ? c.args_loc : c.args[1].front().loc,
           "'" + model_name + "' takes " + std::string(p.parameter_rule()) + " = " + std::to_string(p.par) +
               " parameter" + (p.par == 1 ? "" : "s") + " (passport PAR = " + std::to_string(p.par) +
               ", VPR = " + std::to_string(p.vpr) + "), got " + std::to_string(npar) + " after expanding $DATA lists");
    std::vector<dof> ds;
    for (int n : nodes) ds.push_back(dof{node_dof(sc, n)});
    std::string name = c.label.empty() ? std::string() : sc.prefix + c.label;
    if (!name.empty())
      if (auto f = element_loc_.find(name); f != element_loc_.end())
        fail(c.loc, "an element named '" + name + "' is already defined at " + f->second.str());
    try {
      auto loc = model_->add_by_name(model_name, name, ds, par);
      if (name.empty()) name = instance_name(loc);
    } catch (const pradis::error& e) {
      fail(c.loc, e.message());
    }
    element_loc_[name] = c.loc;
    elements_.push_back({name, c.loc, c.args[1], par});
  }

  /// A ground pivot (catalog.hpp, node_programs): 'PIVOT (x y z q1 q2 q3; the 12 parameters of SPH3X),
  /// elements::add_ground_pivot on body b's reference point and rotational node (the node is made
  /// here if no element has made it yet; an element placed later on the same q1 q2 q3 shares it).
  void add_pivot(const ast::call& c, scope& sc) {
    if (c.args.size() != 2)
      fail(c.args_loc, std::string("a PIVOT needs (nodes; parameters): it ") +
                           (c.args.size() < 2 ? "has no ';' between its nodes and its parameters"
                                              : "has more than one ';'"));
    const std::vector<int> nodes = node_list(c.args[0]);
    if (nodes.size() != 6)
      fail(c.args.front().empty() ? c.args_loc : c.args[0].front().loc,
           "'PIVOT needs 6 nodes (body b's x y z and q1 q2 q3), got " + std::to_string(nodes.size()));
    for (std::size_t k = 0; k < 6; ++k)
      if (nodes[k] == 0)
        fail(c.args[0][k].loc, "a PIVOT holds a body that moves: its node " + std::to_string(k + 1) +
                                   " cannot be the ground (node 0)");
    const std::vector<double> par = expand(c.args[1], "a PIVOT's parameter list");
    if (par.size() != 12)
      fail(c.args[1].empty() ? c.args_loc : c.args[1].front().loc,
           "'PIVOT takes 12 parameters (the joint geometry of SPH3X), got " + std::to_string(par.size()) +
               " after expanding $DATA lists");
    std::vector<dof> ds;
    for (int n : nodes) ds.push_back(dof{node_dof(sc, n)});
    const std::string name = sc.prefix + (c.label.empty() ? "PIVOT " + std::to_string(++unlabelled_pivots_) : c.label);
    if (auto f = element_loc_.find(name); f != element_loc_.end())
      fail(c.loc, "an element or pivot named '" + name + "' is already defined at " + f->second.str());
    const elements::detail::joint_geometry geo{par[0], par[1], par[2], par[3], par[4],  par[5],
                                                par[6], par[7], par[8], par[9], par[10], par[11]};
    try {
      const auto node = model_->find_rotation_node(ds[3]);
      const rotation_node r = node ? *node : model_->add_rotation_node("", ds[3], ds[4], ds[5]);
      if (r.q1.index != ds[3].index || r.q2.index != ds[4].index || r.q3.index != ds[5].index)
        fail(c.args[0][3].loc, "nodes " + std::to_string(nodes[3]) + " " + std::to_string(nodes[4]) + " " +
                                   std::to_string(nodes[5]) +
                                   " are not the q1 q2 q3 of one spatial rotational node, in this order");
      pivots_[name] = model_->nodes<elements::ground_pivot_kind>().size();
      elements::add_ground_pivot(*model_, name, geo, ds[0], ds[1], ds[2], r);
    } catch (const pradis::error& e) {
      fail(c.loc, "PIVOT '" + name + "': " + e.message());
    }
    element_loc_[name] = c.loc;
  }

  std::string instance_name(const instance_location& loc) const {
    std::string out;
    std::size_t t = 0;
    model_->for_each_instances([&](const auto& vec) {
      if (t++ == loc.type) out = vec[static_cast<std::size_t>(loc.index)].name;
    });
    return out;
  }

  void add_instance(const ast::call& c, const ast::fragment& f, scope& sc) {
    if (c.label.empty())
      fail(c.loc, "an instance of fragment " + f.name + " needs a label (it prefixes the names inside)");
    for (const auto& s : sc.stack)
      if (s == f.name) fail(c.program_loc, "fragment " + f.name + " instantiates itself");
    if (sc.stack.size() >= 32) fail(c.program_loc, "fragments nested more than 32 levels deep");  // stack: levels above
    if (!f.has_external) fail(f.loc, "fragment " + f.name + " is used as a sub-structure but has no #EXTERNAL nodes");
    if (++instances_ > max_instances)
      fail(c.loc, "more than " + std::to_string(max_instances) + " fragment instances (do nested instances multiply?)");
    if (c.args.size() > 1) fail(c.args_loc, "a fragment instance takes only its external nodes: 'NAME (nodes)'");
    const std::vector<int> nodes = c.args.empty() ? std::vector<int>{} : node_list(c.args[0]);
    const std::vector<int> ext = node_list(f.external);
    if (nodes.size() != ext.size())
      fail(c.args_loc, "fragment " + f.name + " has " + std::to_string(ext.size()) +
                           " external nodes (#EXTERNAL), got " + std::to_string(nodes.size()));
    std::map<int, int> map;
    for (std::size_t k = 0; k < ext.size(); ++k) {
      if (ext[k] == 0) fail(f.external_loc, "the ground (node 0) cannot be an external node");
      if (!map.emplace(ext[k], node_dof(sc, nodes[k])).second)
        fail(f.external_loc, "node " + std::to_string(ext[k]) + " is listed twice in #EXTERNAL");
    }
    scope inner;
    inner.prefix = sc.prefix + c.label + ".";
    inner.external = &map;
    inner.stack = sc.stack;
    inner.stack.push_back(f.name);
    instantiate(f, inner);
    build_outputs_of(f, inner);
  }

  // ---- #OUTPUT --------------------------------------------------------------------------
  void build_outputs() {
    scope sc;
    build_outputs_of(*main_, sc);
  }

  void build_outputs_of(const ast::fragment& f, scope& sc) {
    for (const auto& c : f.outputs) {
      output_column o;
      o.loc = c.loc;
      const program_info* prog = find_program(output_programs(), c.program);
      if (!prog) {
        std::string hint = find_element_passport(c.program)
                               ? " ('" + c.program + "' is an element model: use it under #STRUCTURE)"
                               : did_you_mean(c.program, names_of(output_programs()));
        fail(c.program_loc, "unknown output program '" + c.program + "'" + hint);
      }
      if (c.program == "X") {
        if (c.args.empty() || c.args.size() > 2 || c.args[0].size() != 1)
          fail(c.args_loc, "'X needs (node; order) or (W:Element(k); 1)");
        if (c.args.size() == 2) {
          if (c.args[1].size() != 1)
            fail(c.args_loc, "'X takes one order after ';' (1 displacement, 2 velocity, 3 acceleration)");
          o.order = whole(c.args[1][0], "the order of 'X (1 displacement, 2 velocity, 3 acceleration)", 1, 3);
        }
        const ast::item& target = c.args[0][0];
        if (target.what == ast::item::kind::work) {
          o.what = output_column::kind::work;
          o.element = sc.prefix + target.text;
          o.index = target.index;
          if (o.order != 1) fail(c.args[1][0].loc, "a work-vector entry has only order 1 (its value)");
          if (auto p = pivots_.find(o.element); p != pivots_.end()) {  // a PIVOT's force on its body
            if (o.index > 3)
              fail(target.index_loc, "PIVOT '" + o.element + "' has 3 outputs, its force on the body along X, Y, "
                                     "Z: W:" + target.text + "(" + std::to_string(o.index) + ") does not exist");
            o.what = output_column::kind::pivot_force;
            o.pivot = p->second;
          } else {
            work_output(o, target);
          }
        } else {
          o.what = output_column::kind::potential;
          const int node = node_list({target}).front();
          if (node == 0) fail(target.loc, "node 0 is the ground: its potential is always zero");
          o.dof = output_dof(f, sc, node, target.loc);
          o.node = node;
        }
      } else if (c.program == "W" || c.program == "LQ") {
        const bool w = c.program == "W";
        const char* usage = w ? "'W needs (q1 q2 q3; k): the three rotation nodes of a spatial node and the axis "
                                "k = 1, 2, 3 (X, Y, Z)"
                              : "'LQ needs (q1 q2 q3): the three rotation nodes of a spatial node";
        if (c.args.empty() || c.args[0].size() != 3 || c.args.size() != (w ? 2u : 1u)) fail(c.args_loc, usage);
        const std::vector<int> nodes = node_list(c.args[0]);
        std::array<int, 3> dofs{};
        int first = -1;  // a component on the ground (node 0) is a fixed angular DOF
        for (std::size_t k = 0; k < 3; ++k)
          if (nodes[k] != 0) {
            dofs[k] = output_dof(f, sc, nodes[k], c.args[0][k].loc);
            if (first < 0) first = dofs[k];
          }
        if (first < 0) fail(c.args[0][0].loc, "nodes 0 0 0 are the ground, not a spatial rotational node");
        const auto rn = model_->find_rotation_node(dof{first});
        if (!rn || rn->q1.index != dofs[0] || rn->q2.index != dofs[1] || rn->q3.index != dofs[2])
          fail(c.args[0][0].loc, "nodes " + std::to_string(nodes[0]) + " " + std::to_string(nodes[1]) + " " +
                                     std::to_string(nodes[2]) +
                                     " are not the q1 q2 q3 of a spatial rotational node, in this order (a node is "
                                     "made by the rotational DOFs of an element such as BODY3)");
        o.rotation = *rn;
        o.nodes = std::to_string(nodes[0]) + " " + std::to_string(nodes[1]) + " " + std::to_string(nodes[2]);
        if (w) {
          if (c.args[1].size() != 1) fail(c.args_loc, usage);
          o.order = whole(c.args[1][0], "the axis of 'W (1 X, 2 Y, 3 Z)", 1, 3);
          o.what = output_column::kind::angular_velocity;
        } else {
          o.what = output_column::kind::norm;
        }
      } else {
        if (!c.args.empty() && !(c.args.size() == 1 && c.args[0].empty()))
          fail(c.args_loc, "'" + c.program + " takes no arguments: '" + c.program + " ()");
        o.what = output_column::kind::statistic;
        o.statistic = c.program;
      }
      o.label = c.label.empty() ? auto_label(c, o) : sc.prefix + c.label;
      if (auto [it, fresh] = output_labels_.emplace(o.label, c.loc); !fresh)
        fail(c.loc, "an output labelled '" + o.label + "' is already defined at " + it->second.str());
      if (outputs_.size() >= max_outputs) fail(c.loc, "more than " + std::to_string(max_outputs) + " outputs");
      outputs_.push_back(std::move(o));
    }
  }

  /// The model DOF of node `node` of fragment f (its external or internal node), for an output.
  int output_dof(const ast::fragment& f, const scope& sc, int node, const location& loc) const {
    if (sc.external) {
      if (auto e = sc.external->find(node); e != sc.external->end()) return e->second;
      if (auto i = sc.internal.find(node); i != sc.internal.end()) return i->second;
      fail(loc, "node " + std::to_string(node) + " is not connected to any element of fragment " + f.name);
    }
    auto it = node_dof_.find(node);
    if (it == node_dof_.end()) fail(loc, "node " + std::to_string(node) + " is not connected to any element");
    return it->second;
  }

  /// Checks 'X (W:Element(k); 1): the element exists and has entry k.
  void work_output(const output_column& o, const ast::item& target) const {
    auto loc = model_->find(o.element);
    if (!loc) {
      std::vector<std::string> names;
      for (const auto& [k, v] : element_loc_) names.push_back(k);
      fail(target.loc, "no element named '" + o.element + "'" + did_you_mean(o.element, names));
    }
    const auto size = model_->work(o.element).size();
    if (static_cast<std::size_t>(o.index) > size)
      fail(target.index_loc, "element '" + o.element + "' (" + std::string(model_->type_name(*loc)) + ") has " +
                                 std::to_string(size) + " work-vector entr" + (size == 1 ? "y" : "ies") + "; W:" +
                                 target.text + "(" + std::to_string(o.index) + ") does not exist");
  }

  static std::string auto_label(const ast::call& c, const output_column& o) {
    switch (o.what) {
      case output_column::kind::potential:
        return "X(" + std::to_string(o.node) + ";" + std::to_string(o.order) + ")";
      case output_column::kind::work:
      case output_column::kind::pivot_force:
        return "X(W:" + o.element + "(" + std::to_string(o.index) + "))";
      case output_column::kind::statistic:
        return c.program;
      case output_column::kind::angular_velocity:
        return "W(" + o.nodes + ";" + std::to_string(o.order) + ")";
      case output_column::kind::norm:
        return "LQ(" + o.nodes + ")";
    }
    return c.program;
  }

  ast::program prog_;
  std::unique_ptr<library_model> model_;
  const ast::fragment* main_ = nullptr;
  std::map<std::string, data_entry> data_;
  std::map<int, int> node_dof_;
  std::map<std::string, location> element_loc_;
  std::vector<element_record> elements_;
  std::vector<output_column> outputs_;
  std::map<std::string, location> output_labels_;
  std::size_t instances_ = 0;
  int unlabelled_pivots_ = 0;                 ///< PIVOTs without a label so far (their names)
  std::map<std::string, std::size_t> pivots_;  ///< PIVOT name -> its index among the model's ground pivots
};

}  // namespace pradis::lang
