#pragma once
/// \file
/// The corrector of pradis::bdf_simulation: modified Newton on the velocities
/// of the free DOFs with u = u_p + (v - u'_p) / c and a = v'_p + c (v - v_p),
/// Newton matrix J = (1/c) K + C + c M, IDA's convergence test and Jacobian
/// reuse (Hindmarsh et al., ACM TOMS 31 (2005) 363-396, section 2.1):
/// - the correction dy = (dv / c, dv) of the displacements and velocities is
///   measured in the weighted RMS norm of the error test; the iteration has
///   converged when ss |dy| <= eps (eps = bdf_options::newton_tolerance), with
///   ss = rate / (1 - rate), rate = (|dy_m| / |dy_0|)^(1/m) from the
///   corrections of this step (for the first correction: the last rate of the
///   previous step, 20 after a new factorisation, 100 after c changed), or at
///   once when the first correction is below 1e-4 eps; the kept rate falls by
///   at most rate_decay per measured correction (kept_rate_ss, as CVODE);
/// - it fails when the rate exceeds newton_options::max_rate, on a non-finite
///   correction, a singular matrix or situation, or after newton_options::itr
///   corrections;
/// - the Jacobian is evaluated and factorised when none is kept, or when c left
///   [c_J (1 - x) / (1 + x), c_J (1 + x) / (1 - x)], x = the window argument
///   (bdf_options::coefficient_change), or when a rotational node turned in
///   the global frame has turned by more than turn_refresh since the
///   factorisation (bdf_options::turn_refresh; the rate estimate is then kept);
///   a kept one has its corrections scaled by 2 / (1 + c / c_J) (IDA); a step
///   that failed with a kept Jacobian is retried at once with a fresh one;
/// - with index-3 constraints in the stabilised index-2 form
///   (index2_stabilisation) the displacements move by (dv + d) / c, d the
///   shift, and the first evaluation of every attempt assembles the Jacobians
///   of the constraint elements for G (the factorisation is still kept).
/// - with a rotated_jacobian, the solution of the kept factorisation is turned
///   from the orientations of the factorisation to the current ones on the
///   entries of the rotational nodes, and for a node in its body frame the
///   right-hand side's moment rows before the solve (rotated_jacobian.hpp);
///   with a rate_form, the accelerations and corrections of its nodes go
///   through their rates (rate_form.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/bdf/constraints.hpp"
#include "pradis/integrators/bdf/history.hpp"
#include "pradis/integrators/bdf/rate_form.hpp"
#include "pradis/integrators/bdf/rotated_jacobian.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis::bdf_detail {

/// What the corrector keeps across steps.
struct newton_memory {
  bool valid = false;  ///< a factorisation is kept
  double c_jac = 0;    ///< the c it was made with
  double ss = 20;      ///< rate / (1 - rate) for the first correction of a step
  std::size_t blocks_version = 0;  ///< the assembler's blocks_version() after the kept matrix's evaluation
};

/// The fastest the kept convergence rate may fall per measured correction
/// (CVODE's CRDOWN).
inline constexpr double rate_decay = 0.3;

/// ss = rate / (1 - rate) kept for the convergence test, from the rate measured
/// in this step and the kept ss_old: rate = max(measured, rate_decay rate_old).
/// The floor keeps one fast contraction, measured just after a factorisation,
/// from standing for the Jacobian in later steps, where it has aged: a step
/// would then pass on its first correction however large that correction is,
/// and the unconverged solutions would feed the history (with a kept Jacobian
/// on the free body this grew the first corrections by 2.5 times per step).
inline double kept_rate_ss(double measured, double ss_old) {
  const double rate = std::max(measured, rate_decay * ss_old / (1 + ss_old));
  return rate / (1 - rate);
}

/// Sets the free DOFs of s from their velocities: u = u_p + (v + sh - u'_p) / c,
/// a = v'_p + c (v - v_p); y_p, yp_p stack (u, v) of the ne equations; sh the
/// shift of the stabilised constraints (index2_stabilisation), or none; rf the
/// rotational nodes in the rate form (their a from the corrector of their rates).
template <class Assembler>
void complete_state(const Assembler& as, global_state& s, const Eigen::VectorXd& y_p, const Eigen::VectorXd& yp_p,
                    double c, const index2_stabilisation* st = nullptr, const rate_form* rf = nullptr) {
  const int ne = as.equations();
  for (int i = 0; i < ne; ++i) {
    const auto d = as.dof_of(i);
    const double v = s.v(d);
    const double sh = st ? st->shift[static_cast<std::size_t>(i)] : 0.0;
    s.u(d) = y_p(i) + (v + sh - yp_p(i)) / c;
    s.a(d) = yp_p(ne + i) + c * (v - y_p(ne + i));
  }
  if (rf) rf->accelerations(s, ne, y_p, yp_p, c);
}

/// The stabilised constraints' part of one Newton iteration (see
/// index2_stabilisation): with `fresh_g` G is taken from the values just
/// assembled (at coefficient c); the constraint rows of `rhs` (holding -F) get
/// -G v / c_J, and st.rhs the right-hand side of the shift.
template <class Assembler>
void stabilised_rows(const Assembler& as, const global_state& s, index2_stabilisation& st, bool fresh_g, double c,
                     double c_jac, std::vector<double>& rhs) {
  const auto& pat = as.pattern();
  const auto vals = as.values();
  std::fill(st.rhs.begin(), st.rhs.end(), 0.0);
  for (const int r : st.rows) {
    const auto b = static_cast<std::size_t>(pat.row_ptr[static_cast<std::size_t>(r)]);
    const auto e = static_cast<std::size_t>(pat.row_ptr[static_cast<std::size_t>(r) + 1]);
    double gv = 0;
    for (std::size_t q = b; q < e; ++q) {
      const auto col = static_cast<std::size_t>(pat.col[q]);
      if (fresh_g) st.g[q] = st.multiplier[col] ? 0.0 : c * vals[q];
      gv += st.g[q] * s.v(as.dof_of(static_cast<int>(col)));
    }
    const double gr = as.residual()(as.dof_of(r));
    rhs[static_cast<std::size_t>(r)] = -gv / c_jac;
    st.rhs[static_cast<std::size_t>(r)] = (gv - c * gr) / c_jac;
  }
}

/// Solves for the correction b1 (and the shift *b2, if given) with the same
/// factorisation: without the residual check where the solver offers that
/// (sparse_lu::solve_unchecked; the corrector's convergence test verifies the
/// corrections), and in one call where it has a two-right-hand-side solve.
template <class Solver>
void solve_corrections(const Solver& solver, std::vector<double>& b1, std::vector<double>* b2) {
  const std::span<double> x1(b1);
  if constexpr (requires { solver.solve_unchecked(x1, x1); }) {
    if (b2)
      solver.solve_unchecked(x1, std::span<double>(*b2));
    else
      solver.solve_unchecked(x1);
  } else if constexpr (requires { solver.solve(x1, x1); }) {
    if (b2)
      solver.solve(x1, std::span<double>(*b2));
    else
      solver.solve(x1);
  } else {
    solver.solve(x1);
    if (b2) solver.solve(std::span<double>(*b2));
  }
}

/// Newton on one step from the predictor (the velocities of s are set to v_p
/// here). Returns whether it converged. `evaluate(coefficients, want_jacobian,
/// constraint_jacobian, iteration)` evaluates the model at s into `as`; with
/// constraint_jacobian (and not want_jacobian) it assembles the Jacobians of
/// the element types that own index-3 multipliers only, enough for G. `failure` receives a
/// singular matrix or situation that ended the last attempt. With rf, the velocity
/// rows of its nodes in y_p, yp_p and dy are rates (rate_form.hpp).
///
/// Slaved DOFs (core/node_kind.hpp, K::slaved), when `slaved`: after every update of the
/// state, `project(s, nullptr, 0)` puts their positions on their nodes' equations
/// (exactly: c = u_k - g_k), and `project(s, &rhs, 1 / c_J)` sets their rows' right-hand
/// sides to the velocity constraint's, -(dc/dt) / c_J (the rows of J are dc/du / c_J), so
/// that the corrections meet dc/dt = 0. With the position constraint's own residual there,
/// its roundoff (~1e-16 |u|) reached the velocities as c times it, above DABSX at steps
/// below ~1e-9 s.
template <class Assembler, class Solver, class Project, class Evaluate>
bool correct(Assembler& as, Solver& solver, global_state& s, const Eigen::VectorXd& y_p, const Eigen::VectorXd& yp_p,
             double c, double c_last, const Eigen::VectorXd& w, const newton_options& nw, double eps,
             double window, double turn_refresh, newton_memory& mem, std::vector<double>& rhs, Eigen::VectorXd& dy,
             run_statistics& stats,
             std::optional<error>& failure, index2_stabilisation* st, const rate_form* rf, rotated_jacobian* rj,
             bool slaved, Project&& project, Evaluate&& evaluate) {
  const int ne = as.equations();
  const jacobian_coefficients jc{1 / c, 1, c};
  bool refresh = !mem.valid;
  if (window < 1 && mem.valid) {
    const double lo = (1 - window) / (1 + window), r = c / mem.c_jac;
    refresh = !(r >= lo && r <= 1 / lo);
  }
  if (c != c_last) mem.ss = 100;
  // A refresh because a node turned in the global frame keeps the rate estimate:
  // the fresher matrix converges no slower than the one it replaces.
  bool keep_rate = false;
  if (!refresh && rj && rj->turned_beyond(s, turn_refresh)) refresh = keep_rate = true;
  // Only c moved and the element blocks of the kept matrix are still in the
  // assembler (keep_blocks, bdf_options::reform_jacobian): J = K / c + C + c M is
  // made again from them at the new c and factorised, without evaluating the
  // elements' Jacobians; the state it belongs to (and the turned matrix's
  // reference) stays the kept one. The driver turns keep_blocks on where this
  // fits (bdf_simulation.hpp); never with stabilised constraints or the rate form
  // (their rows and columns are built with the evaluation).
  bool reform = false;
  if (refresh && !keep_rate && mem.valid && !st && !rf && as.keeps_blocks() &&
      mem.blocks_version == as.blocks_version()) {
    reform = true;
    refresh = false;
  }
  dy.resize(2 * ne);
  failure.reset();
  for (;;) {
    const bool fresh = refresh;
    for (int i = 0; i < ne; ++i) s.v(as.dof_of(i)) = y_p(ne + i);
    if (rf) rf->predicted_velocities(s, ne, y_p);
    if (st) std::fill(st->shift.begin(), st->shift.end(), 0.0);
    complete_state(as, s, y_p, yp_p, c, st, rf);
    if (slaved) project(s, nullptr, 0.0);
    double oldnrm = 0;
    bool converged = false;
    try {
      for (int m = 0; m < nw.itr && !converged; ++m) {
        const bool fresh_g = st && m == 0;  // G at the predictor
        evaluate(jc, refresh, fresh_g && !refresh, m);
        if (refresh) mem.blocks_version = as.blocks_version();
        if (reform) as.reform(jc);
        if (refresh || reform) {
          mem.valid = false;
          solver.factorize(as.values());
          ++stats.factorizations;
          mem.valid = true;
          if (rj && refresh) rj->set_reference(s);
          mem.c_jac = c;
          if (!keep_rate) mem.ss = 20;
          keep_rate = false;
          refresh = reform = false;
        }
        for (int i = 0; i < ne; ++i) rhs[static_cast<std::size_t>(i)] = -as.residual()(as.dof_of(i));
        if (slaved) project(s, &rhs, 1 / mem.c_jac);
        if (st) stabilised_rows(as, s, *st, fresh_g, c, mem.c_jac, rhs);
        if (rj) {
          rj->to_reference(s, rhs);
          if (st) rj->to_reference(s, st->rhs);
        }
        solve_corrections(solver, rhs, st ? &st->rhs : nullptr);
        if (rj) {
          rj->from_reference(s, rhs);
          if (st) rj->from_reference(s, st->rhs);
        }
        ++stats.newton_iterations;
        const double scale = c == mem.c_jac ? 1.0 : 2 / (1 + c / mem.c_jac);
        bool finite = true;
        for (int i = 0; i < ne; ++i) {
          const double dv = scale * rhs[static_cast<std::size_t>(i)];
          double dsh = 0;
          if (st && !st->multiplier[static_cast<std::size_t>(i)]) {
            dsh = st->rhs[static_cast<std::size_t>(i)];
            st->shift[static_cast<std::size_t>(i)] += dsh;
          }
          finite = finite && std::isfinite(dv) && std::isfinite(dsh);
          s.v(as.dof_of(i)) += dv;
          dy(i) = (dv + dsh) / c;
          dy(ne + i) = dv;
        }
        if (!finite) break;
        complete_state(as, s, y_p, yp_p, c, st, rf);
        if (slaved) project(s, nullptr, 0.0);
        if (rf) rf->corrections(s, ne, dy);
        const double delnrm = wrms(dy, w);
        if (m == 0) {
          oldnrm = delnrm;
          if (delnrm <= 1e-4 * eps) converged = true;
        } else {
          const double ratio = delnrm / oldnrm;  // the rate over m iterations (no pow for m = 1)
          const double measured = m == 1 ? ratio : std::pow(ratio, 1.0 / m);
          if (!(measured <= nw.max_rate)) break;
          mem.ss = kept_rate_ss(measured, mem.ss);
        }
        if (mem.ss * delnrm <= eps) converged = true;
      }
    } catch (const error& e) {
      if (e.code() != error_code::singular_situation && e.code() != error_code::singular_matrix) throw;
      failure = e;
      if (e.code() == error_code::singular_matrix) mem.valid = false;
    }
    if (converged) return true;
    if (fresh || (failure && failure->code() == error_code::singular_situation)) return false;
    ++stats.jacobian_retries;
    refresh = true;
    failure.reset();
  }
}

}  // namespace pradis::bdf_detail
