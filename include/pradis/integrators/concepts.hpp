#pragma once
/// \file
/// What the simulation needs from an integration scheme (Integrator) and from
/// a linear solver (LinearSolver): exactly the members the driver calls, so a
/// user's own type that satisfies the concept can be passed to
/// pradis::simulation<Model, Scheme, Solver>.

#include <concepts>
#include <span>
#include <string_view>

#include "pradis/assembly/assembler.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis {

/// A one-step scheme with the velocity v as the Newton unknown. Per DOF, with
/// u0, v0, a0, p0 the state at t_n (p: a pseudo-acceleration the scheme may use
/// as it likes; it starts equal to a and is saved in checkpoints) and h the step:
/// - `S::name`: a name for messages;
/// - `s.coefficients(h)`: the factors {du/dv, 1, da/dv} of the Newton matrix
///   J = cu K + cv C + ca M;
/// - `s.predict(u0, v0, a0, p0, h)`: the predicted velocity at t_n + h;
/// - `s.complete(u0, v0, a0, p0, h, v, u, a, p)`: u, a and p at t_n + h that
///   follow from the velocity v.
/// Optional: `s.coefficients_set()` returning alpha_parameters selects the
/// Newmark-family local error estimate of the error control (otherwise the
/// predictor-based first-order estimate is used); `s.label()` a run-time name
/// for messages (otherwise S::name).
template <class S>
concept Integrator = std::copyable<S> && requires(const S s, double x, double& r) {
  { S::name } -> std::convertible_to<std::string_view>;
  { s.coefficients(x) } -> std::same_as<jacobian_coefficients>;
  { s.predict(x, x, x, x, x) } -> std::same_as<double>;
  s.complete(x, x, x, x, x, x, r, r, r);
};

/// A sparse linear solver for the Newton matrix in the assembler's CSR pattern:
/// - `analyze(pattern)`: symbolic analysis, once per topology (may throw
///   pradis::error with code structurally_singular and the equation as dof());
/// - `factorize(values)`: numeric factorisation of the values in pattern order
///   (throws pradis::error with code singular_matrix and the equation as dof());
/// - `solve(b)`: overwrites b with the solution, using the last factorisation.
/// The simulation keeps a factorisation across solves (modified Newton), so
/// solve() must not disturb it. Optional: `solve(b1, b2)` for two right-hand
/// sides at once (the BDF driver's stabilised constraints need two per
/// iteration; without it, it calls solve() twice), and `solve_unchecked(b)` /
/// `solve_unchecked(b1, b2)`, which the BDF corrector prefers: solves whose
/// residual the solver need not check, because Newton's test judges them
/// (sparse_lu::solve_unchecked).
template <class S>
concept LinearSolver = std::default_initializable<S> && std::movable<S> &&
                       requires(S s, const S cs, const linalg::sparsity_pattern& p, std::span<const double> values,
                                std::span<double> b) {
                         s.analyze(p);
                         s.factorize(values);
                         cs.solve(b);
                       };

}  // namespace pradis
