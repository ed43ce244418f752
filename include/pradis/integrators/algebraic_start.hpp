#pragma once
/// \file
/// The zero step's positions and velocities of the algebraic DOFs: those with neither mass
/// nor viscosity (a node between two springs, the joint of a massless linkage), whose
/// equations F_a(u) = 0 hold no derivative. Initial conditions that leave such a DOF off its
/// equation (a displaced mass whose spring ends at a massless node) used to be met by the
/// first step's Newton iterations, which moved the DOF by d within one step h: a velocity
/// d / h. Under error control the first step is SMIN, so no tolerance passed it, and both
/// drivers ended with code 141 at t = SMIN (a mass on a spring to a massless node held by a
/// second spring, displaced by 0.1 m). Here, before the derivatives of the other DOFs are
/// found (initialisation.hpp, initial_derivatives), Newton solves F_a(u_a) = 0 for the
/// algebraic positions with the other DOFs at their initial values, and dF_a/dt = 0 for
/// their velocities along the motion (rates_along_motion).
///
/// The algebraic DOFs taken: equations of kind 0 with a stiffness diagonal, not a DOF of a node
/// (a rotational node's q1..q3 move with its hidden q4 and its norm; a slaved DOF follows its
/// node), not reached by a constraint row (an index-3 or velocity-level multiplier's row, or an
/// algebraic row without a diagonal: a constraint's DOFs move with its multiplier, which this
/// solve does not have), and not coupled through dF/du, directly or through other algebraic
/// DOFs, to one of those: a group of algebraic DOFs is solved whole or left whole. What is left
/// goes to the first step, as before (the translations of a massless beam's nodes, for one).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/start_newton.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::detail {

/// Per equation: 1 for the algebraic DOFs that algebraic_start solves (see the file comment).
/// `kind` as initial_derivatives classes the equations; kvals: dF/du in the pattern's order.
template <class Model, class Assembler>
std::vector<char> algebraic_rows(const Model& m, const Assembler& as, const std::vector<char>& kind,
                                 const std::vector<double>& kvals) {
  const int ne = as.equations();
  const auto& pat = as.pattern();
  std::vector<char> node(static_cast<std::size_t>(m.dof_count()), 0);
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    for (const auto& n : nodes)
      for (const int d : n.dofs)
        if (d >= 0 && d < m.dof_count()) node[static_cast<std::size_t>(d)] = 1;
  });
  const auto z = [](int i) { return static_cast<std::size_t>(i); };
  // left[i]: an algebraic equation this solve cannot take (a node's DOF, no diagonal, or a column of a
  // constraint's row); then every algebraic equation coupled to one through dF/du is left too, so that a
  // group of algebraic DOFs is solved whole or not at all (a massless beam node's translations stay with
  // its rotations, which the first step moves).
  std::vector<char> left(z(ne), 0);
  std::vector<std::vector<int>> coupled(z(ne));
  for (int i = 0; i < ne; ++i) {
    const char k = kind[z(i)];
    const int q = pat.find(i, i);
    const bool diagonal = q >= 0 && kvals[z(q)] != 0.0;
    if (k == 0 && (!diagonal || node[z(as.dof_of(i))])) left[z(i)] = 1;
    for (int p = pat.row_ptr[z(i)]; p < pat.row_ptr[z(i) + 1]; ++p) {
      const int c = pat.col[z(p)];
      if (k >= 3 || (k == 0 && !diagonal)) left[z(c)] = 1;  // a constraint's row: its columns stay
      if (k == 0 && kind[z(c)] == 0 && c != i) coupled[z(i)].push_back(c), coupled[z(c)].push_back(i);
    }
  }
  std::vector<int> stack;
  for (int i = 0; i < ne; ++i)
    if (left[z(i)] && kind[z(i)] == 0) stack.push_back(i);
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    for (const int c : coupled[z(i)])
      if (!left[z(c)]) left[z(c)] = 1, stack.push_back(c);
  }
  std::vector<char> alg(z(ne), 0);
  for (int i = 0; i < ne; ++i) alg[z(i)] = kind[z(i)] == 0 && !left[z(i)];
  return alg;
}

/// The matrix of the algebraic solve in the pattern's order: `values` (dF/du) in the rows and
/// columns of the algebraic DOFs, the identity elsewhere.
inline void algebraic_matrix(const linalg::sparsity_pattern& pat, const std::vector<char>& alg,
                             std::span<const double> values, std::vector<double>& j) {
  const int ne = static_cast<int>(alg.size());
  for (int r = 0; r < ne; ++r)
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
      const int c = pat.col[static_cast<std::size_t>(q)];
      const auto sq = static_cast<std::size_t>(q);
      if (alg[static_cast<std::size_t>(r)])
        j[sq] = alg[static_cast<std::size_t>(c)] ? values[sq] : 0.0;
      else
        j[sq] = r == c ? 1.0 : 0.0;
    }
}

/// Solves the algebraic DOFs' positions and velocities at the zero step (see the file comment).
/// Newton on F_a(u_a) = 0 with dF_a/du_a, halving a step whose scaled residual (|F| over the
/// DOF's nominal flow) grew above both its value before and DABSI, until a correction is within
/// 1e-10 of its DOF's nominal potential plus its position (applied: the next is round-off), or
/// shrank by less than half while the residual is within DABSI. Then dF_a/dt = 0:
/// dF_a/du_a dv_a = -dF_a/dt. A singular matrix, a non-finite correction, 30 iterations, a step
/// that cannot be halved into a decrease or an element that refuses the states restore the
/// initial values with a warning (the first step then meets the equations, as before). Returns
/// whether it evaluated the model (the caller evaluates again at s); `kvals` as algebraic_rows.
template <class Model, class Assembler, class Solver, class Evaluate>
bool algebraic_start(Model& m, Assembler& as, Solver& solver, global_state& s, run_statistics& stats,
                     diagnostics& log, Evaluate& evaluate, const std::vector<char>& kind,
                     const std::vector<double>& kvals, double dabsi) {
  const std::vector<char> alg = algebraic_rows(m, as, kind, kvals);
  if (std::find(alg.begin(), alg.end(), char{1}) == alg.end()) return false;
  const int ne = as.equations();
  const auto& pat = as.pattern();
  const Eigen::VectorXd u_start = s.u, v_start = s.v;
  std::vector<double> j(kvals.size(), 0.0), z(static_cast<std::size_t>(ne), 0.0);
  auto give_up = [&](const std::string& why) {
    s.u = u_start;
    s.v = v_start;
    log.write("warning: the positions of the DOFs with neither mass nor viscosity were not solved at the zero step (" +
              why + "): they start at their initial values, and the first step meets their equations");
    return true;
  };
  auto residual = [&]() {  // evaluates at s with dF/du; infinity where an element refuses the state
    try {
      evaluate(jacobian_coefficients{1, 0, 0}, true);
    } catch (const error&) {
      return std::numeric_limits<double>::infinity();
    }
    double r = 0;
    for (int i = 0; i < ne; ++i) {
      if (!alg[static_cast<std::size_t>(i)]) continue;
      const auto d = static_cast<std::size_t>(as.dof_of(i));
      const double x = std::abs(as.residual()(static_cast<Eigen::Index>(d))) / m.scales()[d].flow;
      if (!(x <= r)) r = x;
    }
    return r;
  };
  auto move = [&](double f) {
    for (int i = 0; i < ne; ++i)
      if (alg[static_cast<std::size_t>(i)]) s.u(as.dof_of(i)) += f * z[static_cast<std::size_t>(i)];
  };
  // Solves dF_a/du_a x = z (z: the right-hand side in the algebraic rows, 0 elsewhere) at the last evaluation.
  auto solve = [&]() -> std::string {
    algebraic_matrix(pat, alg, as.values(), j);
    try {
      solver.factorize(j);
      ++stats.factorizations;
      solver.solve(z);
    } catch (const error& e) {
      if (e.code() != error_code::singular_matrix) throw;
      return "a singular matrix: " + std::string(e.what());
    }
    for (int i = 0; i < ne; ++i)
      if (alg[static_cast<std::size_t>(i)] && !std::isfinite(z[static_cast<std::size_t>(i)]))
        return "a non-finite correction";
    return {};
  };
  double r = residual();
  if (!std::isfinite(r)) return give_up("an element refuses the initial state");
  double last_size = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it) {
    if (it == 30) return give_up("no convergence in 30 Newton iterations");
    for (int i = 0; i < ne; ++i)
      z[static_cast<std::size_t>(i)] = alg[static_cast<std::size_t>(i)] ? -as.residual()(as.dof_of(i)) : 0.0;
    if (const std::string why = solve(); !why.empty()) return give_up(why);
    double size = 0;
    for (int i = 0; i < ne; ++i) {
      if (!alg[static_cast<std::size_t>(i)]) continue;
      const auto d = as.dof_of(i);
      const double e = std::abs(z[static_cast<std::size_t>(i)]) /
                       (m.scales()[static_cast<std::size_t>(d)].potential + std::abs(s.u(d)));
      if (!(e <= size)) size = e;
    }
    if (size <= 1e-10 || (it > 0 && size > 0.5 * last_size && r <= dabsi)) {
      move(1.0);  // within round-off of the root: taken whatever the residual does
      if (!std::isfinite(residual())) return give_up("an element refuses the solved state");
      break;
    }
    double step = 1.0;
    move(step);
    double r_new = residual();
    for (int halvings = 0; !(r_new <= r) && !(r_new <= dabsi); ++halvings) {
      if (halvings == 40) return give_up("no step lowers the residual");
      step /= 2;
      move(-step);
      r_new = residual();
    }
    r = r_new;
    last_size = size;
  }
  // dF_a/dt = 0 along the motion: the velocities.
  std::vector<double> dfdt;
  try {
    rates_along_motion(m, as, s, evaluate, dfdt);
  } catch (const error& e) {
    return give_up("an element refuses a state next to the start: " + std::string(e.what()));
  }
  if (!std::isfinite(residual())) return give_up("an element refuses the solved state");
  for (int i = 0; i < ne; ++i)
    z[static_cast<std::size_t>(i)] = alg[static_cast<std::size_t>(i)] ? -dfdt[static_cast<std::size_t>(i)] : 0.0;
  if (const std::string why = solve(); !why.empty()) return give_up(why);
  for (int i = 0; i < ne; ++i)
    if (alg[static_cast<std::size_t>(i)]) s.v(as.dof_of(i)) += z[static_cast<std::size_t>(i)];
  return true;
}

}  // namespace pradis::detail
