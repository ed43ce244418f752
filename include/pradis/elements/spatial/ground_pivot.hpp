#pragma once
/// \file
/// The ground pivot: a spherical joint to the ground in reduced form, as a node kind
/// that slaves DOFs (core/node_kind.hpp, K::slaved). A body (reference point x, y, z,
/// rotational node q) is held with its point B on a fixed point A of the ground, like
/// SPH3X with body a the ground, but without multipliers: the body's translations
/// follow its rotation, x = A - X0 - R(q) r_B, and the joint force (-f_x, the flows of
/// the elements on x) reaches the moment rows as -rho_B x f_x. The body has its 7
/// DOFs (x, y, z, q1..q4) and no more, where SPH3X adds its 3 multipliers (and the
/// ground's rotational node); its rotation is all the motion, as in a Ball mobilizer.
/// Exact joint geometry of SPH3X (joints.hpp, joint_geometry; A on the ground, whose
/// rotation is the identity). Added by add_ground_pivot; SPH3X declares the kind, so a
/// model that lists `exact_spherical_joint` can have these nodes (docs/joints.md, "A
/// spherical joint to the ground in reduced form").

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/elements/spatial/joints.hpp"
#include "pradis/model/handles.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

/// What a model keeps about one ground pivot.
struct ground_pivot_record {
  std::array<int, 7> dofs{};  ///< x, y, z of the body's reference point, then q1..q4 of its rotational node
  spatial::vec3 a;            ///< the ground point A (global) [m]
  spatial::vec3 x0;           ///< initial global position of the body's reference point [m]
  spatial::vec3 rb;           ///< joint point B in the body's frame [m]
  std::string name;           ///< the pivot's name (messages)
};

/// What a model keeps about all its ground pivots.
struct ground_pivot_registry {
  std::vector<ground_pivot_record> nodes;  ///< in the order added
  /// The nodes (NodeKind's registry interface).
  const std::vector<ground_pivot_record>& records() const noexcept { return nodes; }
  /// Adds a node (model::add_node checks its DOFs first).
  void add(ground_pivot_record r) { nodes.push_back(std::move(r)); }
};

/// The ground pivot node kind: the equation c = p_B - A = 0 in the rows of x, y, z
/// (slaved), p_B = X0 + x + R(q) r_B (attached_point).
struct ground_pivot_kind {
  using record = ground_pivot_record;
  using registry = ground_pivot_registry;
  static constexpr int size = 7;
  static constexpr std::string_view label = "PIVOT";
  static constexpr std::array<bool, 7> hidden{};
  static constexpr std::array<bool, 7> rows{true, true, true, false, false, false, false};
  static constexpr std::array<bool, 7> slaved{true, true, true, false, false, false, false};
  static constexpr std::array<double, 7> start{};
  static constexpr bool inertial_block = false;

  /// The body point B of a node state (attached_point; with `derivatives`, d omega/dq and dp/dq too).
  static elements::detail::attached_point point(const record& r, const node_values<7>& x, bool derivatives) {
    return {r.x0, r.rb, x.u.head<3>(), x.v.head<3>(), x.u.segment<4>(3), x.v.segment<4>(3), derivatives};
  }
  /// c = p_B - A in rows 0..2; dc/dx = I, dc/dq = dp/dq = -[rho x] Theta (attached_point); no dF/dv.
  static void evaluate(const record& r, const node_values<7>& x, const node_call& call, node_flows<7>& out,
                       element_context& ctx) {
    const spatial::quaternion q = x.u.segment<4>(3);
    const double s = q.squaredNorm();
    if (!(std::sqrt(s) > spatial::lq_near_zero)) {
      ctx.set_identity(label, r.name);
      ctx.singular("ground pivot '" + r.name + "': Lq near zero (the quaternion norm of its body has vanished)");
    }
    const spatial::vec3 rho = spatial::rotation_matrix(q) * r.rb;
    out.f.head<3>() = r.x0 + x.u.head<3>() + rho - r.a;
    if (!call.want_jacobian) return;
    out.K.topRows<3>().setZero();
    out.K.topLeftCorner<3, 3>().setIdentity();
    out.K.block<3, 4>(0, 3) = -spatial::skew(rho) * ((2.0 / s) * spatial::e_matrix(q));
    out.C.topRows<3>().setZero();
  }
  /// The zero step's row k of c'' = x'' + omega' x rho + omega x (omega x rho) = 0, with
  /// omega' = Theta q'' + (d omega / dq) q': over the accelerations (x'', q''), and rhs =
  /// -c''_k at the current accelerations (the right-hand side of the correction).
  static void zero_step_row(const record& r, const node_values<7>& x, int k, Eigen::Matrix<double, 7, 1>& row,
                            double& rhs) {
    const auto p = point(r, x, true);
    row.setZero();
    row(k) = 1;
    row.segment<4>(3) = p.dp_dq.row(k).transpose();
    const spatial::vec3 domega = p.theta * x.a.segment<4>(3) + p.domega_dq * x.v.segment<4>(3);
    const spatial::vec3 acc = x.a.head<3>() + domega.cross(p.rho) + p.omega.cross(p.omega.cross(p.rho));
    rhs = -acc(k);
  }
  /// T: the joint force -f_x on the moment rows, -rho_B x f_x (rows q1..q3, columns x, y, z), and
  /// D = d(-rho_B x w)/dq = -[w x][rho x] Theta (rows q1..q3, columns q1..q4).
  static void carry(const record& r, const node_values<7>& x, const Eigen::Matrix<double, 7, 1>& w,
                    Eigen::Matrix<double, 7, 7>& t, Eigen::Matrix<double, 7, 7>* d) {
    const spatial::quaternion q = x.u.segment<4>(3);
    const spatial::vec3 rho = spatial::rotation_matrix(q) * r.rb;
    t.block<3, 3>(3, 0) = -spatial::skew(rho);
    if (d == nullptr) return;
    const spatial::mat34 theta = (2.0 / q.squaredNorm()) * spatial::e_matrix(q);
    const spatial::vec3 f = w.head<3>();
    d->block<3, 4>(3, 3) = -spatial::skew(f) * spatial::skew(rho) * theta;
  }
  /// Animation geometry (io/model_scene.hpp): the body's arm, from its reference point to B (on A).
  template <class Drawer>
  static void draw(const record& r, Drawer& d) {
    const rotation_slot q{3, 6};
    const int reference = d.body_point_at(r.x0, {0, 1, 2}, q, spatial::vec3::Zero());
    const int b = d.body_point_at(r.x0, {0, 1, 2}, q, r.rb);
    d.line(reference, b);
  }
  /// dc/dt = v_B = x' + omega x rho_B, the velocity of the body's point B.
  /// (attached_point's v, without its other members: this runs after every Newton update.)
  static void slaved_rate(const record& r, const node_values<7>& x, Eigen::Matrix<double, 7, 1>& rate) {
    const spatial::quaternion q = x.u.segment<4>(3);
    const spatial::vec3 rho = spatial::rotation_matrix(q) * r.rb;
    const spatial::mat34 theta = (2.0 / q.squaredNorm()) * spatial::e_matrix(q);
    const spatial::vec3 omega = theta * x.v.segment<4>(3);
    rate.head<3>() = x.v.head<3>() + omega.cross(rho);
  }
};
static_assert(SlavingNodeKind<ground_pivot_kind>);

/// Adds a ground pivot to model m: body b (reference point x, y, z = bx, by, bz, rotational node
/// rb) with its point B (geo.rbx, rby, rbz in its frame; its reference point starts at geo.xb0,
/// yb0, zb0) held on the ground point A = (geo.xa0 + geo.rax, ...): SPH3X from the ground to body b
/// in reduced form (see the file comment). m must list exact_spherical_joint (which declares the
/// kind). A DOF of the body that is the ground, a slaved DOF already owned by another node, or a
/// geometry that is not finite is code 110; the model is then unchanged.
template <class Model>
void add_ground_pivot(Model& m, std::string name, const detail::joint_geometry& geo, dof bx, dof by, dof bz,
                      const rotation_node& rb) {
  if (!geo.finite())
    throw error(error_code::invalid_model,
                "ground pivot '" + name + "': positions and offsets must be finite (a parameter is not finite)");
  ground_pivot_record r;
  r.dofs = {bx.index, by.index, bz.index, rb.q1.index, rb.q2.index, rb.q3.index, rb.q4.index};
  r.a = spatial::vec3(geo.xa0 + geo.rax, geo.ya0 + geo.ray, geo.za0 + geo.raz);
  r.x0 = spatial::vec3(geo.xb0, geo.yb0, geo.zb0);
  r.rb = spatial::vec3(geo.rbx, geo.rby, geo.rbz);
  r.name = std::move(name);
  m.template add_node<ground_pivot_kind>(std::move(r));
}

/// The force of ground pivot i (the i-th add_ground_pivot of the model) on its body, global X, Y, Z
/// [N], at the driver's last model evaluation: the element flows on the body's x, y, z, which the
/// pivot carries to the moment rows (the flows balance inertia against the applied forces, m a - P,
/// and the pivot supplies the difference). Like an element's work vector it belongs to the state of
/// that evaluation (after a converged step, the last Newton iterate). `sim` is any driver
/// (pradis::simulation, pradis::bdf_simulation). A pivot that does not exist, or a driver that has
/// not run, is code 110 (as a DOF outside the model is for the drivers' u()).
template <class Sim>
spatial::vec3 ground_pivot_force(const Sim& sim, std::size_t i) {
  const auto f = sim.get_assembler().template slaved_flows<ground_pivot_kind>();
  const std::size_t count = sim.get_model().template nodes<ground_pivot_kind>().size();
  if (i >= count)
    throw error(error_code::invalid_model, "ground pivot " + std::to_string(i) + " does not exist (indices 0 to " +
                                               std::to_string(count) + " - 1 in the order added)");
  if (f.size() < 7 * (i + 1))
    throw error(error_code::invalid_model,
                "ground pivot " + std::to_string(i) + " has not been evaluated yet: run a stage first");
  return {f[7 * i], f[7 * i + 1], f[7 * i + 2]};
}

}  // namespace pradis::elements
