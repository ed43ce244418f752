// Tests of the PRADIS renumbering levels OPTIM 0..4: row_count, initial_fill, min_fill, and
// the automatic / run-time level selection.

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/linalg/ordering.hpp"
#include "linalg/fill_of.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace {
using pradis_linalg_test::fill_of;

using pradis::error;
using pradis::error_code;
using namespace pradis::linalg;
using entries_t = std::vector<std::pair<int, int>>;

sparsity_pattern grid_pattern(int nx, int ny) {
  entries_t e;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const int i = y * nx + x;
      e.emplace_back(i, i);
      if (x > 0) e.emplace_back(i, i - 1);
      if (x + 1 < nx) e.emplace_back(i, i + 1);
      if (y > 0) e.emplace_back(i, i - nx);
      if (y + 1 < ny) e.emplace_back(i, i + nx);
    }
  return sparsity_pattern::from_entries(nx * ny, e);
}

sparsity_pattern chain_pattern(int n) {
  entries_t e;
  for (int i = 0; i < n; ++i) {
    e.emplace_back(i, i);
    if (i > 0) e.emplace_back(i, i - 1);
    if (i + 1 < n) e.emplace_back(i, i + 1);
  }
  return sparsity_pattern::from_entries(n, e);
}

/// Random pattern with full diagonal; structurally symmetric or not.
sparsity_pattern random_pattern(int n, double density, unsigned seed, bool symmetric) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  entries_t e;
  for (int i = 0; i < n; ++i) {
    e.emplace_back(i, i);
    for (int j = 0; j < i; ++j)
      if (coin(rng) < density) {
        e.emplace_back(i, j);
        if (symmetric) e.emplace_back(j, i);
      }
  }
  return sparsity_pattern::from_entries(n, e);
}

bool is_permutation_of_iota(std::vector<int> p, int n) {
  if (static_cast<int>(p.size()) != n) return false;
  std::sort(p.begin(), p.end());
  for (int k = 0; k < n; ++k)
    if (p[k] != k) return false;
  return true;
}

std::vector<std::set<int>> adjacency_sets(const sparsity_pattern& p) {
  std::vector<std::set<int>> adj(p.n);
  for (int i = 0; i < p.n; ++i)
    for (int q = p.row_ptr[i]; q < p.row_ptr[i + 1]; ++q)
      if (p.col[q] != i) {
        adj[i].insert(p.col[q]);
        adj[p.col[q]].insert(i);
      }
  return adj;
}

std::int64_t deficiency(const std::vector<std::set<int>>& adj, int v) {
  std::int64_t missing = 0;
  for (auto a = adj[v].begin(); a != adj[v].end(); ++a)
    for (auto b = std::next(a); b != adj[v].end(); ++b)
      if (!adj[*a].count(*b)) ++missing;
  return missing;
}

/// Reference minimum deficiency: explicit elimination graph, exact recount at every step,
/// ties by degree then index.
std::vector<int> brute_force_min_fill(const sparsity_pattern& p) {
  auto adj = adjacency_sets(p);
  std::vector<bool> done(p.n, false);
  std::vector<int> perm;
  for (int step = 0; step < p.n; ++step) {
    int best = -1;
    std::int64_t bd = 0;
    for (int i = 0; i < p.n; ++i) {
      if (done[i]) continue;
      const std::int64_t d = deficiency(adj, i);
      if (best < 0 || d < bd || (d == bd && adj[i].size() < adj[best].size())) {
        best = i;
        bd = d;
      }
    }
    perm.push_back(best);
    done[best] = true;
    for (const int a : adj[best]) {
      adj[a].erase(best);
      for (const int b : adj[best])
        if (a != b) adj[a].insert(b);
    }
    adj[best].clear();
  }
  return perm;
}

}  // namespace

TEST_SUITE("linalg") {
  TEST_CASE("every ordering policy returns a permutation on grids, chains, random and empty patterns") {
    std::vector<sparsity_pattern> pats{grid_pattern(7, 5), chain_pattern(50), random_pattern(80, 0.05, 3u, true),
                                       random_pattern(80, 0.05, 4u, false), chain_pattern(1), sparsity_pattern{}};
    for (const auto& p : pats) {
      CAPTURE(p.n);
      CHECK(is_permutation_of_iota(natural_ordering{}(p), p.n));
      CHECK(is_permutation_of_iota(row_count_ordering{}(p), p.n));
      CHECK(is_permutation_of_iota(initial_fill_ordering{}(p), p.n));
      CHECK(is_permutation_of_iota(min_degree_ordering{}(p), p.n));
      CHECK(is_permutation_of_iota(min_fill_ordering{}(p), p.n));
      CHECK(is_permutation_of_iota(automatic_ordering{}(p), p.n));
      for (int level = 0; level <= 4; ++level) CHECK(is_permutation_of_iota(optim_ordering{level}(p), p.n));
    }
  }

  TEST_CASE("row_count orders rows by increasing initial count, stable on ties") {
    // Star 0-{1,2,3} plus edge 3-4: degrees 3,1,1,2,1.
    const auto p = sparsity_pattern::from_entries(
        5, entries_t{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}, {0, 1}, {0, 2}, {0, 3}, {3, 4}});
    CHECK(row_count_ordering{}(p) == std::vector<int>{1, 2, 4, 3, 0});
    // A grid: corners (degree 2) first in index order, then edges (3), then interior (4).
    const auto g = row_count_ordering{}(grid_pattern(3, 3));
    CHECK(g == std::vector<int>{0, 2, 6, 8, 1, 3, 5, 7, 4});
  }

  TEST_CASE("initial_fill orders rows by the fill of eliminating them first, ties by degree then index") {
    // Triangle 0-1-2 with a pendant 3 on 2 and a path 3-4: deficiencies
    // 0:0 (N={1,2} adjacent), 1:0, 2:2 (N={0,1,3}: 0-3, 1-3 missing), 3:1 (N={2,4}), 4:0.
    const auto p = sparsity_pattern::from_entries(
        5, entries_t{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}, {0, 1}, {1, 2}, {0, 2}, {2, 3}, {3, 4}});
    // deficiency 0: nodes 4 (degree 1), 0 and 1 (degree 2) -> 4, 0, 1; then 3 (1), then 2 (2).
    CHECK(initial_fill_ordering{}(p) == std::vector<int>{4, 0, 1, 3, 2});
    // On a grid the corners create one fill each, edges three, interior six.
    CHECK(initial_fill_ordering{}(grid_pattern(3, 3)) == std::vector<int>{0, 2, 6, 8, 1, 3, 5, 7, 4});
  }

  TEST_CASE("min_fill picks exactly the minimum-deficiency node (ties by degree, index) at every step") {
    for (const unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
      for (const double density : {0.04, 0.1, 0.25}) {
        const auto p = random_pattern(45, density, seed * 17u + static_cast<unsigned>(density * 100), seed % 2 == 1);
        CAPTURE(seed);
        CAPTURE(density);
        CHECK(min_fill_ordering{}(p) == brute_force_min_fill(p));
      }
    }
    CHECK(min_fill_ordering{}(grid_pattern(8, 6)) == brute_force_min_fill(grid_pattern(8, 6)));
  }

  TEST_CASE("initial deficiencies (triangle counting) match a brute-force count, hubs included") {
    std::vector<sparsity_pattern> pats{random_pattern(60, 0.1, 7u, true), random_pattern(60, 0.3, 8u, false),
                                       grid_pattern(5, 4)};
    {  // hub 0 tied to every node of a chain 1..39
      entries_t e;
      for (int i = 0; i < 40; ++i) {
        e.emplace_back(i, i);
        if (i > 0) e.emplace_back(0, i);
        if (i > 1) e.emplace_back(i - 1, i);
      }
      pats.push_back(sparsity_pattern::from_entries(40, e));
    }
    for (const auto& p : pats) {
      const auto def = pradis::linalg::detail::node_deficiencies(symmetric_adjacency(p));
      const auto adj = adjacency_sets(p);
      for (int v = 0; v < p.n; ++v) {
        CAPTURE(v);
        CHECK(def[v] == deficiency(adj, v));
      }
    }
    CHECK(brute_force_min_fill(pats.back()) == min_fill_ordering{}(pats.back()));
  }

  TEST_CASE("min_fill orders a 50,000-node hub-and-chain graph without fill (its time is reported)") {
    // Without lazy deletion this graph costs O(n^2) (seconds); the time is printed, not
    // asserted: speed is measured by bench/sparse (pradis_bench_sparse), never by a timed
    // test on a shared machine.
    const int n = 50000;
    entries_t e;
    for (int i = 0; i < n; ++i) {
      e.emplace_back(i, i);
      if (i > 0) e.emplace_back(0, i);
      if (i > 1) e.emplace_back(i - 1, i);
    }
    const auto p = sparsity_pattern::from_entries(n, e);
    sparse_lu<min_fill_ordering> lu;
    lu.analyze(p);
    CHECK(lu.statistics().fill == 0);
    MESSAGE("hub + chain, n = 50000: min_fill ordering " << lu.statistics().order_seconds << " s");
  }

  TEST_CASE("min_fill gives no more fill than min_degree on 30x30 and 60x60 grids, and far less than row_count") {
    for (const int k : {30, 60}) {
      const auto p = grid_pattern(k, k);
      const long f_md = fill_of<min_degree_ordering>(p);
      const long f_mf = fill_of<min_fill_ordering>(p);
      const long f_rc = fill_of<row_count_ordering>(p);
      const long f_if = fill_of<initial_fill_ordering>(p);
      const long f_nat = fill_of<natural_ordering>(p);
      MESSAGE(k << "x" << k << " grid fill: natural " << f_nat << ", row_count " << f_rc << ", initial_fill " << f_if
                << ", min_degree " << f_md << ", min_fill " << f_mf);
      CHECK(f_mf <= f_md);
      CHECK(f_md < f_rc);
    }
  }

  TEST_CASE("every ordering leaves a chain without fill; min_fill orders a 100,000-node chain quickly") {
    const auto c = chain_pattern(2000);
    CHECK(fill_of<natural_ordering>(c) == 0);
    CHECK(fill_of<row_count_ordering>(c) == 0);
    CHECK(fill_of<initial_fill_ordering>(c) == 0);
    CHECK(fill_of<min_degree_ordering>(c) == 0);
    CHECK(fill_of<min_fill_ordering>(c) == 0);
    CHECK(fill_of<automatic_ordering>(c) == 0);
    sparse_lu<min_fill_ordering> lu;
    lu.analyze(chain_pattern(100000));
    CHECK(lu.statistics().fill == 0);
    CHECK(is_permutation_of_iota(lu.permutation(), 100000));
  }

  TEST_CASE("min_degree leaves trees without fill and orders an arrow matrix's hub last") {
    // A random tree (every node tied to one earlier node): a leaf always has degree 1.
    {
      std::mt19937 rng(5u);
      entries_t e{{0, 0}};
      for (int i = 1; i < 3000; ++i) {
        e.emplace_back(i, i);
        e.emplace_back(i, static_cast<int>(rng() % static_cast<unsigned>(i)));
      }
      CHECK(fill_of<min_degree_ordering>(sparsity_pattern::from_entries(3000, e)) == 0);
    }
    // Arrow matrices, hub first: the hub alone (star) or the hub tied to a chain. n = 1000 and
    // 100000 take the dense-node path (hub degree above 10 sqrt(n)), the small ones do not.
    for (const int n : {4, 8, 50, 1000, 100000}) {
      for (const bool with_chain : {false, true}) {
        entries_t e;
        for (int i = 0; i < n; ++i) {
          e.emplace_back(i, i);
          if (i > 0) e.emplace_back(0, i);
          if (with_chain && i > 1) e.emplace_back(i - 1, i);
        }
        const auto p = sparsity_pattern::from_entries(n, e);
        CAPTURE(n);
        CAPTURE(with_chain);
        const auto perm = min_degree_ordering{}(p);
        REQUIRE(is_permutation_of_iota(perm, n));
        CHECK(perm.back() == 0);
        CHECK(fill_of<min_degree_ordering>(p) == 0);
      }
    }
  }

  TEST_CASE("min_degree is deterministic, sees A + A^T, and handles 0x0, 1x1 and isolated nodes") {
    for (const unsigned seed : {11u, 12u, 13u}) {
      const auto p = random_pattern(300, 0.01, seed, false);
      const auto perm = min_degree_ordering{}(p);
      CHECK(min_degree_ordering{}(p) == perm);
      const sparsity_pattern copy = p;
      CHECK(min_degree_ordering{}(copy) == perm);
      // The order of a non-symmetric pattern is the order of its symmetrisation A + A^T.
      entries_t sym;
      for (int i = 0; i < p.n; ++i)
        for (int q = p.row_ptr[i]; q < p.row_ptr[i + 1]; ++q) {
          sym.emplace_back(i, p.col[q]);
          sym.emplace_back(p.col[q], i);
        }
      CHECK(min_degree_ordering{}(sparsity_pattern::from_entries(p.n, sym)) == perm);
    }
    CHECK(min_degree_ordering{}(sparsity_pattern{}).empty());
    CHECK(min_degree_ordering{}(chain_pattern(1)) == std::vector<int>{0});
    CHECK(min_degree_ordering{}(sparsity_pattern::from_entries(1, entries_t{})) == std::vector<int>{0});
    // Isolated nodes (no entry at all, or a diagonal only) among a grid.
    entries_t e;
    const auto g = grid_pattern(6, 6);
    for (int i = 0; i < g.n; ++i)
      for (int q = g.row_ptr[i]; q < g.row_ptr[i + 1]; ++q) e.emplace_back(i + 2, g.col[q] + 2);
    e.emplace_back(1, 1);
    const auto p = sparsity_pattern::from_entries(g.n + 3, e);  // nodes 0 and 38: no entry
    CHECK(is_permutation_of_iota(min_degree_ordering{}(p), p.n));
  }

  TEST_CASE("min_degree orders a 1,000,000-node chain without fill and a 300x300 grid (times reported)") {
    // The times are printed, not asserted (measured 0.11 s and 0.02 s at -O2; speed is
    // checked by bench/sparse, never by a timed test on a shared machine).
    sparse_lu<min_degree_ordering> lu;
    lu.analyze(chain_pattern(1000000));
    CHECK(lu.statistics().fill == 0);
    CHECK(is_permutation_of_iota(lu.permutation(), 1000000));
    MESSAGE("chain, n = 1,000,000: min_degree ordering " << lu.statistics().order_seconds << " s");
    sparse_lu<min_degree_ordering> g;
    g.analyze(grid_pattern(300, 300));
    MESSAGE("300x300 grid: min_degree ordering " << g.statistics().order_seconds << " s, fill "
                                                 << g.statistics().fill);
    CHECK(is_permutation_of_iota(g.permutation(), 90000));
  }

  TEST_CASE("automatic_ordering picks the documented OPTIM level at each size boundary") {
    // Thresholds re-measured with `pradis_bench_sparse --thresholds` (docs/sparse.md).
    const std::vector<std::pair<int, int>> expect{{0, 0},  {1, 0},   {2, 0},   {3, 1},   {9, 1},     {10, 3},
                                                  {49, 3}, {50, 3},  {199, 3}, {499, 3}, {500, 4}, {100000, 4}};
    for (const auto& e : expect) {
      const int n = e.first, level = e.second;  // not a structured binding: CAPTURE's lambda takes them
      CAPTURE(n);
      CHECK(automatic_level(n) == level);
      CHECK(optim_ordering{}.effective_level(n) == level);
    }
    // The automatic permutation is the one of the chosen policy, on a pattern where they differ.
    for (const int n : {2, 3, 9, 10, 49, 50, 499, 500}) {
      CAPTURE(n);
      const auto p = random_pattern(n, 0.3, 100u + static_cast<unsigned>(n), true);
      const auto got = automatic_ordering{}(p);
      switch (automatic_level(n)) {
        case 0: CHECK(got == natural_ordering{}(p)); break;
        case 1: CHECK(got == row_count_ordering{}(p)); break;
        case 2: CHECK(got == initial_fill_ordering{}(p)); break;
        case 3: CHECK(got == min_degree_ordering{}(p)); break;
        default: CHECK(got == min_fill_ordering{}(p)); break;
      }
    }
  }

  TEST_CASE("an OPTIM level is chosen by number; an invalid level is an invalid_option naming 0..4") {
    const auto p = grid_pattern(6, 6);
    CHECK(ordering_for_level(0)(p) == natural_ordering{}(p));
    CHECK(ordering_for_level(1)(p) == row_count_ordering{}(p));
    CHECK(ordering_for_level(2)(p) == initial_fill_ordering{}(p));
    CHECK(ordering_for_level(3)(p) == min_degree_ordering{}(p));
    CHECK(ordering_for_level(4)(p) == min_fill_ordering{}(p));
    CHECK(ordering_name_for_level(4) == "min_fill");
    sparse_lu<optim_ordering> lu(ordering_for_level(4));
    lu.analyze(p);
    CHECK(lu.permutation() == min_fill_ordering{}(p));
    for (const int bad : {-2, 5, 42}) {
      CAPTURE(bad);
      try {
        (void)ordering_for_level(bad);
        FAIL("no throw");
      } catch (const error& e) {
        CHECK(e.code() == error_code::invalid_option);
        CHECK(std::string(e.what()).find("0..4") != std::string::npos);
      }
      sparse_lu<optim_ordering> bad_lu(optim_ordering{bad});
      CHECK_THROWS_AS(bad_lu.analyze(p), error);
    }
  }
}
