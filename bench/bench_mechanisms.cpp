// Time per simulated second of the spatial example mechanisms (issue: spatial
// mechanics): the heavy symmetric top of examples/spinning_top (BODY3 on SPH3 under
// gravity, h = 1 ms, tight Newton tolerances as in the example) and the crankshaft of
// examples/crankshaft (75 DOFs: 8 BEAM3 + BEAMI3, bearings, rod, piston, gas force,
// SHC3 drive; h = 0.1 ms as in the example, the first `ms` of the run-up from rest). Each iteration builds
// the scene and simulates `ms` milliseconds of motion; the counter
// cpu_per_simulated_s is the CPU time per simulated second (console: seconds with an SI
// prefix, "250m" = 0.25 s of CPU per second of motion), steps_per_s the step rate.
// mechanism_crankshaft_cb runs the crankshaft with its shaft as one Craig-Bampton body (FLEX3) and also
// reports runout_difference, its bearing runout against the BEAM3 shaft's; mechanism_crankshaft_bdf runs
// it with the BDF driver under error control.
//
// Full run (Release): build/release/bench/pradis_bench --benchmark_filter=mechanism
//   --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "crankshaft/crankshaft_model.hpp"
#include "spinning_top/top_model.hpp"

namespace {

void mechanism_spinning_top(benchmark::State& state) {
  const double end = static_cast<double>(state.range(0)) * 1e-3;
  long steps = 0;
  for (auto _ : state) {
    pradis_examples::spinning_top top;
    pradis::simulation sim(top.m);
    const auto st = sim.run({.end = end, .out = 0, .smax = 1e-3,
                             .newton = {.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-10, .drlti = 0}});
    steps += st.steps;
    benchmark::DoNotOptimize(sim.u(top.r.q4));
  }
  state.counters["cpu_per_simulated_s"] =
      benchmark::Counter(end * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}
BENCHMARK(mechanism_spinning_top)->ArgName("ms")->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

/// Simulates `ms` milliseconds of the crankshaft on a model of type Model per iteration.
template <class Model>
void crankshaft_run(benchmark::State& state) {
  const double end = static_cast<double>(state.range(0)) * 1e-3;
  long steps = 0;
  for (auto _ : state) {
    Model m;
    const auto h = crankshaft::build(m, crankshaft::parameters{});
    pradis::simulation sim(m);
    const auto st = sim.run({.end = end, .out = 0, .smax = 1e-4});
    steps += st.steps;
    benchmark::DoNotOptimize(sim.u(h.py));
  }
  state.counters["cpu_per_simulated_s"] =
      benchmark::Counter(end * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}

void mechanism_crankshaft(benchmark::State& state) { crankshaft_run<crankshaft::model_type>(state); }
BENCHMARK(mechanism_crankshaft)->ArgName("ms")->Arg(5)->Arg(100)->Unit(benchmark::kMillisecond);

// The same crankshaft with the shaft as one Craig-Bampton body (FLEX3 on 5 boundary nodes, 6 modes;
// crankshaft::cb_model_type). Counters as above, and runout_difference: the largest difference of the
// bearing runout from the BEAM3 shaft's over the run, relative to the peak runout (computed once,
// outside the timing).
void mechanism_crankshaft_cb(benchmark::State& state) {
  crankshaft_run<crankshaft::cb_model_type>(state);
  const double end = static_cast<double>(state.range(0)) * 1e-3;
  const auto beams = crankshaft::bearing_runouts<crankshaft::model_type>(end),
             cb = crankshaft::bearing_runouts<crankshaft::cb_model_type>(end);
  double peak = 0, diff = 0;
  for (std::size_t k = 0; k < std::min(beams.size(), cb.size()); ++k)
    for (std::size_t j = 0; j < 2; ++j) {
      peak = std::max(peak, beams[k][j]);
      diff = std::max(diff, std::abs(beams[k][j] - cb[k][j]));
    }
  state.counters["runout_difference"] = peak > 0 ? diff / peak : 0.0;
}
BENCHMARK(mechanism_crankshaft_cb)->ArgName("ms")->Arg(5)->Arg(100)->Unit(benchmark::kMillisecond);

// The crankshaft with the variable-order BDF driver under error control, DRLTX = DABSX = 1e-4
// (docs/bdf.md, "Stiff, excited modes: the crankshaft"); scaled:1 sets the nominal potential of the
// angular DOFs to 100 rad/s (crankshaft::scale_angular_dofs), scaled:0 leaves it at 1 rad/s.
// Counters as above, and error_rejections_per_step (error-test failures per accepted step) and
// runout_at_end (bearing 1's runout at the end [m]; the example's fixed steps of 0.1 ms give 7.998e-6
// at 100 ms, steps of 0.01 ms 8.076e-6).
void mechanism_crankshaft_bdf(benchmark::State& state) {
  const double end = static_cast<double>(state.range(0)) * 1e-3;
  long steps = 0, rejections = 0;
  double runout = 0;
  for (auto _ : state) {
    crankshaft::model_type m;
    const auto h = crankshaft::build(m, crankshaft::parameters{});
    if (state.range(1) != 0) crankshaft::scale_angular_dofs(m, h, 100.0);
    pradis::bdf_simulation sim(m);
    pradis::run_options o;
    o.end = end;
    o.error_control = true;
    o.smax = 1e-3;
    o.smin = 1e-12;
    o.drltx = 1e-4;
    o.dabsx = 1e-4;
    const auto st = sim.run(o);
    steps += st.steps;
    rejections += st.error_rejections;
    runout = std::hypot(sim.u(h.x[1][1]), sim.u(h.x[1][2]));
  }
  state.counters["cpu_per_simulated_s"] = benchmark::Counter(end * static_cast<double>(state.iterations()),
                                                             benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["error_rejections_per_step"] =
      steps > 0 ? static_cast<double>(rejections) / static_cast<double>(steps) : 0.0;
  state.counters["runout_at_end"] = runout;
}
BENCHMARK(mechanism_crankshaft_bdf)
    ->ArgNames({"ms", "scaled"})
    ->Args({5, 1})
    ->Args({100, 1})
    ->Args({5, 0})
    ->Args({100, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
