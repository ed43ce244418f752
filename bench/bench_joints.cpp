// Exact against penalty joints on a planar pendulum chain (docs/joints.md): N point
// masses (0.5 kg in all) on N links (1 m in all), the first hinged at the origin,
// released horizontally from rest, simulated for 0.4 s with HHT alpha = -0.05 at a
// fixed step. Links are LINKX (exact constraints, axial forces as Lagrange
// multipliers) or LINKD of stiffness k (penalty). Counters: tip_error [m], the
// tip's distance from the independent joint-coordinate solution
// (bench/chain_reference.hpp, RK4 at h = 5e-5, computed once per N), steps and
// Newton iterations per step. The time is per simulated run of 0.4 s.
//
// Full run (Release): build/release/bench/pradis_bench --benchmark_filter=chain_
//   --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "chain_reference.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

namespace {

using joint_chain_model = pradis::model<pradis::elements::point_mass, pradis::elements::planar_rigid_link,
                                        pradis::elements::planar_link, pradis::elements::constant_force>;
constexpr double g = 9.81, t_end = 0.4;

const Eigen::Vector2d& reference_tip(int n) {
  static std::map<int, Eigen::Vector2d> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    const double l = 1.0 / n;
    it = cache.emplace(n, pradis_reference::chain_tip(pradis_reference::chain_reference(n, l, g, t_end, 8000), l)).first;
  }
  return it->second;
}

// One run of the chain: k = 0 exact links, else LINKD of stiffness k. Returns the tip error.
double run_chain(int n, double k, double h, pradis::run_statistics& st) {
  using namespace pradis;
  using namespace pradis::elements;
  const double l = 1.0 / n, m = 0.5 / n;
  joint_chain_model mod;
  std::vector<dof> x(static_cast<std::size_t>(n)), y(x.size());
  for (int i = 0; i < n; ++i) {
    const auto si = static_cast<std::size_t>(i);
    x[si] = mod.add_dof();
    y[si] = mod.add_dof();
    mod.add<point_mass>("", {m}, x[si]);
    mod.add<point_mass>("", {m}, y[si]);
    mod.add<constant_force>("", {-m * g}, y[si]);
    const dof ax = i == 0 ? mod.ground() : x[si - 1], ay = i == 0 ? mod.ground() : y[si - 1];
    if (k > 0)
      mod.add<planar_link>("", {i * l, 0.0, (i + 1) * l, 0.0, k}, ax, ay, x[si], y[si]);
    else
      mod.add<planar_rigid_link>("", {i * l, 0.0, (i + 1) * l, 0.0}, ax, ay, x[si], y[si]);
  }
  simulation<joint_chain_model, alpha_family> sim(mod, alpha_family(hht{-0.05}));
  run_options o{.end = t_end, .smax = h};
  o.newton = {.dabsu = 1e-10, .drltu = 1e-10, .dabsi = 1e-9, .drlti = 1e-12, .itr = 10};
  st = sim.run(o);
  const Eigen::Vector2d tip(1.0 + sim.u(x.back()), sim.u(y.back()));
  return (tip - reference_tip(n)).norm();
}

void chain(benchmark::State& state, double k, double h) {
  const int n = static_cast<int>(state.range(0));
  (void)reference_tip(n);  // outside the timing
  double err = 0;
  pradis::run_statistics st;
  for (auto _ : state) err = run_chain(n, k, h, st);
  state.counters["tip_error"] = err;
  state.counters["steps"] = static_cast<double>(st.steps);
  state.counters["iterations_per_step"] =
      static_cast<double>(st.newton_iterations) / static_cast<double>(std::max(1L, st.steps));
}

void chain_exact_h1e3(benchmark::State& s) { chain(s, 0, 1e-3); }
void chain_exact_h1e4(benchmark::State& s) { chain(s, 0, 1e-4); }
void chain_penalty_k1e6_h1e4(benchmark::State& s) { chain(s, 1e6, 1e-4); }
void chain_penalty_k1e8_h1e4(benchmark::State& s) { chain(s, 1e8, 1e-4); }
BENCHMARK(chain_exact_h1e3)->ArgName("N")->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(chain_exact_h1e4)->ArgName("N")->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(chain_penalty_k1e6_h1e4)->ArgName("N")->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(chain_penalty_k1e8_h1e4)->ArgName("N")->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
