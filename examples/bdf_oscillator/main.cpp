// The variable-order BDF driver (pradis::bdf_simulation, docs/bdf.md) next to
// error-controlled Newmark (pradis::simulation) on a damped oscillator
// m u'' + c u' + k u = 0 (m = 1, k = (2 pi)^2, 2 % damping, u(0) = 1, v(0) = 0) to
// t = 10.3 s, against the exact solution
// u = exp(-z w t) (cos wd t + z w / wd sin wd t), wd = w sqrt(1 - z^2).
// Prints, per tolerance DRLTX = DABSX, the error at the end, the steps and the
// model evaluations of both drivers; then one run whose first half is Newmark's
// and whose second half is BDF's, the BDF driver taking over Newmark's state in
// memory (continue_from).
//
// Usage: bdf_oscillator [--quick]   (--quick: two tolerances only)

#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <string>
#include <vector>

#include <pradis/pradis.hpp>

namespace {

constexpr double w = 2 * std::numbers::pi, zeta = 0.02, end = 10.3;

struct result {
  double error = 0;
  pradis::run_statistics stats;
};

/// The exact displacement and velocity at t.
std::pair<double, double> exact(double t) {
  const double wd = w * std::sqrt(1 - zeta * zeta), e = std::exp(-zeta * w * t);
  return {e * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t)), -e * (w * w / wd) * std::sin(wd * t)};
}

using oscillator_model = pradis::model<pradis::elements::point_mass, pradis::elements::linear_spring,
                                       pradis::elements::linear_damper, pradis::elements::initial_displacement>;

/// Builds the oscillator in m; returns its DOF.
pradis::dof build(oscillator_model& m) {
  using namespace pradis::elements;
  const pradis::dof x = m.add_dof("x");
  m.add<point_mass>("m", {1.0}, x);
  m.add<linear_spring>("k", {w * w}, x, m.ground());
  m.add<linear_damper>("c", {2 * zeta * w}, x, m.ground());
  m.add<initial_displacement>("x0", {1.0}, x);
  return x;
}

/// Error-controlled run options to `end` at DRLTX = DABSX = tol.
pradis::run_options controlled(double tol, double end) {
  pradis::run_options o;
  o.end = end;
  o.smax = 0.5;
  o.smin = 1e-12;
  o.error_control = true;
  o.drltx = tol;
  o.dabsx = tol;
  return o;
}

/// Runs the oscillator with the driver Sim (bdf_simulation or simulation).
template <template <class...> class Sim>
result run(double tol) {
  using namespace pradis;
  oscillator_model m;
  const dof x = build(m);
  Sim<decltype(m)> sim(m);
  result r;
  r.stats = sim.run(controlled(tol, end));
  const auto [u, v] = exact(end);
  r.error = std::max(std::abs(sim.u(x) - u), std::abs(sim.v(x) - v) / w);
  return r;
}

/// Newmark to t = 5 s, then BDF from its state (continue_from) to the end, both at tol.
double handover(double tol) {
  using namespace pradis;
  oscillator_model m;
  const dof x = build(m);
  simulation first(m);
  first.run(controlled(tol, 5.0));
  bdf_simulation second(m);
  second.continue_from(first);  // time, state, element vectors and statistics, not serialised
  second.run(controlled(tol, end));
  const auto [u, v] = exact(end);
  return std::max(std::abs(second.u(x) - u), std::abs(second.v(x) - v) / w);
}

template <class M>
using newmark_sim = pradis::simulation<M>;
template <class M>
using bdf_sim = pradis::bdf_simulation<M>;

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const std::vector<double> tols = quick ? std::vector<double>{1e-3, 1e-6}
                                         : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
  std::printf("%-8s | %-34s | %-34s\n", "DRLTX", "BDF: error / steps / evaluations", "Newmark: error / steps / evaluations");
  for (double tol : tols) {
    const result b = run<bdf_sim>(tol);
    const result n = run<newmark_sim>(tol);
    std::printf("%-8.0e | %10.2e %8ld %10ld       | %10.2e %8ld %10ld\n", tol, b.error, b.stats.steps,
                b.stats.evaluations, n.error, n.stats.steps, n.stats.evaluations);
    if (!(b.error < 1e3 * tol)) return 1;  // a smoke check for CTest
  }
  const double e = handover(1e-6);
  std::printf("Newmark to t = 5 s, then BDF from its state (continue_from), DRLTX = 1e-6: error %.2e\n", e);
  return e < 1e-3 ? 0 : 1;
}
