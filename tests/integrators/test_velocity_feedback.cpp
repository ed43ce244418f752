// A massless node held by springs whose velocity another equation reads (velocity feedback:
// a force on a mass proportional to a sensor point's velocity). The zero step took the node
// for the multiplier of an index-3 constraint (initialisation.hpp, mark_index3_multipliers:
// its row held only stiffness entries, one on an inertial DOF, and its value entered another
// row through C), so it solved the mass's equation for the node's velocity (v_n = -20 m/s
// instead of 0) and left the node off its equation (n = 0 instead of 0.025 m). NEWMARK then
// ended with code 141 at t = 1e-11 and BDF diverged (code 140). A multiplier's row never holds
// a stiffness on its own column; the node's row does, so it is now an algebraic DOF. Its
// velocity is then its displacement's derivative: BDF leaves it out of its norms (DOF class 1,
// driver_core::unused_velocity), as IDA weighs no derivative. While it kept its weight, Newton's
// round-off in the displacement, about eps |n| / h at the first steps (h ~ 1e-11 s), outweighed
// the tolerance, and BDF ended with code 140 at t = 0 from DRLTX = 1e-9 down.
//
// The model: m x'' = -k1 (x - n) - c n', 0 = k1 (n - x) + k2 n, so n = x k1 / (k1 + k2) and
// m x'' + c_e x' + k_e x = 0 with k_e = k1 k2 / (k1 + k2) = 75 N/m, c_e = c k1 / (k1 + k2)
// = 0.125 N s/m: the damped oscillator x = x0 exp(-s t) (cos(w t) + s / w sin(w t)),
// s = c_e / (2 m), w = sqrt(k_e / m - s^2) (any vibrations text, e.g. Thomson, Theory of
// Vibration with Applications, section 2.6).

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <span>
#include <sstream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "testing/test_support.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// F_1 = c v_2 on DOF 1 (c = 0.5 N s/m), nothing on DOF 2: a force on a mass from the velocity of a
/// sensor point (non-reciprocal, as a controller's).
template <class = void>
struct vfb_feedback_t {
  static constexpr pradis::passport passport{.name = "VFB", .ext = 2, .par = 0, .adr = 1, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::mechanical, domain::mechanical};
  static constexpr element_help help{.title = "velocity feedback force",
                                     .name = "F1 = c v2",
                                     .field = "mechanics",
                                     .dofs = "1 - the mass\n2 - the sensor point",
                                     .parameters = "none",
                                     .work = "none",
                                     .special = "none"};
  static constexpr double c = 0.5;
  struct parameters {};
  parameters p;
  explicit vfb_feedback_t(parameters q = {}) : p(q) {}
  static parameters example() { return {}; }
  static vfb_feedback_t from_parameters(std::span<const double>) { return vfb_feedback_t{}; }
  void evaluate(const local_input<vfb_feedback_t>& in, local_output<vfb_feedback_t>& out, element_context&) const {
    out.f(0) = c * in.v(1);
    out.f(1) = 0;
    if (out.want_jacobian) out.C << 0, c, 0, 0;
  }
};
using vfb_feedback = vfb_feedback_t<>;

template <class M>
using vfb_newmark = simulation<M>;
template <class M>
using vfb_bdf = bdf_simulation<M>;

/// Runs the model to 1 s under error control at DRLTX = DABSX = tol; returns the largest |x - exact| over the
/// outputs, and checks the zero step: n on its equation, its velocity 0, the mass's acceleration -k_e x0 / m.
/// `single`: the same oscillator as one mass on a spring k_e and a damper c_e (the reference for the errors).
template <template <class> class Sim>
double vfb_run(double tol, bool single = false) {
  constexpr double m = 1, k1 = 100, k2 = 300, x0 = 0.1;
  const double ke = k1 * k2 / (k1 + k2), ce = vfb_feedback::c * k1 / (k1 + k2), s = ce / (2 * m);
  const double w = std::sqrt(ke / m - s * s);
  using M = model<point_mass, linear_spring, linear_damper, initial_displacement, vfb_feedback>;
  M md;
  const dof x = md.add_dof("x"), n = single ? md.ground() : md.add_dof("n");
  md.add<point_mass>("m", {m}, x);
  md.add<initial_displacement>("x0", {x0}, x);
  if (single) {
    md.add<linear_spring>("k", {ke}, x, md.ground());
    md.add<linear_damper>("c", {ce}, x, md.ground());
  } else {
    md.add<linear_spring>("k1", {k1}, x, n);
    md.add<linear_spring>("k2", {k2}, n, md.ground());
    md.add<vfb_feedback>("feedback", {}, x, n);
  }
  Sim<M> sim(md);
  std::ostringstream log;
  sim.log().to(log);
  double worst = 0;
  bool first = true;
  sim.on_output([&](const auto& st) {
    const double t = st.time();
    if (first) {
      first = false;
      if (!single) {
        CHECK(st.u(n) == doctest::Approx(x0 * k1 / (k1 + k2)).epsilon(1e-14));
        CHECK(st.v(n) == doctest::Approx(0.0).scale(1e-12));
      }
      CHECK(st.a(x) == doctest::Approx(-ke * x0 / m).epsilon(1e-12));
    }
    worst = std::max(worst, std::abs(st.u(x) - x0 * std::exp(-s * t) * (std::cos(w * t) + s / w * std::sin(w * t))));
  });
  sim.run(pradis_test::controlled_run(1.0, tol, 20));
  CHECK(sim.time() == doctest::Approx(1.0));
  if (!single) CHECK(sim.checkpoint().dof_classes[static_cast<std::size_t>(n.index)] == 1.0);  // massless
  return worst;
}

}  // namespace

TEST_SUITE("integrators/velocity feedback from a massless node") {
  TEST_CASE("a force from a massless node's velocity: the node is algebraic at the zero step, and both drivers run") {
    const double n4 = vfb_run<vfb_newmark>(1e-4), n6 = vfb_run<vfb_newmark>(1e-6), n9 = vfb_run<vfb_newmark>(1e-9);
    const double b4 = vfb_run<vfb_bdf>(1e-4), b6 = vfb_run<vfb_bdf>(1e-6), b8 = vfb_run<vfb_bdf>(1e-8);
    const double b10 = vfb_run<vfb_bdf>(1e-10);
    const double sn4 = vfb_run<vfb_newmark>(1e-4, true), sn6 = vfb_run<vfb_newmark>(1e-6, true);
    const double sn9 = vfb_run<vfb_newmark>(1e-9, true), sb4 = vfb_run<vfb_bdf>(1e-4, true);
    const double sb6 = vfb_run<vfb_bdf>(1e-6, true), sb8 = vfb_run<vfb_bdf>(1e-8, true);
    const double sb10 = vfb_run<vfb_bdf>(1e-10, true);
    MESSAGE("|x - exact|: NEWMARK ", n4, " / ", n6, " / ", n9, " at 1e-4 / 1e-6 / 1e-9; BDF ", b4, " / ", b6, " / ", b8,
            " / ", b10, " at 1e-4 / 1e-6 / 1e-8 / 1e-10");
    MESSAGE("one mass, spring and damper: NEWMARK ", sn4, " / ", sn6, " / ", sn9, "; BDF ", sb4, " / ", sb6, " / ", sb8,
            " / ", sb10);
    // Measured: NEWMARK 1.7e-4 / 2.4e-6 / 2.9e-9 (one mass 1.7e-4 / 2.5e-6 / 3.3e-9), BDF 3.6e-5 / 1.2e-6 /
    // 6.5e-8 / 1.4e-9 (one mass 2.9e-5 / 1.3e-6 / 5.6e-8 / 1.1e-9): the feedback through the node costs at most
    // 1.3x the accuracy.
    CHECK(n4 < 1.5 * sn4);
    CHECK(n6 < 1.5 * sn6);
    CHECK(n9 < 1.5 * sn9);
    CHECK(b4 < 1.5 * sb4);
    CHECK(b6 < 1.5 * sb6);
    CHECK(b8 < 1.5 * sb8);
    CHECK(b10 < 1.5 * sb10 + 1e-12);
    CHECK(n4 < 1e-3);
    CHECK(n9 < n4 / 1000);
    CHECK(b8 < b4 / 100);
  }
}
