#pragma once
// The benchmark scene: a planar chain of N bodies and springs, and the fixtures
// that time one Newton iteration and one integration step on it.
//
// Scene: N MD bodies (m = 1 kg, J = 0.1 kg m^2) on the X axis at x = 0, 1, ..., N-1;
// body i and body i+1 joined by a LINKD (k = 1e4 N/m); body 0 held by two LINKD
// to the ground, one along X (from the ground point (-1, 0)) and one along Y
// (from (0, -1)); a constant force F = 1 N on the Y DOF of the last body.
// LINKD acts on translations only and the scene's type list has no rotational
// spring, so every rotation DOF, body 0's included, carries inertia only (it is
// still an equation of the Newton matrix, regular through its J / (gamma h) term).
// Equations (free DOFs): 3 N.

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/model/model.hpp"

namespace pradis_bench {

/// The model type that lists only the element types the chain uses.
using chain_model = pradis::model<pradis::elements::planar_inertia, pradis::elements::planar_link,
                                  pradis::elements::constant_force>;

inline constexpr double body_mass = 1.0;
inline constexpr double body_inertia = 0.1;
inline constexpr double link_stiffness = 1e4;
inline constexpr double tip_force = 1.0;
/// Step of the integration benchmarks and of the Jacobian coefficients (Newmark, average acceleration).
inline constexpr double step = 1e-3;

struct chain_info {
  int bodies = 0;
  pradis::dof tip_y{};
};

/// Builds the chain of `n` bodies into an empty model of type M (chain_model or library_model).
template <class M>
chain_info build_chain(M& m, int n) {
  using pradis::elements::constant_force;
  using pradis::elements::planar_inertia;
  using pradis::elements::planar_link;
  if (n < 1) throw std::invalid_argument("build_chain: need at least one body");
  const pradis::dof g = M::ground();
  std::vector<pradis::dof> x(static_cast<std::size_t>(n)), y(x.size()), r(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::string b = "b" + std::to_string(i + 1);
    x[i] = m.add_dof(b + ".x");
    y[i] = m.add_dof(b + ".y");
    r[i] = m.add_dof(b + ".r");
    m.template add<planar_inertia>("md" + std::to_string(i + 1), {body_mass, body_inertia}, x[i], y[i], r[i]);
  }
  m.template add<planar_link>("ground.x", {-1.0, 0.0, 0.0, 0.0, link_stiffness}, g, g, x[0], y[0]);
  m.template add<planar_link>("ground.y", {0.0, -1.0, 0.0, 0.0, link_stiffness}, g, g, x[0], y[0]);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double xa = static_cast<double>(i);
    m.template add<planar_link>("link" + std::to_string(i + 1), {xa, 0.0, xa + 1.0, 0.0, link_stiffness}, x[i],
                                y[i], x[i + 1], y[i + 1]);
  }
  m.template add<constant_force>("force", {tip_force}, y.back());
  return {n, y.back()};
}

/// Runs every instance's NEWINT hook (LINKD stores its initial length in W(1)),
/// as the simulation does at the start of a stage.
template <class M>
void new_integration(M& m) {
  m.for_each_instances([&](auto& vec) {
    for (auto& in : vec) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (pradis::HasNewIntegration<E>) {
        pradis::element_context ctx(E::passport.name, in.name);
        pradis::assembler<M>::bind(m, in, ctx);
        ctx.newint = true;
        in.element.new_integration(ctx);
      }
    }
  });
}

/// One Newton iteration on a built chain, with the kernel's own parts used
/// directly: assembler::evaluate (flows + Jacobian), right-hand side, sparse LU
/// factorize + solve. The state is fixed (a small deterministic perturbation of
/// the rest state), so every call does the same work.
template <class M>
struct newton_fixture {
  M model;
  pradis::assembler<M> assembler;
  pradis::linalg::sparse_lu<pradis::linalg::min_degree_ordering> lu;
  pradis::global_state state;
  pradis::jacobian_coefficients coefficients;
  pradis::call_info info;
  std::vector<double> rhs;

  explicit newton_fixture(int n) {
    build_chain(model, n);
    new_integration(model);
    std::vector<char> prescribed(static_cast<std::size_t>(model.dof_count()), 0);
    prescribed[0] = 1;  // the ground
    assembler.build(model, prescribed);
    lu.analyze(assembler.pattern());
    state.resize(model.dof_count());
    for (int d = 1; d < model.dof_count(); ++d) {  // DOF 0, the ground, stays at zero
      const double w = 0.37 * d;
      state.u(d) = 1e-3 * std::sin(w);
      state.v(d) = 1e-2 * std::cos(w);
      state.a(d) = 1e-1 * std::sin(2 * w);
    }
    coefficients = pradis::newmark{}.coefficients(step);
    info.time = 0.5;
    info.step = step;
    info.nstep = 1;
    info.want_jacobian = true;
    rhs.assign(static_cast<std::size_t>(assembler.equations()), 0.0);
  }

  int equations() const { return assembler.equations(); }

  void iterate() {
    assembler.evaluate(model, state, coefficients, info);
    const auto& res = assembler.residual();
    const int ne = assembler.equations();
    for (int i = 0; i < ne; ++i) rhs[static_cast<std::size_t>(i)] = -res(assembler.dof_of(i));
    lu.factorize(assembler.values());
    lu.solve(rhs);
  }
};

/// A simulation of the chain that has done its zero step and first step.
template <class M>
struct sim_fixture {
  M model;
  pradis::simulation<M> sim;

  explicit sim_fixture(int n) : model(), sim(model) {
    build_chain(model, n);
    sim.run({.end = step, .smax = step});
  }
  int equations() const { return sim.get_assembler().equations(); }
  /// Integrates `steps` nominal steps in one call of run() (one stage).
  pradis::run_statistics advance(int steps) {
    return sim.run({.end = sim.time() + steps * step, .smax = step});
  }
};

}  // namespace pradis_bench
