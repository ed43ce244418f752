#pragma once
/// \file
/// The zero step's Newton iterations beyond its first linear solve
/// (initialisation.hpp, initial_derivatives): the index-3 constraints' second
/// derivatives, Newton with a line search where viscous DOFs have nonlinear flows,
/// and the rates of the viscous DOFs (docs/architecture.md, "The zero step").

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/node_start.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis::detail {
/// The right-hand side of the kind-3 rows: minus the second time derivative of
/// each constraint g(u) along u(t) = u0 + t v0 + t^2 a0 / 2 (that is G a0 + (dG/dt) v0),
/// by central second differences at the steps e and e / 2 with Richardson
/// extrapolation (error O(e^4)). e = 1e-3 s, smaller for fast motions.
template <class Assembler, class Evaluate>
void constraint_accelerations(Assembler& as, global_state& s, const std::vector<char>& kind, std::vector<double>& rhs,
                              Evaluate& evaluate) {
  const int ne = as.equations();
  const Eigen::VectorXd u0 = s.u;
  const double vmax = s.v.template lpNorm<Eigen::Infinity>(), amax = s.a.template lpNorm<Eigen::Infinity>();
  double e = 1e-3;
  if (vmax > 0) e = std::min(e, 0.05 / vmax);
  if (amax > 0) e = std::min(e, std::sqrt(0.1 / amax));
  std::vector<double> g0(kind.size()), d[2];
  auto rows_at = [&](double t, std::vector<double>& out) {
    s.u = u0 + t * s.v + (0.5 * t * t) * s.a;
    evaluate(jacobian_coefficients{0, 0, 0}, false);
    for (int i = 0; i < ne; ++i) out[static_cast<std::size_t>(i)] = as.residual()(as.dof_of(i));
  };
  rows_at(0.0, g0);
  std::vector<double> gp(kind.size()), gm(kind.size());
  for (int k = 0; k < 2; ++k) {
    const double h = k == 0 ? e : e / 2;
    rows_at(h, gp);
    rows_at(-h, gm);
    d[k].resize(kind.size());
    for (std::size_t i = 0; i < kind.size(); ++i) d[k][i] = (gp[i] - 2 * g0[i] + gm[i]) / (h * h);
  }
  s.u = u0;
  evaluate(jacobian_coefficients{0, 0, 0}, false);
  for (std::size_t i = 0; i < kind.size(); ++i)
    if (kind[i] == 3) rhs[i] = -(4 * d[1][i] - d[0][i]) / 3;
}

/// The zero step's scaled residual: the largest |F_i| / (nominal flow of DOF i, core/domain.hpp)
/// over the equations whose unknown it solves for (inertial, viscous, a velocity-level multiplier or
/// a stiffness DOF whose velocity a source fixes, `kind` 1, 2, 4 or 6), without
/// the nodes' hidden and slaved DOFs (their rows are replaced). NaN if a residual is NaN.
template <class Model, class Assembler>
double start_residual(const Model& m, const Assembler& as, const std::vector<char>& kind) {
  const std::vector<char> hidden = m.hidden_dofs(true);
  double r = 0;
  for (int i = 0; i < as.equations(); ++i) {
    const auto d = static_cast<std::size_t>(as.dof_of(i));
    const char k = kind[static_cast<std::size_t>(i)];
    if ((k != 1 && k != 2 && k != 4 && k != 6) || hidden[d]) continue;
    const double x = std::abs(as.residual()(static_cast<Eigen::Index>(d))) / m.scales()[d].flow;
    if (!(x <= r)) r = x;
  }
  return r;
}

/// The zero step's matrix (initial_derivatives) in the pattern's order: M in the columns of
/// inertial unknowns, C in those of viscous ones, multipliers and fixed stiffness DOFs (kinds 2, 3, 4, 6),
/// the identity on algebraic DOFs; an index-3 constraint row has K in the inertial columns (its second
/// derivative), a kind-5 row (velocity_constraints.hpp) C there (its first derivative).
inline void start_matrix(const linalg::sparsity_pattern& pat, const std::vector<char>& kind, const std::vector<double>& mvals,
                         const std::vector<double>& cvals, const std::vector<double>& kvals, std::vector<double>& j) {
  const int ne = static_cast<int>(kind.size());
  for (int r = 0; r < ne; ++r)
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
      const int c = pat.col[static_cast<std::size_t>(q)];
      const auto sq = static_cast<std::size_t>(q);
      const char k = kind[static_cast<std::size_t>(c)];
      if (kind[static_cast<std::size_t>(r)] == 3) j[sq] = k == 1 ? kvals[sq] : 0.0;
      else if (kind[static_cast<std::size_t>(r)] == 5) j[sq] = k >= 1 ? cvals[sq] : 0.0;
      else j[sq] = k == 1 ? mvals[sq] : (k >= 2 ? cvals[sq] : (r == c ? 1.0 : 0.0));
    }
}

/// Adds f z to the zero step's unknowns: accelerations of inertial equations, velocities of
/// viscous ones, multipliers and fixed stiffness DOFs (`kind` 1, 2-6; z in equation order).
template <class Assembler>
void add_start_correction(const Assembler& as, const std::vector<char>& kind, const std::vector<double>& z, double f,
                          global_state& s) {
  for (int i = 0; i < as.equations(); ++i) {
    const auto d = as.dof_of(i);
    const char k = kind[static_cast<std::size_t>(i)];
    if (k == 1) s.a(d) += f * z[static_cast<std::size_t>(i)];
    if (k >= 2) s.v(d) += f * z[static_cast<std::size_t>(i)];
  }
}

/// The zero step's Newton iterations after its first step (initial_derivatives), when some
/// viscous DOF (kind 2, not a node's hidden or slaved DOF) is an unknown: their flows may be
/// nonlinear in the velocities (an orifice, a check valve, a diode), where one linear solve
/// can land far off (a closed valve's tiny slope puts its node at 2.2e8 Pa: docs/domains.md,
/// "The zero step"). Each iteration evaluates M, C and the residual at the current unknowns,
/// solves with the matrix of start_matrix and, when the scaled residual (start_residual) grew
/// above both its value before the step and DABSI, halves the step back (up to 40 times).
/// Stops after applying a correction whose every component is within 1e-10 of its DOF's
/// nominal potential plus the unknown's magnitude, or without one that shrank by less than half while
/// the scaled residual is within DABSI (round-off), or, with a warning, one that did not shrink
/// at all after a full step (no root nearby: the flow tends to a limit); after 30 iterations,
/// or a step that cannot be halved into a decrease, or a singular matrix, or a non-finite
/// correction, it keeps the best iterate and warns. The first step then fails in Newton if
/// the flows cannot balance. `z` holds the first correction,
/// already applied; r_before is the scaled residual before it.
template <class Model, class Assembler, class Solver, class Evaluate>
void refine_start(Model& m, Assembler& as, Solver& solver, global_state& s, std::vector<double>& z,
                  run_statistics& stats, diagnostics& log, Evaluate& evaluate, const std::vector<char>& kind,
                  std::vector<double>& mvals, std::vector<double>& cvals, const std::vector<double>& kvals,
                  double r_before, double dabsi) {
  const int ne = as.equations();
  const std::vector<char> hidden = m.hidden_dofs(true);
  bool viscous = false;
  for (int i = 0; i < ne; ++i)
    viscous = viscous || (kind[static_cast<std::size_t>(i)] == 2 && !hidden[static_cast<std::size_t>(as.dof_of(i))]);
  if (!viscous) return;
  const bool constraints = std::find(kind.begin(), kind.end(), char{3}) != kind.end();
  const bool velocity_constraints = std::find(kind.begin(), kind.end(), char{5}) != kind.end();
  const auto& pat = as.pattern();
  std::vector<double> j(mvals.size(), 0.0), rhs(static_cast<std::size_t>(ne), 0.0);
  auto residual_at = [&]() {
    try {
      evaluate(jacobian_coefficients{0, 0, 1}, true);
      return start_residual(m, as, kind);
    } catch (const error&) {
      return std::numeric_limits<double>::infinity();  // an element refuses the trial state: halve
    }
  };
  auto warn = [&](const std::string& why) {
    log.write("warning: the zero step's Newton iterations on the initial derivatives " + why +
              ": the first step starts from the best iterate");
  };
  double step = 1.0, last_size = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it) {
    double r = residual_at();
    for (int halvings = 0; !(r <= r_before) && !(r <= dabsi); ++halvings) {
      if (halvings == 40) {
        add_start_correction(as, kind, z, -step, s);  // back to the iterate before this step
        evaluate(jacobian_coefficients{0, 0, 1}, true);
        warn("found no step that lowers the flow residual");
        return;
      }
      step /= 2;
      add_start_correction(as, kind, z, -step, s);
      r = residual_at();
    }
    mvals.assign(as.values().begin(), as.values().end());
    if (it == 30) {  // the rates (viscous_rates) take C and M of this iterate
      if constexpr (Assembler::any_c) {
        evaluate(jacobian_coefficients{0, 1, 0}, true);
        cvals.assign(as.values().begin(), as.values().end());
      }
      warn("did not converge in 30 iterations");
      return;
    }
    for (int i = 0; i < ne; ++i) rhs[static_cast<std::size_t>(i)] = -as.residual()(as.dof_of(i));
    if (constraints) constraint_accelerations(as, s, kind, rhs, evaluate);
    if (velocity_constraints) velocity_constraint_rates(m, as, s, kind, rhs, evaluate);
    if constexpr (Assembler::any_c) {
      evaluate(jacobian_coefficients{0, 1, 0}, true);
      cvals.assign(as.values().begin(), as.values().end());
    }
    start_matrix(pat, kind, mvals, cvals, kvals, j);
    hidden_dof_rows(m, as, s, j, rhs);
    try {
      solver.factorize(j);
      ++stats.factorizations;
      solver.solve(rhs);
    } catch (const error& e) {
      if (e.code() != error_code::singular_matrix) throw;
      warn("met a singular matrix (" + std::string(e.what()) + ")");
      return;
    }
    double size = 0;  // the correction relative to its DOF's nominal potential plus the unknown
    for (int i = 0; i < ne; ++i) {
      const auto d = as.dof_of(i);
      const char k = kind[static_cast<std::size_t>(i)];
      if (k == 0 || hidden[static_cast<std::size_t>(d)]) continue;
      const double x = k == 1 ? s.a(d) : s.v(d);
      const double e = std::abs(rhs[static_cast<std::size_t>(i)]) / (m.scales()[static_cast<std::size_t>(d)].potential + std::abs(x));
      if (!(e <= size)) size = e;
    }
    if (!std::isfinite(size)) {
      warn("met a non-finite correction");
      return;
    }
    if (size <= 1e-10) {
      // Applied: Newton's next error is of the order of its square, round-off. Left out, it would
      // be the first step's correction, and a correction d at a first step h gives the
      // trapezoidal rule's rate 2 d / h, which alternates undamped afterwards (a diode node
      // fed by VDC2: d = 1e-10 V at h = 1e-11 s started an alternation of 20 V/s).
      add_start_correction(as, kind, rhs, 1.0, s);
      return;
    }
    // Corrections that no longer halve while the flows balance to DABSI: round-off. While they do
    // not balance, Newton goes on as long as full steps shrink their corrections at all (an
    // exponential far above its root takes steps of about n Vt each, slow but not stalled: a diode
    // from 0 V), and after a halved step, up to 30 iterations.
    if (it > 0 && size > 0.5 * last_size && r <= dabsi) return;
    if (it > 0 && step == 1.0 && size >= last_size) {  // a halved step (global phase) is not judged
      warn("stopped converging (the corrections no longer shrink)");
      return;
    }
    last_size = size;
    r_before = r;
    z = rhs;
    step = 1.0;
    add_start_correction(as, kind, z, 1.0, s);
  }
}

/// The time derivative dF_i/dt of every equation's residual along the motion
/// u0 + t v + t^2 a / 2, v + t a at the times t0 + t, into `out` (equation order), by
/// forward differences at t = e, e / 2, e / 4 and two Richardson extrapolations (error
/// O(e^3)); e = 1e-3 s, less where a DOF's velocity would change by more than 1e-3 of its
/// nominal potential plus its magnitude, and at most 1e-2 of the step an element
/// recommends. The nearby states are evaluated at their times with the kinematic sources
/// at those times when `evaluate(c, want_jacobian, t)` takes that offset, so dF/dt includes
/// a flow's explicit time dependence. One-sided because the run goes forward: a ramp that
/// starts at t0 (a table source) has its rate after t0. Restores s and evaluates it again,
/// also when an element refuses a nearby state (its error is rethrown).
template <class Model, class Assembler, class Evaluate>
void rates_along_motion(const Model& m, Assembler& as, global_state& s, Evaluate& evaluate, std::vector<double>& out) {
  const int ne = as.equations();
  const Eigen::VectorXd u0 = s.u, v0 = s.v, a0 = s.a, p0 = s.p;  // sources overwrite a, p of their DOFs
  double e = 1e-3;
  for (Eigen::Index d = 0; d < s.a.size(); ++d) {
    const double a = std::abs(a0(d));
    const double lim = 1e-3 * (m.scales()[static_cast<std::size_t>(d)].potential + std::abs(v0(d)));
    if (a * e > lim) e = lim / a;
  }
  if (std::isfinite(as.recommended_step()) && as.recommended_step() > 0) e = std::min(e, 1e-2 * as.recommended_step());
  std::vector<double> f0(static_cast<std::size_t>(ne)), fh(static_cast<std::size_t>(ne)), d[3];
  auto rows_at = [&](double t, std::vector<double>& rows) {
    s.u = u0 + t * v0 + (0.5 * t * t) * a0;
    s.v = v0 + t * a0;
    if constexpr (std::is_invocable_v<Evaluate&, jacobian_coefficients, bool, double>)
      evaluate(jacobian_coefficients{0, 0, 0}, false, t);
    else
      evaluate(jacobian_coefficients{0, 0, 0}, false);
    for (int i = 0; i < ne; ++i) rows[static_cast<std::size_t>(i)] = as.residual()(as.dof_of(i));
  };
  auto restore = [&] {
    s.u = u0;
    s.v = v0;
    s.a = a0;
    s.p = p0;
    evaluate(jacobian_coefficients{0, 0, 0}, false);
  };
  try {
    rows_at(0.0, f0);
    for (int k = 0; k < 3; ++k) {
      const double h = std::ldexp(e, -k);
      rows_at(h, fh);
      d[k].resize(static_cast<std::size_t>(ne));
      for (std::size_t i = 0; i < d[k].size(); ++i) d[k][i] = (fh[i] - f0[i]) / h;
    }
  } catch (const error&) {
    restore();
    throw;
  }
  restore();
  out.resize(static_cast<std::size_t>(ne));
  for (std::size_t i = 0; i < out.size(); ++i) {  // D(h) = F' + F'' h / 2 + F''' h^2 / 6 + ...: eliminate h, then h^2
    const double r1 = 2 * d[1][i] - d[0][i], r2 = 2 * d[2][i] - d[1][i];
    out[i] = (4 * r2 - r1) / 3;
  }
}

/// The right-hand sides of the kind-5 rows in the zero step's solve for the corrections of
/// the accelerations: minus the rows' time derivatives along the motion with the current
/// accelerations (rates_along_motion), G a + dF/dt at fixed a. Leaves the other rows as they are.
template <class Model, class Assembler, class Evaluate>
void velocity_constraint_rates(const Model& m, Assembler& as, global_state& s, const std::vector<char>& kind,
                               std::vector<double>& rhs, Evaluate& evaluate) {
  std::vector<double> dfdt;
  rates_along_motion(m, as, s, evaluate, dfdt);
  for (std::size_t i = 0; i < kind.size(); ++i)
    if (kind[i] == 5) rhs[i] = -dfdt[i];
}

/// The rates of the viscous unknowns at the zero step: a viscous DOF's velocity (a pressure
/// at a node without capacitance, the series point of a spring and a damper) follows from its
/// equation F_i = 0, so its rate a_i follows from dF_i/dt = 0 along the motion. For the
/// viscous equations, velocity-level multipliers and the DOFs they fix (kinds 2, 4 and 6, not a node's
/// hidden or slaved DOF) whose rows hold no inertia entry, dF_i/dt comes from rates_along_motion and
/// C_vv da_v = -dF_v/dt is solved for their rates. Without this they started at 0 and
/// the error test of the first steps saw the jump (a node between a pump and a check valve
/// whose pressure rises with the accumulator behind the valve failed at SMIN); with the
/// explicit time dependence a current source ISIN feeding a resistor starts with
/// v' = R I'(0). A singular C_vv, or an element that refuses one of the nearby states, leaves
/// the rates at 0 with a warning.
template <class Model, class Assembler, class Solver, class Evaluate>
void viscous_rates(Model& m, Assembler& as, Solver& solver, global_state& s, run_statistics& stats,
                   diagnostics& log, Evaluate& evaluate, const std::vector<char>& kind,
                   const std::vector<double>& mvals, const std::vector<double>& cvals) {
  const int ne = as.equations();
  const auto& pat = as.pattern();
  const std::vector<char> hidden = m.hidden_dofs(true);
  std::vector<char> rate(static_cast<std::size_t>(ne), 0);
  bool any = false;
  for (int i = 0; i < ne; ++i) {
    const char k = kind[static_cast<std::size_t>(i)];
    if ((k != 2 && k != 4 && k != 6) || hidden[static_cast<std::size_t>(as.dof_of(i))]) continue;
    bool inertia = false;
    for (int q = pat.row_ptr[static_cast<std::size_t>(i)]; q < pat.row_ptr[static_cast<std::size_t>(i) + 1]; ++q)
      inertia = inertia || mvals[static_cast<std::size_t>(q)] != 0.0;
    rate[static_cast<std::size_t>(i)] = inertia ? 0 : 1;
    any = any || !inertia;
  }
  if (!any) return;
  std::vector<double> dfdt;
  try {
    rates_along_motion(m, as, s, evaluate, dfdt);
  } catch (const error& ex) {  // an element refuses a state next to the start: keep the rates at 0
    log.write("warning: no consistent rates of the viscous DOFs at the zero step: an element refuses a state "
              "next to the start (" + std::string(ex.what()) + "); they start at 0");
    return;
  }
  std::vector<double> j(cvals.size(), 0.0), rhs(static_cast<std::size_t>(ne), 0.0);
  for (int r = 0; r < ne; ++r) {
    const bool row = rate[static_cast<std::size_t>(r)] != 0;
    if (row) rhs[static_cast<std::size_t>(r)] = -dfdt[static_cast<std::size_t>(r)];
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
      const int c = pat.col[static_cast<std::size_t>(q)];
      if (row) j[static_cast<std::size_t>(q)] = rate[static_cast<std::size_t>(c)] ? cvals[static_cast<std::size_t>(q)] : 0.0;
      else j[static_cast<std::size_t>(q)] = r == c ? 1.0 : 0.0;
    }
  }
  try {
    solver.factorize(j);
    ++stats.factorizations;
    solver.solve(rhs);
  } catch (const error& ex) {
    if (ex.code() != error_code::singular_matrix) throw;
    log.write("warning: no consistent rates of the viscous DOFs at the zero step (" + std::string(ex.what()) +
              "): they start at 0");
    evaluate(jacobian_coefficients{0, 0, 0}, false);
    return;
  }
  bool finite = true;
  for (int i = 0; i < ne; ++i) finite = finite && (!rate[static_cast<std::size_t>(i)] || std::isfinite(rhs[static_cast<std::size_t>(i)]));
  if (!finite)  // a user's solver that returns what a singular C_vv gives instead of throwing
    log.write("warning: no consistent rates of the viscous DOFs at the zero step (their solve is not finite): they "
              "start at 0");
  else
    for (int i = 0; i < ne; ++i)
      if (rate[static_cast<std::size_t>(i)]) s.a(as.dof_of(i)) += rhs[static_cast<std::size_t>(i)];
  evaluate(jacobian_coefficients{0, 0, 0}, false);
}

}  // namespace pradis::detail
