#pragma once
/// \file
/// Printing the run statistics of a simulation in one call:
///     std::cout << sim.statistics() << "\n";
/// prints `NSTEP=1200 NREJ=3 NERR=2 NITTOT=2410 NFACT=2411 NJAC=2411 NEVAL=3615 NITER=2 STEP=0.001`,
/// the PRADIS output-variable names of simulation::statistic() plus NERR (steps
/// redone for the local error), NJAC (evaluations with the Jacobian) and NEVAL
/// (all model evaluations).

#include <ostream>
#include <sstream>
#include <string>

#include "pradis/integrators/simulation.hpp"

namespace pradis {

/// Writes the statistics as `KEY=value` pairs on one line (no newline).
inline std::ostream& operator<<(std::ostream& os, const run_statistics& s) {
  os << "NSTEP=" << s.steps << " NREJ=" << s.rejected_steps << " NERR=" << s.error_rejections
     << " NITTOT=" << s.newton_iterations << " NFACT=" << s.factorizations << " NJAC=" << s.jacobian_evaluations
     << " NEVAL=" << s.evaluations
     << " NITER=" << s.last_iterations << " STEP=" << s.last_step;
  return os;
}

/// The statistics as one line of text, as written by operator<<.
inline std::string to_string(const run_statistics& s) {
  std::ostringstream os;
  os << s;
  return os.str();
}

}  // namespace pradis
