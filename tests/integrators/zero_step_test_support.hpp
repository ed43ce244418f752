#pragma once
// What the zero-step tests (test_zero_step_warnings.cpp, test_algebraic_start.cpp) observe of a
// run: its diagnostics log, the pradis::error that ended it (if any), and the state of some DOFs
// at t = 0 and at the end.

#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/integrators/options.hpp"
#include "pradis/model/handles.hpp"

namespace pradis_test {

/// What a run did (observed_run).
struct run_outcome {
  std::string log, what;  ///< the diagnostics log; the message of the error that ended the run
  bool failed = false;    ///< the run ended with a pradis::error
  pradis::error_code code{};
  double t_end = std::numeric_limits<double>::quiet_NaN();  ///< the time reached
  std::vector<double> u0, v0, a0;                           ///< the observed DOFs at t = 0
  std::vector<double> u_end, v_end;                         ///< and at the end
};

/// Runs a fresh driver Sim on md with options o, capturing its log and the DOFs ds at t = 0 and
/// at the end; a pradis::error that ends the run is caught into the outcome.
template <class Sim, class Model>
run_outcome observed_run(Model& md, const std::vector<pradis::dof>& ds, const pradis::run_options& o) {
  Sim sim(md);
  std::ostringstream log;
  sim.log().to(log);
  run_outcome r;
  sim.on_output([&](const auto& s) {
    if (s.time() != 0) return;
    for (const pradis::dof d : ds) r.u0.push_back(s.u(d)), r.v0.push_back(s.v(d)), r.a0.push_back(s.a(d));
  });
  try {
    sim.run(o);
  } catch (const pradis::error& e) {
    r.failed = true;
    r.code = e.code();
    r.what = e.what();
  }
  r.t_end = sim.time();
  for (const pradis::dof d : ds) r.u_end.push_back(sim.u(d)), r.v_end.push_back(sim.v(d));
  r.log = log.str();
  return r;
}

/// How often `what` occurs in `text` (non-overlapping).
inline std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

}  // namespace pradis_test
