// When a reduced body pays (issue: super-elements): the spun-up free steel bar of
// bench/spun_bar.hpp (1 m, 20 mm x 20 mm, torque 5 N m (1 - cos(2 pi 5 t)) at the
// root, h = 0.25 ms) over the first 20 ms of its run-up, as n BEAM3 + BEAMI3
// (mechanism_spun_bar/elements:n) and as one FLEX3 made from the same n elements,
// reduced to its ends and 4 fixed-interface modes (mechanism_spun_bar_flex3/elements:n).
// The beam model grows with n, the FLEX3 model does not (its cost is that of 12
// boundary coordinates and 4 modes whatever n; the reduction itself is done once,
// outside the timing). Counters: cpu_per_simulated_s
// (CPU time per simulated second) and, for FLEX3, deflection_difference: the
// largest difference of the tip deflection in the root's frame from the n-beam
// model's over the first 0.1 s, relative to its peak (computed once, outside the
// timing; the rest is the centrifugal stiffening FLEX3 leaves out, docs/reduction.md).
//
// Full run (Release): build/release/bench/pradis_bench --benchmark_filter=spun_bar
//   --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include "spun_bar.hpp"

namespace {

constexpr double spun_bar_end = 0.02, spun_bar_h = 2.5e-4, spun_bar_m0 = 5.0;

template <class Run>
void spun_bar_timed(benchmark::State& state, Run run) {
  for (auto _ : state) {
    const auto s = run(spun_bar_end);
    benchmark::DoNotOptimize(s.back().deflection);
  }
  state.counters["cpu_per_simulated_s"] = benchmark::Counter(
      spun_bar_end * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void mechanism_spun_bar(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  spun_bar_timed(state, [n](double end) { return spun_bar::spin_beams(spun_bar_m0, end, spun_bar_h, n); });
}
BENCHMARK(mechanism_spun_bar)->ArgName("elements")->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);

void mechanism_spun_bar_flex3(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto p = spun_bar::reduced_bar<4>(n);  // the reduction, once: not part of the time per simulated second
  spun_bar_timed(state, [&p](double end) { return spun_bar::spin_reduced<4>(spun_bar_m0, end, spun_bar_h, p); });
  state.counters["deflection_difference"] =
      spun_bar::deflection_difference(spun_bar::spin_beams(spun_bar_m0, 0.1, spun_bar_h, n),
                                      spun_bar::spin_reduced<4>(spun_bar_m0, 0.1, spun_bar_h, n));
}
BENCHMARK(mechanism_spun_bar_flex3)->ArgName("elements")->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);

}  // namespace
