#pragma once
/// \file
/// Consistent initialisation of pradis::simulation at the zero step:
/// prescribed DOFs (ground, kinematic sources), initial conditions with
/// conflict detection (code 90) and consistent initial derivatives (initial
/// accelerations of inertial DOFs, velocities of first-order DOFs).

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/integrators/algebraic_start.hpp"
#include "pradis/integrators/node_start.hpp"
#include "pradis/integrators/options.hpp"
#include "pradis/integrators/start_newton.hpp"
#include "pradis/integrators/velocity_constraints.hpp"

namespace pradis::detail {

/// Marks the ground and the DOFs driven by kinematic sources as prescribed;
/// two sources on one DOF (or a source on the ground) is code 90. Returns, per
/// DOF, what drives it (for messages).
template <class Model>
std::vector<std::string> detect_sources(Model& m, std::vector<char>& prescribed, diagnostics& log) {
  const int nd = m.dof_count();
  prescribed.assign(static_cast<std::size_t>(nd), 0);
  prescribed[0] = 1;
  std::vector<std::string> driver(static_cast<std::size_t>(nd));
  driver[0] = "the ground";
  m.for_each_instances([&](auto& vec) {
    for (auto& in : vec) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (PrescribesMotion<E>) {
        const auto d = static_cast<std::size_t>(in.dofs[0]);
        if (prescribed[d]) {
          error e(error_code::conflicting_initial,
                  "DOF '" + m.dof_name(static_cast<int>(d)) + "' is already driven by " + driver[d],
                  std::string(E::passport.name), in.name, static_cast<long>(d));
          log.write(e);
          throw e;
        }
        prescribed[d] = 1;
        driver[d] = std::string(E::passport.name) + " '" + in.name + "'";
      }
    }
  });
  return driver;
}

/// Sets the potentials of the DOFs driven by kinematic sources at time t.
template <class Model>
void apply_sources(Model& m, global_state& s, double t) {
  m.for_each_instances([&](auto& vec) {
    for (auto& in : vec) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (PrescribesMotion<E>) {
        const kinematics k = in.element.motion(t);
        const auto d = static_cast<Eigen::Index>(in.dofs[0]);
        s.u(d) = k.u;
        s.v(d) = k.v;
        s.a(d) = k.a;
        s.p(d) = k.a;
      }
    }
  });
}

/// One initial value of an element's zero step: refused (code 90) on a driven
/// DOF or when another element set a different value on the same DOF.
template <class Model>
void apply_initial(const Model& m, element_context& ctx, std::size_t d, double value, Eigen::VectorXd& target,
                   std::vector<std::string>& set_by, const std::vector<std::string>& driver,
                   const std::vector<char>& prescribed, const char* what) {
  if (prescribed[d])
    ctx.fail(error_code::conflicting_initial, std::string("initial ") + what + " on DOF '" +
                                                  m.dof_name(static_cast<int>(d)) + "', which is driven by " + driver[d]);
  const auto i = static_cast<Eigen::Index>(d);
  if (!set_by[d].empty() && target(i) != value)
    ctx.fail(error_code::conflicting_initial,
             std::string("initial ") + what + " " + num(value) + " on DOF '" + m.dof_name(static_cast<int>(d)) +
                 "' conflicts with " + num(target(i)) + " set by '" + set_by[d] + "'");
  target(i) = value;
  set_by[d] = std::string(ctx.instance());
}

/// The initial conditions of the zero step: every element's zero_step()
/// values (displacements, velocities), with conflict detection (code 90).
/// `context_for(instance)` makes an element's context. Returns, per DOF, the
/// instance that set its initial displacement (first) and velocity (second).
template <class Model, class Context>
std::pair<std::vector<std::string>, std::vector<std::string>> apply_initial_conditions(
    Model& m, global_state& s, const std::vector<char>& prescribed, const std::vector<std::string>& driver,
    Context&& context_for) {
  const auto nd = static_cast<std::size_t>(m.dof_count());
  std::vector<std::string> set_u(nd), set_v(nd);
  m.for_each_instances([&](auto& vec) {
    for (auto& in : vec) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (HasZeroStep<E>) {
        element_context ctx = context_for(in);
        ctx.newint = true;
        initial_values<element_traits<E>::n> iv;
        in.element.zero_step(iv, ctx);
        for (int k = 0; k < element_traits<E>::n; ++k) {
          const auto d = static_cast<std::size_t>(in.dofs[static_cast<std::size_t>(k)]);
          if (iv.has_displacement(k))
            apply_initial(m, ctx, d, iv.displacement(k), s.u, set_u, driver, prescribed, "displacement");
          if (iv.has_velocity(k)) apply_initial(m, ctx, d, iv.velocity(k), s.v, set_v, driver, prescribed, "velocity");
        }
      }
    }
  });
  return {std::move(set_u), std::move(set_v)};
}

/// Marks the index-3 constraint equations among the algebraic ones (kind 0) as
/// kind 3: no inertia or viscosity in the whole row (a constraint on positions:
/// only K entries, some in an inertial column, none on the row's own DOF) and the
/// DOF's value enters other equations through C (the multiplier of the flows
/// G^T lambda, the velocity-level unknown of an internal DOF: LINKX, SPH3X, REV3X,
/// ...). A massless node held by springs whose velocity another equation reads has
/// a K diagonal: it stays algebraic. Returns whether any was found.
template <class Pattern>
bool mark_index3_multipliers(const Pattern& pat, const std::vector<double>& mvals, const std::vector<double>& cvals,
                             const std::vector<double>& kvals, std::vector<char>& kind) {
  const int ne = static_cast<int>(kind.size());
  std::vector<char> in_c(kind.size(), 0);
  for (int r = 0; r < ne; ++r)
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q)
      if (pat.col[static_cast<std::size_t>(q)] != r && cvals[static_cast<std::size_t>(q)] != 0.0)
        in_c[static_cast<std::size_t>(pat.col[static_cast<std::size_t>(q)])] = 1;
  bool any = false;
  for (int r = 0; r < ne; ++r) {
    if (kind[static_cast<std::size_t>(r)] != 0 || !in_c[static_cast<std::size_t>(r)]) continue;
    bool position_only = true, on_inertial = false;
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
      const auto sq = static_cast<std::size_t>(q);
      if (mvals[sq] != 0.0 || cvals[sq] != 0.0) position_only = false;
      if (pat.col[sq] == r && kvals[sq] != 0.0) position_only = false;  // a stiffness DOF, not a multiplier
      if (kvals[sq] != 0.0 && kind[static_cast<std::size_t>(pat.col[sq])] == 1) on_inertial = true;
    }
    if (position_only && on_inertial) {
      kind[static_cast<std::size_t>(r)] = 3;
      any = true;
    }
  }
  return any;
}

/// Consistent initial derivatives at the zero step. The unknown of each free
/// DOF is its acceleration if it has inertia (dF/da diagonal nonzero), else its
/// velocity if it has viscosity (a first-order DOF, e.g. the series point of a
/// spring and a damper), else nothing (an algebraic DOF: algebraic_start has put
/// its position on its equation, or the first step's Newton will). Newton on F(u0, v0, a0, 0) = 0 with
/// J = M (inertial columns) + C (viscous columns) + I (algebraic columns): one
/// step, and more while viscous DOFs have nonlinear flows (refine_start).
/// Without it the trapezoidal u-v relation of the Newmark family would carry
/// an inconsistent start as an undamped oscillation of v.
/// Index-3 constraint rows (mark_index3_multipliers) take part too: their
/// multiplier's unknown is its value and their row the constraint's second
/// derivative (constraint_accelerations), so the initial joint forces are the
/// consistent ones; if that matrix is singular (redundant constraints), a warning
/// is logged and they start as algebraic DOFs. So do velocity-level constraints
/// (the currents of floating voltage sources; velocity_constraints.hpp).
/// `evaluate(c, want_jacobian)` evaluates the model at s into `as`. Returns
/// the kind of each equation (1 inertial, 2 viscous, 3 index-3 multiplier,
/// 4 and 5 velocity-level multipliers, 6 a stiffness DOF whose velocity one fixes (velocity_constraints.hpp),
/// 0 algebraic), or an empty vector when no consistent derivatives could be found (a warning is logged
/// and the free DOFs start with zero accelerations).
template <class Model, class Assembler, class Solver, class Evaluate>
std::vector<char> initial_derivatives(Model& m, Assembler& as, Solver& solver, global_state& s,
                                      std::vector<double>& rhs, run_statistics& stats, diagnostics& log,
                                      double dabsi, Evaluate&& evaluate) {
  if constexpr (!Assembler::any_m && !Assembler::any_c) {
    // Every DOF is algebraic (a static model run as a transient): its positions on its equations.
    std::vector<char> kind(static_cast<std::size_t>(as.equations()), 0);
    evaluate(jacobian_coefficients{1, 0, 0}, true);
    const std::vector<double> kvals(as.values().begin(), as.values().end());
    algebraic_start(m, as, solver, s, stats, log, evaluate, kind, kvals, dabsi);
    return kind;
  } else {
    const int ne = as.equations();
    const auto& pat = as.pattern();
    evaluate(jacobian_coefficients{0, 0, 1}, true);
    std::vector<double> mvals(as.values().begin(), as.values().end());
    std::vector<double> cvals(mvals.size(), 0.0);
    for (int i = 0; i < ne; ++i) rhs[static_cast<std::size_t>(i)] = -as.residual()(as.dof_of(i));
    if constexpr (Assembler::any_c) {
      evaluate(jacobian_coefficients{0, 1, 0}, true);
      cvals.assign(as.values().begin(), as.values().end());
    }
    std::vector<char> kind(static_cast<std::size_t>(ne), 0);
    for (int i = 0; i < ne; ++i) {
      const int q = pat.find(i, i);
      if (q >= 0 && mvals[static_cast<std::size_t>(q)] != 0.0) kind[static_cast<std::size_t>(i)] = 1;
      else if (q >= 0 && cvals[static_cast<std::size_t>(q)] != 0.0) kind[static_cast<std::size_t>(i)] = 2;
    }
    // Nodes: a hidden DOF's unknown is its acceleration (the rotational q4's from
    // d2(Lq)/dt2 = 0); the node's other DOFs are inertial by its inertia block.
    mark_node_kinds(m, as, mvals, kind);
    // Index-3 constraint rows (multipliers, docs/joints.md): the multiplier's
    // unknown is its value v, and its row becomes the constraint's second time
    // derivative, G a + (dG/dt) v = 0, so that the initial multipliers and
    // accelerations are consistent with the constraints.
    // Velocity-level constraints (velocity_constraints.hpp): kind 4 is solved with the
    // viscous DOFs and the stiffness DOFs whose velocities it fixes (kind 6); for kind 5 the
    // potentials move onto the constraint first and the row becomes its first time derivative.
    std::vector<double> kvals;
    std::vector<double> rhs_plain = rhs;
    // The flows, M, C and K again, at a state the start has moved.
    auto again = [&] {
      evaluate(jacobian_coefficients{0, 0, 1}, true);
      mvals.assign(as.values().begin(), as.values().end());
      for (int i = 0; i < ne; ++i) rhs[static_cast<std::size_t>(i)] = -as.residual()(as.dof_of(i));
      rhs_plain = rhs;
      if constexpr (Assembler::any_c) {
        evaluate(jacobian_coefficients{0, 1, 0}, true);
        cvals.assign(as.values().begin(), as.values().end());
      }
      evaluate(jacobian_coefficients{1, 0, 0}, true);
      kvals.assign(as.values().begin(), as.values().end());
    };
    if (std::find(kind.begin(), kind.end(), char{0}) != kind.end()) {
      evaluate(jacobian_coefficients{1, 0, 0}, true);
      kvals.assign(as.values().begin(), as.values().end());
      const bool index3 = mark_index3_multipliers(pat, mvals, cvals, kvals, kind);
      const bool velocity = mark_velocity_multipliers(pat, mvals, cvals, kvals, kind);
      // Algebraic DOFs on their equations first (algebraic_start.hpp): the flows on the others follow.
      if (algebraic_start(m, as, solver, s, stats, log, evaluate, kind, kvals, dabsi)) again();
      if (velocity) {
        if (project_velocity_constraints(m, as, kind, mvals, cvals, s, log)) {
          again();  // at the moved potentials
          try {
            velocity_constraint_rates(m, as, s, kind, rhs, evaluate);
          } catch (const error& e) {
            log.write("warning: the constraints of sources across inertial DOFs are met from the first step only: "
                      "an element refuses a state next to the start (" + std::string(e.what()) + ")");
            std::replace(kind.begin(), kind.end(), char{5}, char{0});
          }
        } else {
          log.write("warning: the constraints of sources across inertial DOFs depend on each other: their currents "
                    "start at their initial values");
          std::replace(kind.begin(), kind.end(), char{5}, char{0});
        }
      }
      if (index3) constraint_accelerations(as, s, kind, rhs, evaluate);
    }
    std::vector<double> rhs0 = rhs;
    std::vector<double> j(mvals.size(), 0.0);
    const double r_start = start_residual(m, as, kind);
    for (;;) {
      start_matrix(pat, kind, mvals, cvals, kvals, j);
      rhs = rhs0;
      hidden_dof_rows(m, as, s, j, rhs);
      try {
        solver.factorize(j);
        ++stats.factorizations;
        solver.solve(rhs);
        bool finite = true;
        for (double x : rhs) finite = finite && std::isfinite(x);
        if (!finite) throw error(error_code::singular_matrix, "non-finite initial derivatives");
        add_start_correction(as, kind, rhs, 1.0, s);
        break;
      } catch (const error& e) {
        if (e.code() != error_code::singular_matrix) throw;
        if (std::find_if(kind.begin(), kind.end(), [](char k) { return k >= 3; }) != kind.end()) {
          // Redundant or unsupported constraints (a loop of voltage sources): start them as
          // algebraic DOFs (multipliers at their initial values, met by Newton at the first step).
          log.write("warning: no consistent initial multipliers: the constraint forces and source currents start "
                    "at their initial values (" + std::string(e.what()) + ")");
          std::replace(kind.begin(), kind.end(), char{3}, char{0});
          std::replace(kind.begin(), kind.end(), char{4}, char{0});
          std::replace(kind.begin(), kind.end(), char{5}, char{0});
          std::replace(kind.begin(), kind.end(), char{6}, char{0});
          rhs0 = rhs_plain;
          continue;
        }
        std::string where =
            e.dof() >= 0 && e.dof() < ne ? " (DOF '" + m.dof_name(as.dof_of(static_cast<int>(e.dof()))) + "')" : "";
        log.write("warning: no consistent initial derivatives" + where +
                  ": the run starts with zero initial accelerations on the free DOFs");
        for (int i = 0; i < ne; ++i) s.a(as.dof_of(i)) = 0;
        return {};
      }
    }
    refine_start(m, as, solver, s, rhs, stats, log, evaluate, kind, mvals, cvals, kvals, r_start, dabsi);
    viscous_rates(m, as, solver, s, stats, log, evaluate, kind, mvals, cvals);
    return kind;
  }
}

/// Warns (diagnostics log) about initial conditions that the first step
/// cannot keep: a displacement on an algebraic DOF (neither mass nor
/// viscosity: its displacement follows from its equation), a velocity on a DOF
/// without mass (replaced by the consistent velocity, or, on an algebraic DOF,
/// by the one of the first step). `kind` as returned by initial_derivatives.
template <class Model, class Assembler>
void warn_lost_initial_conditions(const Model& m, const Assembler& as, const std::vector<char>& kind,
                                  const std::vector<std::string>& set_u, const std::vector<std::string>& set_v,
                                  diagnostics& log) {
  if (kind.size() != static_cast<std::size_t>(as.equations())) return;
  for (int i = 0; i < as.equations(); ++i) {
    const auto d = static_cast<std::size_t>(as.dof_of(i));
    const char k = kind[static_cast<std::size_t>(i)];
    if (k == 0 && !set_u[d].empty())
      log.write("warning: the initial displacement set by '" + set_u[d] + "' on DOF '" +
                m.dof_name(static_cast<int>(d)) +
                "' is not kept: the DOF has neither mass nor viscosity, so its displacement follows from its "
                "equation");
    if (k != 1 && !set_v[d].empty())
      log.write("warning: the initial velocity set by '" + set_v[d] + "' on DOF '" + m.dof_name(static_cast<int>(d)) +
                "' is not kept: the DOF has no mass, so its velocity follows from its equation");
  }
}

}  // namespace pradis::detail
