// LINKD evaluation: the element through its interface (planar_link::evaluate on
// a local_input, with the Jacobian, its work vector bound through an
// element_context) against a hand-written Eigen loop over flat arrays computing
// the same flows, length, axial force and 4x4 stiffness (the manual's formulas,
// as in include/pradis/elements/planar/planar_link.hpp, std::hypot included).
// Both read the displacements from the same flat array and write the flows and
// the stiffness into flat arrays of the same layout (4 and 16 doubles per link,
// the stiffness row-major), so the difference is the cost of the interface.
//
// Counter t_per_link: CPU time per link (seconds, console with an SI prefix: "5.1n" = 5.1 ns).
// linkd_element_vs_handwritten runs both interleaved (robust on a loaded machine):
// counters element_ns, handwritten_ns (CPU ns per link) and element/handwritten.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <random>
#include <span>
#include <vector>

#include "pradis/core/element.hpp"
#include "pradis/elements/planar/planar_link.hpp"

namespace {

using pradis::elements::planar_link;
using row_major4 = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;

/// Links of random geometry (length 0.5 to 1.5, any direction), random small displacements.
struct link_set {
  int n = 0;
  // Parameters, structure of arrays (hand-written loop).
  std::vector<double> xa0, ya0, xb0, yb0, k, l0;
  // The same links as elements, with their work vectors (3 per link) in one pool.
  std::vector<planar_link> elements;
  std::vector<double> work;
  // Displacements (4 per link: xA, yA, xB, yB), and the outputs.
  std::vector<double> u, f, stiffness, length, axial;

  explicit link_set(int count) : n(count) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    const auto un = static_cast<std::size_t>(n);
    for (auto* v : {&xa0, &ya0, &xb0, &yb0, &k, &l0, &length, &axial}) v->resize(un);
    work.assign(3 * un, 0.0);
    u.resize(4 * un);
    f.assign(4 * un, 0.0);
    stiffness.assign(16 * un, 0.0);
    elements.reserve(un);
    for (std::size_t i = 0; i < un; ++i) {
      const double len = 1.0 + 0.5 * uni(rng), ang = 3.14159 * uni(rng);
      xa0[i] = 10 * uni(rng);
      ya0[i] = 10 * uni(rng);
      xb0[i] = xa0[i] + len * std::cos(ang);
      yb0[i] = ya0[i] + len * std::sin(ang);
      k[i] = 1e4 * (1.0 + 0.5 * uni(rng));
      for (int j = 0; j < 4; ++j) u[4 * i + static_cast<std::size_t>(j)] = 0.05 * uni(rng);
      elements.emplace_back(planar_link::parameters{xa0[i], ya0[i], xb0[i], yb0[i], k[i]});
      pradis::element_context ctx("LINKD", "bench");
      ctx.work = std::span<double>(work.data() + 3 * i, 3);
      elements.back().new_integration(ctx);  // W(1) = L0
      l0[i] = work[3 * i];
    }
  }

  void run_elements() {
    pradis::local_input<planar_link> in;
    pradis::local_output<planar_link> out;
    out.want_jacobian = true;
    pradis::element_context ctx("LINKD", "bench");
    const double* uu = u.data();
    double* ff = f.data();
    double* kk = stiffness.data();
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      in.u = Eigen::Map<const Eigen::Vector4d>(uu + 4 * ui);
      ctx.work = std::span<double>(work.data() + 3 * ui, 3);
      elements[ui].evaluate(in, out, ctx);
      Eigen::Map<Eigen::Vector4d>(ff + 4 * ui) = out.f;
      Eigen::Map<row_major4>(kk + 16 * ui) = out.K;
    }
  }

  /// Returns false if a link became (nearly) zero-length, where LINKD raises code 75.
  bool run_handwritten() {
    bool ok = true;
    const double* uu = u.data();
    double* ff = f.data();
    double* kk = stiffness.data();
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      const double* q = uu + 4 * ui;
      const double L0 = l0[ui], kl = k[ui];
      const double dx = (xb0[ui] + q[2]) - (xa0[ui] + q[0]);
      const double dy = (yb0[ui] + q[3]) - (ya0[ui] + q[1]);
      const double l = std::hypot(dx, dy);
      ok = ok && l > planar_link::min_length * std::max(1.0, L0);
      const double c = dx / l, s = dy / l, du = l - L0;
      double* fi = ff + 4 * ui;
      fi[0] = -kl * du * c;
      fi[1] = -kl * du * s;
      fi[2] = -fi[0];
      fi[3] = -fi[1];
      length[ui] = l;
      axial[ui] = kl * du;
      const double r = L0 / l;
      const double kxx = kl * (1.0 - r * s * s), kxy = kl * r * s * c, kyy = kl * (1.0 - r * c * c);
      Eigen::Map<row_major4>(kk + 16 * ui) << kxx, kxy, -kxx, -kxy,  //
          kxy, kyy, -kxy, -kyy,                                       //
          -kxx, -kxy, kxx, kxy,                                       //
          -kxy, -kyy, kxy, kyy;
    }
    return ok;
  }
};

/// Runs both variants once and compares every output (they must agree to the last bit
/// but for compiler contraction differences: tolerance 1e-12 relative).
bool same_results(link_set& s) {
  s.run_elements();
  const std::vector<double> f_el = s.f, k_el = s.stiffness, w_el = s.work;
  s.run_handwritten();
  auto close = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)}); };
  for (std::size_t i = 0; i < f_el.size(); ++i)
    if (!close(f_el[i], s.f[i])) return false;
  for (std::size_t i = 0; i < k_el.size(); ++i)
    if (!close(k_el[i], s.stiffness[i])) return false;
  for (std::size_t i = 0; i < s.length.size(); ++i)
    if (!close(w_el[3 * i + 1], s.length[i]) || !close(w_el[3 * i + 2], s.axial[i])) return false;
  return true;
}

benchmark::Counter time_per(double units_per_iteration) {
  return benchmark::Counter(units_per_iteration, benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}

void linkd_element(benchmark::State& st) {
  link_set s(static_cast<int>(st.range(0)));
  if (!same_results(s)) {
    st.SkipWithError("element and hand-written loop disagree");
    return;
  }
  for (auto _ : st) {
    s.run_elements();
    benchmark::DoNotOptimize(s.f.data());
    benchmark::DoNotOptimize(s.stiffness.data());
    benchmark::ClobberMemory();
  }
  st.counters["t_per_link"] = time_per(s.n);
}

void linkd_handwritten(benchmark::State& st) {
  link_set s(static_cast<int>(st.range(0)));
  if (!same_results(s)) {
    st.SkipWithError("element and hand-written loop disagree");
    return;
  }
  for (auto _ : st) {
    bool ok = s.run_handwritten();
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(s.f.data());
    benchmark::DoNotOptimize(s.stiffness.data());
    benchmark::ClobberMemory();
  }
  st.counters["t_per_link"] = time_per(s.n);
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Both variants interleaved in one loop (alternating which goes first), each timed
/// by the thread's CPU clock, so both see the same machine state. Counters: CPU ns
/// per link of each, and their ratio.
void linkd_element_vs_handwritten(benchmark::State& st) {
  link_set s(static_cast<int>(st.range(0)));
  if (!same_results(s)) {
    st.SkipWithError("element and hand-written loop disagree");
    return;
  }
  double t_element = 0, t_hand = 0;
  bool element_first = true;
  for (auto _ : st) {
    const double t0 = thread_cpu_seconds();
    bool ok = true;
    if (element_first)
      s.run_elements();
    else
      ok = s.run_handwritten();
    const double t1 = thread_cpu_seconds();
    if (element_first)
      ok = s.run_handwritten();
    else
      s.run_elements();
    const double t2 = thread_cpu_seconds();
    (element_first ? t_element : t_hand) += t1 - t0;
    (element_first ? t_hand : t_element) += t2 - t1;
    element_first = !element_first;
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(s.f.data());
    benchmark::ClobberMemory();
  }
  const double per = 1e9 / (static_cast<double>(st.iterations()) * s.n);
  st.counters["element_ns"] = t_element * per;
  st.counters["handwritten_ns"] = t_hand * per;
  st.counters["element/handwritten"] = t_element / t_hand;
}

}  // namespace

BENCHMARK(linkd_element)->Arg(1000)->Arg(100000)->ArgName("links")->Unit(benchmark::kMicrosecond);
BENCHMARK(linkd_handwritten)->Arg(1000)->Arg(100000)->ArgName("links")->Unit(benchmark::kMicrosecond);
BENCHMARK(linkd_element_vs_handwritten)->Arg(1000)->Arg(100000)->ArgName("links")->Unit(benchmark::kMicrosecond);
