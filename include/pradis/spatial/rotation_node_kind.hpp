#pragma once
/// \file
/// The spatial rotational node as a node kind (core/node_kind.hpp): the
/// non-normalised quaternion q = (q1, q2, q3, q4) of a point in spatial motion,
/// whose hidden q4 starts at 1 and carries the norm equation
/// Mu d(Lq)/dt = Mu (q . q') / Lq, Lq = |q| (docs/rotations.md). The model, the
/// assembler, the drivers and the consistent initialisation know it only
/// through NodeKind; this file is everything they run for it.
///
/// Also here: the rotational nodes' registry, which a model keeps (which DOFs
/// are the q1, q2, q3 of which node, and the node's hidden q4), and its checks of
/// connections (code 110).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/model/handles.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::spatial {

class rotation_node_registry;

/// The rotational node kind. Its equation is the norm equation in the row of the
/// hidden q4: f = Mu (q . q') / Lq with dF/dq' = Mu q / Lq and
/// dF/dq = Mu (q' / Lq - (q . q') q / Lq^3), Mu = norm_viscosity(DABSI).
struct rotation_node_kind {
  // The NodeKind members (core/node_kind.hpp):
  using record = rotation_node_record;      ///< one node: its DOFs q1..q4 and its first element
  using registry = rotation_node_registry;  ///< the model's nodes of this kind
  static constexpr int size = 4;            ///< q1..q4
  static constexpr std::string_view label = "ROTATION NODE";  ///< the kind's name in messages
  static constexpr std::array<bool, 4> hidden{false, false, false, true};  ///< q4 is hidden
  static constexpr std::array<bool, 4> rows{false, false, false, true};    ///< the norm equation in q4's row
  static constexpr std::array<double, 4> start{0, 0, 0, 1};               ///< the identity rotation
  static constexpr bool inertial_block = true;  ///< q1..q3 are inertial where the node's inertia block reaches their rows

  /// The norm equation's flow on q4 and (call.want_jacobian) its row of dF/du and
  /// dF/dv; only row 3 of out is written. Lq near zero (lq_near_zero) or far from 1
  /// (lq_far_from_one) is code 75 in the name of the node's first element.
  static void evaluate(const record& node, const node_values<4>& x, const node_call& call, node_flows<4>& out,
                       element_context& ctx) {
    const double lq = x.u.norm();
    if (!(lq > lq_near_zero) || !std::isfinite(lq) || !(std::abs(lq - 1.0) <= lq_far_from_one)) {
      const std::string& who = node.owner_instance.empty() ? node.name : node.owner_instance;
      ctx.set_identity(node.owner_type.empty() ? label : std::string_view(node.owner_type), who);
      if (!(lq > lq_near_zero) || !std::isfinite(lq))
        ctx.singular("rotational node '" + node.name + "': Lq near zero (the quaternion norm |q| = " + to_text(lq) +
                     "; it starts at 1 and must stay there): the orientation is undefined");
      ctx.singular("rotational node '" + node.name + "': Lq far from 1 (the quaternion norm |q| = " + to_text(lq) +
                   " has drifted from its start value 1 by more than " + to_text(lq_far_from_one) +
                   "; check the initial quaternion and the step)");
    }
    const double mu = norm_viscosity(call.dabsi);
    const double g = x.u.dot(x.v);
    out.f(3) = mu * g / lq;
    if (!call.want_jacobian) return;
    for (int k = 0; k < 4; ++k) {
      out.K(3, k) = mu * (x.v(k) / lq - g * x.u(k) / (lq * lq * lq));
      out.C(3, k) = mu * x.u(k) / lq;
    }
  }

  /// The zero step's row of q4 (k = 3): the norm equation differentiated once more,
  /// d2(Lq)/dt2 = (q . q'' + |q'|^2 - (q . q')^2 / Lq^2) / Lq = 0, over q''. Without it
  /// q4'' would start inconsistent and the trapezoidal rule would carry the error on as
  /// an undamped alternation of q'' (which enters the moments through E(q) q'').
  static void zero_step_row(const node_values<4>& x, int /*k*/, Eigen::Vector4d& row, double& rhs) {
    const double lq = x.u.norm(), g = x.u.dot(x.v);
    row = x.u / lq;
    rhs = -(x.u.dot(x.a) + x.v.squaredNorm() - g * g / (lq * lq)) / lq;
  }
};

static_assert(NodeKind<rotation_node_kind>);

/// The rotational nodes of a model: their records, which node each external DOF
/// q1, q2, q3 belongs to, and the fully fixed node (all three components on the
/// ground), of which there is at most one. A model keeps one; its add_rotation_node
/// and the rotational slots of its elements (element_traits<E>::rotation_nodes) come
/// here. `add_dof(name)` adds a DOF to the model and returns its index, `dof_name(d)`
/// names DOF d in messages, `dof_count` is the model's DOF count.
class rotation_node_registry {
 public:
  /// The nodes, in the order they were made.
  const std::vector<rotation_node_record>& records() const noexcept { return nodes_; }
  /// The node whose external q1, q2 or q3 is DOF d (not the ground), or -1.
  int node_of(int d) const {
    const auto it = role_.find(d);
    return d == 0 || it == role_.end() ? -1 : it->second.first;
  }

  /// A new node on the existing DOFs t (q1, q2, q3) named `name` (empty: "rotation node
  /// N"), with a new hidden q4. A repeated DOF, a DOF that already belongs to a node or a
  /// second fully fixed node is code 110.
  template <class AddDof, class DofName>
  int add(std::string name, const std::array<int, 3>& t, int dof_count, AddDof&& add_dof, DofName&& dof_name) {
    check_triple(t, "", name, dof_count, dof_name);
    if (name.empty()) name = "rotation node " + std::to_string(nodes_.size() + 1);
    for (int k = 0; k < 3; ++k) {
      const int d = t[static_cast<std::size_t>(k)];
      if (node_of(d) >= 0)
        throw error(error_code::invalid_model,
                    "DOF '" + dof_name(d) + "' already belongs to rotational node '" +
                        nodes_[static_cast<std::size_t>(node_of(d))].name + "'",
                    {}, name);
    }
    if (t == std::array<int, 3>{0, 0, 0} && ground_ >= 0)
      throw error(error_code::invalid_model, "the fully fixed rotational node (all three components on the ground) "
                                             "already exists", {}, name);
    return create(std::move(name), t, add_dof);
  }

  /// The node whose q1, q2, q3 are the DOFs t, for an element of catalog type `type`
  /// named `inst` that connects them through a rotational slot: the existing one, or a
  /// new node (with a new hidden q4) if none of them belongs to one. A DOF that belongs
  /// to another node, or to this node in another role, is code 110. The first such
  /// element becomes the node's owner (named in the node's errors).
  template <class AddDof, class DofName>
  int resolve(const std::array<int, 3>& t, std::string_view type, const std::string& inst, int dof_count,
              AddDof&& add_dof, DofName&& dof_name) {
    check_triple(t, type, inst, dof_count, dof_name);
    int found = -1;
    for (int k = 0; k < 3; ++k) {
      const int d = t[static_cast<std::size_t>(k)];
      if (d == 0) continue;
      const auto it = role_.find(d);
      if (it == role_.end()) continue;
      const auto& rec = nodes_[static_cast<std::size_t>(it->second.first)];
      if (found >= 0 && found != it->second.first)
        throw error(error_code::invalid_model, "the DOFs connected as q1, q2, q3 belong to different rotational nodes",
                    std::string(type), inst);
      if (it->second.second != k || rec.dofs[0] != t[0] || rec.dofs[1] != t[1] || rec.dofs[2] != t[2])
        throw error(error_code::invalid_model,
                    "DOF '" + dof_name(d) + "' is q" + std::to_string(it->second.second + 1) + " of rotational node '" +
                        rec.name + "' (q1, q2, q3 = DOFs " + std::to_string(rec.dofs[0]) + ", " +
                        std::to_string(rec.dofs[1]) + ", " + std::to_string(rec.dofs[2]) +
                        "); an element must connect all three, in this order",
                    std::string(type), inst);
      found = it->second.first;
    }
    if (found < 0 && t == std::array<int, 3>{0, 0, 0}) found = ground_;
    if (found < 0) found = create("rotation node " + std::to_string(nodes_.size() + 1), t, add_dof);
    auto& rec = nodes_[static_cast<std::size_t>(found)];
    if (rec.owner_instance.empty()) {
      rec.owner_type = std::string(type);
      rec.owner_instance = inst;
    }
    return found;
  }

 private:
  /// Refuses a triple with a DOF outside the model or a repeated non-ground DOF (code 110).
  template <class DofName>
  static void check_triple(const std::array<int, 3>& t, std::string_view type, const std::string& inst,
                           int dof_count, DofName&& dof_name) {
    for (int i = 0; i < 3; ++i) {
      const int d = t[static_cast<std::size_t>(i)];
      if (d < 0 || d >= dof_count)
        throw error(error_code::invalid_model, "DOF " + std::to_string(d) + " does not exist in this model",
                    std::string(type), inst);
      for (int j = 0; j < i; ++j)
        if (d != 0 && d == t[static_cast<std::size_t>(j)])
          throw error(error_code::invalid_model,
                      "DOF '" + dof_name(d) + "' is given twice among the q1, q2, q3 of a rotational node",
                      std::string(type), inst);
    }
  }
  template <class AddDof>
  int create(std::string name, const std::array<int, 3>& t, AddDof&& add_dof) {
    const int idx = static_cast<int>(nodes_.size());
    const int q4 = add_dof(name + ".q4");
    nodes_.push_back(rotation_node_record{std::move(name), {t[0], t[1], t[2], q4}, {}, {}});
    for (int k = 0; k < 3; ++k)
      if (t[static_cast<std::size_t>(k)] != 0) role_[t[static_cast<std::size_t>(k)]] = {idx, k};
    if (t == std::array<int, 3>{0, 0, 0}) ground_ = idx;
    return idx;
  }

  std::vector<rotation_node_record> nodes_;
  std::unordered_map<int, std::pair<int, int>> role_;  // external DOF -> (node, component)
  int ground_ = -1;
};

}  // namespace pradis::spatial
