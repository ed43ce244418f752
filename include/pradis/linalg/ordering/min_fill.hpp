#pragma once
/// \file
/// PRADIS renumbering method III (OPTIM 4, Tinney scheme 3): minimum local fill, also called
/// minimum deficiency, with EXACT fill scores maintained incrementally.

#include <cstdint>
#include <functional>
#include <queue>
#include <string_view>
#include <tuple>
#include <vector>

#include "pradis/linalg/ordering/initial_fill.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// Ordering policy "min_fill": at every step the uneliminated node whose elimination creates
/// the fewest new nonzeros (the fewest missing edges among its current neighbours) is chosen;
/// ties go to the smaller current degree, then to the lower original index, so the result
/// depends on nothing but the pattern. The pattern is treated as structurally symmetric.
///
/// Implementation: an explicit elimination graph (one duplicate-free adjacency vector per
/// node, membership tested with stamped marker arrays) and exact deficiencies updated
/// incrementally, never recomputed:
///  - removing the pivot p from a neighbour u loses the missing pairs {p, x}:
///    def(u) -= (deg(u) - 1) - |N(u) ∩ N(p)|;
///  - adding a fill edge {a, b} inside the new clique N(p) removes the missing pair {a, b}
///    from every common neighbour w (def(w) -= 1) and adds the pairs {b, x}, x in N(a) \ N(b)
///    to a (def(a) += |N(a)| - |N(a) ∩ N(b)|), and symmetrically to b.
/// Only the clique members and the common neighbours of new edges (nodes within distance 2
/// of p) change, and exactly those are re-queued. The cost is O(sum over fill edges {a,b}
/// of deg(b)) plus O(sum over pivots of |N(p)|^2 + sum over u in N(p) of deg(u)).
/// The minimum is taken from a binary heap of (deficiency, degree, index) with lazy deletion
/// (an entry is stale when its node is eliminated or its key no longer matches).
/// Measured (g++ -O2, CPU time, docs/data/sparse_orderings.csv): 0.27 s for a 128x128 and
/// 2.0 s for a 256x256 5-point grid, 1.2 s for a 100,000-DOF truss girder, 6.8 s for a 24^3
/// 7-point grid (3D cliques are large: the O(fill * degree) term dominates). Fill on 2D grids
/// is 0.75-0.99 of AMD's (0.75 at 256x256), on the truss 0.90.
/// Eliminated nodes are removed from adjacency lists lazily (skipped, compacted when half
/// dead), and the longest list of a clique is not scanned when its pivot is removed, so
/// eliminating the many neighbours of a "hub" (a node tied to very many DOFs) does not cost
/// the hub's degree each time unless fill edges are added to the hub.
struct min_fill_ordering {
  /// Policy name, "min_fill".
  static constexpr std::string_view name = "min_fill";

  /// Returns perm with perm[k] = original index of the k-th pivot.
  /// `a` must satisfy sparsity_pattern::is_valid().
  std::vector<int> operator()(const sparsity_pattern& a) const {
    const int n = a.n;
    std::vector<int> perm;
    if (n <= 0) return perm;
    perm.reserve(static_cast<std::size_t>(n));
    const sparsity_pattern g = symmetric_adjacency(a);
    std::vector<std::int64_t> def = detail::node_deficiencies(g);

    // adj[v] may still hold eliminated nodes (lazy deletion, so that eliminating a neighbour
    // of a high-degree node does not cost that node's degree); deg[v] is the live degree, and
    // a list is compacted once more than half of it is dead.
    std::vector<std::vector<int>> adj(static_cast<std::size_t>(n));
    std::vector<int> deg(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      adj[i].assign(g.col.begin() + g.row_ptr[i], g.col.begin() + g.row_ptr[i + 1]);
      deg[i] = static_cast<int>(adj[i].size());
    }

    using key_t = std::tuple<std::int64_t, int, int>;  // (deficiency, degree, index)
    std::priority_queue<key_t, std::vector<key_t>, std::greater<key_t>> heap;
    {
      std::vector<key_t> init;
      init.reserve(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) init.emplace_back(def[i], deg[i], i);
      heap = decltype(heap)(std::greater<key_t>{}, std::move(init));
    }

    std::vector<char> done(static_cast<std::size_t>(n), 0);
    std::vector<std::int64_t> kmark(static_cast<std::size_t>(n), -1);  // member of current N(p)
    std::vector<std::int64_t> amark(static_cast<std::size_t>(n), -1);  // member of current N(a)
    std::vector<std::int64_t> tmark(static_cast<std::size_t>(n), -1);  // touched this step
    std::vector<int> kpos(static_cast<std::size_t>(n), -1);            // index in the clique
    std::int64_t astamp = 0;
    std::vector<int> clique, touched;
    std::vector<std::int64_t> inside;  // per clique member: neighbours inside the clique

    for (int step = 0; step < n; ++step) {
      int p = -1;
      while (!heap.empty()) {
        const auto [d, dg, i] = heap.top();
        heap.pop();
        if (!done[i] && d == def[i] && dg == deg[i]) { p = i; break; }
      }
      // The heap always holds a current entry for every live node (every key change pushes).
      perm.push_back(p);
      done[p] = 1;
      clique.clear();
      for (const int u : adj[p])
        if (!done[u]) clique.push_back(u);
      std::vector<int>().swap(adj[p]);
      touched.clear();
      // The member with the longest list is never scanned in step 1: its edges inside the clique
      // are counted from the other ends.
      std::size_t big = 0;
      for (std::size_t iu = 0; iu < clique.size(); ++iu) {
        const int u = clique[iu];
        kmark[u] = step;
        kpos[u] = static_cast<int>(iu);
        tmark[u] = step;
        touched.push_back(u);
        if (adj[u].size() > adj[clique[big]].size()) big = iu;
      }

      // 1. Remove p from its neighbours' graphs (lazily); count each member's neighbours in
      // the clique: def(u) -= (deg(u) - 1) - |N(u) ∩ N(p)|.
      inside.assign(clique.size(), 0);
      for (std::size_t iu = 0; iu < clique.size(); ++iu) {
        if (iu == big) continue;
        for (const int x : adj[clique[iu]])
          if (kmark[x] == step && !done[x]) {
            ++inside[iu];
            if (kpos[x] == static_cast<int>(big)) ++inside[big];
          }
      }
      std::int64_t missing = 0;
      const auto full = static_cast<std::int64_t>(clique.size()) - 1;
      for (std::size_t iu = 0; iu < clique.size(); ++iu) {
        const int u = clique[iu];
        def[u] -= static_cast<std::int64_t>(deg[u] - 1) - inside[iu];
        --deg[u];
        missing += full - inside[iu];
        auto& au = adj[u];
        if (au.size() > 2 * static_cast<std::size_t>(deg[u]) + 8) {
          std::size_t w = 0;
          for (const int x : au)
            if (!done[x]) au[w++] = x;
          au.resize(w);
        }
      }

      // 2. Complete N(p) to a clique, one fill edge at a time, updating deficiencies exactly.
      // Members already adjacent to the whole clique are skipped (late elimination stages
      // eliminate cliques: then there is nothing to add at all).
      for (std::size_t ia = 0; ia < clique.size() && missing > 0; ++ia) {
        if (inside[ia] == full) continue;
        const int va = clique[ia];
        const std::int64_t sa = ++astamp;
        for (const int x : adj[va])
          if (!done[x]) amark[x] = sa;
        for (std::size_t ib = ia + 1; ib < clique.size(); ++ib) {
          const int vb = clique[ib];
          if (amark[vb] == sa) continue;  // already adjacent
          std::int64_t common = 0;
          for (const int w : adj[vb])
            if (amark[w] == sa) {  // live: only live nodes are marked
              ++common;
              --def[w];
              if (tmark[w] != step) { tmark[w] = step; touched.push_back(w); }
            }
          def[va] += deg[va] - common;
          def[vb] += deg[vb] - common;
          adj[va].push_back(vb);
          amark[vb] = sa;
          adj[vb].push_back(va);
          ++deg[va];
          ++deg[vb];
          ++inside[ia];
          ++inside[ib];
          missing -= 2;
        }
      }
      for (const int u : touched) heap.emplace(def[u], deg[u], u);
    }
    return perm;
  }
};

}  // namespace pradis::linalg
