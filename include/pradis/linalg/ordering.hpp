#pragma once
/// \file
/// Fill-reducing orderings for the sparse LU: the OrderingPolicy concept and the policies
/// pradis ships, one per PRADIS renumbering level OPTIM 0..4 (natural_ordering,
/// row_count_ordering, initial_fill_ordering, min_degree_ordering, min_fill_ordering), plus
/// automatic_ordering (level by size) and optim_ordering (level chosen at run time).

#include <concepts>
#include <string_view>
#include <vector>

#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg {

/// OrderingPolicy: a small stateless type with `static constexpr std::string_view name` and
/// `std::vector<int> operator()(const sparsity_pattern&) const` returning perm with
/// perm[k] = original index of the k-th pivot (a permutation of 0..n-1). It must treat the
/// pattern as structurally symmetric (use the union of A and A^T); symmetric_adjacency()
/// gives that graph. sparse_lu default-constructs the policy, hence std::default_initializable.
template <class O>
concept OrderingPolicy = std::default_initializable<O> &&
    requires(const O& o, const sparsity_pattern& p) {
      { O::name } -> std::convertible_to<std::string_view>;
      { o(p) } -> std::same_as<std::vector<int>>;
    };

}  // namespace pradis::linalg

#include "pradis/linalg/ordering/automatic.hpp"
#include "pradis/linalg/ordering/initial_fill.hpp"
#include "pradis/linalg/ordering/min_degree.hpp"
#include "pradis/linalg/ordering/min_fill.hpp"
#include "pradis/linalg/ordering/natural.hpp"
#include "pradis/linalg/ordering/row_count.hpp"

namespace pradis::linalg {
static_assert(OrderingPolicy<natural_ordering>);
static_assert(OrderingPolicy<min_degree_ordering>);
static_assert(OrderingPolicy<row_count_ordering>);
static_assert(OrderingPolicy<initial_fill_ordering>);
static_assert(OrderingPolicy<min_fill_ordering>);
static_assert(OrderingPolicy<automatic_ordering>);
static_assert(OrderingPolicy<optim_ordering>);
}  // namespace pradis::linalg
