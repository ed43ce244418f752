// Consumer of an installed pradis: found with find_package(pradis), linked as
// pradis::pradis. Builds the smallest useful model, a 1-DOF oscillator (mass on
// a spring to the ground, released from an initial displacement), runs it over
// one period and compares with the exact solution u(t) = u0 cos(w t).
// Exit status 0 when everything agrees, 1 otherwise.
// Built and run by the CTest test consumer_find_package (tests/build_tests.cmake).

#include <pradis/pradis.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

int main() {
  using namespace pradis;
  using namespace pradis::elements;

  const double m_kg = 2.0, k_n_per_m = 200.0, u0 = 0.1;
  const double w = std::sqrt(k_n_per_m / m_kg);  // 10 rad/s
  const double period = 2 * std::numbers::pi / w;

  // Only the three listed element types are compiled into this model.
  model<point_mass, linear_spring, initial_displacement> m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {.m = m_kg}, x);
  m.add<linear_spring>("spring", {.k = k_n_per_m}, x, m.ground());
  m.add<initial_displacement>("start", {.u0 = u0}, x);

  simulation sim(m, newmark{});  // average acceleration: beta = 1/4, gamma = 1/2
  double max_error = 0;
  int outputs = 0;
  sim.on_output([&](const auto& s) {
    max_error = std::max(max_error, std::abs(s.u(x) - u0 * std::cos(w * s.time())));
    ++outputs;
  });
  sim.run({.end = period, .out = period / 50, .smax = 1e-3});

  const double spring_force = m.work("spring")[0];  // W:spring(1), k (u2 - u1), here -k u
  std::printf("pradis consumer: %d outputs, %ld steps, max |u - u0 cos(wt)| = %.3g m, u(T) = %.6f m\n", outputs,
              sim.statistics().steps, max_error, sim.u(x));

  bool ok = true;
  auto expect = [&](bool cond, const char* what) {
    if (!cond) {
      std::printf("FAILED: %s\n", what);
      ok = false;
    }
  };
  expect(outputs == 51, "an output at t = 0 and 50 outputs at OUT intervals");
  expect(std::abs(sim.time() - period) < 1e-12, "the run ends at END");
  expect(max_error < 1e-3 * u0, "the displacement follows u0 cos(w t) within 1e-3 u0");
  expect(std::abs(spring_force + k_n_per_m * sim.u(x)) < 1e-9, "the spring's work vector holds its force");

  // A bad parameter is reported as pradis::error with code 100 and the instance name.
  try {
    model<point_mass> bad;
    bad.add<point_mass>("negative", {.m = -1.0}, bad.add_dof());
    simulation s(bad);
    s.run({.end = 0.1});
    expect(false, "a negative mass is rejected");
  } catch (const pradis::error& e) {
    expect(e.number() == 100 && e.instance() == "negative", "code 100 names the instance");
  }

  std::printf(ok ? "pradis consumer: OK\n" : "pradis consumer: FAILED\n");
  return ok ? 0 : 1;
}
