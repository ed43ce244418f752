// The scheme and solver concepts state what the simulation uses: a scheme
// written by a user (not derived from the library's alpha family) and a user's
// dense linear solver run a simulation; the runtime-selectable alpha family
// switches scheme between stages exactly as a checkpoint-and-reload with the
// new scheme does.
//
// Reference: the trapezoidal rule (average acceleration) on m u'' + k u = 0 has
// the exact discrete solution u_n = u0 cos(n theta), tan(theta / 2) = Omega / 2,
// Omega = w h (Hughes, The Finite Element Method, Dover 2000, section 9.3).

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <span>
#include <sstream>
#include <vector>

#include "dense_test_solver.hpp"
#include "integrator_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_test::tight_newton;

namespace {

/// A user's trapezoidal rule with the velocity as the Newton unknown, written
/// from its definition: v = v0 + h (a0 + a) / 2, u = u0 + h (v0 + v) / 2.
struct user_trapezoidal {
  static constexpr std::string_view name = "TRAPEZ";
  jacobian_coefficients coefficients(double h) const { return {h / 2, 1.0, 2 / h}; }
  double predict(double, double v0, double a0, double, double h) const { return v0 + h * a0; }
  void complete(double u0, double v0, double a0, double, double h, double v, double& u, double& a, double& p) const {
    a = 2 * (v - v0) / h - a0;
    u = u0 + 0.5 * h * (v0 + v);
    p = a;
  }
};
static_assert(Integrator<user_trapezoidal>);
static_assert(!AlphaFamilyIntegrator<user_trapezoidal>);
static_assert(Integrator<alpha_family> && AlphaFamilyIntegrator<alpha_family>);

/// A user's dense LU solver for small models: CSR values into a dense matrix.
using user_dense_lu = pradis_test::dense_test_solver<>;
struct no_solve {
  void analyze(const linalg::sparsity_pattern&) {}
  void factorize(std::span<const double>) {}
};
static_assert(LinearSolver<user_dense_lu>);
static_assert(LinearSolver<linalg::sparse_lu<linalg::automatic_ordering>>);
static_assert(!LinearSolver<no_solve>);
static_assert(!LinearSolver<int>);

using user_osc_model = model<point_mass, linear_spring, linear_damper, initial_displacement, initial_velocity, sine_force>;

/// Two masses on springs (a chain to the ground), damped, one of them shaken.
void build_chain(user_osc_model& m) {
  const auto d = m.add_dofs(2, "x");
  m.add<point_mass>("m1", {1.0}, d[0]);
  m.add<point_mass>("m2", {2.0}, d[1]);
  m.add<linear_spring>("k1", {400.0}, d[0], m.ground());
  m.add<linear_spring>("k2", {900.0}, d[0], d[1]);
  m.add<linear_damper>("c2", {0.5}, d[0], d[1]);
  m.add<initial_displacement>("x0", {0.1}, d[0]);
  m.add<sine_force>("shake", {.amplitude = 5, .frequency = 2, .phase_deg = 0, .offset = 0}, d[1]);
}

run_options user_stage(double end, double h = 1e-3) { return {.end = end, .smax = h, .newton = tight_newton()}; }

/// Bit-for-bit equality of two final states.
bool same_state(const global_state& a, const global_state& b) {
  return a.u == b.u && a.v == b.v && a.a == b.a && a.p == b.p;
}

}  // namespace

TEST_SUITE("integrators/user types") {
  TEST_CASE("a user-written trapezoidal scheme follows the exact discrete solution of the trapezoidal rule") {
    const double w = 10.0, h = 0.02, u0 = 0.3;
    user_osc_model m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("spring", {w * w}, x, m.ground());
    m.add<initial_displacement>("x0", {u0}, x);
    simulation sim(m, user_trapezoidal{});
    const double theta = 2 * std::atan(w * h / 2);
    double worst = 0;
    int rows = 0;
    sim.on_output([&](const auto& s) {
      const double n = std::round(s.time() / h);
      worst = std::max(worst, std::abs(s.u(x) - u0 * std::cos(n * theta)));
      ++rows;
    });
    sim.run(user_stage(2.0, h));
    CHECK(rows == 101);
    CHECK(worst < 1e-9);
    // The same numbers as the library's average-acceleration Newmark (up to round-off).
    user_osc_model m2;
    const dof x2 = m2.add_dof("x");
    m2.add<point_mass>("mass", {1.0}, x2);
    m2.add<linear_spring>("spring", {w * w}, x2, m2.ground());
    m2.add<initial_displacement>("x0", {u0}, x2);
    simulation ref(m2, newmark{});
    ref.run(user_stage(2.0, h));
    CHECK(sim.u(x) == doctest::Approx(ref.u(x2)).epsilon(1e-10));
  }

  TEST_CASE("a user scheme outside the alpha family runs with error control (first-order error estimate)") {
    user_osc_model m;
    build_chain(m);
    simulation sim(m, user_trapezoidal{});
    run_options o = user_stage(0.5, 1e-2);
    o.error_control = true;
    o.dabsx = 1e-6;
    o.drltx = 1e-6;
    sim.run(o);
    CHECK(sim.time() == 0.5);
    CHECK(sim.statistics().steps > 50);  // the tolerance forces steps below SMAX
    // The error-controlled result is close to a fine fixed-step one of the same scheme.
    user_osc_model m2;
    build_chain(m2);
    simulation fine(m2, user_trapezoidal{});
    fine.run(user_stage(0.5, 1e-4));
    for (int d = 1; d <= 2; ++d) CHECK(std::abs(sim.state().u(d) - fine.state().u(d)) < 1e-4);
  }

  TEST_CASE("a user's dense linear solver gives the results of the sparse LU") {
    user_osc_model a, b;
    build_chain(a);
    build_chain(b);
    simulation<user_osc_model, newmark, user_dense_lu> sa(a);
    simulation sb(b, newmark{});
    sa.run(user_stage(0.3));
    sb.run(user_stage(0.3));
    CHECK(sa.solver().factorizations > 0);
    for (int d = 1; d <= 2; ++d) {
      CHECK(sa.state().u(d) == doctest::Approx(sb.state().u(d)).epsilon(1e-10));
      CHECK(sa.state().v(d) == doctest::Approx(sb.state().v(d)).epsilon(1e-10));
    }
  }

  TEST_CASE("alpha_family computes what the scheme it was made from computes, bit for bit") {
    user_osc_model a, b;
    build_chain(a);
    build_chain(b);
    simulation<user_osc_model, alpha_family> sa(a, hht(-0.2));
    simulation sb(b, hht(-0.2));
    sa.run(user_stage(0.3));
    sb.run(user_stage(0.3));
    CHECK(same_state(sa.state(), sb.state()));
    CHECK(sa.scheme().label() == "HHT");
    // Option messages carry the name of the scheme in use.
    CHECK_THROWS_WITH_AS(sa.run({.end = 1.0, .smax = -1}), doctest::Contains("HHT: SMAX"), error);
  }

  TEST_CASE("set_scheme between stages equals a checkpoint reloaded into a simulation with the new scheme") {
    user_osc_model a, b;
    build_chain(a);
    build_chain(b);
    simulation<user_osc_model, alpha_family> sa(a, newmark{});
    sa.run(user_stage(0.25));
    std::stringstream cp;
    sa.save_checkpoint(cp);
    sa.set_scheme(generalized_alpha(0.5));
    CHECK(sa.scheme().label() == "GALPHA");
    sa.run(user_stage(0.5));

    simulation<user_osc_model, alpha_family> sb(b, generalized_alpha(0.5));
    sb.load_checkpoint(cp);
    sb.restart_scheme();
    sb.run(user_stage(0.5));
    CHECK(sa.time() == sb.time());
    CHECK(sa.statistics().steps == sb.statistics().steps);
    CHECK(same_state(sa.state(), sb.state()));
    // The switch took effect: the Newmark run to 0.5 differs.
    user_osc_model c;
    build_chain(c);
    simulation sc(c, newmark{});
    sc.run(user_stage(0.25));
    sc.run(user_stage(0.5));
    CHECK_FALSE(same_state(sa.state(), sc.state()));
  }
}
