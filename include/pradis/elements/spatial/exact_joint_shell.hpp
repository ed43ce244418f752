#pragma once
/// \file
/// The element shell shared by the exact spatial joints (SPH3X, REV3X, UNI3X,
/// CYL3X, PRI3X, FIX3X, PTL3X, PTP3X), their parameter layouts and the joint
/// frames. A joint kind supplies its passport, help, parameters and constraint
/// rows (exact_constraint_rows.hpp); the shell supplies the rest of the element.

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/elements/spatial/exact_constraint_rows.hpp"
#include "pradis/elements/spatial/joints.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// The two bodies of an exact joint at one evaluation: the attached joint points
/// (with the rotation matrices R(q_a) = a.r, R(q_b) = b.r).
struct joint_bodies {
  const attached_point& a;  ///< joint point A of body a
  const attached_point& b;  ///< joint point B of body b
};

/// A unit vector and the code-100 check of its raw value (finite, non-zero).
inline void check_joint_vector(element_context& ctx, const char* what, double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  if (!(n > 0) || !std::isfinite(n))
    ctx.invalid_parameter(std::string(what) + " = (" + to_text(x) + ", " + to_text(y) + ", " + to_text(z) +
                          ") must be finite and non-zero (a zero vector or not finite)");
}

/// An orthonormal joint frame fixed in a body: the axis e, the reference t
/// (the given t made perpendicular to e) and n = e x t.
struct joint_frame {
  spatial::vec3 e = spatial::vec3::UnitZ();  ///< unit axis
  spatial::vec3 t = spatial::vec3::UnitX();  ///< unit reference vector, perpendicular to e
  spatial::vec3 n = spatial::vec3::UnitY();  ///< e x t
  joint_frame() = default;
  /// From a raw axis and reference vector (left unchanged where they are invalid;
  /// check_joint_frame reports it).
  joint_frame(const spatial::vec3& axis, const spatial::vec3& ref) {
    e = unit_axis(axis);
    const spatial::vec3 tp = ref - e.dot(ref) * e;
    if (!(tp.norm() > 1e-9 * ref.norm())) return;
    t = unit_axis(tp);
    n = e.cross(t);
  }
};

/// Code 100 unless the axis and the reference vector of a joint frame are finite,
/// non-zero and not parallel.
inline void check_joint_frame(element_context& ctx, const char* axis_name, const char* ref_name,
                              const spatial::vec3& axis, const spatial::vec3& ref) {
  check_joint_vector(ctx, axis_name, axis.x(), axis.y(), axis.z());
  check_joint_vector(ctx, ref_name, ref.x(), ref.y(), ref.z());
  const spatial::vec3 e = axis.normalized();
  if (!((ref - e.dot(ref) * e).norm() > 1e-9 * ref.norm()))
    ctx.invalid_parameter(std::string("the reference vector ") + ref_name + " is parallel to the axis " + axis_name +
                          " (they must span the joint frame)");
}

/// Parameters of SPH3X: the joint geometry alone (PAR 1..12).
struct point_joint_parameters {
  joint_geometry geo;  ///< initial positions and joint points (PAR 1..12)
  /// From the flat PAR list (PAR = 12).
  static point_joint_parameters read(std::span<const double> v) {
    return {joint_geometry{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]}};
  }
};

/// Parameters of PTL3X and PTP3X: the geometry and one vector fixed in body a.
struct one_axis_parameters {
  joint_geometry geo;             ///< initial positions and joint points (PAR 1..12)
  double ex = 0, ey = 0, ez = 1;  ///< the vector in body a's frame (PAR 13..15)
  /// From the flat PAR list (PAR = 15).
  static one_axis_parameters read(std::span<const double> v) {
    return {point_joint_parameters::read(v).geo, v[12], v[13], v[14]};
  }
  spatial::vec3 axis() const { return {ex, ey, ez}; }
};

/// Parameters of REV3X, UNI3X and CYL3X: the geometry, an axis e_a fixed in body a
/// and an axis e_b fixed in body b.
struct two_axis_parameters {
  joint_geometry geo;                ///< initial positions and joint points (PAR 1..12)
  double eax = 0, eay = 0, eaz = 1;  ///< axis e_a in body a's frame (PAR 13..15)
  double ebx = 0, eby = 0, ebz = 1;  ///< axis e_b in body b's frame (PAR 16..18)
  /// From the flat PAR list (PAR = 18).
  static two_axis_parameters read(std::span<const double> v) {
    return {point_joint_parameters::read(v).geo, v[12], v[13], v[14], v[15], v[16], v[17]};
  }
  spatial::vec3 axis_a() const { return {eax, eay, eaz}; }
  spatial::vec3 axis_b() const { return {ebx, eby, ebz}; }
};

/// Parameters of PRI3X and FIX3X: the geometry and a joint frame (axis e and
/// reference t) in each body.
struct two_frame_parameters {
  joint_geometry geo;                ///< initial positions and joint points (PAR 1..12)
  double eax = 0, eay = 0, eaz = 1;  ///< axis e_a in body a's frame (PAR 13..15)
  double tax = 1, tay = 0, taz = 0;  ///< reference t_a in body a's frame (PAR 16..18)
  double ebx = 0, eby = 0, ebz = 1;  ///< axis e_b in body b's frame (PAR 19..21)
  double tbx = 1, tby = 0, tbz = 0;  ///< reference t_b in body b's frame (PAR 22..24)
  /// From the flat PAR list (PAR = 24).
  static two_frame_parameters read(std::span<const double> v) {
    return {point_joint_parameters::read(v).geo, v[12], v[13], v[14], v[15], v[16], v[17],
            v[18], v[19], v[20], v[21], v[22], v[23]};
  }
  joint_frame frame_a() const { return {{eax, eay, eaz}, {tax, tay, taz}}; }
  joint_frame frame_b() const { return {{ebx, eby, ebz}, {tbx, tby, tbz}}; }
  /// Code 100 unless both frames are valid.
  void check(element_context& ctx) const {
    check_joint_frame(ctx, "e_a", "t_a", {eax, eay, eaz}, {tax, tay, taz});
    check_joint_frame(ctx, "e_b", "t_b", {ebx, eby, ebz}, {tbx, tby, tbz});
  }
};

/// The element shell of an exact spatial joint. Kind supplies:
/// - `passport` (EXT = 12, ENT = 2 + the number of rows), `help`, `parameters`
///   (with a `geo` member and a static `read`), the member `p`, `example()`;
/// - `check(ctx)`: its own parameter checks (code 100);
/// - `rows(bodies, mu, out, work)`: adds its constraint rows with the multipliers
///   mu (local 14 on) and writes its geometric work outputs;
/// - `force_work` / `moment_work`: the first work index of the force on body b and
///   of the moment on b about B (-1: not reported).
/// The shell checks the geometry (code 100), the quaternion norms (code 75),
/// zeroes the flows, and writes the reactions (joint_reactions_on_b).
template <class Kind>
struct exact_joint : Kind {
  /// A's q1..q3 at local 3..5 with hidden q4 at 12; B's at 9..11 with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};

  explicit exact_joint(typename Kind::parameters q) : Kind(q) {}
  /// From the flat PAR list.
  static exact_joint from_parameters(std::span<const double> v) { return exact_joint(Kind::parameters::read(v)); }
  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): the arms of the two bodies.
  template <class Drawer>
  void draw(Drawer& d) const {
    this->p.geo.draw(d);
  }
  void new_integration(element_context& ctx) const {
    if (!this->p.geo.finite()) ctx.invalid_parameter("positions and offsets must be finite (a parameter is not finite)");
    Kind::check(ctx);
  }
  void evaluate(const local_input<exact_joint>& in, local_output<exact_joint>& out, element_context& ctx) const {
    using namespace spatial;
    if (!two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    // The flows use no derivative of the points, the rows only dp/dq (exact_constraint_rows.hpp).
    using level = attached_point::level;
    const auto ab = this->p.geo.points(in, out.want_jacobian ? level::position : level::none);
    const joint_bodies s{ab.first, ab.second};
    begin_exact_joint(out);
    constexpr int rows = Kind::passport.ent - 2;
    const Eigen::Matrix<double, rows, 1> mu = in.v.template segment<rows>(first_multiplier);
    Kind::rows(s, mu, out, ctx.work);
    const auto [force, moment] = joint_reactions_on_b(s.b, out);
    for (int i = 0; i < 3; ++i) {
      ctx.work[static_cast<std::size_t>(Kind::force_work + i)] = force(i);
      if constexpr (Kind::moment_work >= 0) ctx.work[static_cast<std::size_t>(Kind::moment_work + i)] = moment(i);
    }
  }
  /// States the checks may use: both quaternion norms are not near zero.
  bool admissible(const local_input<exact_joint>& in) const { return two_quaternions_admissible(in); }
};

}  // namespace pradis::elements::detail
