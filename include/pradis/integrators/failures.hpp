#pragma once
/// \file
/// The errors that end a run of pradis::simulation, each naming the DOF, the
/// elements on it and the time: a singular Newton matrix, Newton failing at
/// SMIN, a state that is no longer finite.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/dependent_equations.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis::detail {

/// The message for equations that depend on each other (dependent_equations.hpp). When
/// every one is a multiplier's row (an element's internal DOF without a diagonal entry),
/// the constraints are redundant and their elements are named; else `plain` gets the DOFs
/// of the dependent equations appended (at most 8).
template <class Model, class Assembler>
std::string dependence_text(const Model& m, const Assembler& as, const dependent_equations& dep,
                            const std::string& plain) {
  std::vector<int> dofs;
  bool multipliers = true;
  for (std::size_t k = 0; k < dep.rows.size(); ++k) {
    dofs.push_back(as.dof_of(dep.rows[k]));
    multipliers = multipliers && dep.no_diagonal[k];
  }
  std::string owners;
  m.for_each_instances([&](const auto& vec) {
    for (const auto& in : vec) {
      using T = std::remove_cvref_t<decltype(in.element)>;
      bool owns = false, other = false;
      for (std::size_t k = 0; k < in.dofs.size(); ++k) {
        if (std::find(dofs.begin(), dofs.end(), in.dofs[k]) == dofs.end()) continue;
        (k >= static_cast<std::size_t>(T::passport.ext) ? owns : other) = true;
      }
      if (owns) owners += (owners.empty() ? "" : ", ") + std::string(T::passport.name) + " '" + in.name + "'";
      multipliers = multipliers && !other;
    }
  });
  if (multipliers && !owners.empty())
    return "redundant constraints: the equations of " + owners + " depend on each other (" +
           std::to_string(dep.deficiency) + " more than the motion they hold needs), so the Newton matrix is "
           "singular and the constraint forces are not determined; remove a joint, or use one that holds fewer "
           "directions (a second bearing on a rigid shaft: PTL3X or CYL3X instead of REV3X)";
  std::string list;
  for (std::size_t k = 0; k < dofs.size() && k < 8; ++k) list += (k ? ", '" : "'") + m.dof_name(dofs[k]) + "'";
  if (dofs.size() > 8) list += ", ...";
  return plain + "; the equations of DOFs " + list + " depend on each other";
}

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
  if (e.code() == error_code::singular_matrix)
    if (const auto dep = find_dependent_equations(as); dep && dep->rows.size() >= 2)
      msg = dependence_text(m, as, *dep, msg);
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
