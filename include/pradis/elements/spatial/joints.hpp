#pragma once
/// \file
/// SPH3 (spherical joint) and REV3 (revolute joint) between two bodies in spatial
/// motion, as stiff penalty couplings: a spring-damper on the mismatch of two
/// attachment points and, for REV3, on the misalignment of two hinge axes. The
/// constraint is met to O(load / stiffness): a gap of F / k at a transmitted force F.

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

namespace detail {
/// The geometry of a joint: initial reference-point positions and attachment offsets.
struct joint_geometry {
  double xa0 = 0, ya0 = 0, za0 = 0;  ///< initial global position of body a's reference point [m]
  double rax = 0, ray = 0, raz = 0;  ///< joint point A in body a's frame [m]
  double xb0 = 0, yb0 = 0, zb0 = 0;  ///< initial global position of body b's reference point [m]
  double rbx = 0, rby = 0, rbz = 0;  ///< joint point B in body b's frame [m]
  /// Whether every entry is finite.
  bool finite() const {
    for (double x : {xa0, ya0, za0, rax, ray, raz, xb0, yb0, zb0, rbx, rby, rbz})
      if (!std::isfinite(x)) return false;
    return true;
  }
  /// The two attached points of a two-body element.
  template <class In>
  std::pair<attached_point, attached_point> points(const In& in) const {
    return two_points(in, spatial::vec3(xa0, ya0, za0), spatial::vec3(rax, ray, raz), spatial::vec3(xb0, yb0, zb0),
                      spatial::vec3(rbx, rby, rbz));
  }
};

/// The DOF lines of the help texts of SPH3 and REV3.
inline constexpr std::string_view joint_dof_help =
    "1 - translation of body a's reference point along X [m]\n"
    "2 - along Y [m]\n"
    "3 - along Z [m]\n"
    "4 - rotation potential q1 of body a's rotational node (flow: moment about X) [-]\n"
    "5 - q2 of body a [-]\n"
    "6 - q3 of body a [-]\n"
    "7 - translation of body b's reference point along X [m]\n"
    "8 - along Y [m]\n"
    "9 - along Z [m]\n"
    "10 - rotation potential q1 of body b's rotational node [-]\n"
    "11 - q2 of body b [-]\n"
    "12 - q3 of body b [-] (connect DOFs 1-6 or 7-12 to the ground for a joint to the ground)";
/// The parameter lines of the help text of SPH3.
inline constexpr std::string_view spherical_joint_parameter_help =
    "1 - initial X of body a's reference point [m]\n"
    "2 - initial Y of body a's reference point [m]\n"
    "3 - initial Z of body a's reference point [m]\n"
    "4 - x of joint point A from a's reference point, body a frame [m]\n"
    "5 - y of A, body a frame [m]\n"
    "6 - z of A, body a frame [m]\n"
    "7 - initial X of body b's reference point [m]\n"
    "8 - initial Y of body b's reference point [m]\n"
    "9 - initial Z of body b's reference point [m]\n"
    "10 - x of joint point B from b's reference point, body b frame [m]\n"
    "11 - y of B, body b frame [m]\n"
    "12 - z of B, body b frame [m]\n"
    "13 - penalty stiffness k on the gap p_B - p_A [N/m] (> 0)\n"
    "14 - penalty damping c on the gap rate [N s/m] (>= 0)";
}  // namespace detail

/// SPH3: spherical (ball) joint between point A of body a and point B of body b, as a
/// stiff isotropic spring-damper on the gap d = p_B - p_A (p = X0 + x + R(q) r, see
/// SD3): F = k d + c d', -F on A's x, y, z and -rho_A x F on A's q1..q3, +F and
/// rho_B x F on B's. A transmitted force F opens the gap by |F| / k: k is a penalty
/// parameter, to be chosen so that this is negligible (and c ~ 0.1 ... 1 x 2 sqrt(k m)
/// to damp the joint's own stiff mode, whose frequency is about sqrt(k / m)).
struct spherical_joint {
  static constexpr pradis::passport passport{.name = "SPH3", .ext = 12, .ent = 2, .par = 14, .wrk = 4, .adr = 1, .ign = 3};
  /// A's q1..q3 at local 3..5 with hidden q4 at 12; B's at 9..11 with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "spherical joint (penalty) between two bodies in spatial motion",
      .name = "Spherical joint: stiff isotropic spring-damper on the gap between two body-fixed points [N]",
      .field = "mechanics, spatial motion",
      .dofs = detail::joint_dof_help,
      .parameters = detail::spherical_joint_parameter_help,
      .work = "1 - gap |p_B - p_A| [m]\n2 - joint force on body b, X [N]\n3 - Y [N]\n4 - Z [N]",
      .special = "code 100 if k <= 0, c < 0 or a parameter is not finite; code 75 if a quaternion norm comes near "
                 "zero. The constraint holds to |F| / k (F the transmitted force)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    detail::joint_geometry geo;  ///< initial positions and joint points (PAR 1..12)
    double k = 0;                ///< penalty stiffness [N/m]
    double c = 0;                ///< penalty damping [N s/m]
  };
  parameters p;

  explicit spherical_joint(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {{0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.2, 0.4, -0.5, -0.1, 0.25, 0.2}, 800.0, 15.0};
  }
  static spherical_joint from_parameters(std::span<const double> v) {
    return spherical_joint({{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]}, v[12], v[13]});
  }
  /// NEWINT: parameter checks (code 100).
  void new_integration(element_context& ctx) const {
    if (!p.geo.finite()) ctx.invalid_parameter("positions and offsets must be finite");
    if (!(p.k > 0) || !std::isfinite(p.k)) ctx.invalid_parameter("stiffness k = " + to_text(p.k) + " must be finite and > 0 (k <= 0)");
    if (!(p.c >= 0) || !std::isfinite(p.c)) ctx.invalid_parameter("damping c = " + to_text(p.c) + " must be finite and >= 0 (c < 0)");
  }
  void evaluate(const local_input<spherical_joint>& in, local_output<spherical_joint>& out, element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    const auto [a, b] = p.geo.points(in);
    const vec3 d = b.p - a.p;
    const vec3 f = p.k * d + p.c * (b.v - a.v);
    ctx.work[0] = d.norm();
    for (int i = 0; i < 3; ++i) ctx.work[static_cast<std::size_t>(i + 1)] = -f(i);
    detail::two_point_flows(a, b, f, p.k * mat3::Identity(), p.c * mat3::Identity(), out);
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<spherical_joint>& in) const { return detail::two_quaternions_admissible(in); }
};

}  // namespace pradis::elements
