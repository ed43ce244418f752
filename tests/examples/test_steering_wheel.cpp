// The steering-wheel impact (examples/steering_wheel/steering_wheel_model.hpp) on a
// reduced wheel (8 rim segments, one element per spoke), against invariants and the
// spring-mass estimate:
// - momentum balance of the head: m (v_end - v_0) = integral of the contact force on
//   the head (Newton's second law; the head carries no other force). Newmark's
//   average acceleration updates v_{n+1} = v_n + h (a_n + a_{n+1}) / 2 with the
//   accelerations that balance the forces at the step ends, so the trapezoidal sum of
//   the force samples (from the contacts' work vectors) equals m (v_end - v_0) to the
//   Newton tolerance;
// - energy: with an elastic contact (c = 0) and no numerical damping, kinetic + beam
//   strain + contact energy stays at (1/2) m v0^2. The average-acceleration rule conserves
//   it exactly for a linear system (Hughes, The Finite Element Method, 1987, 9.3); here
//   the contact switches on and off within steps and the beams are geometrically
//   nonlinear, so the energy error falls with the step instead of vanishing: below
//   1e-3 at the step used and at least twice smaller at half the step;
// - the spring-mass estimate: the head (mass m) on the wheel's static stiffness at the
//   junction, k_w (measured in the same model), in series with the contact spring k_c:
//   k = k_w k_c / (k_w + k_c), peak deceleration v0 sqrt(k/m), time in contact
//   pi sqrt(m/k), largest head travel v0 sqrt(m/k) (a linear oscillator released at
//   v0). The wheel's own mass (1.6 kg against the head's 6.8 kg) is neglected by the
//   estimate; a tip mass mu m on the spring changes the frequency by O(mu) and its
//   higher modes ripple the force. The bands (travel 5 %, contact time 10 %, peak
//   20 %) are stated as the accuracy of the estimate, the peak's being the loosest
//   because the ripple adds to it (the example's full wheel: peak 169 g against 156 g).

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "pradis/io/post.hpp"
#include "steering_wheel/steering_wheel_model.hpp"
#include "testing/test_support.hpp"

using namespace pradis;

namespace {
/// The reduced wheel.
steering_wheel::parameters reduced() {
  steering_wheel::parameters P;
  P.rim_segments = 8;
  P.spoke_segments = 1;
  return P;
}

/// One impact: samples of time, the head's force along Z, its velocity and displacement, the energy.
struct impact {
  std::vector<double> t, fz, v, u, e;
  steering_wheel::handles h;
};
impact run(const steering_wheel::parameters& P, double end, double step) {
  steering_wheel::model_type m;
  impact r;
  r.h = steering_wheel::build(m, P);
  simulation sim(m);
  sim.on_output([&](const auto& s) {
    r.t.push_back(s.time());
    r.fz.push_back(steering_wheel::head_force(s, m, r.h)[2]);
    r.v.push_back(s.v(r.h.head_x[2]));
    r.u.push_back(s.u(r.h.head_x[2]));
    r.e.push_back(steering_wheel::energy(m, r.h, P).total());
  });
  // Tight absolute Newton tolerances (the force residual 1e-8 N per DOF keeps the momentum
  // balance exact to ~1e-12 N s); tighter ones fail at round-off and cut steps.
  sim.run({.end = end, .out = 0, .smax = step, .newton = {.dabsu = 1e-10, .drltu = 0, .dabsi = 1e-8, .drlti = 0, .itr = 8}});
  return r;
}
}  // namespace

TEST_SUITE("examples/steering_wheel") {
  TEST_CASE("the head's momentum change equals the impulse of the contact forces; the elastic impact keeps its energy") {
    steering_wheel::parameters P = reduced();
    P.c_contact = 0;
    const impact r = run(P, 0.016, 5e-5);
    REQUIRE(r.t.size() > 100);
    double impulse = 0;
    for (std::size_t i = 1; i < r.t.size(); ++i) impulse += 0.5 * (r.t[i] - r.t[i - 1]) * (r.fz[i] + r.fz[i - 1]);
    const double dp = P.head_mass * (r.v.back() - r.v.front());
    MESSAGE("impulse ", impulse, " N s, m dv ", dp, " N s, rebound ", r.v.back(), " m/s");
    CHECK(r.v.front() == -P.v0);
    CHECK(impulse == doctest::Approx(dp).epsilon(1e-8));
    // The head came back (the impact is over): positive velocity, no force at the end.
    CHECK(r.v.back() > 0);
    CHECK(r.fz.back() == 0);
    const double e0 = 0.5 * P.head_mass * P.v0 * P.v0;
    auto worst = [&](const impact& x) {
      double d = 0;
      for (double e : x.e) d = std::max(d, std::abs(e / e0 - 1));
      return d;
    };
    CHECK(r.e.front() == doctest::Approx(e0).epsilon(1e-12));
    CHECK(worst(r) < 1e-3);
    MESSAGE("energy: largest relative deviation ", worst(r), " (step 5e-5 s)");
    // Half the step: the deviation falls (measured by 2.9: between first order, the
    // contact switching within a step, and the scheme's second order; at least 2 asked).
    // Not under the sanitizers (-O0, some 200x slower): the same code paths as the run above.
    if (pradis_test::sanitized) return;
    const impact fine = run(P, 0.016, 2.5e-5);
    MESSAGE("energy: largest relative deviation ", worst(fine), " (2.5e-5 s)");
    CHECK(worst(fine) < worst(r) / 2);
  }

  TEST_CASE("the peak deceleration, contact time and head travel agree with the spring-mass estimate") {
    const steering_wheel::parameters P = reduced();
    const double kw = steering_wheel::static_stiffness(P, 10.0);
    // Linearity of the static solution at a small load: twice the load, the same stiffness.
    CHECK(steering_wheel::static_stiffness(P, 20.0) == doctest::Approx(kw).epsilon(1e-4));
    const double k = kw * P.k_contact / (kw + P.k_contact), w = std::sqrt(k / P.head_mass);
    const impact r = run(P, 0.016, 5e-5);
    std::vector<double> a;
    for (double f : r.fz) a.push_back(f / P.head_mass);
    const post::peak_value pk = post::peak(r.t, a);
    // In contact: where the force is positive (the half-way crossing of a tiny threshold).
    const post::interval contact = post::longest_above(r.t, a, 1e-6);
    double travel = 0;
    for (double u : r.u) travel = std::max(travel, -u - P.gap);
    MESSAGE("k_wheel ", kw, " N/m; peak ", pk.value, " (estimate ", P.v0 * w, ") m/s^2; contact ", contact.duration,
            " (", std::numbers::pi / w, ") s; travel ", travel, " (", P.v0 / w, ") m");
    CHECK(travel == doctest::Approx(P.v0 / w).epsilon(0.05));
    CHECK(contact.duration == doctest::Approx(std::numbers::pi / w).epsilon(0.10));
    CHECK(pk.value == doctest::Approx(P.v0 * w).epsilon(0.20));
  }
}
