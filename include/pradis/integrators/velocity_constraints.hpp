#pragma once
/// \file
/// Velocity-level constraints at the zero step: an equation whose row holds only
/// viscosity entries and no diagonal, and whose unknown enters other equations
/// through C, such as a floating voltage source (VDC2, VSIN2, VTAB2: the row
/// y(t) - (v+ - v-) = 0, the unknown its current) or a node joined only by such
/// sources. Without them in the zero step the source current took its value at
/// the first step, the potentials jumped, and a run under error control failed at
/// SMIN (docs/domains-electric-pneumatic.md, "Sources"; docs/architecture.md,
/// "The zero step").
///
/// Two kinds (initialisation.hpp, initial_derivatives):
/// - kind 4, when the row reaches through C some viscous unknown (kind 2) or
///   another kind-4 equation, and otherwise only inertial unknowns: the row is
///   solved as it stands together with the viscous DOFs, the inertial potentials
///   in it as the initial conditions set them; the unknown is the DOF's value v;
/// - kind 5, when every unknown the row reaches through C is inertial (kind 1; a
///   capacitor across the source): the row constrains potentials that the initial
///   conditions fix. They are moved onto the constraint as an impulsive flow
///   would move them (project_velocity_constraints, with a warning), and the row
///   is replaced by its time derivative, G a + dF/dt = 0 (start_newton.hpp,
///   velocity_constraint_rates), solved with the accelerations for the
///   multiplier's value.
/// - kind 6, a DOF with a stiffness diagonal and no inertia in its row whose velocity a
///   kind-4 row fixes and whose row the row's unknown enters through C (a floating voltage
///   source across an inductor: the node's flux linkage u is a state, the inductor's current
///   follows from it, and the source fixes the node's voltage v). Its displacement stays as
///   the initial conditions set it; its unknown is its velocity v, solved with the kind-4
///   rows, and its row is solved for their currents. Before, such a row stayed algebraic
///   and the potential jumped at the first step, where a run under error control failed
///   with code 141 at SMIN.
/// A row that reaches an unknown of another kind (a multiplier, an algebraic DOF whose
/// row no source current enters) stays algebraic (kind 0) and is met at the first step.

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "pradis/core/diagnostics.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/options.hpp"
#include "pradis/integrators/start_newton.hpp"

namespace pradis::detail {

/// Marks kinds 4, 5 and 6 among the algebraic equations (kind 0, see the file comment):
/// the candidates are the equations whose unknown enters another row through C and
/// whose own row has no inertia or stiffness entry and a C entry on another unknown.
/// A stiffness DOF (kind 0, a stiffness diagonal, no inertia entry in its row) is fixed
/// by a candidate whose row reaches it through C and whose unknown enters its row through C.
/// A candidate whose row reaches through C an unknown that is neither inertial, nor
/// viscous, nor a candidate, nor a fixed stiffness DOF is dropped, until none changes; then
/// a candidate whose row reaches only inertial unknowns is kind 5, the others kind 4 (their
/// rows reach some viscous unknown, candidate or fixed DOF, which the row then fixes, the
/// inertial potentials it reaches staying as the initial conditions set them), and the
/// fixed stiffness DOFs kind 6. `kvals` may be empty (no stiffness evaluated; then no
/// kind 6). Returns whether any kind 5 was marked.
template <class Pattern>
bool mark_velocity_multipliers(const Pattern& pat, const std::vector<double>& mvals, const std::vector<double>& cvals,
                               const std::vector<double>& kvals, std::vector<char>& kind) {
  const int ne = static_cast<int>(kind.size());
  auto row = [&](int r, auto&& f) {
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q)
      f(static_cast<std::size_t>(q), pat.col[static_cast<std::size_t>(q)]);
  };
  std::vector<char> in_c(kind.size(), 0), cand(kind.size(), 0);
  for (int r = 0; r < ne; ++r)
    row(r, [&](std::size_t q, int c) {
      if (c != r && cvals[q] != 0.0) in_c[static_cast<std::size_t>(c)] = 1;
    });
  for (int r = 0; r < ne; ++r) {
    if (kind[static_cast<std::size_t>(r)] != 0 || !in_c[static_cast<std::size_t>(r)]) continue;
    bool velocity_only = true, on_other = false;
    row(r, [&](std::size_t q, int c) {
      if (mvals[q] != 0.0 || (!kvals.empty() && kvals[q] != 0.0)) velocity_only = false;
      if (cvals[q] != 0.0 && c != r) on_other = true;
    });
    cand[static_cast<std::size_t>(r)] = velocity_only && on_other;
  }
  // The stiffness DOFs (kind 0, a K diagonal, no M entry in the row) that some candidate may fix.
  std::vector<char> stiff(kind.size(), 0), fixed(kind.size(), 0);
  for (int r = 0; r < ne && !kvals.empty(); ++r) {
    if (kind[static_cast<std::size_t>(r)] != 0 || cand[static_cast<std::size_t>(r)]) continue;
    bool inertia = false, diagonal = false;
    row(r, [&](std::size_t q, int c) {
      inertia = inertia || mvals[q] != 0.0;
      diagonal = diagonal || (c == r && kvals[q] != 0.0);
    });
    stiff[static_cast<std::size_t>(r)] = diagonal && !inertia;
  }
  // fixed[j]: a candidate c reaches stiffness DOF j through C (C(c, j)) and its unknown enters j's row (C(j, c)).
  auto update_fixed = [&] {
    bool changed = false;
    for (int j = 0; j < ne; ++j) {
      if (!stiff[static_cast<std::size_t>(j)]) continue;
      bool f = false;
      row(j, [&](std::size_t q, int c) {
        if (c == j || cvals[q] == 0.0 || !cand[static_cast<std::size_t>(c)]) return;
        const int back = pat.find(c, j);
        f = f || (back >= 0 && cvals[static_cast<std::size_t>(back)] != 0.0);
      });
      char& fj = fixed[static_cast<std::size_t>(j)];
      if (f != static_cast<bool>(fj)) fj = f, changed = true;
    }
    return changed;
  };
  // reach[r]: bit 1 an inertial unknown, bit 2 a viscous one, a candidate or a fixed stiffness DOF, bit 4
  // anything else.
  std::vector<char> reach(kind.size(), 0);
  for (bool changed = true; changed;) {
    changed = update_fixed();
    for (int r = 0; r < ne; ++r) {
      if (!cand[static_cast<std::size_t>(r)]) continue;
      char bits = 0;
      row(r, [&](std::size_t q, int c) {
        if (c == r || cvals[q] == 0.0) return;
        const auto cc = static_cast<std::size_t>(c);
        bits |= kind[cc] == 1 ? 1 : (kind[cc] == 2 || cand[cc] || fixed[cc] ? 2 : 4);
      });
      reach[static_cast<std::size_t>(r)] = bits;
      if (bits & 4) {
        cand[static_cast<std::size_t>(r)] = 0;
        changed = true;
      }
    }
  }
  // A kind-5 candidate's unknown must enter inertial rows only; one that a kind-4 row reaches is dropped.
  bool any5 = false;
  for (int r = 0; r < ne; ++r)
    if (cand[static_cast<std::size_t>(r)]) kind[static_cast<std::size_t>(r)] = reach[static_cast<std::size_t>(r)] == 1 ? 5 : 4;
  for (int r = 0; r < ne; ++r)
    if (kind[static_cast<std::size_t>(r)] == 4)
      row(r, [&](std::size_t q, int c) {
        if (cvals[q] != 0.0 && kind[static_cast<std::size_t>(c)] == 5) kind[static_cast<std::size_t>(c)] = 0;
      });
  update_fixed();
  for (int j = 0; j < ne; ++j)
    if (fixed[static_cast<std::size_t>(j)]) kind[static_cast<std::size_t>(j)] = 6;
  for (char k : kind) any5 = any5 || k == 5;
  return any5;
}

/// Moves the potentials of the inertial unknowns onto the kind-5 constraints: with G the
/// rows' C entries in those columns, g their residuals and W the inverse of M's diagonal
/// there, v -= W G^T (G W G^T)^-1 g (exact for constraints linear in v, as the sources').
/// That is what an impulsive constraint flow does to inertias on their own: a source
/// between two capacitors to the ground moves their charges by equal and opposite amounts
/// (C1 dv1 = -C2 dv2), a source from one capacitor to the ground sets that one. A
/// warning names each moved DOF with its old and new value. Returns false, changing nothing,
/// when G W G^T is singular (two sources across one capacitor).
template <class Model, class Assembler>
bool project_velocity_constraints(const Model& m, const Assembler& as, const std::vector<char>& kind,
                                  const std::vector<double>& mvals, const std::vector<double>& cvals, global_state& s,
                                  diagnostics& log) {
  const auto& pat = as.pattern();
  std::vector<int> rows;
  for (int r = 0; r < static_cast<int>(kind.size()); ++r)
    if (kind[static_cast<std::size_t>(r)] == 5) rows.push_back(r);
  const auto n = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd ggt = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd g(n);
  auto entry = [&](int r, int c) {  // G(r, c): the C entry if column c is inertial
    const int q = pat.find(r, c);
    return q >= 0 && kind[static_cast<std::size_t>(c)] == 1 ? cvals[static_cast<std::size_t>(q)] : 0.0;
  };
  auto weight = [&](int c) {  // 1 / M(c, c); 1 for an inertial column without a diagonal (a node's hidden DOF)
    const int q = pat.find(c, c);
    return q >= 0 && mvals[static_cast<std::size_t>(q)] != 0.0 ? 1.0 / mvals[static_cast<std::size_t>(q)] : 1.0;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    const int ri = rows[static_cast<std::size_t>(i)];
    g(i) = as.residual()(as.dof_of(ri));
    for (Eigen::Index k = 0; k < n; ++k) {
      const int rk = rows[static_cast<std::size_t>(k)];
      for (int q = pat.row_ptr[static_cast<std::size_t>(ri)]; q < pat.row_ptr[static_cast<std::size_t>(ri) + 1]; ++q) {
        const int c = pat.col[static_cast<std::size_t>(q)];
        if (kind[static_cast<std::size_t>(c)] == 1) ggt(i, k) += entry(ri, c) * weight(c) * entry(rk, c);
      }
    }
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(ggt);
  if (lu.rank() < n) return false;
  const Eigen::VectorXd y = lu.solve(g);
  std::vector<double> dv(kind.size(), 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int ri = rows[static_cast<std::size_t>(i)];
    for (int q = pat.row_ptr[static_cast<std::size_t>(ri)]; q < pat.row_ptr[static_cast<std::size_t>(ri) + 1]; ++q) {
      const int c = pat.col[static_cast<std::size_t>(q)];
      if (kind[static_cast<std::size_t>(c)] == 1) dv[static_cast<std::size_t>(c)] -= weight(c) * entry(ri, c) * y(i);
    }
  }
  for (std::size_t c = 0; c < dv.size(); ++c) {
    if (dv[c] == 0.0) continue;
    const auto d = as.dof_of(static_cast<int>(c));
    const double old = s.v(d);
    s.v(d) += dv[c];
    log.write("warning: the initial potential of DOF '" + m.dof_name(static_cast<int>(d)) + "' moves from " +
              num(old) + " to " + num(s.v(d)) + " to meet the constraint of a source across it (" +
              "the constraint holds from t = 0)");
  }
  return true;
}

}  // namespace pradis::detail
