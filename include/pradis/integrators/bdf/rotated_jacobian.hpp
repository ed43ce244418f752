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
/// whose inexact solutions then held BDF at orders 2-3.
///
/// The body frame. When every element on a node has body-fixed flows
/// (core/element.hpp, HasBodyFixedFlows: a rigid body whose centre of mass is
/// the node's point, body-fixed torques), its rows are R(q) times moments in
/// body axes and its columns act through the body angular velocity
/// omega_b = (2/s) G(q) q'. Then J ~ T T0^T J0 S_b with T = R(q) on the moment
/// rows and S_b^-1 = (G(q)^T G(q0) + q q0^T) / s0: the node's moment rows of the
/// right-hand side are turned by R(q0) R(q)^T before the solve and its entries of
/// the solution by S_b^-1 after it. This is exact for the inertia of any rigid
/// body, which depends on omega_b alone: a body tumbling about changing axes
/// keeps Newton's rate. A joint in the ground frame does not turn with the body,
/// so a node with any other element keeps the global frame.
///
/// Used for the nodes whose four DOFs are free equations. Never allocates after
/// build().

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>
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
  /// Selects the nodes of m whose four DOFs are free equations of `as`
  /// (enabled: else none); with body_frame, those whose elements all have
  /// body-fixed flows (body_fixed_nodes) are turned in their body frame.
  template <class Model, class Assembler>
  void build(const Model& m, const Assembler& as, bool enabled, bool body_frame) {
    nodes_.clear();
    if (!enabled) return;
    const std::vector<char> fixed = body_frame ? body_fixed_nodes(m) : std::vector<char>{};
    for (const free_rotation_node& n : free_rotation_nodes(m.rotation_nodes(), as))
      nodes_.push_back({n.dof, n.eq, body_frame && fixed[static_cast<std::size_t>(n.node)] != 0});
  }
  /// The number of nodes turned in their body frame.
  int body_frame_nodes() const noexcept {
    int k = 0;
    for (const entry& e : nodes_) k += e.body ? 1 : 0;
    return k;
  }
  /// No node is handled (disabled, or no rotational node with four free DOFs).
  bool empty() const noexcept { return nodes_.empty(); }

  /// Records the orientations of the factorised matrix (after a factorisation at s).
  void set_reference(const global_state& s) {
    for (entry& e : nodes_) {
      e.q0 = get(s.u, e);
      if (e.body) e.r0 = spatial::rotation_matrix(e.q0);
      e.a0 = e.body ? spatial::g_matrix(e.q0) : spatial::e_matrix(e.q0);
      e.inv_s0 = 1 / e.q0.squaredNorm();
    }
  }
  /// Whether a node turned in the global frame has turned by more than `angle`
  /// [rad] since the reference (bdf_options::turn_refresh); never for angle >= pi.
  /// The angle between q0 and q is 2 acos(|q0.q| / (|q0| |q|)).
  bool turned_beyond(const global_state& s, double angle) const {
    if (!(angle < std::numbers::pi)) return false;
    const double c = std::cos(angle / 2);
    for (const entry& e : nodes_) {
      if (e.body) continue;
      const spatial::quaternion q = get(s.u, e);
      const double d = std::abs(q.dot(e.q0));
      if (d < c * std::sqrt(q.squaredNorm() / e.inv_s0)) return true;
    }
    return false;
  }
  /// R(q0) R(q)^T on the moment rows of a right-hand side of the nodes turned
  /// in their body frame (before the solve with J0).
  void to_reference(const global_state& s, std::span<double> b) const {
    for (const entry& e : nodes_) {
      if (!e.body) continue;
      const spatial::vec3 v(at(b, e, 0), at(b, e, 1), at(b, e, 2));
      const spatial::vec3 m = e.r0 * (spatial::rotation_matrix(get(s.u, e)).transpose() * v);
      for (int j = 0; j < 3; ++j) at(b, e, j) = m(j);
    }
  }
  /// S^-1 (S_b^-1 in the body frame) on the node entries of a solution of J0 (after the solve).
  void from_reference(const global_state& s, std::span<double> x) const {
    for (const entry& e : nodes_) apply(e, s, x);
  }

 private:
  struct entry {
    std::array<int, 4> dof{};  // global DOFs of q1..q4
    std::array<int, 4> eq{};   // their equations
    bool body = false;         // turned in the body frame
    spatial::quaternion q0 = spatial::identity();
    spatial::mat3 r0 = spatial::mat3::Identity();  // R(q0), body frame only
    spatial::mat34 a0 = spatial::e_matrix(spatial::identity());  // G(q0) (body frame) or E(q0)
    double inv_s0 = 1;                                           // 1 / (q0 . q0)
  };
  static double& at(std::span<double> x, const entry& e, int j) {
    return x[static_cast<std::size_t>(e.eq[static_cast<std::size_t>(j)])];
  }
  template <class V>
  static spatial::quaternion get(const V& x, const entry& e) {
    return {x(e.dof[0]), x(e.dof[1]), x(e.dof[2]), x(e.dof[3])};
  }
  static void apply(const entry& e, const global_state& s, std::span<double> x) {
    const spatial::quaternion q = get(s.u, e);
    double v[4];
    for (int j = 0; j < 4; ++j) v[j] = at(x, e, j);
    // S^-1 v = (A(q)^T (A(q0) v) + q (q0 . v)) / s0, without forming the 4 x 4 matrix,
    // in scalar arithmetic: w = A(q0) v, and with A = G (body frame) or E,
    // A(q)^T w = (q4 w +- q_v x w, -q_v . w).
    double w[3];
    for (int r = 0; r < 3; ++r) w[r] = e.a0(r, 0) * v[0] + e.a0(r, 1) * v[1] + e.a0(r, 2) * v[2] + e.a0(r, 3) * v[3];
    const double qv = e.q0(0) * v[0] + e.q0(1) * v[1] + e.q0(2) * v[2] + e.q0(3) * v[3];
    const double sg = e.body ? 1.0 : -1.0;
    const double c[3] = {q(1) * w[2] - q(2) * w[1], q(2) * w[0] - q(0) * w[2], q(0) * w[1] - q(1) * w[0]};
    for (int k = 0; k < 3; ++k) at(x, e, k) = (q(3) * w[k] + sg * c[k] + q(k) * qv) * e.inv_s0;
    at(x, e, 3) = (q(3) * qv - (q(0) * w[0] + q(1) * w[1] + q(2) * w[2])) * e.inv_s0;
  }
  std::vector<entry> nodes_;
};

}  // namespace pradis::bdf_detail
