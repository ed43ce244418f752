#pragma once
/// \file
/// The runner of the model language: a session turns an ast::program into a
/// library_model, its outputs and its list of actions (model_builder.hpp),
/// checks the actions (action_checks.hpp), then executes them: run stages,
/// displays, $REPLACE, $SAVE, $RESTORE, writing the results as they are computed.

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/integrators/simulation.hpp"
#include "pradis/io/csv_file.hpp"
#include "pradis/io/model_scene.hpp"
#include "pradis/io/progress.hpp"
#include "pradis/io/table.hpp"
#include "pradis/lang/action_checks.hpp"
#include "pradis/lang/drivers.hpp"
#include "pradis/lang/peaks.hpp"
#include "pradis/lang/run_types.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/spatial/node_state.hpp"

namespace pradis::lang {

/// A model file turned into a model and a list of actions.
class session : public action_checker, public stage_drivers<session> {
  friend class stage_drivers<session>;

 public:
  /// Largest number of checkpoints the SAVE key of one stage may write.
  static constexpr double max_checkpoints = 10000;

  /// Builds the model and checks outputs and actions. Throws lang_error.
  explicit session(ast::program prog) : action_checker(std::move(prog)), stage_drivers<session>(*model_) {
    std::vector<std::string> names;
    for (const auto& o : outputs_) names.push_back(o.label);
    results_ = io::table(names);
    for (const auto& a : prog_.actions)
      if (a.what == ast::action::kind::print && a.stage.program == "VTK") {
        if (!scene_) scene_ = io::model_scene(*model_);
        if (scene_->points() == 0)
          fail(a.stage.loc, "VTK has nothing to draw: no element of the model has a geometry (BEAM3, BEAMI3, SD3, "
                            "the spatial joints, PIVOT, CSPHPL, CSPHSP and TRIPL draw themselves)");
      }
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
    if (!(settings_.max_rows >= 1) || !std::isfinite(settings_.max_rows))
      throw pradis::error(error_code::invalid_option,
                          "run_settings::max_rows = " + num(settings_.max_rows) + " must be a finite number >= 1");
    if (settings_.write_files) open_results();
    try {
      run_actions();
    } catch (...) {
      if (csv_ && csv_->is_open()) {  // not if writing it was what failed
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

  /// Every output sampled over time (column order as outputs()).
  const io::table& results() const noexcept { return results_; }
  /// Files written by run().
  const std::vector<std::string>& files() const noexcept { return files_; }
  /// One report per executed stage.
  const std::vector<stage_report>& stages() const noexcept { return reports_; }
  /// What the 'PEAK displays found, one entry per display and output, in file order.
  const std::vector<peak_summary>& summaries() const noexcept { return summaries_; }
  /// The plots the 'DISP calls of the run asked for (their CSV files are written).
  const std::vector<plot_request>& plots() const noexcept { return plots_; }

 private:
  void note(const std::string& s) const {
    if (progress_ && settings_.log) progress_->clear();  // the log may share the terminal
    if (settings_.log) *settings_.log << s << '\n';
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
         (early && has_driver() ? ", up to t = " + num(time_now()) : std::string()) + ")");
    files_.push_back(f->path());
  }

  // ---- actions: execution -------------------------------------------------------------------
  /// The current driver's time.
  double time_now() const {
    return visit([](const auto& s) { return s.time(); });
  }

  template <class Sim>
  void record(const Sim& s) {
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
        case output_column::kind::pivot_force:
          row.push_back(elements::ground_pivot_force(s, o.pivot)(o.index - 1));
          break;
      }
    }
    if (static_cast<double>(results_.rows()) >= settings_.max_rows)
      throw pradis::error(error_code::invalid_option,
                          "the run has produced " + num(settings_.max_rows) + " output rows, the most pradis writes: make OUT "
                          "larger (or SMAX, with OUT = 0: a row every step)");
    results_.add_row(s.time(), row);
    if (csv_) csv_->add_row(s.time(), row);
    if (scene_) {  // the positions of the animation's points, for the VTK displays
      std::vector<spatial::point_motion> m;
      m.reserve(scene_->points());
      for (std::size_t i = 0; i < scene_->points(); ++i) m.push_back(scene_->motion(s, i));
      frames_.push_back(std::move(m));
    }
  }

  /// Stops the run if run_settings::stop was set (by a signal).
  template <class Sim>
  void check_stop(const Sim& s) const {
    if (settings_.stop && *settings_.stop) throw interrupted(s.time());
  }

  /// Adds the session's observers to a driver that stage_drivers made.
  template <class Sim>
  void attach(Sim& s) {
    // The driver's warnings and notes join the report lines; its errors (and the elements'
    // messages of a failed step) do not: the session reports a run's error itself, located.
    s.log().to([this](std::string_view line) {
      if (line.rfind("pradis error ", 0) != 0) note(std::string(line));
    });
    s.on_output([this](const Sim& x) {
      record(x);
      show_progress(x);  // also at t0, before the first step
      check_stop(x);
    });
    // Every accepted step; the progress line itself redraws at most ten times a second.
    s.on_step([this](const Sim& x) {
      show_progress(x);
      check_stop(x);
    });
  }

  template <class Sim>
  void show_progress(const Sim& x) {
    if (!progress_) return;
    const run_statistics& st = x.statistics();
    progress_->update(x.time(), st.last_step, st.last_iterations, st.newton_iterations);
  }

  [[noreturn]] void rethrow(const pradis::error& e, const ast::call& c) const {
    if (e.code() == error_code::io_error) throw e;  // a results file: the message names it, not the model
    std::string what = std::string(e.element_type());
    if (!e.instance().empty()) what += (what.empty() ? "'" : " '") + e.instance() + "'";
    std::string msg = e.message();
    // The one-step driver's option messages start with its scheme's label (stage_scheme::label()):
    // name the program as written.
    if (e.code() == error_code::invalid_option)
      for (const char* p : {"SHTERM: ", "NEWMARK: ", "HHT: ", "GALPHA: "})
        if (msg.rfind(p, 0) == 0) {
          msg = c.program + ": " + msg.substr(std::strlen(p));
          break;
        }
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
    if (st.bdf)
      use_bdf(st.bdf_opt);
    else
      use_scheme(st.scheme);
    visit([&](auto& s) {
      if (s.solver().ordering().level != st.optim)
        s.set_solver(linalg::sparse_lu<linalg::optim_ordering>(linalg::optim_ordering{st.optim}));
    });
    const double t0 = started_ ? time_now() : 0.0;
    if (started_ && !(st.opt.end > t0))
      fail(c.args_loc, "END = " + num(st.opt.end) + " must be after the current time " + num(t0));
    if (st.save > 0) check_save(st, t0);
    if (st.opt.out > 0 && static_cast<double>(results_.rows()) + (st.opt.end - t0) / st.opt.out > settings_.max_rows)
      fail(st.out_loc, "OUT = " + num(st.opt.out) + " would write " + num(std::floor((st.opt.end - t0) / st.opt.out)) +
                           " output rows in this stage (from t = " + num(t0) + " to END = " + num(st.opt.end) +
                           "); at most " + num(settings_.max_rows) + " rows are written in a run: make OUT larger");
    stage_report r{c.label, c.program, t0, st.opt.end, {}};
    const run_statistics before = visit([](const auto& s) { return s.statistics(); });
    struct progress_guard {
      io::progress_line* p;
      ~progress_guard() {
        if (p) p->end();
      }
    } guard{progress_.get()};
    if (progress_) progress_->begin((c.label.empty() ? "" : c.label + " ") + c.program, t0, st.opt.end);
    try {
      if (st.save > 0) {
        // The stage's start note or warning once, not per piece (run_options::start_notes).
        const std::string start = pradis::detail::stage_start_text(t0, st.opt.end, st.opt.smax, st.opt.max_steps);
        if (!start.empty()) note(start);
        for (;;) {
          const double next = next_save_time(started_ ? time_now() : t0, st.save);
          const double tol = 1e-9 * st.save;
          const bool last = !(next < st.opt.end - tol);
          run_options o = st.opt;
          o.start_notes = false;
          if (!last) o.end = next;
          run_piece(o, st.opt.end, st.opt.max_steps, before.steps);
          started_ = true;
          if (!last || std::abs(next - st.opt.end) <= tol) write_interval_checkpoint(c);
          if (last) break;
        }
      } else {
        visit([&](auto& s) { (void)s.run(st.opt); });
      }
    } catch (const pradis::error& e) {
      rethrow(e, c);
    }
    started_ = true;
    r.stats = visit([](const auto& s) { return s.statistics(); }) - before;
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
    std::snprintf(t, sizeof t, "%.15g", time_now());
    const std::string p = path_in_output(settings_.stem + ".t" + t + ".chk");
    write_checkpoint(p, c.loc);
    note("checkpoint: " + p + " (t = " + num(time_now()) + ", SAVE of " + c.program + ")");
    files_.push_back(p);
  }

  std::string path_in_output(const std::string& name) const {
    std::filesystem::path p(name);
    if (p.is_relative()) p = std::filesystem::path(settings_.output_dir) / p;
    return p.string();
  }

  void display(const ast::call& c) {
    const auto d = display_options(c);
    if (c.program == "VTK") return animation(c, d);
    if (c.program == "PEAK") return peaks(c, d);
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

  /// A 'VTK display: `<dir>/vtk/<stem>.<label>.pvd` and one `.vtu` per output
  /// row between START and END (the frames recorded with the rows).
  void animation(const ast::call& c, const display_spec& d) {
    ++displays_;
    if (!settings_.write_files) return;
    io::vtk_series vtk(std::filesystem::path(path_in_output("vtk")), display_file(c, displays_), *scene_);
    for (std::size_t r = 0; r < results_.rows(); ++r) {
      const double time = results_.at(r, 0);
      if (time >= d.start && time <= d.end) vtk.write(time, frames_[r]);
    }
    files_.push_back(vtk.collection().string());
    note(c.program + ": " + vtk.collection().string() + " (" + std::to_string(vtk.frames()) + " frames)");
  }

  /// A 'PEAK display: per output, the peak and (THRESHOLD) the longest and total
  /// time at or above the threshold over the rows between START and END; kept in
  /// summaries(), written to the log and to `<stem>.<label>.csv`.
  void peaks(const ast::call& c, const display_spec& d) {
    ++displays_;
    std::vector<std::string> labels;
    for (const auto& o : outputs_) labels.push_back(o.label);
    std::vector<peak_summary> found;
    try {
      found = peak_summaries(results_, labels, d.columns, d.start, d.end, d.threshold, d.magnitude,
                             c.label.empty() ? "PEAK" + std::to_string(displays_) : c.label);
    } catch (const pradis::error& e) {  // no row in the window, or a non-finite output value
      fail(c.loc, c.program + ": " + e.message());
    }
    for (const auto& p : found) note(c.program + ": " + describe(p));
    summaries_.insert(summaries_.end(), found.begin(), found.end());
    if (!settings_.write_files) return;
    const std::string path = path_in_output(display_file(c, displays_)) + ".csv";
    write_peak_csv(path, found);
    files_.push_back(path);
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
      model_->structure_changed();  // the element's Jacobian structure may depend on its parameters
      r.values = std::move(v);
    }
  }

  /// Writes the current driver's checkpoint followed by the scheme record.
  void write_checkpoint(const std::string& p, const location& where) {
    errno = 0;
    std::ofstream f(p, std::ios::binary);
    if (!f) fail(where, "cannot write the checkpoint '" + p + "'" + os_reason());
    try {
      write_checkpoint_to(f);
    } catch (const pradis::error& e) {
      fail(where, e.message());
    }
    errno = 0;
    f.close();
    if (!f) fail(where, "cannot write the checkpoint '" + p + "'" + os_reason());
  }

  void save(const ast::action& a) {
    if (!started_) fail(a.loc, "$SAVE before any stage has run: nothing to save");
    const std::string p = path_in_output(a.path);
    write_checkpoint(p, a.loc);
    note("checkpoint: " + p + " (t = " + num(time_now()) + ")");
    files_.push_back(p);
  }

  void restore(const ast::action& a) {
    const std::string p = path_in_output(a.path);
    errno = 0;
    std::ifstream f(p, std::ios::binary);
    if (!f) fail(a.loc, "cannot read the checkpoint '" + p + "'" + os_reason());
    const std::string bytes{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
    if (auto why = restore_from(bytes)) fail(a.loc, "checkpoint '" + p + "': " + *why);
    note("restored: " + p + " (t = " + num(time_now()) + ")");
  }

  io::table results_{std::vector<std::string>{}};
  std::unique_ptr<io::progress_line> progress_;
  int displays_ = 0;
  run_settings settings_;
  std::vector<std::string> files_;
  std::vector<stage_report> reports_;
  std::unique_ptr<io::csv_file> csv_;  ///< `<stem>.csv` while the run writes it
  std::vector<plot_request> plots_;
  std::vector<peak_summary> summaries_;
  std::optional<io::vtk_scene> scene_;                    ///< the animation's geometry, if a 'VTK display asks for it
  std::vector<std::vector<spatial::point_motion>> frames_;  ///< its point motions, one entry per results_ row
};

}  // namespace pradis::lang
