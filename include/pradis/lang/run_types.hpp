#pragma once
/// \file
/// The plain types of a model-language run: how a session writes its results
/// (run_settings), what it asks the application to plot (plot_request), the
/// exception of an interrupted run, the scheme of a stage, one output column
/// and the report of one stage.

#include <csignal>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/post.hpp"
#include "pradis/lang/source.hpp"
#include "pradis/spatial/node_state.hpp"

namespace pradis::lang {

/// How a session writes its results.
struct run_settings {
  std::string output_dir = ".";  ///< directory for CSV, PNG and checkpoints ($SAVE/$RESTORE paths are relative to it)
  std::string stem = "model";    ///< prefix of the output files
  bool plot = true;              ///< false: 'DISP requests no PNG (session::plots() stays empty)
  bool write_files = true;       ///< false: no CSV and no SAVE-interval checkpoints (tests)
  std::ostream* log = nullptr;   ///< report lines (stages, files written, the integrators' warnings and notes), or none
  /// A one-line progress display redrawn in place while a stage runs (for a
  /// terminal: `pradis run` passes stderr when it is one), or none.
  std::ostream* progress = nullptr;
  /// Set to non-zero (by a signal handler: `pradis run` on SIGINT and SIGTERM)
  /// to stop the run at the next step: run() then closes the results file with
  /// the rows computed so far and throws lang::interrupted. Null: never stops.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// Largest number of output rows of a run (all stages; at least 1): 10 million
  /// rows of 10 outputs are 800 MB in memory and about 2 GB of CSV. A stage whose
  /// OUT would exceed it is refused before it runs; with OUT = 0 (a row every step)
  /// the run stops with an error when it is reached, keeping the rows written.
  double max_rows = 1e7;
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
  /// The name of the scheme class (its messages carry label()).
  static constexpr std::string_view name = "STAGE";
  /// PRADIS's Stoermer scheme (SHTERM).
  stage_scheme() : stage_scheme(stoermer{}) {}
  /// The scheme with the parameters of `s` (newmark, stoermer, hht, generalized_alpha).
  explicit stage_scheme(const alpha_scheme& s) : stage_scheme(s.coefficients_set()) {}
  /// The scheme with parameters taken from one of the library's schemes (not checked again).
  explicit stage_scheme(const alpha_parameters& q) { p_ = q; }
  /// The program these parameters are (SHTERM, NEWMARK, HHT or GALPHA), for the
  /// simulation's messages and notes: SHTERM is Newmark's beta = 1/2, gamma = 1,
  /// HHT has alpha_m = 0 and alpha_f != 0, GALPHA alpha_m != 0.
  std::string_view label() const noexcept {
    if (p_.alpha_m != 0) return "GALPHA";
    if (p_.alpha_f != 0) return "HHT";
    return p_.beta == 0.5 && p_.gamma == 1.0 ? "SHTERM" : "NEWMARK";
  }
};

/// One output variable (#OUTPUT line).
struct output_column {
  enum class kind { potential, work, statistic, angular_velocity, norm, pivot_force };
  std::string label;
  location loc;
  kind what = kind::potential;
  int node = 0, dof = 0, order = 1;  ///< potential: node, model DOF, 1 u / 2 v / 3 a
  std::string element;               ///< work: instance name; pivot_force: the PIVOT's name
  int index = 0;                     ///< work: 1-based entry; pivot_force: 1 X, 2 Y, 3 Z
  std::size_t pivot = 0;             ///< pivot_force: the ground pivot's index in the model
  std::string statistic;             ///< statistic: NSTEP, NITER, ...
  rotation_node rotation{};          ///< angular_velocity ('W, component in order) and norm ('LQ)
  std::string nodes;                 ///< 'W, 'LQ: the three node numbers as written, for the label
};

/// What a 'PEAK display found for one output (see post.hpp for the definitions).
struct peak_summary {
  std::string display;             ///< the display's label (or PEAK<k>)
  std::string output;              ///< the output's label
  post::peak_value peak;           ///< the peak sample
  std::optional<double> threshold;  ///< THRESHOLD, if given
  post::interval longest;          ///< the longest interval at or above it (duration 0 if none or no threshold)
  double total = 0;                ///< the total time at or above it
};

/// What one run stage did (for the report of `pradis run`).
struct stage_report {
  std::string label, program;
  double t0 = 0, t1 = 0;
  run_statistics stats;
};

}  // namespace pradis::lang
