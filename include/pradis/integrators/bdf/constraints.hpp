#pragma once
/// \file
/// Index-3 constraints (exact joints) in pradis::bdf_simulation: which
/// equations are their rows, the velocities they act on, the data of the
/// stabilised index-2 form the corrector uses (docs/bdf.md, "Index-3
/// constraints"), and the check that no such constraint moves with a driven
/// DOF.

#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pradis/assembly/assembler.hpp"

namespace pradis::bdf_detail {

/// The stabilised index-2 form of the index-3 constraints (exact joints) in
/// the corrector (Gear, Gupta and Leimkuhler, J. Comput. Appl. Math. 12-13
/// (1985) 77-90): u' = v + sh, sh a correction across the constraints, with
/// the position constraint g(u) = 0 (the constraint rows of F) and the
/// velocity constraint G v = 0 both met. G (= c times the constraint rows of
/// the Newton matrix, multiplier columns left out) is taken at the attempt's
/// first evaluation, at the predictor. Each iteration solves twice with the
/// kept factorisation: once for dv with the constraint rows' residual replaced
/// by G v / c_J (so that G (v + dv) = 0), once for the shift d with right-hand
/// side (G v - c g) / c_J on the constraint rows and 0 elsewhere (so that
/// G (dv + d) = -c g: the position constraint is met to first order). The shift
/// lies in the span of M^-1 G^T for large c. Sized by the driver when it builds
/// the equations; the corrector does not allocate.
struct index2_stabilisation {
  std::vector<int> rows;         ///< equations of the index-3 constraint rows
  std::vector<char> multiplier;  ///< per equation: the multiplier of such a row (left out of G)
  std::vector<double> g;         ///< per pattern position: G on the constraint rows (others unused)
  std::vector<double> shift;     ///< per equation: the accumulated shift sh of this attempt
  std::vector<double> rhs;       ///< per equation: the second right-hand side and its solution
};

/// Fills, from the equations of `as` and the index-3 multipliers (per DOF),
/// index2 (per equation: a velocity an index-3 row acts on, the columns of the
/// row) and, when `stabilise`, the rows and buffers of st (else st is emptied).
template <class Assembler>
void mark_constraints(const Assembler& as, const std::vector<char>& index3, bool stabilise, std::vector<char>& index2,
                      index2_stabilisation& st) {
  const int ne = as.equations();
  const auto is3 = [&](int eq) {
    const auto d = static_cast<std::size_t>(as.dof_of(eq));
    return d < index3.size() && index3[d] != 0;
  };
  index2.assign(static_cast<std::size_t>(ne), 0);
  st.rows.clear();
  st.multiplier.assign(static_cast<std::size_t>(ne), 0);
  const auto& pat = as.pattern();
  for (int r = 0; r < ne; ++r) {
    if (!is3(r)) continue;
    st.rows.push_back(r);
    st.multiplier[static_cast<std::size_t>(r)] = 1;
    for (int q = pat.row_ptr[static_cast<std::size_t>(r)]; q < pat.row_ptr[static_cast<std::size_t>(r) + 1]; ++q) {
      const int c = pat.col[static_cast<std::size_t>(q)];
      if (c != r && !is3(c)) index2[static_cast<std::size_t>(c)] = 1;
    }
  }
  if (!stabilise || st.rows.empty()) {
    st = {};
    return;
  }
  st.g.assign(pat.col.size(), 0.0);
  st.shift.assign(static_cast<std::size_t>(ne), 0.0);
  st.rhs.assign(static_cast<std::size_t>(ne), 0.0);
}

/// The first element instance that owns an index-3 multiplier and acts on a
/// driven DOF (a kinematic source; the ground, DOF 0, is not one), as (instance
/// name, DOF name); none if there is none.
template <class Model>
std::optional<std::pair<std::string, std::string>> driven_constraint(Model& m, const std::vector<char>& index3,
                                                                      const std::vector<char>& prescribed) {
  std::optional<std::pair<std::string, std::string>> found;
  m.for_each_instances([&](auto& vec) {
    for (auto& in : vec) {
      if (found) return;
      bool owns = false;
      for (const auto d : in.dofs) owns = owns || (static_cast<std::size_t>(d) < index3.size() && index3[static_cast<std::size_t>(d)]);
      if (!owns) continue;
      for (const auto d : in.dofs) {
        const auto k = static_cast<std::size_t>(d);
        if (d != 0 && k < prescribed.size() && prescribed[k]) {
          found = std::make_pair(std::string(in.name), m.dof_name(static_cast<int>(d)));
          return;
        }
      }
    }
  });
  return found;
}

/// Per element type (in the model's order): whether an instance of it owns an
/// index-3 multiplier. The stabilised form assembles these types' Jacobians at
/// each attempt's start for G (call_info::jacobian_types), not the whole model's.
template <class Model>
std::vector<char> constraint_types(Model& m, const std::vector<char>& index3) {
  std::vector<char> types;
  m.for_each_instances([&](auto& vec) {
    bool owns = false;
    for (auto& in : vec)
      for (const auto d : in.dofs)
        owns = owns || (static_cast<std::size_t>(d) < index3.size() && index3[static_cast<std::size_t>(d)]);
    types.push_back(owns ? 1 : 0);
  });
  return types;
}

}  // namespace pradis::bdf_detail
