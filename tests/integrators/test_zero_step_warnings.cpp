// The warning paths of the zero step's Newton iterations (integrators/start_newton.hpp):
// refine_start, which iterates Newton with a line search on the viscous DOFs after the first
// solve of initial_derivatives (initialisation.hpp), and viscous_rates, which solves
// C_vv da_v = -dF_v/dt for the rates of the viscous DOFs. Each test drives a real run into
// one path with a small element whose viscous flow law provably gets there (the math is in
// the comments), and checks the warning in the log, the documented fallback state at t = 0
// and what the run does next.
// Sources of the expected values:
// - the warning texts: start_newton.hpp, refine_start's `warn` ("...on the initial
//   derivatives " + why + ": the first step starts from the best iterate") and
//   viscous_rates' singular branch ("no consistent rates ... (" + what + "): they start at 0");
// - the fallback states: the doc comments of refine_start (the best iterate; back to the
//   iterate before the step that cannot be halved into a decrease) and of viscous_rates
//   (rates at 0);
// - Newton on a root of f(w) = sign(w) |w|^n converges linearly, w_{k+1} = (1 - 1/n) w_k
//   (w - f / f' = w - w / n; Ortega and Rheinboldt, Iterative Solution of Nonlinear Equations
//   in Several Variables, 1970, 10.2, on roots where f' vanishes);
// - the error codes: core/error.hpp (131 singular_matrix, 140 newton_failure).
// Defaults used below (integrators/options.hpp, core/domain.hpp): DABSI = 0.1, and a DOF
// added without a domain has nominal potential 1 m/s and nominal flow 1 N, so the scaled
// residual of refine_start is |F| in N and its correction size |dv| / (1 + |v|).

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "dense_test_solver.hpp"
#include "zero_step_test_support.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using pradis_test::count_of;
using pradis_test::observed_run;
using pradis_test::run_outcome;

namespace {

/// A one-DOF viscous flow F = Law::f(v) with dF/dv = Law::dfdv(v) (ADR 2, IGN 3: only the C block).
template <class Law>
struct zsw_flow_t {
  static constexpr pradis::passport passport{.name = Law::name, .ext = 1, .par = 0, .adr = 2, .ign = 3};
  static constexpr element_help help{.title = "one-DOF viscous flow of a zero-step test",
                                     .name = "F = Law::f(v), dF/dv = Law::dfdv(v)",
                                     .field = "mechanics",
                                     .dofs = "1 - the DOF",
                                     .parameters = "none",
                                     .work = "none",
                                     .special = "none"};
  struct parameters {};
  parameters p;
  explicit zsw_flow_t(parameters q = {}) : p(q) {}
  static parameters example() { return {}; }
  static zsw_flow_t from_parameters(std::span<const double>) { return zsw_flow_t{}; }
  void evaluate(const local_input<zsw_flow_t>& in, local_output<zsw_flow_t>& out, element_context&) const {
    out.f(0) = Law::f(in.v(0));
    if (out.want_jacobian) out.C(0, 0) = Law::dfdv(in.v(0));
  }
};

/// Coulomb friction without regularisation (sign(0) = 0) under a push P: F = c v + R sign(v) - P.
/// R = 3 P: the friction holds the push, and F has no root (F(0) = -P, F(v > 0) >= R - P).
struct zsw_coulomb {
  static constexpr std::string_view name = "ZSWCOUL";
  static constexpr double c = 1, r = 3, push = 1;
  static double f(double v) { return c * v + r * ((v > 0) - (v < 0)) - push; }
  static double dfdv(double) { return c; }
};

/// Drag of a massless float in a stream of speed vs: F = c sign(w) |w|^n, w = v - vs. The slope
/// vanishes at the root w = 0, so Newton converges only linearly, at the rate q = 1 - 1/n.
struct zsw_drag {
  static constexpr std::string_view name = "ZSWDRAG";
  static constexpr double c = 1, n = 1.96, vs = 5;
  static double f(double v) { return c * (v < vs ? -1 : 1) * std::pow(std::abs(v - vs), n); }
  static double dfdv(double v) { return c * n * std::pow(std::abs(v - vs), n - 1); }
};

/// A friction characteristic with a falling (Stribeck-like) branch: F = v^3 - 3 v + 3 [N, v in
/// m/s]; dF/dv = 3 v^2 - 3 vanishes at v = 1. Its one real root is v = -2.1038 (Cardano).
struct zsw_stribeck {
  static constexpr std::string_view name = "ZSWSTRIB";
  static double f(double v) { return v * v * v - 3 * v + 3; }
  static double dfdv(double v) { return 3 * v * v - 3; }
};

/// Three viscous DOFs a, b, w (no mass on their diagonals) with a rank-1 C block on (a, b):
///   F_a = v_a + v_b + v_w - Pa,  F_b = v_a + v_b + 2 v_w - Pb,  F_w = v_a + v_w + m a_a.
/// The zero step's matrix (start_matrix: C in the viscous columns) is [[1,1,1],[1,1,2],[1,0,1]],
/// det = 1, so the first solve is exact and refine_start stops at once. viscous_rates then takes
/// only the rows without an inertia entry (a and b; row w holds M_wa = m) and their columns:
/// C_vv = [[1,1],[1,1]], singular.
template <class = void>
struct zsw_block_t {
  static constexpr pradis::passport passport{.name = "ZSWBLOCK", .ext = 3, .par = 0, .adr = 2, .ign = 0};
  static constexpr element_help help{.title = "viscous block of rank 1 on two DOFs",
                                     .name = "see the test",
                                     .field = "mechanics",
                                     .dofs = "1 - a\n2 - b\n3 - w",
                                     .parameters = "none",
                                     .work = "none",
                                     .special = "none"};
  static constexpr double pa = 1, pb = 3, mass = 0.5;
  struct parameters {};
  parameters p;
  explicit zsw_block_t(parameters q = {}) : p(q) {}
  static parameters example() { return {}; }
  static zsw_block_t from_parameters(std::span<const double>) { return zsw_block_t{}; }
  void evaluate(const local_input<zsw_block_t>& in, local_output<zsw_block_t>& out, element_context&) const {
    out.f(0) = in.v(0) + in.v(1) + in.v(2) - pa;
    out.f(1) = in.v(0) + in.v(1) + 2 * in.v(2) - pb;
    out.f(2) = in.v(0) + in.v(2) + mass * in.a(0);
    if (!out.want_jacobian) return;
    out.C(0, 0) = out.C(0, 1) = out.C(0, 2) = 1;
    out.C(1, 0) = out.C(1, 1) = 1;
    out.C(1, 2) = 2;
    out.C(2, 0) = out.C(2, 2) = 1;
    out.M(2, 0) = mass;
  }
};
using zsw_block = zsw_block_t<>;

/// A user's solver for diagonal matrices, x_i = b_i / A_ii, with no check at all: on a zero
/// pivot it returns what IEEE division gives (+-inf, or NaN for 0 / 0).
struct zsw_diagonal_solver {
  void analyze(const linalg::sparsity_pattern& p) { pattern = p; }
  void factorize(std::span<const double> values) {
    diag.assign(static_cast<std::size_t>(pattern.n), 0.0);
    for (int i = 0; i < pattern.n; ++i)
      if (const int q = pattern.find(i, i); q >= 0) diag[static_cast<std::size_t>(i)] = values[static_cast<std::size_t>(q)];
  }
  void solve(std::span<double> b) const {
    for (std::size_t i = 0; i < b.size(); ++i) b[i] /= diag[i];
  }
  linalg::sparsity_pattern pattern;
  std::vector<double> diag;
};

/// A run of one zsw_flow_t<Law> on one DOF, with the one-step (Newmark) or the BDF driver.
template <class Law, bool Bdf, class Solver = linalg::sparse_lu<linalg::automatic_ordering>>
run_outcome zsw_law_run(const run_options& o) {
  using E = zsw_flow_t<Law>;
  model<E> md;
  const dof v = md.add_dof("v");
  md.template add<E>("law", {}, v);
  if constexpr (Bdf) return observed_run<bdf_simulation<model<E>, Solver>>(md, {v}, o);
  else return observed_run<simulation<model<E>, newmark, Solver>>(md, {v}, o);
}

/// refine_start's warning (start_newton.hpp, the `warn` lambda).
std::string zsw_refine_warning(const std::string& why) {
  return "warning: the zero step's Newton iterations on the initial derivatives " + why +
         ": the first step starts from the best iterate";
}
/// viscous_rates' warning on a singular C_vv (start_newton.hpp), around the solver's message.
const std::string zsw_rates_head =
    "warning: no consistent rates of the viscous DOFs at the zero step (pradis error 131";
const std::string zsw_rates_tail = "): they start at 0";

const run_options zsw_short{.end = 1e-2, .smax = 1e-3};

}  // namespace

TEST_SUITE("integrators/zero step warnings") {
  TEST_CASE("refine_start: no step lowers the flow residual (Coulomb friction holding a push)") {
    // From v = 0: F(0) = -P, the first solve's correction is z = P / c = 1. Along it,
    // F(t z) = t P + R - P >= 2 P for every t in (0, 1] (R = 3 P), above |F(0)| = P = 1 and
    // DABSI = 0.1, so all 40 halvings (down to t = 2^-40) fail: back to v = 0, a warning.
    // F has no root, so the first step fails in Newton (code 140) at t = 0.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      const run_outcome r =
          bdf ? zsw_law_run<zsw_coulomb, true>(zsw_short) : zsw_law_run<zsw_coulomb, false>(zsw_short);
      CAPTURE(r.log);
      CHECK(count_of(r.log, zsw_refine_warning("found no step that lowers the flow residual")) == 1);
      REQUIRE(r.v0.size() == 1);
      CHECK(r.v0[0] == 0.0);  // the iterate before the step: the start
      CHECK(r.a0[0] == 0.0);  // viscous_rates: F does not change along the motion (v0 = a0 = 0)
      CHECK(r.failed);
      CHECK(r.code == error_code::newton_failure);
      CHECK(r.what.find("Newton does not converge at SMIN") != std::string::npos);
      CHECK(r.t_end == 0.0);
      CHECK(r.v_end[0] == 0.0);
    }
  }

  TEST_CASE("refine_start: 30 iterations at Newton's linear rate on a root where dF/dv = 0 (drag in a stream)") {
    // Error e = vs - v, e0 = 5 from v = 0; each Newton step multiplies it by q = 1 - 1/n =
    // 0.4898 (exactly, for a pure power law), so each correction is q times the one before
    // (the size test "shrank by less than half" never fires: q < 1/2, and |v| grows, so the
    // relative size shrinks even faster) and |F| falls by q^n each time (no halving). The
    // correction of iteration k (0-based) is e0 q^(k+1) (1 - q) / (1 + |v|) >= 5 q^30 0.51 / 6
    // = 2.1e-10 > 1e-10 for k <= 29, so the loop reaches it == 30 and warns. The start is the
    // last iterate: 1 solve in initial_derivatives + 30 in refine_start, e = e0 q^31 = 1.23e-9.
    // The run then completes at the stream speed: v = vs, u = vs t.
    // (The BDF driver is left out: it fails with code 140 on this law even when the zero step
    // converges without a warning, e.g. for n = 1.5: the Newton matrix c n |w|^(n-1) vanishes at
    // the root, which the zero step does not cause.)
    const run_outcome r = zsw_law_run<zsw_drag, false>(zsw_short);
    CAPTURE(r.log);
    CHECK(count_of(r.log, zsw_refine_warning("did not converge in 30 iterations")) == 1);
    CHECK(r.log.find("stopped converging") == std::string::npos);
    const double q = 1 - 1 / zsw_drag::n;
    REQUIRE(r.v0.size() == 1);
    CHECK(zsw_drag::vs - r.v0[0] == doctest::Approx(zsw_drag::vs * std::pow(q, 31)).epsilon(1e-6));  // 1.2287e-9
    CHECK(r.a0[0] == 0.0);  // F depends on v only and a = 0 along the motion: dF/dt = 0
    CHECK_FALSE(r.failed);
    CHECK(r.t_end == doctest::Approx(zsw_short.end).epsilon(1e-12));
    CHECK(r.v_end[0] == doctest::Approx(zsw_drag::vs).epsilon(1e-9));                  // measured 5 - 3e-11
    CHECK(r.u_end[0] == doctest::Approx(zsw_drag::vs * zsw_short.end).epsilon(1e-9));  // measured 0.05 - 6e-13
  }

  TEST_CASE("refine_start and viscous_rates: a singular matrix at the best iterate (friction with a falling branch)") {
    // From v = 0: F(0) = 3, dF/dv(0) = -3, so the first correction is z = 1 (exact in binary):
    // v = 1, where |F| = 1 < 3 is accepted and dF/dv = 3 - 3 = 0 exactly. refine_start's 1x1
    // matrix is [0]: sparse_lu throws singular_matrix, refine_start warns and keeps v = 1 (the
    // best iterate). viscous_rates gets the same C_vv = [0]: its warning, the rate stays 0.
    // The first step's Newton matrix at v = 1 is a multiple of dF/dv(1) = 0 too, at every step
    // size, so the run ends at t = 0 with code 131 (the root v = -2.10 is never approached).
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      const run_outcome r =
          bdf ? zsw_law_run<zsw_stribeck, true>(zsw_short) : zsw_law_run<zsw_stribeck, false>(zsw_short);
      CAPTURE(r.log);
      // refine_start's warning around sparse_lu's message (the `warn` lambda, "met a singular matrix (" + what + ")").
      const std::size_t path3 = r.log.find(
          "warning: the zero step's Newton iterations on the initial derivatives met a singular matrix "
          "(pradis error 131");
      CHECK(path3 != std::string::npos);
      CHECK(r.log.find("): the first step starts from the best iterate", path3) != std::string::npos);
      CHECK(count_of(r.log, "the first step starts from the best iterate") == 1);
      const std::size_t path5 = r.log.find(zsw_rates_head);
      CHECK(path5 != std::string::npos);
      CHECK(path5 > path3);  // refine_start runs first (initial_derivatives)
      CHECK(r.log.find(zsw_rates_tail, path5) != std::string::npos);
      REQUIRE(r.v0.size() == 1);
      CHECK(r.v0[0] == 1.0);
      CHECK(r.a0[0] == 0.0);
      CHECK(r.failed);
      CHECK(r.code == error_code::singular_matrix);
      CHECK(r.what.find("the Newton matrix is singular at DOF 'v'") != std::string::npos);
      CHECK(r.t_end == 0.0);
      CHECK(r.v_end[0] == 1.0);
    }
  }

  TEST_CASE("refine_start: a non-finite correction from a user solver that does not check its result") {
    // The law of the previous test, solved by a user LinearSolver (dense_test_solver: Eigen's
    // PartialPivLU, no singularity or finiteness checks). At v = 1 it factorises [0] without
    // complaint and solves 0 z = -F(1) = -1 as z = -1 / 0 = -inf: refine_start's size test sees
    // a non-finite correction, warns and keeps v = 1. (With sparse_lu this path cannot be
    // reached: its solve() throws singular_matrix for a non-finite solution component, see the
    // previous test, and the assembler turns a non-finite flow or Jacobian entry into an error,
    // which refine_start takes as a refused trial state.) viscous_rates then solves C_vv a = 0 with
    // C_vv = 0: Eigen's LU returns 0 there, so the rate stays 0 without a warning. The first step's Newton gets no finite correction at
    // v = 1 either: code 140 at t = 0.
    using dense = pradis_test::dense_test_solver<>;
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      const run_outcome r =
          bdf ? zsw_law_run<zsw_stribeck, true, dense>(zsw_short) : zsw_law_run<zsw_stribeck, false, dense>(zsw_short);
      CAPTURE(r.log);
      CHECK(count_of(r.log, zsw_refine_warning("met a non-finite correction")) == 1);
      REQUIRE(r.v0.size() == 1);
      CHECK(r.v0[0] == 1.0);
      CHECK(r.a0[0] == 0.0);
      CHECK(r.failed);
      CHECK(r.code == error_code::newton_failure);
      CHECK(r.t_end == 0.0);
      CHECK(r.v_end[0] == 1.0);
    }
  }

  TEST_CASE("viscous_rates: a singular C_vv after a converged zero step; the rates start at 0 and the run goes on") {
    // zsw_block: the first solve gives v_w = Pb - Pa = 2, v_a = -v_w = -2 (row w with a_a = 0),
    // v_b = Pa - v_a - v_w = 1; refine_start's next correction is 0 (linear flows), no warning.
    // viscous_rates: C_vv = [[1,1],[1,1]] on (a, b) is singular, so the warning and rates 0. They
    // are also the exact rates: the rows give v_a + v_b = Pa - v_w and v_w = Pb - Pa for all t,
    // and row w the ODE m v_a' = -(v_a + v_w), at rest from v_a = -v_w. So the run completes
    // with the velocities constant and u = v t.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      model<zsw_block> md;
      const dof a = md.add_dof("a"), b = md.add_dof("b"), w = md.add_dof("w");
      md.add<zsw_block>("block", {}, a, b, w);
      const run_outcome r = bdf ? observed_run<bdf_simulation<model<zsw_block>>>(md, {a, b, w}, zsw_short)
                                : observed_run<simulation<model<zsw_block>>>(md, {a, b, w}, zsw_short);
      CAPTURE(r.log);
      CHECK(count_of(r.log, zsw_rates_head) == 1);
      CHECK(r.log.find(zsw_rates_tail) != std::string::npos);
      CHECK(r.log.find("Newton iterations on the initial derivatives") == std::string::npos);
      CHECK_FALSE(r.failed);
      CHECK(r.t_end == doctest::Approx(zsw_short.end).epsilon(1e-12));
      const double pa = zsw_block::pa, pb = zsw_block::pb;
      const double v[3] = {pa - pb, pa, pb - pa};  // a, b, w
      REQUIRE(r.v0.size() == 3);
      for (std::size_t i = 0; i < 3; ++i) {
        CAPTURE(i);
        CHECK(r.v0[i] == doctest::Approx(v[i]).epsilon(1e-14));
        CHECK(r.a0[i] == 0.0);
        CHECK(r.v_end[i] == doctest::Approx(v[i]).epsilon(1e-12));
        CHECK(r.u_end[i] == doctest::Approx(v[i] * zsw_short.end).epsilon(1e-12));
      }
    }
  }

  TEST_CASE("viscous_rates: a user solver that returns NaN for the rates: a warning and rates of 0") {
    // The cubic law of the two tests above with zsw_diagonal_solver: refine_start's correction at
    // v = 1 is -F / F' = -1 / 0 = -inf (its warning, v stays 1), and viscous_rates' solve of
    // C_vv a = -dF/dt there is 0 / 0 = NaN (F does not change along the motion at rest): the rates
    // would not be finite, so they start at 0 with a warning instead of a NaN state.
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      const run_outcome r = bdf ? zsw_law_run<zsw_stribeck, true, zsw_diagonal_solver>(zsw_short)
                                : zsw_law_run<zsw_stribeck, false, zsw_diagonal_solver>(zsw_short);
      CAPTURE(r.log);
      CHECK(count_of(r.log, zsw_refine_warning("met a non-finite correction")) == 1);
      CHECK(count_of(r.log, "warning: no consistent rates of the viscous DOFs at the zero step (their solve is not "
                             "finite): they start at 0") == 1);
      REQUIRE(r.v0.size() == 1);
      CHECK(r.v0[0] == 1.0);
      CHECK(r.a0[0] == 0.0);
      CHECK(r.failed);
      CHECK(r.t_end == 0.0);
    }
  }
}
