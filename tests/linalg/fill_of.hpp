#pragma once
// The fill-in of the symbolic LU factorisation of a pattern under an ordering
// (shared by the sparse-LU and the ordering tests).

#include "pradis/linalg/sparse_lu.hpp"

namespace pradis_linalg_test {
template <class Ordering>
long fill_of(const pradis::linalg::sparsity_pattern& p) {
  pradis::linalg::sparse_lu<Ordering> lu;
  lu.analyze(p);
  return lu.statistics().fill;
}
}  // namespace pradis_linalg_test
