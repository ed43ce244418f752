// Newton on a very stiff element with tight tolerances: a pendulum on a LINKD of
// k = 1e12 (omega h = 1e3 at h = 1e-3). The element computes its force from the
// absolute positions X0 + u, whose round-off eps |X0 + u| becomes a force k eps
// ~ 2e-4 N that no velocity correction within the tolerance removes, far above
// DABSI = 1e-6. Newton must recognise that floor (the unknowns passed the
// correction test twice and the corrections stalled) instead of failing: before,
// the run cut its steps again and again: 2.4 million steps for 2 s.

#include <doctest/doctest.h>

#include <cmath>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
using pendulum_model = model<point_mass, planar_link, planar_rigid_link, constant_force>;

struct stiff_pendulum_run {
  run_statistics stats;
  double x = 0, y = 0;
};

// Mass 1 on a link of length 1 from the origin, released from the horizontal;
// k > 0: LINKD of stiffness k, k = 0: the exact LINKX. HHT alpha = -0.1, fixed h.
stiff_pendulum_run pendulum(double k, double h, double end) {
  pendulum_model m;
  const dof x = m.add_dof("x"), y = m.add_dof("y");
  m.add<point_mass>("mx", {1.0}, x);
  m.add<point_mass>("my", {1.0}, y);
  if (k > 0)
    m.add<planar_link>("rod", {0.0, 0.0, 1.0, 0.0, k}, m.ground(), m.ground(), x, y);
  else
    m.add<planar_rigid_link>("rod", {0.0, 0.0, 1.0, 0.0}, m.ground(), m.ground(), x, y);
  m.add<constant_force>("weight", {-9.81}, y);
  simulation<pendulum_model, alpha_family> sim(m, alpha_family(hht{-0.1}));
  run_options o{.end = end, .smax = h};
  o.newton = {.dabsu = 1e-10, .drltu = 1e-10, .dabsi = 1e-6, .drlti = 1e-12, .itr = 8};
  stiff_pendulum_run out;
  out.stats = sim.run(o);
  out.x = sim.u(x);
  out.y = sim.u(y);
  return out;
}
}  // namespace

TEST_SUITE("integrators/newton on stiff elements") {
  TEST_CASE("a 1e12 penalty link with tight Newton tolerances runs at its fixed step without cuts") {
    const stiff_pendulum_run stiff = pendulum(1e12, 1e-3, 0.5), exact = pendulum(0, 1e-3, 0.5);
    CHECK(stiff.stats.steps == 500);
    CHECK(stiff.stats.rejected_steps == 0);
    // At most ITR iterations per step (measured: about 3).
    CHECK(stiff.stats.newton_iterations <= 8 * 500);
    // The same motion as the exact link to the penalty's compliance (m g / k ~ 1e-11)
    // and the Newton tolerance.
    CHECK(std::abs(stiff.x - exact.x) < 1e-8);
    CHECK(std::abs(stiff.y - exact.y) < 1e-8);
  }
}
