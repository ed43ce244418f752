// The work-precision benchmark's peers (SUNDIALS IDA/CVODE, Boost.Odeint) integrate
// the manual's two-body system (Fig. 3.3, section 3.6.9) from equations written out
// by hand in bench/work_precision/two_bodies_problem.hpp. For the comparison to be
// honest those must be pradis's equations: at random states (u, v, a) the residual
// M a + g(u) and the stiffness dg/du must equal the residual and the K block that
// pradis assembles from its elements (MD, LINKD, F), to round-off.

#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/integrators/simulation.hpp"
#include "two_bodies_problem.hpp"

using namespace pradis;
namespace tb = wp::two_bodies;

TEST_CASE("bench two-body peer equations equal pradis's assembled residual and stiffness at random states") {
  tb::model_type m;
  std::vector<dof> d;
  tb::build(m, d);
  // One short stage runs NEWINT (LINKD stores L0 in W(1)) and leaves the link's
  // direction state at its initial direction.
  simulation sim(m, newmark{});
  sim.run({.end = 1e-4, .smax = 1e-4});

  std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
  prescribed[0] = 1;  // the ground
  assembler<tb::model_type> as;
  as.build(m, prescribed);
  REQUIRE(as.equations() == tb::n);
  std::vector<int> eq_of(static_cast<std::size_t>(m.dof_count()), -1);
  for (int e = 0; e < as.equations(); ++e) eq_of[static_cast<std::size_t>(as.dof_of(e))] = e;

  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> small(-0.3, 0.3), big(-20.0, 20.0);
  const std::vector<double> mass = tb::mass();
  global_state s;
  s.resize(m.dof_count());
  for (int trial = 0; trial < 20; ++trial) {
    for (int i = 0; i < tb::n; ++i) {
      const auto g = static_cast<Eigen::Index>(d[static_cast<std::size_t>(i)].index);
      s.u(g) = small(rng);  // the link keeps its direction within 0.3 m of the start (no reversal)
      s.v(g) = big(rng);
      s.a(g) = big(rng);
    }
    double u[tb::n], g[tb::n];
    for (int i = 0; i < tb::n; ++i) u[i] = s.u(d[static_cast<std::size_t>(i)].index);
    tb::forces(u, g);
    as.evaluate(m, s, {1.0, 0.0, 0.0}, call_info{0.0, 1e-3, 1, 0, true, nullptr});
    for (int i = 0; i < tb::n; ++i) {
      const auto gi = static_cast<Eigen::Index>(d[static_cast<std::size_t>(i)].index);
      const double peer = mass[static_cast<std::size_t>(i)] * s.a(gi) + g[i];
      CHECK(peer == doctest::Approx(as.residual()(gi)).epsilon(1e-12).scale(as.abs_sum()(gi)));
    }
    // K block (cu = 1, cv = ca = 0 gives J = K) against the peer's dg/du.
    Eigen::MatrixXd gu;
    tb::stiffness(u, gu);
    const auto& pat = as.pattern();
    const auto vals = as.values();
    for (int i = 0; i < tb::n; ++i)
      for (int j = 0; j < tb::n; ++j) {
        const int q = pat.find(eq_of[static_cast<std::size_t>(d[static_cast<std::size_t>(i)].index)],
                               eq_of[static_cast<std::size_t>(d[static_cast<std::size_t>(j)].index)]);
        const double assembled = q >= 0 ? vals[static_cast<std::size_t>(q)] : 0.0;
        CHECK(gu(i, j) == doctest::Approx(assembled).epsilon(1e-12).scale(tb::k));
      }
  }
}
