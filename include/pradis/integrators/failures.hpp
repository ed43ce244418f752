#pragma once
/// \file
/// The errors that end a run of pradis::simulation, each naming the DOF, the
/// elements on it and the time: a singular Newton matrix, Newton failing at
/// SMIN, a state that is no longer finite.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis::detail {

/// The error of a singular (or structurally singular) Newton matrix, naming
/// the DOF of the equation e.dof() and the elements on it; e itself when the
/// equation is not known.
template <class Model, class Assembler>
error singular_error(const Model& m, const Assembler& as, const error& e, double t) {
  if (e.dof() < 0 || e.dof() >= as.equations()) return e;
  const int d = as.dof_of(static_cast<int>(e.dof()));
  std::string on;
  m.for_each_instances([&](const auto& vec) {
    for (const auto& in : vec)
      if (std::find(in.dofs.begin(), in.dofs.end(), d) != in.dofs.end()) {
        using T = std::remove_cvref_t<decltype(in.element)>;
        if (!on.empty()) on += ", ";
        on += std::string(T::passport.name) + " '" + in.name + "'";
      }
  });
  std::string msg = e.code() == error_code::structurally_singular
                        ? "DOF '" + m.dof_name(d) + "' has no Jacobian entry: no element acts on it"
                        : "the Newton matrix is singular at DOF '" + m.dof_name(d) + "' (elements on it: " +
                              (on.empty() ? std::string("none") : on) +
                              "); a DOF needs stiffness, viscosity or mass, or a support";
  return error(e.code(), msg + " [t = " + num(t) + "]", {}, {}, d);
}

/// The error of a step that failed at SMIN: the element's singular situation
/// if one ended the last attempt, else Newton's failure naming the DOF with
/// the largest residual at the last attempt.
template <class Model, class Assembler>
error smin_error(const Model& m, const Assembler& as, const std::optional<error>& last, double smin, double t,
                 double h) {
  if (last)
    return error(last->code(), last->message() + " (persists at SMIN = " + num(smin) + ", t = " + num(t) + ")",
                 last->element_type(), last->instance(), last->dof());
  int worst = -1;
  double wr = -1;
  for (int i = 0; i < as.equations(); ++i) {
    const double r = std::abs(as.residual()(as.dof_of(i)));
    if (!(r <= wr)) {
      wr = r;
      worst = as.dof_of(i);
    }
  }
  return error(error_code::newton_failure,
               "Newton does not converge at SMIN: step " + num(h) + " at t = " + num(t) +
                   (worst >= 0 ? "; largest residual " + num(wr) + " on DOF '" + m.dof_name(worst) + "'" : ""),
               {}, {}, worst);
}

/// The error of a converged state that is not finite (u, v or a of a free
/// DOF, e.g. an overflow of u on a first-order DOF whose flows stay finite),
/// naming the DOF and the time; none when the state is finite.
template <class Model, class Assembler>
std::optional<error> non_finite_state(const Model& m, const Assembler& as, const global_state& s, double t,
                                      double h) {
  for (int i = 0; i < as.equations(); ++i) {
    const auto d = as.dof_of(i);
    const char* what = !std::isfinite(s.u(d))   ? "displacement"
                       : !std::isfinite(s.v(d)) ? "velocity"
                       : !std::isfinite(s.a(d)) ? "acceleration"
                                                : nullptr;
    if (!what) continue;
    return error(error_code::non_finite,
                 std::string("the ") + what + " of DOF '" + m.dof_name(d) + "' is no longer finite at t = " + num(t) +
                     " (u = " + num(s.u(d)) + ", v = " + num(s.v(d)) + ", a = " + num(s.a(d)) + ", step " + num(h) +
                     ")",
                 {}, {}, d);
  }
  return std::nullopt;
}

}  // namespace pradis::detail
