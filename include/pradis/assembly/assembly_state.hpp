#pragma once
/// \file
/// What the drivers hand to the assembler (assembler.hpp): the coefficients of the Newton
/// matrix, the global state of all DOFs and the facts of an element call.

#include <Eigen/Core>
#include <vector>

#include "pradis/core/diagnostics.hpp"

namespace pradis {

/// Coefficients with which the integrator combines the local Jacobian blocks.
struct jacobian_coefficients {
  double cu = 0;  ///< factor of K = dF/du
  double cv = 0;  ///< factor of C = dF/dv
  double ca = 0;  ///< factor of M = dF/da
};

/// Global potentials of all DOFs (ground and prescribed DOFs included).
/// `p` is the integrator's pseudo-acceleration (equal to `a` for Newmark and
/// Stoermer); elements never see it.
struct global_state {
  Eigen::VectorXd u, v, a, p;
  void resize(int n) {
    u.setZero(n);
    v.setZero(n);
    a.setZero(n);
    p.setZero(n);
  }
};

/// Facts the assembler hands to every element call (time, step number, ...).
struct call_info {
  double time = 0;              ///< TIME of the call
  double step = 0;              ///< STEP, the current step
  long nstep = 0;               ///< NSTEP, the step number (0 at the zero step)
  int niter = 0;                ///< NITER, the Newton iteration within the step
  bool want_jacobian = true;    ///< assemble the whole Newton matrix into values()
  diagnostics* log = nullptr;   ///< where element warnings and errors are written (nullptr: nowhere)
  double dabsi = 0.1;  ///< DABSI of the run: sets Mu of the rotational nodes' norm equation (spatial::norm_viscosity)
  /// Without want_jacobian: per element type (in the model's order), the types whose Jacobians are
  /// assembled into values() anyway, the others left out (a partial Jacobian: complete only on the rows
  /// that no other type touches, e.g. the constraint row of a multiplier). Null: none.
  const std::vector<char>* jacobian_types = nullptr;
};

}  // namespace pradis
