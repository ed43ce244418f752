#pragma once
/// \file
/// The rate form of the rotational nodes under pradis::bdf_simulation
/// (bdf_options::rotation_rates, docs/bdf.md "Rotational nodes").
///
/// The BDF history holds y = (u, v) for every free DOF. For a rotational node
/// whose four potentials q are all free, the velocity half instead holds the
/// body angular velocity and the norm rate (s = q.q, G(q) of quaternion.hpp)
///     w = (2/s) G(q) q',   r = q.q' / s,   so that   q' = (1/2) G(q)^T w + r q,
/// in the rows of q1, q2, q3 (w) and q4 (r). The displacement half keeps q. The
/// Newton unknown stays q' (and the Newton matrix (1/c) K + C + c M, since
/// dq''/dq' = c I + O(1)); the corrector gives w' = w'_p + c (w - w_p),
/// r' = r'_p + c (r - r_p), and from them
///     q'' = (1/2) G(q')^T w + (1/2) G(q)^T w' + r' q + r q'.
/// Why: in the second-order form the local error of q' is an angular-velocity
/// error that turns into an orientation error growing over the run; the body
/// rates of a rigid body vary slowly and their BDF local error is small. With
/// fixed steps the free body's error fell to that of BDF on the first-order
/// equations in (q, omega) (docs/bdf.md).
///
/// Error weights: the three rows of w share 1 / (DRLTX |w| + DABSX 2 p), |w| the
/// node's angular speed and p the nominal potential of q (the error of a vector
/// does not depend on the frame it is written in); r, a gauge rate held to 0 by
/// the node's norm equation, is left out (weight 0). Everything here is
/// invariant under q -> l q, so renormalisation (rotations.hpp) leaves these
/// rows alone. Never allocates after build().

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/integrators/bdf/node_dofs.hpp"
#include "pradis/model/handles.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::bdf_detail {

/// The rates of a rotational node (see the file comment).
struct node_rates {
  spatial::vec3 w;  ///< body angular velocity (2/s) G(q) q' (or its derivative)
  double r = 0;     ///< norm rate q.q' / s (or its derivative)
};

/// (w, r) of a quaternion q and its rate qd.
inline node_rates rates_of(const spatial::quaternion& q, const spatial::quaternion& qd) {
  const double s = q.squaredNorm();
  return {(2 / s) * (spatial::g_matrix(q) * qd), q.dot(qd) / s};
}

/// (w', r') from q, q', q'': w' = (2/s) G(q) q'' - 2 r w, r' = (q'.q' + q.q'') / s - 2 r^2.
inline node_rates rate_derivatives_of(const spatial::quaternion& q, const spatial::quaternion& qd,
                                      const spatial::quaternion& qdd) {
  const double s = q.squaredNorm();
  const node_rates x = rates_of(q, qd);
  return {(2 / s) * (spatial::g_matrix(q) * qdd) - 2 * x.r * x.w, (qd.squaredNorm() + q.dot(qdd)) / s - 2 * x.r * x.r};
}

/// q'' from q, q', (w, r) and (w', r'): the derivative of q' = (1/2) G(q)^T w + r q.
inline spatial::quaternion acceleration_of(const spatial::quaternion& q, const spatial::quaternion& qd,
                                           const node_rates& x, const node_rates& xd) {
  return 0.5 * (spatial::g_matrix(qd).transpose() * x.w) + 0.5 * (spatial::g_matrix(q).transpose() * xd.w) +
         xd.r * q + x.r * qd;
}

/// The rotational nodes in the rate form and the maps between the velocity
/// half of the history and the state (see the file comment).
class rate_form {
 public:
  /// Selects the nodes whose four DOFs are free equations (enabled: else none).
  template <class Assembler>
  void build(const std::vector<rotation_node_record>& nodes, const Assembler& as, bool enabled) {
    nodes_.clear();
    if (enabled) nodes_ = free_rotation_nodes(nodes, as);
  }
  /// No node is handled (disabled, or no rotational node with four free DOFs).
  bool empty() const noexcept { return nodes_.empty(); }
  /// Whether equation i is a velocity row held in the rate form.
  bool holds(int i) const noexcept {
    for (const entry& e : nodes_)
      for (const int q : e.eq)
        if (q == i) return true;
    return false;
  }

  /// Writes (w, r) of the state into the velocity rows of y (offset ne) and,
  /// with yp, (w', r') into yp.
  void rates(const global_state& s, int ne, Eigen::VectorXd& y, Eigen::VectorXd* yp = nullptr) const {
    for (const entry& e : nodes_) {
      const spatial::quaternion q = get(s.u, e), qd = get(s.v, e);
      put(rates_of(q, qd), ne, e, y);
      if (yp) put(rate_derivatives_of(q, qd, get(s.a, e)), ne, e, *yp);
    }
  }
  /// The predicted q' of every node, (1/2) G(q_p)^T w_p + r_p q_p, from the
  /// predictor y_p (q_p in the displacement rows, (w_p, r_p) in the velocity rows).
  void predicted_velocities(global_state& s, int ne, const Eigen::VectorXd& y_p) const {
    for (const entry& e : nodes_) {
      spatial::quaternion q;
      node_rates x;
      for (int j = 0; j < 4; ++j) q(j) = y_p(e.eq[j]);
      for (int j = 0; j < 3; ++j) x.w(j) = y_p(ne + e.eq[j]);
      x.r = y_p(ne + e.eq[3]);
      const spatial::quaternion qd = 0.5 * (spatial::g_matrix(q).transpose() * x.w) + x.r * q;
      for (int j = 0; j < 4; ++j) s.v(e.dof[j]) = qd(j);
    }
  }
  /// The velocity rows of the correction e = y - y_p of a converged step: the
  /// rates of the state s minus their predictors.
  void errors(const global_state& s, int ne, const Eigen::VectorXd& y_p, Eigen::VectorXd& e) const {
    rates(s, ne, e);
    for (const entry& n : nodes_)
      for (const int q : n.eq) e(ne + q) -= y_p(ne + q);
  }
  /// The corrector of the rates: sets q'' of every node of s from its q, q' and
  /// the predictors (y_p, yp_p) of (w, r) at the coefficient c.
  void accelerations(global_state& s, int ne, const Eigen::VectorXd& y_p, const Eigen::VectorXd& yp_p,
                     double c) const {
    for (const entry& e : nodes_) {
      const spatial::quaternion q = get(s.u, e), qd = get(s.v, e);
      const node_rates x = rates_of(q, qd);
      node_rates xd;
      for (int j = 0; j < 3; ++j)
        xd.w(j) = yp_p(ne + e.eq[j]) + c * (x.w(j) - y_p(ne + e.eq[j]));
      xd.r = yp_p(ne + e.eq[3]) + c * (x.r - y_p(ne + e.eq[3]));
      const spatial::quaternion qdd = acceleration_of(q, qd, x, xd);
      for (int j = 0; j < 4; ++j) s.a(e.dof[j]) = qdd(j);
    }
  }
  /// Replaces the velocity corrections dq' in the rows of dy (offset ne) by the
  /// corrections (dw, dr) they make at the state s (linearised).
  void corrections(const global_state& s, int ne, Eigen::VectorXd& dy) const {
    for (const entry& e : nodes_) {
      const spatial::quaternion q = get(s.u, e);
      spatial::quaternion dqd;
      for (int j = 0; j < 4; ++j) dqd(j) = dy(ne + e.eq[j]);
      put(rates_of(q, dqd), ne, e, dy);
    }
  }
  /// The error weights of the rate rows (see the file comment); p the nominal
  /// potential of each DOF (dof_scale::potential).
  /// index2 and hv: the rows whose weight is multiplied by hv (the plain
  /// index-3 form, bdf_simulation::set_weights).
  template <class Scales>
  void weights(const global_state& s, int ne, double drltx, double dabsx, const Scales& scales,
               const std::vector<char>& index2, double hv, Eigen::VectorXd& w) const {
    for (const entry& e : nodes_) {
      const double speed = rates_of(get(s.u, e), get(s.v, e)).w.norm();
      for (int j = 0; j < 3; ++j) {
        const double p = scales[static_cast<std::size_t>(e.dof[j])].potential;
        const auto i = static_cast<std::size_t>(e.eq[j]);
        w(ne + e.eq[j]) = (i < index2.size() && index2[i] ? hv : 1.0) / (drltx * speed + dabsx * 2 * p);
      }
      w(ne + e.eq[3]) = 0;
    }
  }

 private:
  using entry = free_rotation_node;
  template <class V>
  static spatial::quaternion get(const V& x, const entry& e) {
    return {x(e.dof[0]), x(e.dof[1]), x(e.dof[2]), x(e.dof[3])};
  }
  static void put(const node_rates& x, int ne, const entry& e, Eigen::VectorXd& y) {
    for (int j = 0; j < 3; ++j) y(ne + e.eq[j]) = x.w(j);
    y(ne + e.eq[3]) = x.r;
  }
  std::vector<entry> nodes_;
};

}  // namespace pradis::bdf_detail
