// pradis: the command-line runner of the pradis kernel, with every element of
// the built-in library compiled in.
//
//   pradis run [FILE] [-o DIR] [--no-plot] [-q] [--progress|--no-progress]
//                                                 run a model file (no FILE: the built-in example)
//   pradis list                                   catalog of elements and programs
//   pradis help NAME                              reference of an element or program
//   pradis check NAME [--points N] [--seed S]     finite-difference Jacobian check of an element
//
// Exit status: 0 success, 1 error in the model or the run (or a wrong Jacobian), 2 bad command line.

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/gnuplot.hpp"
#include "pradis/lang/lang.hpp"

namespace {

/// Set by SIGINT and SIGTERM: the session stops at the next step and keeps the
/// rows so far. A second signal of the same kind ends the program at once.
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  stop_signal = sig;
  std::signal(sig, SIG_DFL);
}

constexpr const char* main_usage =
    "usage: pradis <command> [options]\n"
    "\n"
    "commands:\n"
    "  run [FILE] [-o DIR] [--no-plot] [-q] [--progress|--no-progress]\n"
    "                                         run a model file (without FILE: the built-in two-body example)\n"
    "  list                                   catalog of element models, integration, output and display programs\n"
    "  help NAME                              full reference of an element model or a program\n"
    "  check NAME [--points N] [--seed S]     finite-difference Jacobian check of an element\n"
    "\n"
    "`pradis <command> --help` describes one command. The model language: docs/language.md.\n";

constexpr const char* run_usage =
    "usage: pradis run [FILE] [-o DIR] [--no-plot] [-q] [--progress|--no-progress]\n"
    "\n"
    "Runs the model file FILE: builds the model, runs the stages of $RUN, executes\n"
    "$PRINT, $REPLACE, $SAVE and $RESTORE in file order, and writes every output of\n"
    "#OUTPUT to DIR/<name>.csv (<name> = FILE without its extension). 'TABL writes\n"
    "DIR/<name>.<label>.csv, 'DISP also DIR/<name>.<label>.png (with gnuplot).\n"
    "Without FILE, runs the built-in example: the manual's two-body system\n"
    "(examples/models/two_bodies.prd).\n"
    "\n"
    "options:\n"
    "  -o DIR         output directory (default: the current directory); created if needed\n"
    "  --no-plot      do not call gnuplot: 'DISP writes its CSV only\n"
    "  -q             quiet: print errors only (and no progress line unless --progress)\n"
    "  --progress     show the progress line on stderr even if stderr is not a terminal\n"
    "  --no-progress  never show the progress line\n"
    "\n"
    "While a stage runs, a one-line progress display on stderr (only when stderr\n"
    "is a terminal) shows the simulated time, the percentage of the stage, the step\n"
    "size, the Newton iterations and the elapsed and estimated remaining time; it\n"
    "is redrawn in place at most ten times a second and cleared when the stage ends.\n"
    "\n"
    "The rows of DIR/<name>.csv are written as they are computed (to\n"
    "DIR/<name>.csv.part, renamed when the run ends); if a stage fails or the run is\n"
    "interrupted (Ctrl-C, SIGTERM), the rows computed so far are kept in DIR/<name>.csv.\n"
    "A failed plot (no gnuplot) is a warning.\n"
    "\n"
    "Errors in the file are reported as `file:line:column: error: message` with the\n"
    "offending line; the exit status is then 1 (also when a file cannot be written;\n"
    "130 after SIGINT, 143 after SIGTERM).\n";

constexpr const char* list_usage =
    "usage: pradis list\n\nPrints the catalog: element models, integration programs, output programs and\n"
    "display programs, one line each.\n";
constexpr const char* help_usage =
    "usage: pradis help NAME\n\nPrints the full reference of the element model or program NAME (case-insensitive):\n"
    "for an element its passport, nodes, parameters, work vector and special situations,\n"
    "generated from the element's own passport and help text.\n";
constexpr const char* check_usage =
    "usage: pradis check NAME [--points N] [--seed S] [--failures-only]\n\n"
    "Checks the Jacobian of element NAME (with its example parameters) against central\n"
    "finite differences at N random admissible states (default 3), printing for each\n"
    "state the flows and the table of numerical versus analytical derivatives (the\n"
    "manual's section 3.6.8 harness). Exit status 1 if any entry is wrong.\n";

bool is_help(const std::string& a) { return a == "--help" || a == "-h"; }

int usage_error(const std::string& msg, const char* usage) {
  std::cerr << "pradis: " << pradis::lang::printable(msg) << "\n\n" << usage;
  return 2;
}

bool parse_int(const std::string& s, long lo, long hi, long& out) {
  try {
    std::size_t n = 0;
    const long v = std::stol(s, &n);
    if (n != s.size() || v < lo || v > hi) return false;
    out = v;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

int cmd_run(const std::vector<std::string>& args) {
  std::string file, dir = ".";
  bool plot = true, quiet = false;
  int progress = -1;  // -1: if stderr is a terminal; 0: off; 1: on
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (is_help(a)) {
      std::cout << run_usage;
      return 0;
    }
    if (a == "-o") {
      if (i + 1 >= args.size()) return usage_error("-o needs a directory", run_usage);
      dir = args[++i];
      if (dir.empty()) return usage_error("-o needs a directory name, not an empty string", run_usage);
    } else if (a == "--no-plot") {
      plot = false;
    } else if (a == "-q") {
      quiet = true;
    } else if (a == "--progress" || a == "--no-progress") {
      progress = a == "--progress" ? 1 : 0;  // the last of them counts
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "' of run", run_usage);
    } else if (file.empty()) {
      file = a;
    } else {
      return usage_error("run takes one model file, got '" + file + "' and '" + a + "'", run_usage);
    }
  }
  std::unique_ptr<pradis::lang::session> s;
  // Plots after the CSV files are written, also after a failed or interrupted
  // run (for the displays that ran); a failed plot is a warning.
  auto plot_all = [&] {
    if (!s) return;
    for (const auto& p : s->plots()) {
      const std::string why = pradis_apps::plot_png(p.names, p.csv, p.png, p.title);
      if (!why.empty())
        std::cerr << "pradis: warning: " << why << "; the data are in " << p.csv << '\n';
      else if (!quiet)
        std::cout << "DISP: " << p.png << '\n';
    }
  };
  try {
    pradis::lang::ast::program prog;
    std::string stem;
    if (file.empty()) {
      if (!quiet)
        std::cout << "pradis: no model file given: running the built-in example, the manual's two-body system ("
                  << pradis::lang::builtin_example_name << ")\n";
      prog = pradis::lang::parse_string(std::string(pradis::lang::builtin_example),
                                        std::string(pradis::lang::builtin_example_name));
      stem = "two_bodies";
    } else {
      prog = pradis::lang::parse_file(file);
      stem = std::filesystem::path(file).stem().string();
      if (stem.empty()) stem = "model";
    }
    s = std::make_unique<pradis::lang::session>(std::move(prog));
    const bool show_progress = progress == 1 || (progress == -1 && !quiet && isatty(fileno(stderr)) == 1);
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    s->run({.output_dir = dir,
            .stem = stem,
            .plot = plot,
            .write_files = true,
            .log = quiet ? nullptr : &std::cout,
            .progress = show_progress ? &std::cerr : nullptr,
            .stop = &stop_signal});
    plot_all();
    return 0;
  } catch (const pradis::lang::interrupted& e) {
    std::cout.flush();
    std::cerr << "pradis: interrupted at t = " << e.time() << "; the rows computed so far are kept\n";
    plot_all();
    return stop_signal == SIGTERM ? 143 : 130;
  } catch (const pradis::lang::lang_error& e) {
    std::cout.flush();
    std::cerr << e.what() << '\n' << e.excerpt();
    plot_all();
    return 1;
  } catch (const pradis::error& e) {
    std::cout.flush();
    std::cerr << "pradis: error: " << pradis::lang::printable(e.what()) << '\n';
    plot_all();
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "pradis: error: " << pradis::lang::printable(e.what()) << '\n';
    return 1;
  }
}

int cmd_list(const std::vector<std::string>& args) {
  if (!args.empty() && is_help(args[0])) {
    std::cout << list_usage;
    return 0;
  }
  if (!args.empty()) return usage_error("list takes no arguments", list_usage);
  pradis::lang::print_catalog(std::cout);
  return 0;
}

int cmd_help(const std::vector<std::string>& args) {
  if (args.empty() || is_help(args[0])) {
    std::cout << help_usage;
    return args.empty() ? 2 : 0;
  }
  if (args.size() != 1) return usage_error("help takes one NAME", help_usage);
  return pradis::lang::print_reference(std::cout, std::cerr, args[0]) ? 0 : 1;
}

int cmd_check(const std::vector<std::string>& args) {
  pradis::lang::check_options o;
  std::string name;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    long v = 0;
    if (is_help(a)) {
      std::cout << check_usage;
      return 0;
    }
    if (a == "--points" || a == "--seed") {
      if (i + 1 >= args.size() ||
          !parse_int(args[i + 1], a == "--points" ? 1 : 0, a == "--points" ? 100000 : 4294967295L, v))
        return usage_error(a + " needs a whole number" + (a == "--points" ? " from 1 to 100000" : " >= 0"),
                           check_usage);
      ++i;
      if (a == "--points")
        o.points = static_cast<int>(v);
      else
        o.seed = static_cast<unsigned>(v);
    } else if (a == "--failures-only") {
      o.verbose = false;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + a + "' of check", check_usage);
    } else if (name.empty()) {
      name = a;
    } else {
      return usage_error("check takes one element NAME", check_usage);
    }
  }
  if (name.empty()) return usage_error("check needs an element NAME", check_usage);
  try {
    return pradis::lang::check_by_name(std::cout, std::cerr, name, o);
  } catch (const pradis::error& e) {
    std::cerr << "pradis: error: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
      std::cerr << main_usage;
      return 2;
    }
    const std::string cmd = args.front();
    args.erase(args.begin());
    if (is_help(cmd)) {
      std::cout << main_usage;
      return 0;
    }
    if (cmd == "--version") {
      std::cout << "pradis 0.1.0\n";
      return 0;
    }
    if (cmd == "run") return cmd_run(args);
    if (cmd == "list") return cmd_list(args);
    if (cmd == "help") return cmd_help(args);
    if (cmd == "check") return cmd_check(args);
    return usage_error(
        "unknown command '" + cmd + "'" + pradis::lang::did_you_mean(cmd, {"run", "list", "help", "check"}),
        main_usage);
  } catch (const std::exception& e) {
    std::cerr << "pradis: internal error: " << e.what() << '\n';
    return 1;
  }
}
