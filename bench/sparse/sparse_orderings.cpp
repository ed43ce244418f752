// Sparse orderings and factorisation kernels, all contenders in one process:
//   pradis sparse_lu with every ordering policy (natural, row_count, initial_fill, min_degree,
//   min_fill, and AMD's permutation when SuiteSparse is available),
//   SuiteSparse KLU (klu_analyze / klu_factor / klu_refactor / klu_solve, BTF + AMD),
//   Eigen SparseLU with COLAMD,
//   and AMD's own fill (amd_order + its symbolic count) as the reference.
// Matrices: 2D 5-point grids, 3D 7-point grids, planar truss girders (2 DOFs per node).
//
// google-benchmark times one REFACTORISATION per iteration (same pattern, same values; for
// Eigen SparseLU, which has no refactorisation, a full factorize()). Ordering, first
// factorisation and solve are timed once per contender in its setup (solve: mean over repeats).
// All times in the CSV are process CPU seconds (robust against a loaded machine); the
// refactorisation time is the mean over the iterations of google-benchmark's final run.
// pradis order_s is the ordering policy alone (symbolic factorisation not included); KLU's is
// klu_analyze (BTF + AMD + its symbolic analysis); Eigen's is analyzePattern (COLAMD + etree).
// At the end one CSV table is written:
//   matrix,n,nnz_a,solver,ordering,nnz_factor,order_s,factor_s,refactor_s,solve_s
// Flags (besides google-benchmark's): --csv=PATH (default docs/data/sparse_orderings.csv),
// --small (smallest size of each family only: the CTest smoke run),
// --thresholds=PATH (only the OPTIM threshold sweep on small matrices, see run_thresholds()),
// --max-n=N (with --thresholds: only the matrices with n <= N; a quick before/after check).
// Weak orderings are skipped where they are hopeless (natural on large 2D/3D grids,
// row_count/initial_fill above 5000 DOFs); min_fill is skipped on the 32^3 grid (its exact
// deficiency updates cost O(fill * degree), about half a minute already on 24^3).

#include <benchmark/benchmark.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/linalg/sparsity.hpp"

#ifdef PRADIS_BENCH_HAVE_SUITESPARSE
#include <amd.h>
#include <klu.h>
#endif

namespace {

using namespace pradis::linalg;
/// All times are PROCESS CPU times (clock_gettime(CLOCK_PROCESS_CPUTIME_ID)); every contender
/// is single-threaded, and CPU time is robust against other load on the machine, which wall
/// time is not.
struct clock_type {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};

double seconds_since(double t0) { return clock_type::now() - t0; }

/// Mean time of f() over repeats until at least min_total seconds (at least 3, at most 1000).
template <class F>
double mean_time(F&& f, double min_total = 0.05) {
  int reps = 0;
  const auto t0 = clock_type::now();
  double el = 0;
  do {
    f();
    ++reps;
    el = seconds_since(t0);
  } while ((reps < 3 || el < min_total) && reps < 1000);
  return el / reps;
}

enum class family { grid2d, grid3d, truss };

struct test_matrix {
  std::string name;
  family fam;
  sparsity_pattern pattern;
  std::vector<double> values;  // CSR order
};

test_matrix from_triplets(std::string name, family fam, int n, const std::vector<std::pair<int, int>>& ij,
                          const std::vector<double>& v) {
  test_matrix m{std::move(name), fam, sparsity_pattern::from_entries(n, ij), {}};
  m.values.assign(static_cast<std::size_t>(m.pattern.nnz()), 0.0);
  // from_entries sorts; find each entry once (setup only).
  for (std::size_t k = 0; k < ij.size(); ++k) m.values[m.pattern.find(ij[k].first, ij[k].second)] += v[k];
  return m;
}

/// 5-point (2D) / 7-point (3D) convection-diffusion-like operator: diagonally dominant,
/// numerically non-symmetric (-1.1 / -0.9 off the diagonal).
test_matrix grid(int k, int dim) {
  const int n = dim == 2 ? k * k : k * k * k;
  std::vector<std::pair<int, int>> ij;
  std::vector<double> v;
  ij.reserve(static_cast<std::size_t>(n) * (2 * dim + 1));
  v.reserve(ij.capacity());
  const int stride[3] = {1, k, k * k};
  for (int i = 0; i < n; ++i) {
    ij.emplace_back(i, i);
    v.push_back(2.0 * dim + 0.01);
    int rem = i;
    for (int d = 0; d < dim; ++d) {
      const int c = rem % k;
      rem /= k;
      if (c > 0) { ij.emplace_back(i, i - stride[d]); v.push_back(-1.1); }
      if (c + 1 < k) { ij.emplace_back(i, i + stride[d]); v.push_back(-0.9); }
    }
  }
  return from_triplets((dim == 2 ? "grid2d_k" : "grid3d_k") + std::to_string(k), dim == 2 ? family::grid2d : family::grid3d,
                       n, ij, v);
}

/// Jacobian of a planar truss girder: ny x nx nodes (numbered along the height first), bars
/// to the right, up and both diagonals of each panel; 2 DOFs per node, 2x2 blocks
/// k * c c^T per bar, a mass term on the diagonal (diagonal-heavy, as M/h^2 + K), and
/// off-diagonal blocks scaled by 1 +- 0.1 sin(bar) (numerically non-symmetric).
test_matrix truss(int ny, int nx) {
  const int nodes = nx * ny, n = 2 * nodes;
  std::vector<std::pair<int, int>> ij;
  std::vector<double> v;
  auto id = [ny](int x, int y) { return x * ny + y; };
  for (int i = 0; i < n; ++i) {
    ij.emplace_back(i, i);
    v.push_back(8.0);
  }
  int bar = 0;
  auto add_bar = [&](int a, int b, double cx, double cy) {
    const double len = std::sqrt(cx * cx + cy * cy);
    const double c[2] = {cx / len, cy / len};
    const double s = 1.0 + 0.1 * std::sin(static_cast<double>(bar++));
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) {
        const double kpq = c[p] * c[q] / len;
        ij.emplace_back(2 * a + p, 2 * a + q); v.push_back(kpq);
        ij.emplace_back(2 * b + p, 2 * b + q); v.push_back(kpq);
        ij.emplace_back(2 * a + p, 2 * b + q); v.push_back(-kpq * s);
        ij.emplace_back(2 * b + p, 2 * a + q); v.push_back(-kpq / s);
      }
  };
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y) {
      if (x + 1 < nx) add_bar(id(x, y), id(x + 1, y), 1, 0);
      if (y + 1 < ny) add_bar(id(x, y), id(x, y + 1), 0, 1);
      if (x + 1 < nx && y + 1 < ny) {
        add_bar(id(x, y), id(x + 1, y + 1), 1, 1);
        add_bar(id(x + 1, y), id(x, y + 1), -1, 1);
      }
    }
  return from_triplets("truss_" + std::to_string(ny) + "x" + std::to_string(nx), family::truss, n, ij, v);
}

struct csv_row {
  std::string matrix;
  int n = 0;
  long nnz_a = 0;
  std::string solver, ordering;
  long nnz_factor = 0;
  double order_s = -1, factor_s = -1, refactor_s = -1, solve_s = -1;  // < 0: not applicable
};

std::vector<std::shared_ptr<csv_row>> g_rows;

/// Max |x - 1| for a solution of A x = A * ones (a sanity check of every contender).
double check_solution(const test_matrix& m, const std::function<void(std::vector<double>&)>& solve) {
  std::vector<double> b(static_cast<std::size_t>(m.pattern.n), 0.0);
  for (int i = 0; i < m.pattern.n; ++i)
    for (int q = m.pattern.row_ptr[i]; q < m.pattern.row_ptr[i + 1]; ++q) b[i] += m.values[q];
  solve(b);
  double err = 0;
  for (const double x : b) err = std::max(err, std::abs(x - 1.0));
  return err;
}

void warn_if_wrong(const csv_row& r, double err) {
  if (!(err < 1e-6))
    std::fprintf(stderr, "WARNING: %s %s/%s: solution error %.3g\n", r.matrix.c_str(), r.solver.c_str(),
                 r.ordering.c_str(), err);
}

#ifdef PRADIS_BENCH_HAVE_SUITESPARSE
/// Ordering policy that returns AMD's permutation (for pradis's kernel on AMD's order).
struct amd_ordering {
  static constexpr std::string_view name = "amd";
  std::vector<int> operator()(const sparsity_pattern& a) const {
    std::vector<int> perm(static_cast<std::size_t>(a.n));
    double control[AMD_CONTROL], info[AMD_INFO];
    amd_defaults(control);
    if (a.n > 0 && amd_order(a.n, a.row_ptr.data(), a.col.data(), perm.data(), control, info) < AMD_OK)
      throw std::runtime_error("amd_order failed");
    return perm;
  }
};
#endif

/// pradis sparse_lu with one ordering policy.
template <class Ordering>
void register_pradis(const std::shared_ptr<const test_matrix>& m) {
  auto row = std::make_shared<csv_row>();
  row->matrix = m->name;
  row->n = m->pattern.n;
  row->nnz_a = m->pattern.nnz();
  row->solver = "pradis";
  row->ordering = std::string(Ordering::name);
  g_rows.push_back(row);
  auto lu = std::make_shared<sparse_lu<Ordering>>();
  benchmark::RegisterBenchmark(("pradis/" + row->ordering + "/" + m->name).c_str(),
                               [m, row, lu](benchmark::State& state) {
                                 if (!lu->factorized()) {
                                   const auto to = clock_type::now();
                                   benchmark::DoNotOptimize(Ordering{}(m->pattern));
                                   row->order_s = seconds_since(to);
                                   lu->analyze(m->pattern);
                                   row->nnz_factor = lu->statistics().nnz_factor;
                                   const auto t0 = clock_type::now();
                                   lu->factorize(m->values);
                                   row->factor_s = seconds_since(t0);
                                   std::vector<double> b(static_cast<std::size_t>(m->pattern.n), 1.0);
                                   row->solve_s = mean_time([&] {  // b reset: repeated solves would overflow
                                     std::fill(b.begin(), b.end(), 1.0);
                                     lu->solve(b);
                                   });
                                   warn_if_wrong(*row, check_solution(*m, [&](std::vector<double>& x) { lu->solve(x); }));
                                 }
                                 const auto t0 = clock_type::now();
                                 for (auto _ : state) lu->factorize(m->values);
                                 row->refactor_s = seconds_since(t0) / static_cast<double>(state.iterations());
                                 state.counters["nnz_factor"] = static_cast<double>(row->nnz_factor);
                               })
      ->Unit(benchmark::kMillisecond);
}

/// Eigen SparseLU with COLAMD (no refactorisation: the loop times factorize()).
void register_eigen(const std::shared_ptr<const test_matrix>& m) {
  auto row = std::make_shared<csv_row>();
  row->matrix = m->name;
  row->n = m->pattern.n;
  row->nnz_a = m->pattern.nnz();
  row->solver = "eigen_sparselu";
  row->ordering = "colamd";
  g_rows.push_back(row);
  using mat_t = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  struct state_t {
    mat_t a;
    Eigen::SparseLU<mat_t, Eigen::COLAMDOrdering<int>> lu;
    bool ready = false;
  };
  auto st = std::make_shared<state_t>();
  benchmark::RegisterBenchmark(("eigen_sparselu/colamd/" + m->name).c_str(),
                               [m, row, st](benchmark::State& state) {
                                 if (!st->ready) {
                                   std::vector<Eigen::Triplet<double, int>> t;
                                   for (int i = 0; i < m->pattern.n; ++i)
                                     for (int q = m->pattern.row_ptr[i]; q < m->pattern.row_ptr[i + 1]; ++q)
                                       t.emplace_back(i, m->pattern.col[q], m->values[q]);
                                   st->a.resize(m->pattern.n, m->pattern.n);
                                   st->a.setFromTriplets(t.begin(), t.end());
                                   st->a.makeCompressed();
                                   auto t0 = clock_type::now();
                                   st->lu.analyzePattern(st->a);
                                   row->order_s = seconds_since(t0);
                                   t0 = clock_type::now();
                                   st->lu.factorize(st->a);
                                   row->factor_s = seconds_since(t0);
                                   if (st->lu.info() != Eigen::Success) state.SkipWithError("SparseLU failed");
                                   // nnzL counts L's unit diagonal (supernodal storage), nnzU the diagonal.
                                   row->nnz_factor = static_cast<long>(st->lu.nnzL() + st->lu.nnzU()) - m->pattern.n;
                                   Eigen::VectorXd b = Eigen::VectorXd::Ones(m->pattern.n), x;
                                   row->solve_s = mean_time([&] { x = st->lu.solve(b); });
                                   warn_if_wrong(*row, check_solution(*m, [&](std::vector<double>& v) {
                                                   Eigen::Map<Eigen::VectorXd> vb(v.data(), m->pattern.n);
                                                   Eigen::VectorXd y = st->lu.solve(vb);
                                                   vb = y;
                                                 }));
                                   st->ready = true;
                                 }
                                 const auto t0 = clock_type::now();
                                 for (auto _ : state) st->lu.factorize(st->a);
                                 row->refactor_s = seconds_since(t0) / static_cast<double>(state.iterations());
                                 state.counters["nnz_factor"] = static_cast<double>(row->nnz_factor);
                               })
      ->Unit(benchmark::kMillisecond);
}

#ifdef PRADIS_BENCH_HAVE_SUITESPARSE
/// KLU with its defaults (BTF, AMD, partial pivoting with tol 0.001). The CSR arrays of A are
/// the CSC arrays of A^T, so KLU factors A^T and klu_tsolve solves A x = b.
void register_klu(const std::shared_ptr<const test_matrix>& m) {
  auto row = std::make_shared<csv_row>();
  row->matrix = m->name;
  row->n = m->pattern.n;
  row->nnz_a = m->pattern.nnz();
  row->solver = "klu";
  row->ordering = "btf+amd";
  g_rows.push_back(row);
  struct state_t {
    klu_common common{};
    klu_symbolic* sym = nullptr;
    klu_numeric* num = nullptr;
    std::vector<int> ap, ai;
    ~state_t() {
      if (num) klu_free_numeric(&num, &common);
      if (sym) klu_free_symbolic(&sym, &common);
    }
  };
  auto st = std::make_shared<state_t>();
  benchmark::RegisterBenchmark(("klu/btf+amd/" + m->name).c_str(),
                               [m, row, st](benchmark::State& state) {
                                 double* ax = const_cast<double*>(m->values.data());
                                 if (!st->num) {
                                   klu_defaults(&st->common);
                                   st->ap = m->pattern.row_ptr;
                                   st->ai = m->pattern.col;
                                   auto t0 = clock_type::now();
                                   st->sym = klu_analyze(m->pattern.n, st->ap.data(), st->ai.data(), &st->common);
                                   row->order_s = seconds_since(t0);
                                   t0 = clock_type::now();
                                   st->num = klu_factor(st->ap.data(), st->ai.data(), ax, st->sym, &st->common);
                                   row->factor_s = seconds_since(t0);
                                   if (!st->sym || !st->num) {
                                     state.SkipWithError("KLU failed");
                                     return;
                                   }
                                   row->nnz_factor =
                                       static_cast<long>(st->num->lnz) + st->num->unz - m->pattern.n + st->num->nzoff;
                                   std::vector<double> b(static_cast<std::size_t>(m->pattern.n), 1.0);
                                   row->solve_s =
                                       mean_time([&] {
                                         std::fill(b.begin(), b.end(), 1.0);
                                         klu_tsolve(st->sym, st->num, m->pattern.n, 1, b.data(), &st->common);
                                       });
                                   warn_if_wrong(*row, check_solution(*m, [&](std::vector<double>& x) {
                                                   klu_tsolve(st->sym, st->num, m->pattern.n, 1, x.data(), &st->common);
                                                 }));
                                 }
                                 const auto t0 = clock_type::now();
                                 for (auto _ : state) klu_refactor(st->ap.data(), st->ai.data(), ax, st->sym, st->num, &st->common);
                                 row->refactor_s = seconds_since(t0) / static_cast<double>(state.iterations());
                                 state.counters["nnz_factor"] = static_cast<double>(row->nnz_factor);
                               })
      ->Unit(benchmark::kMillisecond);
}

/// AMD reference: amd_order's time and its own symbolic count, nnz(L+U) = 2 Lnz + n.
void add_amd_reference(const test_matrix& m) {
  auto row = std::make_shared<csv_row>();
  row->matrix = m.name;
  row->n = m.pattern.n;
  row->nnz_a = m.pattern.nnz();
  row->solver = "amd_reference";
  row->ordering = "amd";
  std::vector<int> perm(static_cast<std::size_t>(m.pattern.n));
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  row->order_s = mean_time([&] { amd_order(m.pattern.n, m.pattern.row_ptr.data(), m.pattern.col.data(), perm.data(), control, info); }, 0.02);
  row->nnz_factor = 2 * static_cast<long>(info[AMD_LNZ]) + m.pattern.n;
  g_rows.push_back(row);
}
#endif

void write_csv(const std::string& path) {
  std::ofstream os(path);
  if (!os) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return;
  }
  os << "matrix,n,nnz_a,solver,ordering,nnz_factor,order_s,factor_s,refactor_s,solve_s\n";
  auto num = [](double x) {
    if (x < 0) return std::string();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return std::string(buf);
  };
  for (const auto& r : g_rows)
    os << r->matrix << ',' << r->n << ',' << r->nnz_a << ',' << r->solver << ',' << r->ordering << ','
       << r->nnz_factor << ',' << num(r->order_s) << ',' << num(r->factor_s) << ',' << num(r->refactor_s) << ','
       << num(r->solve_s) << '\n';
  std::printf("wrote %zu rows to %s\n", g_rows.size(), path.c_str());
}


/// Block chain: nb bodies of 2 DOFs in a row, each coupled to its neighbours (the Jacobian
/// pattern of a chain of planar bodies joined by links).
test_matrix chain2(int nb) {
  std::vector<std::pair<int, int>> ij;
  std::vector<double> v;
  const int n = 2 * nb;
  for (int b = 0; b < nb; ++b)
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) {
        ij.emplace_back(2 * b + p, 2 * b + q);
        v.push_back(p == q ? 8.0 : 0.5);
        if (b + 1 < nb) {
          ij.emplace_back(2 * b + p, 2 * (b + 1) + q);
          v.push_back(-1.1 + 0.1 * q);
          ij.emplace_back(2 * (b + 1) + p, 2 * b + q);
          v.push_back(-0.9 - 0.1 * q);
        }
      }
  return from_triplets("chain_" + std::to_string(nb), family::truss, n, ij, v);
}

/// One row of the OPTIM threshold sweep: cost of one ordering on one small matrix.
struct threshold_row {
  std::string matrix;
  int n = 0;
  int level = 0;
  long nnz_factor = 0;
  double analyze_s = 0, refactor_s = 0, solve_s = 0;
};

/// Median of `runs` mean times of f() (each mean over >= 3 calls and >= 5 ms).
template <class F>
double median_time(F&& f, int runs = 5) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) t.push_back(mean_time(f, 0.005));
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// Measures analyze (ordering + symbolic phase), refactorisation and solve for every OPTIM
/// level on small and middle-sized model-like matrices (2D and 3D grids, truss girders 2 and
/// 10 nodes high, 2-DOF body chains) with 2..~8000 DOFs, and writes them to a CSV. The cost of a level for a run with R
/// refactorisations per topology is analyze_s + R * (refactor_s + solve_s); see
/// docs/sparse.md for the crossovers that set automatic_level().
void run_thresholds(const std::string& path, int max_n) {
  std::vector<test_matrix> mats;
  for (int k = 2; k <= 32; ++k) mats.push_back(grid(k, 2));
  for (const int k : {40, 48, 64, 90}) mats.push_back(grid(k, 2));
  for (const int k : {4, 6, 8, 10, 13, 16}) mats.push_back(grid(k, 3));
  for (const int nx : {25, 50, 100, 200, 400}) mats.push_back(truss(10, nx));
  for (const int nx : {1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40, 50, 60, 80, 100, 125, 160, 200, 250})
    mats.push_back(truss(2, nx));
  for (const int nb : {1, 2, 3, 4, 5, 6, 8, 10, 15, 20, 25, 30, 40, 50, 75, 100, 150, 200, 300, 400, 500})
    mats.push_back(chain2(nb));
  std::erase_if(mats, [&](const test_matrix& m) { return m.pattern.n > max_n; });
  std::ofstream os(path);
  if (!os) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return;
  }
  os << "matrix,n,nnz_a,level,ordering,nnz_factor,analyze_s,refactor_s,solve_s\n";
  for (const auto& m : mats) {
    for (int level = optim_min_level; level <= optim_max_level; ++level) {
      sparse_lu<optim_ordering> lu(ordering_for_level(level));
      threshold_row r{m.name, m.pattern.n, level, 0, 0, 0, 0};
      r.analyze_s = median_time([&] { lu.analyze(m.pattern); });
      lu.factorize(m.values);
      r.nnz_factor = lu.statistics().nnz_factor;
      r.refactor_s = median_time([&] { lu.factorize(m.values); });
      std::vector<double> b(static_cast<std::size_t>(m.pattern.n), 1.0);
      r.solve_s = median_time([&] {
        std::fill(b.begin(), b.end(), 1.0);
        lu.solve(b);
      });
      char buf[256];
      std::snprintf(buf, sizeof buf, "%s,%d,%ld,%d,%s,%ld,%.4g,%.4g,%.4g\n", r.matrix.c_str(), r.n,
                    static_cast<long>(m.pattern.nnz()), level, std::string(ordering_name_for_level(level)).c_str(),
                    r.nnz_factor, r.analyze_s, r.refactor_s, r.solve_s);
      os << buf;
      std::fputs(buf, stdout);
    }
  }
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv = "docs/data/sparse_orderings.csv";
  bool small = false;
  std::string thresholds;
  int max_n = std::numeric_limits<int>::max();
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--csv=", 6) == 0) csv = argv[i] + 6;
    else if (std::strcmp(argv[i], "--small") == 0) small = true;
    else if (std::strncmp(argv[i], "--thresholds=", 13) == 0) thresholds = argv[i] + 13;
    else if (std::strncmp(argv[i], "--max-n=", 8) == 0) max_n = std::atoi(argv[i] + 8);
    else args.push_back(argv[i]);
  }
  if (!thresholds.empty()) {  // OPTIM threshold sweep only (no google-benchmark run)
    run_thresholds(thresholds, max_n);
    return 0;
  }
  int bargc = static_cast<int>(args.size());
  benchmark::Initialize(&bargc, args.data());
  if (benchmark::ReportUnrecognizedArguments(bargc, args.data())) return 1;

  std::vector<std::shared_ptr<const test_matrix>> mats;
  for (const int k : {32, 64, 128, 256}) {
    mats.push_back(std::make_shared<const test_matrix>(grid(k, 2)));
    if (small) break;
  }
  for (const int k : {8, 16, 24, 32}) {
    mats.push_back(std::make_shared<const test_matrix>(grid(k, 3)));
    if (small) break;
  }
  for (const int nx : {50, 150, 500, 1500, 5000}) {  // 1,000 .. 100,000 DOFs
    mats.push_back(std::make_shared<const test_matrix>(truss(10, nx)));
    if (small) break;
  }

  for (const auto& m : mats) {
    const int n = m->pattern.n;
    const bool natural_ok = m->fam == family::truss || (m->fam == family::grid2d && n <= 16384) ||
                            (m->fam == family::grid3d && n <= 4096);
    if (natural_ok) register_pradis<natural_ordering>(m);
    if (n <= 5000) {
      register_pradis<row_count_ordering>(m);
      register_pradis<initial_fill_ordering>(m);
    }
    register_pradis<min_degree_ordering>(m);
    if (!(m->fam == family::grid3d && n > 15000)) register_pradis<min_fill_ordering>(m);
#ifdef PRADIS_BENCH_HAVE_SUITESPARSE
    register_pradis<amd_ordering>(m);
    register_klu(m);
    add_amd_reference(*m);
#endif
    register_eigen(m);
  }

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  write_csv(csv);
  return 0;
}
