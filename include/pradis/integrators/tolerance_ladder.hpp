#pragma once
/// \file
/// What accuracy costs on a user's own model: runs the model with error control
/// at a ladder of tolerances (DRLTX), measures the error of each rung's final
/// state against a reference run at a tighter tolerance, and reports CPU time,
/// steps, Newton iterations, factorisations and the cost of each extra digit.
///
/// Usage:
///     pradis::model<...> m = ...;                       // the model, not yet run
///     auto r = pradis::tolerance_ladder(m, {.end = 1.0, .smax = 1e-2}, pradis::newmark{});
///     r.print(std::cout);
///
/// The reference is a separate run at DRLTX = (tightest rung) x reference_factor
/// (default: two decades below the tightest rung), so every rung, the tightest
/// included, gets a measured error. The achieved error of a rung is trustworthy
/// while it is well above the reference's own error, which the ladder cannot
/// measure; with error control at order 2, two decades of tolerance give the
/// reference roughly two decades less error than the tightest rung.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/integrators/statistics_io.hpp"
#include "pradis/model/model.hpp"

namespace pradis {

/// Options of a tolerance ladder.
struct ladder_options {
  /// DRLTX of the rungs; each finite and > 0. The rungs are run and reported
  /// loosest first whatever the order given.
  std::vector<double> tolerances{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  /// The reference run uses DRLTX = min(tolerances) * reference_factor, with
  /// 0 < reference_factor <= 1 (1: the tightest rung is its own reference and
  /// reports error 0).
  double reference_factor = 1e-2;
  /// DABSX of a run = absolute_factor * its DRLTX (> 0): the absolute part of
  /// the local error tolerance, in velocity units, follows the ladder too.
  double absolute_factor = 1.0;
  /// The Newton tolerances DABSU, DRLTU and DRLTI of a run are lowered to
  /// max(newton_factor * DRLTX, 1e-12) (never raised above the given options),
  /// so that the Newton error stays below the requested accuracy; 0 keeps the
  /// given Newton options (newton_factor >= 0).
  double newton_factor = 1e-3;
  /// CPU time of a run: the minimum over this many repetitions (>= 1).
  int repeats = 1;
};

/// One rung of a tolerance ladder (or the reference run).
struct ladder_rung {
  double tolerance = 0;  ///< DRLTX of the run
  /// Error of the final state against the reference: see ladder_state_error().
  double error = 0;
  double cpu_s = 0;       ///< process CPU time of the run [s] (minimum over the repetitions)
  run_statistics stats;   ///< statistics of the run
  /// CPU-time factor per extra decade of achieved error relative to the previous
  /// (looser) rung: (cpu / cpu_prev)^(1 / log10(error_prev / error)). NaN for the
  /// first rung, for the reference, and where the error did not fall.
  double time_per_digit = std::numeric_limits<double>::quiet_NaN();
  global_state final_state;  ///< u, v, a of all DOFs at the end of the run
};

/// The result of tolerance_ladder().
struct ladder_result {
  std::string scheme;             ///< name of the integration scheme
  std::vector<ladder_rung> rungs; ///< loosest first
  ladder_rung reference;          ///< the reference run (error 0)

  /// Prints the table: DRLTX, error, correct digits (-log10 error), CPU time,
  /// steps, Newton iterations, factorisations and the time factor per digit.
  void print(std::ostream& os) const {
    char line[200];
    std::snprintf(line, sizeof line, "tolerance ladder (%s), reference DRLTX = %.1e: CPU %.3g s, %s\n",
                  scheme.c_str(), reference.tolerance, reference.cpu_s, to_string(reference.stats).c_str());
    os << line;
    os << "    DRLTX      error  digits    CPU [s]     steps    Newton  factoriz.  time x per digit\n";
    for (const ladder_rung& r : rungs) {
      char digits[16], per[24];
      if (r.error > 0) std::snprintf(digits, sizeof digits, "%6.2f", -std::log10(r.error));
      else std::snprintf(digits, sizeof digits, "%6s", "exact");
      if (std::isfinite(r.time_per_digit)) std::snprintf(per, sizeof per, "%8.2f", r.time_per_digit);
      else std::snprintf(per, sizeof per, "%8s", "-");
      std::snprintf(line, sizeof line, "  %7.1e  %9.3e  %s  %9.3e  %8ld  %8ld  %9ld  %s\n", r.tolerance, r.error, digits,
                    r.cpu_s, r.stats.steps, r.stats.newton_iterations, r.stats.factorizations, per);
      os << line;
    }
  }
};

/// Error of a final state y against a reference: the larger of
/// |u - u_ref|_inf / |u_ref|_inf and |v - v_ref|_inf / |v_ref|_inf over all DOFs
/// (displacements and velocities each relative to their own largest reference
/// value; absolute where that is zero).
inline double ladder_state_error(const global_state& y, const global_state& ref) {
  auto part = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    if (b.size() == 0) return 0.0;
    const double d = (a - b).cwiseAbs().maxCoeff(), s = b.cwiseAbs().maxCoeff();
    return s > 0 ? d / s : d;
  };
  return std::max(part(y.u, ref.u), part(y.v, ref.v));
}

/// Runs copies of the model `m` (which is not changed) with the scheme and the
/// run options `base` (one stage from the zero step to base.end, with error
/// control switched on and DRLTX, DABSX and the Newton tolerances set per rung
/// as ladder_options describes) at every tolerance of the ladder and at the
/// reference tolerance, and returns the table. Throws pradis::error
/// (invalid_option, naming the option) for an empty ladder, a tolerance that is
/// not finite and > 0, or another option out of range; a run that fails throws
/// its own error, with the rung's DRLTX added to the message.
template <class... Es, Integrator Scheme = newmark>
ladder_result tolerance_ladder(const model<Es...>& m, const run_options& base, Scheme scheme = {},
                               const ladder_options& lo = {}) {
  auto bad = [](const std::string& msg) { throw error(error_code::invalid_option, "tolerance ladder: " + msg); };
  if (lo.tolerances.empty()) bad("the option 'tolerances' is empty: give at least one DRLTX");
  for (std::size_t i = 0; i < lo.tolerances.size(); ++i)
    if (!(lo.tolerances[i] > 0) || !std::isfinite(lo.tolerances[i]))
      bad("tolerances[" + std::to_string(i) + "] = " + to_text(lo.tolerances[i]) + " must be finite and > 0");
  if (!(lo.reference_factor > 0 && lo.reference_factor <= 1))
    bad("reference_factor = " + to_text(lo.reference_factor) + " must be in (0, 1]");
  if (!(lo.absolute_factor > 0) || !std::isfinite(lo.absolute_factor))
    bad("absolute_factor = " + to_text(lo.absolute_factor) + " must be finite and > 0");
  if (!(lo.newton_factor >= 0) || !std::isfinite(lo.newton_factor))
    bad("newton_factor = " + to_text(lo.newton_factor) + " must be finite and >= 0");
  if (lo.repeats < 1) bad("repeats = " + std::to_string(lo.repeats) + " must be >= 1");

  std::vector<double> tols = lo.tolerances;
  std::sort(tols.begin(), tols.end(), [](double a, double b) { return a > b; });

  auto run_one = [&](double tol) {
    run_options o = base;
    o.error_control = true;
    o.drltx = tol;
    o.dabsx = lo.absolute_factor * tol;
    if (lo.newton_factor > 0) {
      const double nt = std::max(lo.newton_factor * tol, 1e-12);
      o.newton.dabsu = std::min(o.newton.dabsu, nt);
      o.newton.drltu = std::min(o.newton.drltu, nt);
      o.newton.drlti = std::min(o.newton.drlti, nt);
    }
    ladder_rung r;
    r.tolerance = tol;
    r.cpu_s = std::numeric_limits<double>::infinity();
    for (int k = 0; k < lo.repeats; ++k) {
      model<Es...> copy = m;
      simulation<model<Es...>, Scheme> sim(copy, scheme);
      const std::clock_t c0 = std::clock();
      try {
        r.stats = sim.run(o);
      } catch (const error& e) {
        throw error(e.code(), "tolerance ladder, DRLTX = " + to_text(tol) + ": " + e.message(), e.element_type(),
                    e.instance(), e.dof());
      }
      const std::clock_t c1 = std::clock();
      r.cpu_s = std::min(r.cpu_s, static_cast<double>(c1 - c0) / CLOCKS_PER_SEC);
      r.final_state = sim.state();
    }
    return r;
  };

  ladder_result out;
  out.scheme = std::string(Scheme::name);
  out.reference = run_one(tols.back() * lo.reference_factor);
  for (double tol : tols) {
    ladder_rung r = run_one(tol);
    r.error = ladder_state_error(r.final_state, out.reference.final_state);
    if (!out.rungs.empty()) {
      const ladder_rung& p = out.rungs.back();
      const double digits = p.error > 0 && r.error > 0 ? std::log10(p.error / r.error) : 0.0;
      if (digits > 0 && p.cpu_s > 0 && r.cpu_s > 0) r.time_per_digit = std::pow(r.cpu_s / p.cpu_s, 1.0 / digits);
    }
    out.rungs.push_back(std::move(r));
  }
  return out;
}

}  // namespace pradis
