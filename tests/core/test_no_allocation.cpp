// The hot paths do not allocate: every library element's evaluate (with and
// without the Jacobian), assembler::evaluate over a built model, sparse_lu
// factorize + solve after analyze, and a whole integration step
// (simulation::run of one step after the first stage; bdf_simulation::run under error control).
//
// How: this file replaces the global operator new/delete (all variants) of the
// whole test executable with versions that forward to malloc/free and count,
// but only on the thread that armed them and only while an allocation_probe
// is alive; everywhere else they behave like the standard ones. Eigen's
// dynamic-size storage does not use operator new but malloc, so on glibc (and
// without a sanitizer, which owns malloc itself) malloc, calloc and realloc are
// interposed as well, forwarding to glibc's __libc_* entry points and counting
// under the same rule. Where that is unavailable the malloc check is skipped
// and only operator new/delete are counted.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/linalg/sparsity.hpp"
#include "pradis/model/model.hpp"
#include "../elements/condensed_parts.hpp"
#include "testing/test_support.hpp"  // PRADIS_TEST_SANITIZED

// ---------------------------------------------------------------------------
// Counting allocator hooks
// ---------------------------------------------------------------------------

namespace {

struct allocation_counts {
  long news = 0;      ///< operator new / new[] calls (all variants)
  long deletes = 0;   ///< operator delete / delete[] calls with a non-null pointer
  long mallocs = 0;   ///< malloc / calloc / realloc calls (where interposed)
};

constinit thread_local int armed = 0;
constinit thread_local allocation_counts counts{};

void* counted_new(std::size_t n) {
  if (armed) ++counts.news;
  void* p = std::malloc(n == 0 ? 1 : n);
  if (!p) throw std::bad_alloc();
  return p;
}
void* counted_new(std::size_t n, std::align_val_t al) {
  if (armed) ++counts.news;
  const auto a = static_cast<std::size_t>(al);
  const std::size_t size = n == 0 ? a : (n + a - 1) / a * a;  // aligned_alloc wants a multiple of the alignment
  void* p = std::aligned_alloc(a, size);
  if (!p) throw std::bad_alloc();
  return p;
}
void counted_delete(void* p) noexcept {
  if (!p) return;
  if (armed) ++counts.deletes;
  std::free(p);
}

#if defined(__GLIBC__) && !defined(PRADIS_TEST_SANITIZED)
#define PRADIS_TEST_COUNTS_MALLOC 1
constexpr bool counts_malloc = true;
#else
constexpr bool counts_malloc = false;
#endif

/// Counts the allocations made on this thread while alive.
class allocation_probe {
 public:
  allocation_probe() {
    counts = {};
    ++armed;
  }
  ~allocation_probe() { --armed; }
  allocation_probe(const allocation_probe&) = delete;
  allocation_probe& operator=(const allocation_probe&) = delete;
  /// Counts so far (read them while the probe is alive: reading allocates nothing).
  allocation_counts counts_now() const { return counts; }
};

}  // namespace

void* operator new(std::size_t n) { return counted_new(n); }
void* operator new[](std::size_t n) { return counted_new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t al) { return counted_new(n, al); }
void* operator new[](std::size_t n, std::align_val_t al) { return counted_new(n, al); }
void* operator new(std::size_t n, std::align_val_t al, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n, al);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, std::align_val_t al, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n, al);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { counted_delete(p); }
void operator delete[](void* p) noexcept { counted_delete(p); }
void operator delete(void* p, std::size_t) noexcept { counted_delete(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_delete(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { counted_delete(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { counted_delete(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_delete(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_delete(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_delete(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_delete(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { counted_delete(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { counted_delete(p); }

#ifdef PRADIS_TEST_COUNTS_MALLOC
// glibc's own entry points (exported, stable since 2.2.5); free needs no hook:
// everything is still allocated by glibc.
extern "C" void* __libc_malloc(std::size_t) noexcept;
extern "C" void* __libc_calloc(std::size_t, std::size_t) noexcept;
extern "C" void* __libc_realloc(void*, std::size_t) noexcept;
extern "C" void* malloc(std::size_t n) noexcept {
  if (armed) ++counts.mallocs;
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t n, std::size_t size) noexcept {
  if (armed) ++counts.mallocs;
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, std::size_t n) noexcept {
  if (armed) ++counts.mallocs;
  return __libc_realloc(p, n);
}
#endif

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

namespace {

using namespace pradis;
using namespace pradis::elements;

/// Runs f() under a probe and returns the counts.
template <class F>
allocation_counts count_allocations(F&& f) {
  allocation_probe probe;
  f();
  return probe.counts_now();
}

void check_none(const allocation_counts& c) {
  CHECK(c.news == 0);
  CHECK(c.deletes == 0);
  CHECK(c.mallocs == 0);
}

template <class E>
void check_element_does_not_allocate() {
  constexpr passport p = E::passport;
  CAPTURE(p.name);
  E e(E::example());
  int npar = p.par;
  if constexpr (requires { e.parameter_count(); }) npar = e.parameter_count();
  std::vector<double> work(static_cast<std::size_t>(p.work_size(npar)), 0.0);
  std::vector<double> old_state(static_cast<std::size_t>(p.state_size(npar)), 0.0);
  std::vector<double> new_state(old_state.size(), 0.0);
  element_context ctx(p.name, "probe");
  ctx.work = work;
  ctx.old_state = old_state;
  ctx.new_state = new_state;
  ctx.npar = npar;
  if constexpr (HasNewIntegration<E>) {  // NEWINT at the zero step, as the simulation does
    ctx.newint = true;
    e.new_integration(ctx);
    ctx.newint = false;
  }
  ctx.time = 0.25;
  ctx.step = 1e-3;
  ctx.nstep = 3;
  local_input<E> in;
  for (int k = 0; k < element_traits<E>::n; ++k) {  // a small, admissible, non-trivial state
    in.u(k) = 0.01 * (k + 1);
    in.v(k) = 0.1 * (k + 1) - 0.2;
    in.a(k) = 0.5 * (k + 1) - 1.0;
  }
  // Rotational nodes: a unit quaternion (the vector part as above, q4 completing the norm).
  for (const rotation_slot& sl : element_traits<E>::rotation_nodes)
    in.u(sl.q4) = std::sqrt(1.0 - in.u.segment(sl.q1, 3).squaredNorm());
  in.t = 0.25;
  local_output<E> out, out_nojac;
  out_nojac.want_jacobian = false;
  const allocation_counts c = count_allocations([&] {
    out.clear();
    e.evaluate(in, out, ctx);
    out_nojac.clear();
    e.evaluate(in, out_nojac, ctx);
  });
  check_none(c);
  CHECK(out.f.allFinite());
}

template <class... Es>
void check_all_elements(type_list<Es...>) {
  (check_element_does_not_allocate<Es>(), ...);
}

/// The benchmark scene (bench/chain.hpp), small: N MD bodies on the X axis, LINKD
/// between neighbours, body 1 held by two LINKD to the ground, a force on the last body.
template <class M>
void build_chain(M& m, int n) {
  const dof g = M::ground();
  std::vector<dof> x, y;
  for (int i = 0; i < n; ++i) {
    x.push_back(m.add_dof());
    y.push_back(m.add_dof());
    const dof r = m.add_dof();
    m.template add<planar_inertia>("", {1.0, 0.1}, x.back(), y.back(), r);
  }
  m.template add<planar_link>("", {-1.0, 0.0, 0.0, 0.0, 1e4}, g, g, x[0], y[0]);
  m.template add<planar_link>("", {0.0, -1.0, 0.0, 0.0, 1e4}, g, g, x[0], y[0]);
  for (int i = 0; i + 1 < n; ++i)
    m.template add<planar_link>("", {double(i), 0.0, double(i + 1), 0.0, 1e4}, x[static_cast<std::size_t>(i)],
                                y[static_cast<std::size_t>(i)], x[static_cast<std::size_t>(i + 1)],
                                y[static_cast<std::size_t>(i + 1)]);
  m.template add<constant_force>("", {1.0}, y.back());
}

template <class M>
void new_integration(M& m) {
  m.for_each_instances([&](auto& vec) {
    for (auto& in : vec) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      if constexpr (HasNewIntegration<E>) {
        element_context ctx(E::passport.name, in.name);
        assembler<M>::bind(m, in, ctx);
        in.element.new_integration(ctx);
      }
    }
  });
}

/// A 2D 5-point grid (n x n nodes) with non-symmetric, diagonally dominant values:
/// an LU with real fill-in.
struct grid_matrix {
  linalg::sparsity_pattern pattern;
  std::vector<double> values;
};
grid_matrix make_grid(int n) {
  std::vector<std::pair<int, int>> e;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      e.emplace_back(id(i, j), id(i, j));
      if (i > 0) e.emplace_back(id(i, j), id(i - 1, j));
      if (i + 1 < n) e.emplace_back(id(i, j), id(i + 1, j));
      if (j > 0) e.emplace_back(id(i, j), id(i, j - 1));
      if (j + 1 < n) e.emplace_back(id(i, j), id(i, j + 1));
    }
  grid_matrix g;
  g.pattern = linalg::sparsity_pattern::from_entries(n * n, e);
  g.values.resize(static_cast<std::size_t>(g.pattern.nnz()));
  for (int r = 0; r < g.pattern.n; ++r)
    for (int q = g.pattern.row_ptr[static_cast<std::size_t>(r)]; q < g.pattern.row_ptr[static_cast<std::size_t>(r) + 1];
         ++q) {
      const int c = g.pattern.col[static_cast<std::size_t>(q)];
      g.values[static_cast<std::size_t>(q)] = c == r ? 4.5 : (c > r ? -1.0 : -0.7);
    }
  return g;
}

/// max |A x - b| for a CSR matrix.
double residual_norm(const linalg::sparsity_pattern& p, const std::vector<double>& v, const std::vector<double>& x,
                     const std::vector<double>& b) {
  double worst = 0;
  for (int r = 0; r < p.n; ++r) {
    double s = -b[static_cast<std::size_t>(r)];
    for (int q = p.row_ptr[static_cast<std::size_t>(r)]; q < p.row_ptr[static_cast<std::size_t>(r) + 1]; ++q)
      s += v[static_cast<std::size_t>(q)] * x[static_cast<std::size_t>(p.col[static_cast<std::size_t>(q)])];
    worst = std::max(worst, std::abs(s));
  }
  return worst;
}

// A one-step simulation after two stages of one step (zero step, build, analyze, warm-up): 18
// further steps of 1 ms allocate nothing.
template <class Sim>
void check_one_step_steps_do_not_allocate(Sim& sim) {
  sim.run({.end = 1e-3, .smax = 1e-3});
  sim.run({.end = 2e-3, .smax = 1e-3});
  run_statistics many{};
  const allocation_counts counts = count_allocations([&] { many = sim.run({.end = 20e-3, .smax = 1e-3}); });
  check_none(counts);
  CHECK(many.steps == 18);
}

// bdf_simulation::run restarts its history at every stage (start_history: the stage's set-up,
// which sizes its tables anew); its steps must not allocate. So a stage of many steps allocates
// exactly what a stage of a few does.
template <class Sim>
void check_bdf_steps_do_not_allocate(Sim& sim, run_options o) {
  o.end = 0.02;
  sim.run(o);  // zero step, build, analyze, the first steps and orders
  o.end = 0.04;
  sim.run(o);  // warm-up of a later stage
  run_statistics few{}, many{};
  o.end = 0.05;
  const allocation_counts a = count_allocations([&] { few = sim.run(o); });
  o.end = 0.4;
  const allocation_counts b = count_allocations([&] { many = sim.run(o); });
  MESSAGE("BDF stages of ", few.steps, " and ", many.steps, " steps: ", a.news, " / ", b.news, " news, ", a.mallocs,
          " / ", b.mallocs, " mallocs (the set-up of a stage)");
  CHECK(many.steps > few.steps + 20);
  CHECK(b.news == a.news);
  CHECK(b.deletes == a.deletes);
  CHECK(b.mallocs == a.mallocs);
}

}  // namespace

// ---------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------

TEST_SUITE("core/allocation") {
  TEST_CASE("the counting hooks see an allocation while armed, and only then") {
    std::vector<int>* outside = new std::vector<int>(100, 1);  // not armed: not counted
    const allocation_counts c = count_allocations([&] {
      std::vector<int> v(1000, 2);
      // Heap storage reached through a volatile pointer, so the pair is not elided.
      int* volatile q = new int[64];
      q[0] = v[999];
      delete[] q;
    });
    delete outside;
    CHECK(c.news >= 1);  // the compiler may elide the vector's allocation, not the volatile one
    CHECK(c.deletes == c.news);
    if (counts_malloc) {
      // Eigen's dynamic storage goes to malloc directly, not through operator new.
      double sum = 0;
      const allocation_counts ce = count_allocations([&] {
        Eigen::VectorXd big = Eigen::VectorXd::Ones(1000);
        double* volatile data = big.data();
        sum = data[0] + big.sum();
      });
      CHECK(sum == doctest::Approx(1001.0));
      CHECK(ce.mallocs >= 1);
      CHECK(ce.news == 0);
    } else {
      MESSAGE("malloc is not interposed here (sanitizer or non-glibc): only operator new/delete are counted");
    }
    CHECK(armed == 0);
  }

  TEST_CASE("no library element allocates in evaluate (with and without the Jacobian)") {
    check_all_elements(library_elements{});
  }

  TEST_CASE("condensed super-elements do not allocate in evaluate (their Newton iterations are fixed-size)") {
    check_element_does_not_allocate<pradis_condensed_tests::star>();
    check_element_does_not_allocate<pradis_condensed_tests::beam_parts>();
    check_element_does_not_allocate<pradis_condensed_tests::beam2>();  // an inner rotational node condensed
  }

  TEST_CASE("assembler::evaluate over a built planar chain (N = 50) does not allocate") {
    auto run = [](auto& m) {
      using M = std::remove_cvref_t<decltype(m)>;
      build_chain(m, 50);
      new_integration(m);
      std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
      prescribed[0] = 1;
      assembler<M> a;
      a.build(m, prescribed);
      REQUIRE(a.equations() == 150);
      global_state s;
      s.resize(m.dof_count());
      for (int d = 1; d < m.dof_count(); ++d) {
        s.u(d) = 1e-3 * std::sin(0.37 * d);
        s.v(d) = 1e-2 * std::cos(0.37 * d);
        s.a(d) = 0.1 * std::sin(0.74 * d);
      }
      const jacobian_coefficients c = newmark{}.coefficients(1e-3);
      call_info with_jacobian{0.5, 1e-3, 2, 1, true, nullptr};
      call_info flows_only{0.5, 1e-3, 2, 0, false, nullptr};
      a.keep_blocks(true);                 // the BDF driver's kept blocks (reform) as well
      a.evaluate(m, s, c, with_jacobian);  // warm-up, outside the probe
      const allocation_counts counts = count_allocations([&] {
        a.evaluate(m, s, c, with_jacobian);
        a.evaluate(m, s, c, flows_only);
        a.evaluate(m, s, c, with_jacobian);
        a.reform(c);
      });
      check_none(counts);
      CHECK(a.residual().allFinite());
    };
    SUBCASE("model listing the chain's element types") {
      model<planar_inertia, planar_link, constant_force> m;
      run(m);
    }
    SUBCASE("library_model") {
      library_model m;
      run(m);
    }
  }

  TEST_CASE("sparse_lu factorize and solve do not allocate after analyze") {
    auto check_matrix = [](const linalg::sparsity_pattern& p, const std::vector<double>& values) {
      linalg::sparse_lu<linalg::min_degree_ordering> lu;
      lu.analyze(p);
      std::vector<double> b(static_cast<std::size_t>(p.n));
      for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::sin(1.0 + static_cast<double>(i));
      std::vector<double> x = b;
      lu.factorize(values);  // warm-up, outside the probe
      const allocation_counts counts = count_allocations([&] {
        lu.factorize(values);
        lu.solve(x);
        lu.factorize(values);
      });
      check_none(counts);
      x = b;
      lu.solve(x);
      CHECK(residual_norm(p, values, x, b) < 1e-9);
    };
    SUBCASE("5-point grid 30 x 30 (fill-in)") {
      const grid_matrix g = make_grid(30);
      check_matrix(g.pattern, g.values);
    }
    SUBCASE("saddle point: grid 10 x 10 with 20 zero-diagonal constraint rows, and the condition estimate") {
      const grid_matrix g = make_grid(10);
      std::vector<std::pair<int, int>> ij;
      std::vector<double> v;
      for (int r = 0; r < 100; ++r)
        for (int q = g.pattern.row_ptr[static_cast<std::size_t>(r)]; q < g.pattern.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
          ij.emplace_back(r, g.pattern.col[static_cast<std::size_t>(q)]);
          v.push_back(g.values[static_cast<std::size_t>(q)]);
        }
      for (int c = 0; c < 20; ++c) {  // constraint c: u_{5c} - u_{5c+1} = 0, zero diagonal stored
        const int r = 100 + c;
        for (const auto& [j, w] : {std::pair{5 * c, 1.0}, std::pair{5 * c + 1, -1.0}}) {
          ij.emplace_back(r, j), v.push_back(w);
          ij.emplace_back(j, r), v.push_back(w);
        }
        ij.emplace_back(r, r), v.push_back(0.0);
      }
      const auto p = linalg::sparsity_pattern::from_entries(120, ij);
      std::vector<double> values(static_cast<std::size_t>(p.nnz()), 0.0);
      for (std::size_t k = 0; k < ij.size(); ++k)
        values[static_cast<std::size_t>(p.find(ij[k].first, ij[k].second))] += v[k];
      linalg::sparse_lu<linalg::min_degree_ordering> lu;
      lu.analyze(p);
      lu.factorize(values);  // warm-up: finds the zero diagonals and re-analyses once
      CHECK(lu.statistics().reanalyses == 1);
      std::vector<double> x(120, 1.0);
      const allocation_counts counts = count_allocations([&] {
        lu.factorize(values);
        lu.solve(x);
        lu.estimate_condition();
      });
      check_none(counts);
      CHECK(lu.statistics().reanalyses == 1);
      CHECK(lu.statistics().perturbed_pivots == 0);
    }
    SUBCASE("Newton matrix of the planar chain (N = 50)") {
      model<planar_inertia, planar_link, constant_force> m;
      build_chain(m, 50);
      new_integration(m);
      std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
      prescribed[0] = 1;
      assembler<decltype(m)> a;
      a.build(m, prescribed);
      global_state s;
      s.resize(m.dof_count());
      a.evaluate(m, s, newmark{}.coefficients(1e-3), call_info{});
      const std::vector<double> values(a.values().begin(), a.values().end());
      check_matrix(a.pattern(), values);
    }
  }

  TEST_CASE("simulation::run of further steps does not allocate once the first stage has run") {
    model<planar_inertia, planar_link, constant_force> m;
    build_chain(m, 50);
    simulation sim(m);
    sim.run({.end = 1e-3, .smax = 1e-3});  // zero step, build, analyze, first step
    sim.run({.end = 2e-3, .smax = 1e-3});  // warm-up of a later stage
    run_statistics one{}, many{};
    const allocation_counts counts = count_allocations([&] {
      one = sim.run({.end = 3e-3, .smax = 1e-3});
      many = sim.run({.end = 19e-3, .smax = 1e-3});
    });
    check_none(counts);
    CHECK(one.steps == 1);
    CHECK(many.steps == 16);
    CHECK(std::isfinite(sim.v(dof{m.dof_count() - 2})));
  }

  TEST_CASE("BDF steps under error control do not allocate (a stage allocates its set-up only)") {
    model<planar_inertia, planar_link, constant_force> m;
    build_chain(m, 50);
    bdf_simulation sim(m);
    check_bdf_steps_do_not_allocate(sim, {.smax = 1e-3, .error_control = true, .dabsx = 1e-6, .drltx = 1e-6});
    CHECK(std::isfinite(sim.v(dof{m.dof_count() - 2})));
  }

  TEST_CASE("steps of a body on a ground pivot (slaved translations: the carry and the projection) do not "
            "allocate, under HHT and BDF") {
    using model_type = model<rigid_body, exact_spherical_joint, spatial_force, initial_rotation>;
    const auto build = [](model_type& m) {
      const auto x = m.add_dofs(3, "x");
      const rotation_node r = m.add_rotation_node("r");
      m.add<rigid_body>("body", {1, 0.01, 0.01, 0.02, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
      const elements::detail::joint_geometry tip{0, 0, 0, 0, 0, 0, 0, 0, 0.1, 0, 0, -0.1};
      elements::add_ground_pivot(m, "tip", tip, x[0], x[1], x[2], r);
      m.add<spatial_force>("weight", {0, 0, -9.81, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
      m.add<initial_rotation>("start", {1, 0, 0, 30, 0, 0, 30}, r);
      return r;
    };
    {
      model_type m;
      const rotation_node r = build(m);
      simulation sim(m, hht(-0.1));
      check_one_step_steps_do_not_allocate(sim);
      CHECK(std::isfinite(sim.u(r.q4)));
    }
    {
      model_type m;
      const rotation_node r = build(m);
      bdf_simulation sim(m);
      check_bdf_steps_do_not_allocate(sim, {.smax = 1e-3, .error_control = true, .dabsx = 1e-6, .drltx = 1e-6});
      CHECK(std::isfinite(sim.u(r.q4)));
    }
  }

  TEST_CASE("steps of a spatial model (BODY3, M3B, F3B, F3A on a rotational node with its norm equation) "
            "do not allocate") {
    model<rigid_body, body_torque, body_force, offset_force, initial_rotation> m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    m.add<rigid_body>("body", rigid_body::example(), x[0], x[1], x[2], r);
    m.add<body_torque>("torque", body_torque::example(), r);
    m.add<body_force>("force", body_force::example(), x[0], x[1], x[2], r);
    m.add<offset_force>("weight", offset_force::example(), x[0], x[1], x[2], r);
    m.add<initial_rotation>("start", initial_rotation::example(), r);
    simulation sim(m);
    check_one_step_steps_do_not_allocate(sim);
    CHECK(std::isfinite(sim.u(r.q4)));
  }

  TEST_CASE("steps of a spatial model with the connecting elements SD3, RSD3, SPH3, REV3, SHC3 (ends on the ground) do not allocate") {
    model<rigid_body, spatial_spring_damper, rotational_spring_damper, spherical_joint, revolute_joint, shaft_coupling,
          velocity_source, initial_rotation>
        m;
    const auto xa = m.add_dofs(3, "xa");
    const auto xb = m.add_dofs(3, "xb");
    const rotation_node ra = m.add_rotation_node("ra"), rb = m.add_rotation_node("rb");
    const dof g = m.ground();
    m.add<rigid_body>("a", rigid_body::example(), xa[0], xa[1], xa[2], ra);
    m.add<rigid_body>("b", rigid_body::example(), xb[0], xb[1], xb[2], rb);
    m.add<spatial_spring_damper>("sd", spatial_spring_damper::example(), xa[0], xa[1], xa[2], ra, xb[0], xb[1], xb[2],
                                 rb);
    m.add<rotational_spring_damper>("rsd", rotational_spring_damper::example(), g, g, g, rb);
    m.add<spherical_joint>("ball", spherical_joint::example(), g, g, g, g, g, g, xa[0], xa[1], xa[2], ra);
    m.add<revolute_joint>("hinge", revolute_joint::example(), xa[0], xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
    const dof shaft = m.add_dof("shaft");
    m.add<shaft_coupling>("coupling", shaft_coupling::example(), shaft, rb);
    m.add<velocity_source>("drive", {0, 0, 0, 2.0}, shaft);
    m.add<initial_rotation>("start", initial_rotation::example(), ra);
    simulation sim(m);
    check_one_step_steps_do_not_allocate(sim);
    CHECK(std::isfinite(sim.u(rb.q4)));
  }

  TEST_CASE("steps of a spatial beam model (BEAM3, BEAMI3, M3B) do not allocate") {
    model<elastic_beam, beam_inertia, body_torque> m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    const beam_inertia::parameters in{7800, 1e-4, 1e-9, 1e-9, 2e-9, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    m.add<elastic_beam>("beam", {2e11, 8e10, 1e-4, 1e-9, 1e-9, 2e-9, 0, 0, 0, 1, 0, 0, 0, 1, 0}, m.ground(), m.ground(),
                        m.ground(), m.ground(), m.ground(), m.ground(), x[0], x[1], x[2], r);
    m.add<beam_inertia>("mass", in, m.ground(), m.ground(), m.ground(), m.ground(), m.ground(), m.ground(), x[0], x[1],
                        x[2], r);
    m.add<body_torque>("torque", {0.01, 0.02, -0.01, 0, 0, 0, 0, 0}, r);
    simulation sim(m);
    check_one_step_steps_do_not_allocate(sim);
    CHECK(std::isfinite(sim.u(r.q4)));
  }
}
