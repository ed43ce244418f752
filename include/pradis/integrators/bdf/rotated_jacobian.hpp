#pragma once
/// \file
/// The kept Newton matrix of pradis::bdf_simulation turned with the rotational
/// nodes (bdf_options::rotated_jacobian, docs/bdf.md "Newton").
///
/// The equations of a rotational node are the moments about the global axes and
/// the norm equation (docs/rotations.md): they do not turn with the node. Its
/// columns do: they act on q' = (1/2) E(q)^T omega + r q (quaternion.hpp; omega
/// the global angular velocity, r = q.q'/s, s = q.q), so the matrix has the form
/// B A(q) with A(q) = [(2/s) E(q); q^T / s], the map q' -> (omega, r), and B the
/// matrix in (omega, r) terms. When the node has turned from q0, where the kept
/// matrix J0 was factorised, to q, the kept factorisation serves for
///     J ~ J0 S,   S = A(q0)^-1 A(q),   S^-1 = (E(q)^T E(q0) + q q0^T) / s0,
/// and a Newton solve becomes dv = S^-1 J0^-1 (-F): a 4 x 4 product on the
/// node's entries of the solution. The approximation keeps B, the matrix in
/// global terms: exact for what depends on the global angular velocity alone,
/// such as a joint at a point of the body's spin axis and the inertia of a body
/// symmetric about that axis. The top spinning at 30 rad/s on its exact joint
/// turns by 0.15 rad in a step of 5 ms; the unturned kept matrix slowed Newton,
/// whose inexact solutions then held BDF at orders 2-3. Used for the nodes whose
/// four DOFs are free equations. Never allocates after build().

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/integrators/bdf/node_dofs.hpp"
#include "pradis/model/handles.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::bdf_detail {

/// The rotational nodes of the turned kept Newton matrix and the orientations
/// q0 of the factorisation (see the file comment).
class rotated_jacobian {
 public:
  /// Selects the nodes whose four DOFs are free equations (enabled: else none).
  template <class Assembler>
  void build(const std::vector<rotation_node_record>& nodes, const Assembler& as, bool enabled) {
    nodes_.clear();
    if (!enabled) return;
    for (const free_rotation_node& n : free_rotation_nodes(nodes, as)) nodes_.push_back({n.dof, n.eq});
  }
  /// No node is handled (disabled, or no rotational node with four free DOFs).
  bool empty() const noexcept { return nodes_.empty(); }

  /// Records the orientations of the factorised matrix (after a factorisation at s).
  void set_reference(const global_state& s) {
    for (entry& e : nodes_) e.q0 = get(s.u, e);
  }
  /// S^-1 on the node entries of a solution of J0 (after the solve).
  void from_reference(const global_state& s, std::span<double> x) const {
    for (const entry& e : nodes_) apply(e, s, x);
  }

 private:
  struct entry {
    std::array<int, 4> dof{};  // global DOFs of q1..q4
    std::array<int, 4> eq{};   // their equations
    spatial::quaternion q0 = spatial::identity();
  };
  template <class V>
  static spatial::quaternion get(const V& x, const entry& e) {
    return {x(e.dof[0]), x(e.dof[1]), x(e.dof[2]), x(e.dof[3])};
  }
  static void apply(const entry& e, const global_state& s, std::span<double> x) {
    const spatial::quaternion q = get(s.u, e);
    const Eigen::Matrix4d m =
        (spatial::e_matrix(q).transpose() * spatial::e_matrix(e.q0) + q * e.q0.transpose()) / e.q0.squaredNorm();
    spatial::quaternion v;
    for (int j = 0; j < 4; ++j) v(j) = x[static_cast<std::size_t>(e.eq[j])];
    const spatial::quaternion r = m * v;
    for (int j = 0; j < 4; ++j) x[static_cast<std::size_t>(e.eq[j])] = r(j);
  }
  std::vector<entry> nodes_;
};

}  // namespace pradis::bdf_detail
