#pragma once
/// \file
/// Rotational nodes under pradis::bdf_simulation: the norm Lq = |q| of a node's
/// quaternion is brought back to 1 when it has drifted (docs/bdf.md, "Rotational
/// nodes").
///
/// Why. The norm equation Mu dLq/dt = 0 holds Lq at the velocity level only, so a
/// step's local error in the direction of q stays in Lq: a BDF1 step q_{n+1} =
/// q_n + h q'_{n+1} with q_{n+1} . q'_{n+1} = 0 shrinks it by h^2 |q'|^2 / 2. With
/// a loose tolerance (DRLTX = 1e-2 on a top spinning at 30 rad/s) Lq left
/// [0.9, 1.1] within a second and the run failed with code 75 (Lq far from 1).
///
/// Exactness. Every formula of the rotational nodes is invariant under q -> l q
/// (docs/rotations.md), so the model's motion is the same for (l q, l q', l q'').
/// The BDF history is linear in y = (u, v): scaling the rows of the node's four
/// potentials (displacements and velocities, every column) by l = 1 / Lq gives the
/// history of that scaled motion. The kept factorisation is dropped (dF/dq scales).

#include <cmath>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/integrators/bdf/history.hpp"
#include "pradis/integrators/bdf/rate_form.hpp"
#include "pradis/model/handles.hpp"

namespace pradis::bdf_detail {

/// Renormalises, after an accepted step, every rotational node whose norm left
/// [1 - band, 1 + band] (bdf_options::lq_renormalise) and whose DOFs q1..q4 are all
/// free equations or the ground: scales u, v, a of those DOFs in s and their rows
/// in the history (not the velocity rows of a node in the rate form, rf: its
/// rates are scale invariant). Returns the number of nodes renormalised.
template <class Assembler>
int renormalise_rotation_nodes(const std::vector<rotation_node_record>& nodes, const Assembler& as, global_state& s,
                               history& hist, double band, const rate_form& rf) {
  const int ne = as.equations();
  int count = 0;
  for (const rotation_node_record& node : nodes) {
    double s2 = 0;
    bool free = true;
    for (const int d : node.dofs) {
      if (d == 0) continue;  // a component on the ground stays 0
      free = free && as.equation_of(d) >= 0;
      s2 += s.u(d) * s.u(d);
    }
    const double lq = std::sqrt(s2);
    if (!free || !(std::abs(lq - 1) > band) || !(lq > 0) || !std::isfinite(lq)) continue;
    const double l = 1 / lq;
    for (const int d : node.dofs) {
      if (d == 0) continue;
      s.u(d) *= l;
      s.v(d) *= l;
      s.a(d) *= l;
      s.p(d) *= l;
      const int e = as.equation_of(d);
      hist.scale_row(e, l);
      if (!rf.holds(e)) hist.scale_row(ne + e, l);
    }
    ++count;
  }
  return count;
}

}  // namespace pradis::bdf_detail
