// pradis kernel benchmarks (google-benchmark).
//
//   newton_iteration<M>/N:n   one Newton iteration on the chain of n bodies (3 n equations):
//                             assembler::evaluate with the Jacobian + RHS + sparse LU factorize + solve.
//   full_step/N:n             simulation::run of exactly one step (run({.end = t + h, .smax = h})).
//   full_step_x16/N:n         simulation::run of 16 steps in one call (one stage); the time column is
//                             per run, the counters per step: the difference to full_step is the per-run
//                             cost (a NEWINT pass over all elements, option checks).
//   model_type_ratio/N:1000   one Newton iteration in a model listing only the chain's element types
//                             against pradis::library_model (all library types), interleaved; counter
//                             library/listed = CPU time ratio (expected 1.00), listed_us / library_us
//                             = CPU microseconds per iteration of each (the time column is their sum).
//   model_type_ratio_step1/N:n, model_type_ratio_step16/N:n
//                             the same, for whole simulation steps: one run() of 1 (or 16) steps in each
//                             model type, interleaved; counters library/listed, listed_us and library_us
//                             per step. N:1 is a 3-equation model, where per-type overhead shows.
//   newton_parts/N:n          the Newton iteration split: assembly (+ RHS) against LU factorize + solve.
//   linkd_* (bench_linkd.cpp) LINKD through its element interface against a hand-written Eigen loop.
//
// Counters:
//   t_per_dof   time per equation (free DOF) of the work timed in one benchmark iteration, per step
//               for full_step*: CPU time / (iterations x equations [x steps per run]). It is a google-
//               benchmark rate counter with kInvert, so its unit is seconds: the console prints it with
//               an SI prefix ("23.5n" = 23.5 ns per DOF), JSON/CSV output gives plain seconds.
//   equations   number of equations (3 N).
//   newton_per_step, steps_per_run   Newton iterations per accepted step and accepted steps per run()
//               call (averages over the timed loop).
//
// Scene: see chain.hpp. Full run (Release):
//   pradis_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <ctime>
#include <memory>

#include "chain.hpp"

namespace {

using pradis_bench::chain_model;
using pradis_bench::newton_fixture;
using pradis_bench::sim_fixture;

/// Seconds per (iteration x units): a rate counter, inverted.
benchmark::Counter time_per(double units_per_iteration) {
  return benchmark::Counter(units_per_iteration, benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}

template <class M>
void newton_iteration(benchmark::State& st) {
  newton_fixture<M> f(static_cast<int>(st.range(0)));
  f.iterate();  // warm-up (first touch of the factor storage)
  for (auto _ : st) {
    f.iterate();
    benchmark::DoNotOptimize(f.rhs.data());
    benchmark::ClobberMemory();
  }
  st.counters["equations"] = f.equations();
  st.counters["nnz_factor"] = static_cast<double>(f.lu.statistics().nnz_factor);
  st.counters["t_per_dof"] = time_per(f.equations());
}

/// run() of `steps_per_run` steps per benchmark iteration. Under the constant
/// tip force the undamped chain keeps gaining energy, so the scene is rebuilt
/// (timer paused) every ~200 steps to keep every timed step alike.
void full_step_runs(benchmark::State& st, int steps_per_run) {
  const int n = static_cast<int>(st.range(0));
  auto f = std::make_unique<sim_fixture<chain_model>>(n);
  const int runs_per_scene = std::max(1, 200 / steps_per_run);
  int runs = 0;
  long steps = 0, newton = 0, rejected = 0;
  for (auto _ : st) {
    if (runs == runs_per_scene) {
      st.PauseTiming();
      f.reset();
      f = std::make_unique<sim_fixture<chain_model>>(n);
      runs = 0;
      st.ResumeTiming();
    }
    const pradis::run_statistics s = f->advance(steps_per_run);
    ++runs;
    steps += s.steps;
    newton += s.newton_iterations;
    rejected += s.rejected_steps;
  }
  const double iters = static_cast<double>(st.iterations());
  st.counters["equations"] = f->equations();
  st.counters["steps_per_run"] = static_cast<double>(steps) / iters;
  st.counters["newton_per_step"] = steps > 0 ? static_cast<double>(newton) / static_cast<double>(steps) : 0.0;
  if (rejected > 0) st.counters["rejected"] = static_cast<double>(rejected);
  st.counters["t_per_dof"] = time_per(static_cast<double>(f->equations()) * steps_per_run);
}

void full_step(benchmark::State& st) { full_step_runs(st, 1); }
void full_step_x16(benchmark::State& st) { full_step_runs(st, 16); }

/// CPU time of the calling thread, in seconds (robust to other load on the machine,
/// like google-benchmark's own CPU-time column).
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Whether two result vectors agree to rounding (1e-9 of their largest entry).
bool agree(const std::vector<double>& a, const std::vector<double>& b) {
  double scale = 0, diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    scale = std::max(scale, std::abs(a[i]));
    diff = std::max(diff, std::abs(a[i] - b[i]));
  }
  return a.size() == b.size() && diff <= 1e-9 * scale;
}

/// The same Newton iteration in the two model types, interleaved (alternating
/// which goes first) and each timed by the thread's CPU clock, so both see the
/// same machine state.
void model_type_ratio(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  newton_fixture<chain_model> listed(n);
  newton_fixture<pradis::library_model> library(n);
  listed.iterate();
  library.iterate();
  // The two models sum the flows on a DOF in their own type order (library_model
  // lists F before MD and LINKD), so the corrections agree to rounding, not bit for bit.
  if (!agree(listed.rhs, library.rhs)) {
    st.SkipWithError("the two model types give different Newton corrections");
    return;
  }
  double t_listed = 0, t_library = 0;
  bool listed_first = true;
  for (auto _ : st) {
    const double t0 = thread_cpu_seconds();
    if (listed_first)
      listed.iterate();
    else
      library.iterate();
    const double t1 = thread_cpu_seconds();
    if (listed_first)
      library.iterate();
    else
      listed.iterate();
    const double t2 = thread_cpu_seconds();
    (listed_first ? t_listed : t_library) += t1 - t0;
    (listed_first ? t_library : t_listed) += t2 - t1;
    listed_first = !listed_first;
    benchmark::DoNotOptimize(listed.rhs.data());
    benchmark::DoNotOptimize(library.rhs.data());
  }
  const double iters = static_cast<double>(st.iterations());
  const double us_listed = 1e6 * t_listed / iters;
  const double us_library = 1e6 * t_library / iters;
  st.counters["listed_us"] = us_listed;    // CPU microseconds per Newton iteration, model<MD, LINKD, F>
  st.counters["library_us"] = us_library;  // CPU microseconds per Newton iteration, pradis::library_model
  st.counters["library/listed"] = us_library / us_listed;  // the ratio; expected 1.00
}

/// The same simulation steps in the two model types, side by side: each
/// benchmark iteration runs one stage of `steps` steps (run() with its NEWINT
/// pass and option checks) in a model listing only the chain's types and in
/// pradis::library_model, alternating which goes first, each timed by the
/// thread's CPU clock. Both scenes are rebuilt (not timed) every ~200 steps.
/// On small models the per-step work is a few microseconds, so whatever the
/// kernel does per element *type* (library_model lists every library type) shows here.
void model_type_ratio_step(benchmark::State& st, int steps) {
  const int n = static_cast<int>(st.range(0));
  auto listed = std::make_unique<sim_fixture<chain_model>>(n);
  auto library = std::make_unique<sim_fixture<pradis::library_model>>(n);
  const int runs_per_scene = std::max(1, 200 / steps);
  int runs = 0;
  double t_listed = 0, t_library = 0;
  bool listed_first = true;
  for (auto _ : st) {
    if (runs == runs_per_scene) {
      st.PauseTiming();
      listed = std::make_unique<sim_fixture<chain_model>>(n);
      library = std::make_unique<sim_fixture<pradis::library_model>>(n);
      runs = 0;
      st.ResumeTiming();
    }
    const double t0 = thread_cpu_seconds();
    if (listed_first)
      (void)listed->advance(steps);
    else
      (void)library->advance(steps);
    const double t1 = thread_cpu_seconds();
    if (listed_first)
      (void)library->advance(steps);
    else
      (void)listed->advance(steps);
    const double t2 = thread_cpu_seconds();
    (listed_first ? t_listed : t_library) += t1 - t0;
    (listed_first ? t_library : t_listed) += t2 - t1;
    listed_first = !listed_first;
    ++runs;
  }
  std::vector<double> u_listed, u_library;
  for (int d = 0; d < listed->model.dof_count(); ++d) {
    u_listed.push_back(listed->sim.u(pradis::dof{d}));
    u_library.push_back(library->sim.u(pradis::dof{d}));
  }
  if (!agree(u_listed, u_library)) {
    st.SkipWithError("the two model types give different results");
    return;
  }
  const double per_step = 1e6 / (static_cast<double>(st.iterations()) * steps);
  st.counters["equations"] = listed->equations();
  st.counters["listed_us"] = t_listed * per_step;    // CPU microseconds per step, model<MD, LINKD, F>
  st.counters["library_us"] = t_library * per_step;  // CPU microseconds per step, pradis::library_model
  st.counters["library/listed"] = t_library / t_listed;
}
void model_type_ratio_step1(benchmark::State& st) { model_type_ratio_step(st, 1); }
void model_type_ratio_step16(benchmark::State& st) { model_type_ratio_step(st, 16); }

/// Where a Newton iteration's time goes: assembler::evaluate (with the Jacobian)
/// and the right-hand side, against sparse LU factorize + solve, each timed by the
/// thread's CPU clock. Counters: CPU ns per equation of each part.
void newton_parts(benchmark::State& st) {
  newton_fixture<chain_model> f(static_cast<int>(st.range(0)));
  f.iterate();
  double t_assemble = 0, t_lu = 0;
  const int ne = f.equations();
  for (auto _ : st) {
    const double t0 = thread_cpu_seconds();
    f.assembler.evaluate(f.model, f.state, f.coefficients, f.info);
    const auto& res = f.assembler.residual();
    for (int i = 0; i < ne; ++i) f.rhs[static_cast<std::size_t>(i)] = -res(f.assembler.dof_of(i));
    const double t1 = thread_cpu_seconds();
    f.lu.factorize(f.assembler.values());
    f.lu.solve(f.rhs);
    const double t2 = thread_cpu_seconds();
    t_assemble += t1 - t0;
    t_lu += t2 - t1;
    benchmark::DoNotOptimize(f.rhs.data());
  }
  const double per = 1e9 / (static_cast<double>(st.iterations()) * ne);
  st.counters["assemble_ns_per_dof"] = t_assemble * per;
  st.counters["lu_ns_per_dof"] = t_lu * per;
}

}  // namespace

BENCHMARK_TEMPLATE(newton_iteration, chain_model)
    ->RangeMultiplier(10)
    ->Range(10, 100000)
    ->ArgName("N")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(newton_iteration, pradis::library_model)->Arg(1000)->ArgName("N")->Unit(benchmark::kMicrosecond);
BENCHMARK(full_step)->RangeMultiplier(10)->Range(10, 100000)->ArgName("N")->Unit(benchmark::kMicrosecond);
BENCHMARK(full_step_x16)->RangeMultiplier(10)->Range(10, 100000)->ArgName("N")->Unit(benchmark::kMicrosecond);
BENCHMARK(model_type_ratio)->Arg(1)->Arg(10)->Arg(1000)->ArgName("N")->Unit(benchmark::kMicrosecond);
BENCHMARK(model_type_ratio_step1)->Arg(1)->Arg(10)->Arg(1000)->ArgName("N")->Unit(benchmark::kMicrosecond);
BENCHMARK(model_type_ratio_step16)->Arg(1)->Arg(10)->Arg(1000)->ArgName("N")->Unit(benchmark::kMicrosecond);
BENCHMARK(newton_parts)->Arg(1000)->Arg(100000)->ArgName("N")->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
#ifdef NDEBUG
  benchmark::AddCustomContext("pradis_assertions", "off (NDEBUG)");
#else
  benchmark::AddCustomContext("pradis_assertions", "on (no NDEBUG: Eigen and kernel asserts are active)");
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
