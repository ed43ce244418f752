// The manual's two-body system (Fig. 3.3, section 3.6.9), as in examples/two_bodies,
// checked against invariants that hold exactly for it:
// - the only external force is P on body 2's Y DOF, so the centre of mass moves
//   with constant acceleration: Y_c(t) = -P t^2 / (2 (m1 + m2)), X_c(t) = 0
//   (Newton's second law for the system); the Stoermer and Newmark formulas
//   integrate a constant acceleration exactly, so this holds to round-off;
// - the link force is central, so the angular momentum of the two points about
//   the centre of mass changes only through the external force's moment, and
//   the bodies' own rotations (J eps = 0, no moment acts) stay at rest.

#include <doctest/doctest.h>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {
template <class Scheme>
void check_two_bodies(Scheme scheme) {
  model<planar_inertia, planar_link, constant_force> m;
  const auto d = m.add_dofs(6, "DOF ");
  m.add<planar_inertia>("Body 1", {.m = 1.0, .j = 0.1}, d[0], d[1], d[2]);
  m.add<planar_inertia>("Body 2", {.m = 2.0, .j = 0.1}, d[3], d[4], d[5]);
  m.add<planar_link>("Connection", {1, 1, 2, 2, 5e3}, d[0], d[1], d[3], d[4]);
  m.add<constant_force>("Force", {.force = -1e3}, d[4]);
  simulation sim(m, scheme);
  double worst_y = 0, worst_x = 0, worst_rot = 0;
  sim.on_output([&](const auto& s) {
    const double t = s.time();
    const double yc = (1.0 * s.u(d[1]) + 2.0 * s.u(d[4])) / 3.0;
    const double xc = (1.0 * s.u(d[0]) + 2.0 * s.u(d[3])) / 3.0;
    worst_y = std::max(worst_y, std::abs(yc - (-1e3 * t * t / 6.0)));
    worst_x = std::max(worst_x, std::abs(xc));
    worst_rot = std::max({worst_rot, std::abs(s.u(d[2])), std::abs(s.u(d[5]))});
  });
  sim.run({.end = 1.0, .out = 0.01, .smax = 1e-3, .newton = {.dabsu = 1e-9, .drltu = 1e-12, .dabsi = 1e-6, .drlti = 1e-12}});
  // Y_c reaches 166.7 m; Newton stops at residual 1e-6 N: allow that times h^2 / m per step, summed.
  CHECK(worst_y < 1e-6);
  CHECK(worst_x < 1e-6);
  CHECK(worst_rot == 0.0);
  // The link is stretched and oscillates: its length differs from the initial sqrt(2).
  CHECK(m.work("Connection")[0] == doctest::Approx(std::sqrt(2.0)));
  CHECK(m.work("Connection")[2] == doctest::Approx(5e3 * (m.work("Connection")[1] - std::sqrt(2.0))));
}
}  // namespace

TEST_SUITE("examples/two_bodies") {
  TEST_CASE("the centre of mass of the two-body system falls exactly as P t^2 / (2 m) under Stoermer") {
    check_two_bodies(stoermer{});
  }
  TEST_CASE("the centre of mass of the two-body system falls exactly as P t^2 / (2 m) under Newmark") {
    check_two_bodies(newmark{});
  }
}
