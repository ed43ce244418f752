#pragma once
/// \file
/// The builder and runner of the model language: a session turns an
/// ast::program into a library_model (every element type of the built-in
/// library), its outputs and its list of actions (run stages, displays,
/// $REPLACE, $SAVE, $RESTORE), checks everything that can be checked before the
/// run with `file:line:column` messages, then executes the actions.

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/progress.hpp"
#include "pradis/io/csv_file.hpp"
#include "pradis/io/table.hpp"
#include "pradis/lang/ast.hpp"
#include "pradis/lang/catalog.hpp"
#include "pradis/lang/parser.hpp"
#include "pradis/spatial/node_state.hpp"

namespace pradis::lang {

/// How a session writes its results.
struct run_settings {
  std::string output_dir = ".";  ///< directory for CSV, PNG and checkpoints ($SAVE/$RESTORE paths are relative to it)
  std::string stem = "model";    ///< prefix of the output files
  bool plot = true;              ///< false: 'DISP requests no PNG (session::plots() stays empty)
  bool write_files = true;       ///< false: no CSV and no SAVE-interval checkpoints (tests)
  std::ostream* log = nullptr;   ///< report lines (stages, files written), or none
  /// A one-line progress display redrawn in place while a stage runs (for a
  /// terminal: `pradis run` passes stderr when it is one), or none.
  std::ostream* progress = nullptr;
  /// Set to non-zero (by a signal handler: `pradis run` on SIGINT and SIGTERM)
  /// to stop the run at the next step: run() then closes the results file with
  /// the rows computed so far and throws lang::interrupted. Null: never stops.
  const volatile std::sig_atomic_t* stop = nullptr;
};

/// A plot that a 'DISP asked for: the application draws it (the library does
/// not run external programs; `pradis run` uses gnuplot, apps/common/gnuplot.hpp).
struct plot_request {
  std::vector<std::string> names;  ///< column labels (the CSV's columns after time)
  std::string csv, png, title;     ///< data file (already written), image to draw, title
};

/// Thrown by session::run() when run_settings::stop was set: the run stopped at
/// time(); the results file holds the rows computed until then.
class interrupted : public std::runtime_error {
 public:
  /// The run stopped at simulated time t.
  explicit interrupted(double t) : std::runtime_error("run interrupted"), t_(t) {}
  /// Simulated time at which the run stopped.
  double time() const noexcept { return t_; }

 private:
  double t_;
};

/// The integration scheme of a language stage: any member of the alpha family
/// (SHTERM, NEWMARK, HHT, GALPHA), given by its four parameters, which the
/// library's scheme classes have validated. The arithmetic is alpha_scheme's,
/// so a stage computes exactly what the library's scheme of the same name does.
class stage_scheme : public alpha_scheme {
 public:
  /// Prefix of the simulation's option messages (the session replaces it by the program name).
  static constexpr std::string_view name = "STAGE";
  /// PRADIS's Stoermer scheme (SHTERM).
  stage_scheme() : stage_scheme(stoermer{}) {}
  /// The scheme with the parameters of `s` (newmark, stoermer, hht, generalized_alpha).
  explicit stage_scheme(const alpha_scheme& s) : stage_scheme(s.coefficients_set()) {}
  /// The scheme with parameters taken from one of the library's schemes (not checked again).
  explicit stage_scheme(const alpha_parameters& q) { p_ = q; }
};

/// One output variable (#OUTPUT line).
struct output_column {
  enum class kind { potential, work, statistic, angular_velocity, norm };
  std::string label;
  location loc;
  kind what = kind::potential;
  int node = 0, dof = 0, order = 1;  ///< potential: node, model DOF, 1 u / 2 v / 3 a
  std::string element;               ///< work: instance name
  int index = 0;                     ///< work: 1-based entry
  std::string statistic;             ///< statistic: NSTEP, NITER, ...
  rotation_node rotation{};          ///< angular_velocity ('W, component in order) and norm ('LQ)
  std::string nodes;                 ///< 'W, 'LQ: the three node numbers as written, for the label
};

/// What one run stage did (for the report of `pradis run`).
struct stage_report {
  std::string label, program;
  double t0 = 0, t1 = 0;
  run_statistics stats;
};

/// A model file turned into a model and a list of actions.
class session {
 public:
  /// The simulation of a model file: OPTIM picks the ordering level of its solver per stage.
  using sim_type = simulation<library_model, stage_scheme, linalg::sparse_lu<linalg::optim_ordering>>;
  /// Largest number of element instances a model file may create.
  static constexpr std::size_t max_elements = 200000;
  /// Largest number of fragment instances, of outputs and of values in one list.
  static constexpr std::size_t max_instances = 200000, max_outputs = 10000, max_list = 100000;
  /// Largest number of checkpoints the SAVE key of one stage may write.
  static constexpr double max_checkpoints = 10000;
  /// Largest number of output rows of a run (all stages): 10 million rows of
  /// 10 outputs are 800 MB in memory and about 2 GB of CSV.
  static constexpr double max_rows = 1e7;

  /// Builds the model and checks outputs and actions. Throws lang_error.
  explicit session(ast::program prog) : prog_(std::move(prog)), model_(std::make_unique<library_model>()) {
    build_data();
    build_structure();
    build_outputs();
    check_actions();
  }
  session(const session&) = delete;
  session& operator=(const session&) = delete;

  /// Executes the actions in file order and writes `<stem>.csv` with every
  /// output. Throws lang_error (model errors during the run are located at the
  /// element's line, run failures at the stage's line), pradis::error with code
  /// io_error if a file cannot be written (with the system's reason), or
  /// interrupted (run_settings::stop).
  ///
  /// The rows of `<stem>.csv` are written as they are computed, to
  /// `<stem>.csv.part`; the output directory and that file are created before
  /// the first stage, so an unusable directory fails at once. When the run ends,
  /// normally or by an error or interruption, the file is closed (checked) and
  /// renamed to `<stem>.csv`, so the rows computed before a failure are kept; if
  /// writing the file fails, it is removed rather than left truncated.
  void run(const run_settings& s = {}) {
    settings_ = s;
    progress_ = settings_.progress ? std::make_unique<io::progress_line>(*settings_.progress) : nullptr;
    if (settings_.write_files) open_results();
    try {
      run_actions();
    } catch (...) {
      if (csv_) {
        try {
          close_results(true);
        } catch (const pradis::error& e) {  // the run's error comes first; report the file's too
          note("results: " + e.message());
        }
      }
      throw;
    }
    if (csv_) close_results(false);
  }

  /// The model (every library element type).
  library_model& model() noexcept { return *model_; }
  /// The outputs, in #OUTPUT order.
  const std::vector<output_column>& outputs() const noexcept { return outputs_; }
  /// Every output sampled over time (column order as outputs()).
  const io::table& results() const noexcept { return results_; }
  /// The model DOF of a node number of the file (throws std::out_of_range if the node is not used).
  int dof_of_node(int node) const { return node_dof_.at(node); }
  /// The current value of a $DATA name.
  const std::vector<double>& data(const std::string& name) const { return data_.at(name).values; }
  /// Files written by run().
  const std::vector<std::string>& files() const noexcept { return files_; }
  /// One report per executed stage.
  const std::vector<stage_report>& stages() const noexcept { return reports_; }
  /// The plots the 'DISP calls of the run asked for (their CSV files are written).
  const std::vector<plot_request>& plots() const noexcept { return plots_; }
  /// The simulation (null before the first stage or $RESTORE).
  const sim_type* simulation_ptr() const noexcept { return sim_.get(); }

 private:
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
  void note(const std::string& s) const {
    if (progress_ && settings_.log) progress_->clear();  // the log may share the terminal
    if (settings_.log) *settings_.log << s << '\n';
  }
  static std::string num(double x) {
    std::ostringstream os;
    os.precision(10);
    os << x;
    return os.str();
  }

  void run_actions() {
    for (const auto& a : prog_.actions) {
      switch (a.what) {
        case ast::action::kind::run:
          run_stage(a.stage);
          break;
        case ast::action::kind::print:
          display(a.stage);
          break;
        case ast::action::kind::replace:
          replace(a);
          break;
        case ast::action::kind::save:
          save(a);
          break;
        case ast::action::kind::restore:
          restore(a);
          break;
      }
    }
  }

  /// Creates the output directory and starts `<stem>.csv` (as `<stem>.csv.part`),
  /// so that an unusable directory is reported before any stage runs.
  void open_results() {
    std::error_code ec;
    const std::string& dir = settings_.output_dir;
    if (dir.empty()) throw pradis::error(error_code::io_error, "the output directory name is empty");
    std::filesystem::create_directories(dir, ec);
    if (!ec && !std::filesystem::is_directory(dir, ec)) ec = std::make_error_code(std::errc::not_a_directory);
    if (ec)
      throw pradis::error(error_code::io_error, "cannot use the output directory '" + dir + "': " +
                                                    ec.message());
    if (outputs_.empty()) return;
    std::vector<std::string> names;
    for (const auto& o : outputs_) names.push_back(o.label);
    csv_ = std::make_unique<io::csv_file>(path_in_output(settings_.stem + ".csv"), names);
  }

  /// Closes `<stem>.csv` (checked) under its final name. `early`: the run did not
  /// finish (an error or an interruption); the rows computed so far are kept.
  void close_results(bool early) {
    auto f = std::move(csv_);
    f->commit();
    note(std::string(early ? "results so far: " : "results: ") + f->path() + " (" + std::to_string(f->rows()) +
         " rows, " + std::to_string(outputs_.size()) + " outputs" +
         (early && sim_ ? ", up to t = " + num(sim_->time()) : std::string()) + ")");
    files_.push_back(f->path());
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
      } else if (const ast::fragment* sub = find_fragment(c.program); sub && !c.program.empty()) {
        add_instance(c, *sub, sc);
      } else {
        std::vector<std::string> cands = element_names();
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
    if (sc.stack.size() > 32) fail(c.program_loc, "fragments nested more than 32 levels deep");
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
    std::vector<std::string> names;
    for (const auto& o : outputs_) names.push_back(o.label);
    results_ = io::table(names);
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
          auto loc = model_->find(o.element);
          if (!loc) {
            std::vector<std::string> names;
            for (const auto& [k, v] : element_loc_) names.push_back(k);
            fail(target.loc, "no element named '" + o.element + "'" + did_you_mean(o.element, names));
          }
          const auto size = model_->work(o.element).size();
          if (static_cast<std::size_t>(o.index) > size)
            fail(target.index_loc, "element '" + o.element + "' (" + std::string(model_->type_name(*loc)) + ") has " +
                                       std::to_string(size) + " work-vector entr" + (size == 1 ? "y" : "ies") +
                                       "; W:" + target.text + "(" + std::to_string(o.index) + ") does not exist");
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

  static std::string auto_label(const ast::call& c, const output_column& o) {
    switch (o.what) {
      case output_column::kind::potential:
        return "X(" + std::to_string(o.node) + ";" + std::to_string(o.order) + ")";
      case output_column::kind::work:
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

  // ---- actions: static checks ----------------------------------------------------------------
  void check_actions() {
    for (const auto& a : prog_.actions) {
      if (a.what == ast::action::kind::run) (void)stage_options(a.stage);
      if (a.what == ast::action::kind::print) (void)display_options(a.stage);
      if (a.what == ast::action::kind::replace)
        for (const auto& d : a.definitions) {
          if (!data_.count(d.name))
            fail(d.loc, "$REPLACE of an undefined $DATA name '" + d.name + "'" + did_you_mean(d.name, data_names()));
          (void)expand(d.values, "$REPLACE");
        }
    }
    // Two displays must not write the same file: labels that differ only in
    // characters replaced by '_' ("a b", "a_b"), or in case (a file system may
    // not tell "A" from "a"), or a label such as DISP2 that is also an unlabelled
    // display's name.
    std::map<std::string, location> files;
    int k = 0;
    for (const auto& a : prog_.actions) {
      if (a.what != ast::action::kind::print) continue;
      const ast::call& c = a.stage;
      const std::string f =
          upper(c.label.empty() ? upper(c.program) + std::to_string(++k) : (++k, file_part(c.label)));
      if (auto [it, fresh] = files.emplace(f, c.loc); !fresh)
        fail(c.loc, "this display would write the same files as the display at " + it->second.str() + " (<stem>." +
                        f + ".csv; labels become file names with characters other than letters, digits, - and _ "
                        "replaced by _, and case is ignored): give it another label");
    }
    bool any_run = false;
    for (const auto& a : prog_.actions) any_run = any_run || a.what == ast::action::kind::run;
    if (!any_run) fail(prog_.end, "missing section $RUN (at least one stage, e.g. `Calculation 'SHTERM (END=1)`)");
  }

  struct stage_spec {
    run_options opt;
    alpha_parameters scheme;  ///< the program's scheme, validated
    double save = 0;          ///< SAVE: checkpoint interval (0: none)
    location save_loc;        ///< where SAVE is
    location out_loc;         ///< where OUT is
    int optim = -1;           ///< OPTIM: ordering level 0..4, or -1 to choose by size
  };

  /// The program that owns a scheme key (BETA, GAMMA, ALPHA, RHOINF), or "" for a common key.
  static std::string owner_of_key(const std::string& k) {
    if (k == "BETA" || k == "GAMMA") return "NEWMARK";
    if (k == "ALPHA") return "HHT";
    if (k == "RHOINF") return "GALPHA";
    return "";
  }

  stage_spec stage_options(const ast::call& c) const {
    const program_info* prog = find_program(integration_programs(), c.program);
    if (!prog) {
      std::string hint = find_element_passport(c.program)
                             ? " ('" + c.program + "' is an element model: use it under #STRUCTURE)"
                             : did_you_mean(c.program, names_of(integration_programs()));
      fail(c.program_loc, "unknown integration program '" + c.program + "'" + hint);
    }
    stage_spec s;
    newmark_parameters np{};
    double alpha = hht{}.alpha(), rho = generalized_alpha{}.rho_inf();
    std::set<std::string> seen;
    bool has_end = false;
    static const std::vector<std::string> known{"END",   "OUT",   "SMAX",  "SMIN",    "IGNORE",  "DABSU",
                                                "DRLTU", "DABSI", "DRLTI", "ITR",     "SECOND",  "BETA",
                                                "GAMMA", "ALPHA", "RHOINF", "DABSX",  "DRLTX",   "CONTROL",
                                                "PREDICT", "SAVE",  "OPTIM"};
    for (const auto& g : c.args)
      for (const auto& it : g) {
        if (it.what != ast::item::kind::keyed)
          fail(it.loc, "an integration program takes KEY=value arguments (e.g. END=1)");
        const std::string& k = it.text;
        if (!seen.insert(k).second) fail(it.loc, "key " + k + " is given twice");
        const ast::item& v = it.value.front();
        bool is_unimpl = false;
        for (const auto& u : unimplemented_run_keys()) is_unimpl = is_unimpl || u == k;
        if (is_unimpl) {
          std::string own;
          for (const char* q : {"BETA", "GAMMA", "ALPHA", "RHOINF"})
            if (owner_of_key(q) == c.program) own += std::string(" ") + q;
          fail(it.loc, "key " + k + " of " + c.program +
                           " is not implemented by pradis yet (implemented: END OUT SMAX SMIN IGNORE DABSU DRLTU DABSI "
                           "DRLTI ITR SECOND DABSX DRLTX CONTROL PREDICT SAVE OPTIM" +
                           own + ")");
        }
        const std::string owner = owner_of_key(k);
        if (!owner.empty() && owner != c.program)
          fail(it.loc, "key " + k + " belongs to " + owner + ", not to " + c.program +
                           (c.program == "SHTERM" ? " (SHTERM has fixed BETA = 1/2, GAMMA = 1)" : ""));
        if (k == "END") {
          s.opt.end = scalar(v, "END");
          has_end = true;
        } else if (k == "OUT") {
          s.opt.out = scalar(v, "OUT");
          s.out_loc = it.loc;
        }
        else if (k == "SMAX")
          s.opt.smax = scalar(v, "SMAX");
        else if (k == "SMIN")
          s.opt.smin = scalar(v, "SMIN");
        else if (k == "IGNORE")
          s.opt.ignore = whole(v, "IGNORE", 0, 1) == 1;
        else if (k == "SECOND")
          s.opt.newton.second = whole(v, "SECOND", 0, 1) == 1;
        else if (k == "DABSU")
          s.opt.newton.dabsu = scalar(v, "DABSU");
        else if (k == "DRLTU")
          s.opt.newton.drltu = scalar(v, "DRLTU");
        else if (k == "DABSI")
          s.opt.newton.dabsi = scalar(v, "DABSI");
        else if (k == "DRLTI")
          s.opt.newton.drlti = scalar(v, "DRLTI");
        else if (k == "ITR")
          s.opt.newton.itr = whole(v, "ITR", 1, 1000);
        else if (k == "DABSX") {
          s.opt.dabsx = scalar(v, "DABSX");
          s.opt.error_control = true;
        } else if (k == "DRLTX") {
          s.opt.drltx = scalar(v, "DRLTX");
          s.opt.error_control = true;
        } else if (k == "CONTROL") {
          s.opt.control = scalar(v, "CONTROL");
          s.opt.error_control = true;
        } else if (k == "PREDICT") {
          s.opt.predict = whole(v, "PREDICT", 0, 1) == 1;
          s.opt.error_control = true;
        } else if (k == "SAVE") {
          s.save = scalar(v, "SAVE");
          s.save_loc = it.loc;
          if (!(s.save > 0) || !std::isfinite(s.save))
            fail(it.loc, "SAVE = " + num(s.save) +
                             " must be a number > 0 (the interval of simulated time between checkpoints)");
        } else if (k == "OPTIM")
          s.optim = whole(v, "OPTIM", linalg::optim_min_level, linalg::optim_max_level);
        else if (k == "BETA")
          np.beta = scalar(v, "BETA");
        else if (k == "GAMMA")
          np.gamma = scalar(v, "GAMMA");
        else if (k == "ALPHA") {
          alpha = scalar(v, "ALPHA");
          try {
            (void)hht(alpha);
          } catch (const pradis::error&) {
            fail(it.loc, "HHT: ALPHA = " + num(alpha) + " is outside its valid range -1/3 <= ALPHA <= 0");
          }
        } else if (k == "RHOINF") {
          rho = scalar(v, "RHOINF");
          try {
            (void)generalized_alpha(rho);
          } catch (const pradis::error&) {
            fail(it.loc, "GALPHA: RHOINF = " + num(rho) + " is outside its valid range 0 <= RHOINF <= 1");
          }
        } else
          fail(it.loc, "unknown key " + k + " of " + c.program + did_you_mean(k, known));
      }
    if (!has_end) fail(c.args_loc, c.program + " needs END=<end time>");
    try {
      if (c.program == "SHTERM")
        s.scheme = stoermer{}.coefficients_set();
      else if (c.program == "NEWMARK")
        s.scheme = newmark(np).coefficients_set();
      else if (c.program == "HHT")
        s.scheme = hht(alpha).coefficients_set();
      else
        s.scheme = generalized_alpha(rho).coefficients_set();
    } catch (const pradis::error& e) {
      fail(c.args_loc, e.message());
    }
    return s;
  }

  struct display_spec {
    std::vector<int> columns;
    double start = -HUGE_VAL, end = HUGE_VAL;
  };

  display_spec display_options(const ast::call& c) const {
    if (!find_program(display_programs(), c.program))
      fail(c.program_loc,
           "unknown display program '" + c.program + "'" + did_you_mean(c.program, names_of(display_programs())));
    display_spec d;
    for (const auto& g : c.args)
      for (const auto& it : g) {
        if (it.what == ast::item::kind::keyed) {
          if (it.text == "START")
            d.start = scalar(it.value.front(), "START");
          else if (it.text == "END")
            d.end = scalar(it.value.front(), "END");
          else if (it.text == "OUT" || it.text == "FORMF")
            fail(it.loc,
                 "key " + it.text + " of " + c.program + " is not implemented by pradis yet (implemented: START END)");
          else
            fail(it.loc, "unknown key " + it.text + " of " + c.program + did_you_mean(it.text, {"START", "END"}));
        } else if (it.what == ast::item::kind::name) {
          int found = -1;
          std::vector<std::string> labels;
          for (std::size_t k = 0; k < outputs_.size(); ++k) {
            labels.push_back(outputs_[k].label);
            if (outputs_[k].label == it.text) found = static_cast<int>(k);
          }
          if (found < 0) fail(it.loc, "no output labelled '" + it.text + "'" + did_you_mean(it.text, labels));
          d.columns.push_back(found);
        } else {
          fail(it.loc, "a display program takes output labels and START=, END=");
        }
      }
    if (d.columns.empty())
      for (std::size_t k = 0; k < outputs_.size(); ++k) d.columns.push_back(static_cast<int>(k));
    if (d.columns.empty()) fail(c.loc, "nothing to display: the model has no #OUTPUT");
    return d;
  }

  // ---- actions: execution -------------------------------------------------------------------
  void record(const sim_type& s) {
    std::vector<double> row;
    row.reserve(outputs_.size());
    for (const auto& o : outputs_) {
      switch (o.what) {
        case output_column::kind::potential: {
          const dof d{o.dof};
          row.push_back(o.order == 1 ? s.u(d) : (o.order == 2 ? s.v(d) : s.a(d)));
          break;
        }
        case output_column::kind::work:
          row.push_back(s.get_model().work(o.element)[static_cast<std::size_t>(o.index - 1)]);
          break;
        case output_column::kind::statistic:
          row.push_back(s.statistic(o.statistic));
          break;
        case output_column::kind::angular_velocity:
          row.push_back(spatial::node_angular_velocity(s, o.rotation)(o.order - 1));
          break;
        case output_column::kind::norm:
          row.push_back(spatial::node_norm(s, o.rotation));
          break;
      }
    }
    if (static_cast<double>(results_.rows()) >= max_rows)
      throw pradis::error(error_code::invalid_option,
                          "the run has produced " + num(max_rows) + " output rows, the most pradis writes: make OUT "
                          "larger (or SMAX, with OUT = 0: a row every step)");
    results_.add_row(s.time(), row);
    if (csv_) csv_->add_row(s.time(), row);
  }

  /// Stops the run if run_settings::stop was set (by a signal).
  void check_stop(const sim_type& s) const {
    if (settings_.stop && *settings_.stop) throw interrupted(s.time());
  }

  std::unique_ptr<sim_type> make_sim(const alpha_parameters& p) {
    auto s = std::make_unique<sim_type>(*model_, stage_scheme(p));
    s->on_output([this](const sim_type& x) {
      record(x);
      show_progress(x);  // also at t0, before the first step
      check_stop(x);
    });
    // Every accepted step; the progress line itself redraws at most ten times a second.
    s->on_step([this](const sim_type& x) {
      show_progress(x);
      check_stop(x);
    });
    return s;
  }

  void show_progress(const sim_type& x) {
    if (!progress_) return;
    const run_statistics& st = x.statistics();
    progress_->update(x.time(), st.last_step, st.last_iterations, st.newton_iterations);
  }

  static bool same_scheme(const alpha_parameters& a, const alpha_parameters& b) {
    return a.alpha_m == b.alpha_m && a.alpha_f == b.alpha_f && a.beta == b.beta && a.gamma == b.gamma;
  }

  /// A simulation with the scheme p, continuing the current one (via an in-memory
  /// checkpoint) if any. A change of scheme starts the new one afresh (its
  /// pseudo-acceleration p = a, as at t = 0), unless the previous scheme is not
  /// known (a $RESTORE of a checkpoint without the session's scheme record).
  void use_scheme(const alpha_parameters& p) {
    if (sim_ && same_scheme(scheme_, p)) {
      scheme_known_ = true;
      return;
    }
    auto next = make_sim(p);
    if (sim_ && started_) {
      std::stringstream ss;
      sim_->save_checkpoint(ss);
      next->load_checkpoint(ss);
      if (scheme_known_) next->restart_scheme();
    }
    sim_ = std::move(next);
    scheme_ = p;
    scheme_known_ = true;
  }

  [[noreturn]] void rethrow(const pradis::error& e, const ast::call& c) const {
    if (e.code() == error_code::io_error) throw e;  // a results file: the message names it, not the model
    std::string what = std::string(e.element_type());
    if (!e.instance().empty()) what += (what.empty() ? "'" : " '") + e.instance() + "'";
    std::string msg = e.message();
    const std::string prefix = std::string(stage_scheme::name) + ": ";
    if (e.code() == error_code::invalid_option && msg.rfind(prefix, 0) == 0)
      msg = c.program + ": " + msg.substr(prefix.size());
    msg = (what.empty() ? "" : what + ": ") + msg + " (pradis error " + std::to_string(e.number()) + ", " +
          std::string(to_string(e.code())) + ")";
    if (!e.instance().empty())
      if (auto f = element_loc_.find(e.instance()); f != element_loc_.end())
        fail(f->second, msg + "; during the stage at " + c.loc.str());
    fail(c.loc, msg);
  }

  /// The first checkpoint time of the SAVE grid after t: the smallest k SAVE > t
  /// (k whole). The grid is absolute (multiples of SAVE from t = 0), so a run
  /// restarted from a checkpoint meets the same checkpoint times.
  static double next_save_time(double t, double save) {
    double k = std::floor(t / save);
    while (k * save <= t) k += 1;
    return k * save;
  }

  /// Checks that the SAVE grid of a stage from t0 to end is usable.
  void check_save(const stage_spec& st, double t0) const {
    const double count = (st.opt.end - t0) / st.save;
    if (count > max_checkpoints)
      fail(st.save_loc, "SAVE = " + num(st.save) + " would write " + num(std::floor(count)) +
                            " checkpoints in this stage (from t = " + num(t0) + " to END = " + num(st.opt.end) +
                            "); at most " + num(max_checkpoints) + " are allowed");
    if (st.opt.end / st.save > 1e11)
      fail(st.save_loc, "SAVE = " + num(st.save) + " is too small for END = " + num(st.opt.end) +
                            ": checkpoint times k SAVE need k <= 1e11");
  }

  /// Runs one stage; with SAVE, in pieces that end at the checkpoint times.
  void run_stage(const ast::call& c) {
    const stage_spec st = stage_options(c);  // again: $REPLACE may have changed $DATA values
    use_scheme(st.scheme);
    if (sim_->solver().ordering().level != st.optim)
      sim_->set_solver(linalg::sparse_lu<linalg::optim_ordering>(linalg::optim_ordering{st.optim}));
    const double t0 = started_ ? sim_->time() : 0.0;
    if (started_ && !(st.opt.end > t0))
      fail(c.args_loc, "END = " + num(st.opt.end) + " must be after the current time " + num(t0));
    if (st.save > 0) check_save(st, t0);
    if (st.opt.out > 0 && static_cast<double>(results_.rows()) + (st.opt.end - t0) / st.opt.out > max_rows)
      fail(st.out_loc, "OUT = " + num(st.opt.out) + " would write " + num(std::floor((st.opt.end - t0) / st.opt.out)) +
                           " output rows in this stage (from t = " + num(t0) + " to END = " + num(st.opt.end) +
                           "); at most " + num(max_rows) + " rows are written in a run: make OUT larger");
    stage_report r{c.label, c.program, t0, st.opt.end, {}};
    const run_statistics before = sim_->statistics();
    struct progress_guard {
      io::progress_line* p;
      ~progress_guard() {
        if (p) p->end();
      }
    } guard{progress_.get()};
    if (progress_) progress_->begin((c.label.empty() ? "" : c.label + " ") + c.program, t0, st.opt.end);
    try {
      if (st.save > 0) {
        for (;;) {
          const double next = next_save_time(started_ ? sim_->time() : t0, st.save);
          const double tol = 1e-9 * st.save;
          const bool last = !(next < st.opt.end - tol);
          run_options o = st.opt;
          if (!last) o.end = next;
          (void)sim_->run(o);
          started_ = true;
          if (!last || std::abs(next - st.opt.end) <= tol) write_interval_checkpoint(c);
          if (last) break;
        }
      } else {
        (void)sim_->run(st.opt);
      }
    } catch (const pradis::error& e) {
      rethrow(e, c);
    }
    started_ = true;
    r.stats = sim_->statistics() - before;
    if (progress_) progress_->end();
    note("stage " + std::to_string(reports_.size() + 1) + (c.label.empty() ? "" : " '" + c.label + "'") + " " +
         c.program + ": t = " + num(r.t0) + " .. " + num(r.t1) + ", " + std::to_string(r.stats.steps) + " steps, " +
         std::to_string(r.stats.rejected_steps) + " rejected, " + std::to_string(r.stats.newton_iterations) +
         " Newton iterations");
    reports_.push_back(r);
  }

  /// `<stem>.t<time>.chk` in the output directory, time with 15 significant digits.
  void write_interval_checkpoint(const ast::call& c) {
    if (!settings_.write_files) return;
    char t[40];
    std::snprintf(t, sizeof t, "%.15g", sim_->time());
    const std::string p = path_in_output(settings_.stem + ".t" + t + ".chk");
    write_checkpoint(p, c.loc);
    note("checkpoint: " + p + " (t = " + num(sim_->time()) + ", SAVE of " + c.program + ")");
    files_.push_back(p);
  }

  std::string path_in_output(const std::string& name) const {
    std::filesystem::path p(name);
    if (p.is_relative()) p = std::filesystem::path(settings_.output_dir) / p;
    return p.string();
  }

  static std::string file_part(const std::string& label) {
    std::string s;
    for (char ch : label) s += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_') ? ch : '_';
    return s;
  }

  void display(const ast::call& c) {
    const auto d = display_options(c);
    std::vector<std::string> names;
    for (int k : d.columns) names.push_back(outputs_[static_cast<std::size_t>(k)].label);
    io::table t(names);
    for (std::size_t r = 0; r < results_.rows(); ++r) {
      const double time = results_.at(r, 0);
      if (time < d.start || time > d.end) continue;
      std::vector<double> row;
      for (int k : d.columns) row.push_back(results_.at(r, static_cast<std::size_t>(k) + 1));
      t.add_row(time, row);
    }
    ++displays_;
    if (!settings_.write_files) return;
    const std::string base = path_in_output(display_file(c, displays_));
    t.write_csv(base + ".csv");  // a pradis::error (io_error) names the file and the reason
    files_.push_back(base + ".csv");
    note(c.program + ": " + base + ".csv");
    if (c.program == "DISP" && settings_.plot)
      plots_.push_back({names, base + ".csv", base + ".png", c.label.empty() ? settings_.stem : c.label});
  }

  /// `<stem>.<label>` of the k-th display (1-based), without extension.
  std::string display_file(const ast::call& c, int k) const {
    return settings_.stem + "." + (c.label.empty() ? upper(c.program) + std::to_string(k) : file_part(c.label));
  }

  void replace(const ast::action& a) {
    for (const auto& d : a.definitions) data_[d.name].values = expand(d.values, "$REPLACE");
    for (auto& r : elements_) {
      std::vector<double> v = expand(r.params, "an element's parameter list");
      if (v == r.values) continue;
      if (v.size() != r.values.size())
        fail(a.loc, "$REPLACE changes the number of parameters of '" + r.name + "' from " +
                        std::to_string(r.values.size()) + " to " + std::to_string(v.size()) +
                        " (the count is fixed when the model is built; element at " + r.loc.str() + ")");
      for (double x : v)
        if (!std::isfinite(x)) fail(a.loc, "$REPLACE gives '" + r.name + "' a non-finite parameter");
      const auto loc = *model_->find(r.name);
      std::size_t t = 0;
      library_model::for_each_type([&]<class E>(std::type_identity<E>) {
        if (t++ == loc.type)
          model_->instances<E>()[static_cast<std::size_t>(loc.index)].element = E::from_parameters(v);
      });
      r.values = std::move(v);
    }
  }

  /// The record a session appends to a checkpoint: the scheme's four parameters
  /// and this tag at the very end (a checkpoint of the library has none).
  static constexpr char scheme_tag[8] = {'P', 'R', 'L', 'A', 'N', 'G', '0', '1'};
  static constexpr std::size_t scheme_record = 4 * sizeof(double) + sizeof scheme_tag;

  /// Writes the simulation's checkpoint followed by the scheme record.
  void write_checkpoint(const std::string& p, const location& where) {
    errno = 0;
    std::ofstream f(p, std::ios::binary);
    if (!f) fail(where, "cannot write the checkpoint '" + p + "'" + os_reason());
    try {
      sim_->save_checkpoint(f);
    } catch (const pradis::error& e) {
      fail(where, e.message());
    }
    const double q[4] = {scheme_.alpha_m, scheme_.alpha_f, scheme_.beta, scheme_.gamma};
    f.write(reinterpret_cast<const char*>(q), sizeof q);
    f.write(scheme_tag, sizeof scheme_tag);
    errno = 0;
    f.close();
    if (!f) fail(where, "cannot write the checkpoint '" + p + "'" + os_reason());
  }

  void save(const ast::action& a) {
    if (!started_) fail(a.loc, "$SAVE before any stage has run: nothing to save");
    const std::string p = path_in_output(a.path);
    write_checkpoint(p, a.loc);
    note("checkpoint: " + p + " (t = " + num(sim_->time()) + ")");
    files_.push_back(p);
  }

  void restore(const ast::action& a) {
    const std::string p = path_in_output(a.path);
    errno = 0;
    std::ifstream f(p, std::ios::binary);
    if (!f) fail(a.loc, "cannot read the checkpoint '" + p + "'" + os_reason());
    const std::string bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    // The scheme that wrote it, if the session's record is there.
    alpha_parameters q = stoermer{}.coefficients_set();
    bool known = false;
    if (bytes.size() >= scheme_record &&
        std::memcmp(bytes.data() + bytes.size() - sizeof scheme_tag, scheme_tag, sizeof scheme_tag) == 0) {
      double v[4];
      std::memcpy(v, bytes.data() + bytes.size() - scheme_record, sizeof v);
      // Ranges of the four programs: alpha_m, alpha_f < 1, 0 < beta <= 1, 1/2 <= gamma <= 3/2.
      const bool ok = std::isfinite(v[0]) && std::isfinite(v[1]) && v[0] < 1 && v[1] < 1 && v[2] > 0 &&
                      v[2] <= 1 && v[3] >= 0.5 && v[3] <= 1.5;
      if (!ok) fail(a.loc, "checkpoint '" + p + "': its record of the integration scheme is damaged");
      q = {v[0], v[1], v[2], v[3]};
      known = true;
    }
    sim_ = make_sim(q);
    scheme_ = q;
    scheme_known_ = known;
    std::istringstream is(bytes);
    try {
      sim_->load_checkpoint(is);
    } catch (const pradis::error& e) {
      fail(a.loc, "checkpoint '" + p + "': " + e.message());
    }
    started_ = true;
    note("restored: " + p + " (t = " + num(sim_->time()) + ")");
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
  io::table results_{std::vector<std::string>{}};
  std::unique_ptr<sim_type> sim_;
  alpha_parameters scheme_{};
  bool scheme_known_ = false;  ///< false after restoring a checkpoint without the scheme record
  std::unique_ptr<io::progress_line> progress_;
  bool started_ = false;
  int displays_ = 0;
  run_settings settings_;
  std::vector<std::string> files_;
  std::vector<stage_report> reports_;
  std::unique_ptr<io::csv_file> csv_;  ///< `<stem>.csv` while the run writes it
  std::vector<plot_request> plots_;
};

}  // namespace pradis::lang
