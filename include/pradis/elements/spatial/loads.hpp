#pragma once
/// \file
/// F3, F3B, F3A, M3, M3B: force and torque sources in spatial motion, constant plus
/// harmonic, in global axes or fixed to a rotational node (body axes); F3A applies a
/// global force at a point fixed to a body (a weight at an offset centre of mass).

#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

/// Parameters of the spatial load sources: P(t) = P0 + A sin(2 pi f t + phase),
/// componentwise, in global axes (F3, M3) or body axes (F3B, M3B).
struct spatial_load_parameters {
  double p0x = 0, p0y = 0, p0z = 0;  ///< constant part P0 [N] or [N m]
  double ax = 0, ay = 0, az = 0;     ///< amplitude A [N] or [N m]
  double frequency = 0;              ///< f [Hz] (>= 0)
  double phase_deg = 0;              ///< phase [deg]

  /// From the flat PAR vector (8 entries).
  static spatial_load_parameters from(std::span<const double> v) { return {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]}; }
  /// P(t).
  spatial::vec3 at(double t) const {
    const double s = std::sin(2 * std::numbers::pi * frequency * t + phase_deg * std::numbers::pi / 180);
    return spatial::vec3(p0x + ax * s, p0y + ay * s, p0z + az * s);
  }
  /// NEWINT checks (code 100) and the STEPMD recommendation of the frequency.
  void check(element_context& ctx) const {
    for (double x : {p0x, p0y, p0z, ax, ay, az, phase_deg})
      if (!std::isfinite(x)) ctx.invalid_parameter("constant part, amplitude and phase must be finite");
    if (!(frequency >= 0) || !std::isfinite(frequency))
      ctx.invalid_parameter("frequency f = " + to_text(frequency) + " must be finite and >= 0");
  }
  /// Recommends 20 steps per period (as FSIN).
  void recommend(element_context& ctx) const {
    if (frequency > 0 && (ax != 0 || ay != 0 || az != 0)) ctx.recommend_step(1.0 / (20.0 * frequency));
  }
};

namespace detail {
/// The parameter lines of the help texts of the spatial load sources.
inline constexpr std::string_view spatial_load_parameter_help =
    "1 - constant part P0, X component\n"
    "2 - constant part P0, Y component\n"
    "3 - constant part P0, Z component\n"
    "4 - amplitude A, X component\n"
    "5 - amplitude A, Y component\n"
    "6 - amplitude A, Z component\n"
    "7 - frequency f [Hz] (>= 0)\n"
    "8 - phase [deg]";
}  // namespace detail

template <class = void>
struct spatial_force_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using spatial_force = spatial_force_t<>;
/// F3: force P(t) = P0 + A sin(2 pi f t + phase) in global axes on a point's
/// translations x, y, z. Flows -P(t).
template <class>
struct spatial_force_t {
  static constexpr pradis::passport passport{.name = "F3", .ext = 3, .par = 8, .wrk = 3, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "force in global axes on a point in spatial motion",
      .name = "Source of a spatial force P0 + A sin(2 pi f t + phase), global axes [N]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation along X [m]\n2 - translation along Y [m]\n3 - translation along Z [m]",
      .parameters = detail::spatial_load_parameter_help,
      .work = "1 - current force, X [N]\n2 - current force, Y [N]\n3 - current force, Z [N]",
      .special = "code 100 if f < 0 or a parameter is not finite; recommends a step of at most 1/(20 f)"};
  using parameters = spatial_load_parameters;
  parameters p;
  explicit spatial_force_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.0, -2.0, 0.5, 0.3, 0.2, -0.1, 2.0, 30.0}; }
  static spatial_force from_parameters(std::span<const double> v) { return spatial_force(parameters::from(v)); }
  void new_integration(element_context& ctx) const { p.check(ctx); }
  void evaluate(const local_input<spatial_force>& in, local_output<spatial_force>& out, element_context& ctx) const {
    const spatial::vec3 f = p.at(in.t);
    out.f = -f;
    for (int k = 0; k < 3; ++k) ctx.work[static_cast<std::size_t>(k)] = f(k);
    p.recommend(ctx);
    if (out.want_jacobian) out.K.setZero();
  }
  /// The local Jacobian entries that can be nonzero (core/element.hpp,
  /// HasJacobianStructure): none, the force depends on time alone.
  bool jacobian_entry(int, int) const noexcept { return false; }
};

template <class = void>
struct spatial_torque_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using spatial_torque = spatial_torque_t<>;
/// M3: torque n(t) = P0 + A sin(2 pi f t + phase) in global axes on the q1, q2, q3 of
/// a spatial rotational node (their flows are moments about X, Y, Z). Flows -n(t).
template <class>
struct spatial_torque_t {
  static constexpr pradis::passport passport{.name = "M3", .ext = 3, .par = 8, .wrk = 3, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "torque in global axes on a spatial rotational node",
      .name = "Source of a spatial moment P0 + A sin(2 pi f t + phase), global axes [N m]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - rotation potential q1 (flow: moment about X) [-]\n"
              "2 - rotation potential q2 (flow: moment about Y) [-]\n"
              "3 - rotation potential q3 (flow: moment about Z) [-]",
      .parameters = detail::spatial_load_parameter_help,
      .work = "1 - current moment about X [N m]\n2 - current moment about Y [N m]\n3 - current moment about Z [N m]",
      .special = "code 100 if f < 0 or a parameter is not finite; recommends a step of at most 1/(20 f)"};
  using parameters = spatial_load_parameters;
  parameters p;
  explicit spatial_torque_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.5, 0.2, -0.3, 0.1, 0.0, 0.2, 1.0, 0.0}; }
  static spatial_torque from_parameters(std::span<const double> v) { return spatial_torque(parameters::from(v)); }
  void new_integration(element_context& ctx) const { p.check(ctx); }
  void evaluate(const local_input<spatial_torque>& in, local_output<spatial_torque>& out, element_context& ctx) const {
    const spatial::vec3 n = p.at(in.t);
    out.f = -n;
    for (int k = 0; k < 3; ++k) ctx.work[static_cast<std::size_t>(k)] = n(k);
    p.recommend(ctx);
    if (out.want_jacobian) out.K.setZero();
  }
  /// The local Jacobian entries that can be nonzero (core/element.hpp,
  /// HasJacobianStructure): none, the moment depends on time alone.
  bool jacobian_entry(int, int) const noexcept { return false; }
};

template <class = void>
struct body_force_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using body_force = body_force_t<>;
/// F3B: force P(t) = P0 + A sin(2 pi f t + phase) fixed to a body (components in the
/// axes of the rotational node q), applied at the point x, y, z. Flows -R(q) P(t) on
/// x, y, z, none on q; dF/dq = [rho x] (2/s) E(q), rho = R(q) P(t).
template <class>
struct body_force_t {
  static constexpr pradis::passport passport{.name = "F3B", .ext = 6, .ent = 1, .par = 8, .wrk = 3, .adr = 1, .ign = 23};
  /// q1..q3 are local DOFs 4..6, the hidden q4 the internal DOF 7.
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{3, 6}}};
  static constexpr element_help help{
      .title = "body-fixed force on a point in spatial motion",
      .name = "Source of a force P0 + A sin(2 pi f t + phase) given in the axes of a rotational node [N]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of the point of application along X [m]\n"
              "2 - translation along Y [m]\n"
              "3 - translation along Z [m]\n"
              "4 - rotation potential q1 of the body's rotational node [-]\n"
              "5 - rotation potential q2 [-]\n"
              "6 - rotation potential q3 [-]",
      .parameters = detail::spatial_load_parameter_help,
      .work = "1 - current force, global X [N]\n2 - current force, global Y [N]\n3 - current force, global Z [N]",
      .special = "code 100 if f < 0 or a parameter is not finite; code 75 if the quaternion norm comes near zero; "
                 "recommends a step of at most 1/(20 f)"};
  using parameters = spatial_load_parameters;
  parameters p;
  explicit body_force_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.0, -2.0, 0.5, 0.3, 0.2, -0.1, 2.0, 30.0}; }
  static body_force from_parameters(std::span<const double> v) { return body_force(parameters::from(v)); }
  void new_integration(element_context& ctx) const { p.check(ctx); }
  void evaluate(const local_input<body_force>& in, local_output<body_force>& out, element_context& ctx) const {
    using namespace spatial;
    const quaternion q = in.u.segment<4>(3);
    const double s = q.squaredNorm();
    if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    const vec3 f = rotation_matrix(q) * p.at(in.t);
    out.f.setZero();
    out.f.head<3>() = -f;
    for (int k = 0; k < 3; ++k) ctx.work[static_cast<std::size_t>(k)] = f(k);
    p.recommend(ctx);
    if (!out.want_jacobian) return;
    out.K.setZero();
    out.K.block<3, 4>(0, 3) = skew(f) * ((2.0 / s) * e_matrix(q));
  }
  /// States the checks may use: the quaternion norm is not near zero.
  bool admissible(const local_input<body_force>& in) const { return in.u.segment<4>(3).norm() > 0.2; }
};

template <class = void>
struct offset_force_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using offset_force = offset_force_t<>;
/// F3A: force P(t) = P0 + A sin(2 pi f t + phase) in global axes, applied at a point
/// fixed to a body: offset c (body frame) from the body's reference point x, y, z, whose
/// orientation is the rotational node q. With rho = R(q) c the flows are -P on x, y, z
/// and -(rho x P) on q1, q2, q3 (the moment about the reference point), none on q4;
/// d(-(rho x P))/dq = -[P x][rho x] (2/s) E(q) (drho = dtheta x rho,
/// dtheta = (2/s) E(q) dq). The weight of a body whose reference point is not its
/// centre of mass, e.g. a top or a pendulum whose node sits at its pivot.
template <class>
struct offset_force_t {
  static constexpr pradis::passport passport{
      .name = "F3A", .ext = 6, .ent = 1, .par = 11, .wrk = 6, .adr = 1, .ign = 23};
  /// q1..q3 are local DOFs 4..6, the hidden q4 the internal DOF 7.
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{3, 6}}};
  static constexpr element_help help{
      .title = "force in global axes at a point fixed to a body in spatial motion",
      .name = "Source of a force P0 + A sin(2 pi f t + phase), global axes, at an offset point of a body [N]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of the body's reference point along X [m]\n"
              "2 - translation along Y [m]\n"
              "3 - translation along Z [m]\n"
              "4 - rotation potential q1 of the body's rotational node (flow: moment about X) [-]\n"
              "5 - rotation potential q2 (flow: moment about Y) [-]\n"
              "6 - rotation potential q3 (flow: moment about Z) [-]",
      .parameters = "1 - x of the point of application from the reference point, body frame [m]\n"
                    "2 - y of the point of application, body frame [m]\n"
                    "3 - z of the point of application, body frame [m]\n"
                    "4 - constant part P0, X component (global) [N]\n"
                    "5 - constant part P0, Y component\n"
                    "6 - constant part P0, Z component\n"
                    "7 - amplitude A, X component\n"
                    "8 - amplitude A, Y component\n"
                    "9 - amplitude A, Z component\n"
                    "10 - frequency f [Hz] (>= 0)\n"
                    "11 - phase [deg]",
      .work = "1 - current force, X [N]\n2 - current force, Y [N]\n3 - current force, Z [N]\n"
              "4 - its moment about the reference point, X [N m]\n5 - moment, Y [N m]\n6 - moment, Z [N m]",
      .special = "code 100 if f < 0 or a parameter is not finite; code 75 if the quaternion norm comes near zero; "
                 "recommends a step of at most 1/(20 f)"};
  /// Typed parameters, in PAR order.
  struct parameters {
    double cx = 0, cy = 0, cz = 0;  ///< point of application from the reference point (body frame) [m]
    spatial_load_parameters load;   ///< the force P(t), global axes [N]
  };
  parameters p;
  explicit offset_force_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.3, -0.2, 0.5, {1.0, -2.0, 0.5, 0.3, 0.2, -0.1, 2.0, 30.0}}; }
  static offset_force from_parameters(std::span<const double> v) {
    return offset_force({v[0], v[1], v[2], spatial_load_parameters::from(v.subspan(3))});
  }
  void new_integration(element_context& ctx) const {
    for (double x : {p.cx, p.cy, p.cz})
      if (!std::isfinite(x)) ctx.invalid_parameter("the offset of the point of application must be finite");
    p.load.check(ctx);
  }
  void evaluate(const local_input<offset_force>& in, local_output<offset_force>& out, element_context& ctx) const {
    using namespace spatial;
    const quaternion q = in.u.segment<4>(3);
    const double s = q.squaredNorm();
    if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    const vec3 f = p.load.at(in.t);
    const vec3 rho = rotation_matrix(q) * vec3(p.cx, p.cy, p.cz);
    const vec3 n = rho.cross(f);
    out.f.setZero();
    out.f.head<3>() = -f;
    out.f.segment<3>(3) = -n;
    for (int k = 0; k < 3; ++k) {
      ctx.work[static_cast<std::size_t>(k)] = f(k);
      ctx.work[static_cast<std::size_t>(k + 3)] = n(k);
    }
    p.load.recommend(ctx);
    if (!out.want_jacobian) return;
    out.K.setZero();
    out.K.block<3, 4>(3, 3) = -(skew(f) * skew(rho)) * ((2.0 / s) * e_matrix(q));
  }
  /// The local Jacobian entries that can be nonzero (core/element.hpp,
  /// HasJacobianStructure): the moment rows q1..q3 in the columns q1..q4; the force
  /// depends on time alone, and q4's row has no flow.
  bool jacobian_entry(int r, int c) const noexcept { return r >= 3 && r < 6 && c >= 3; }
  /// States the checks may use: the quaternion norm is not near zero.
  bool admissible(const local_input<offset_force>& in) const { return in.u.segment<4>(3).norm() > 0.2; }
};

template <class = void>
struct body_torque_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using body_torque = body_torque_t<>;
/// M3B: torque n(t) = P0 + A sin(2 pi f t + phase) fixed to a body (components in the
/// axes of its rotational node). Flows -R(q) n(t) on q1, q2, q3, none on q4;
/// dF/dq = [R n x] (2/s) E(q).
template <class>
struct body_torque_t {
  static constexpr pradis::passport passport{.name = "M3B", .ext = 3, .ent = 1, .par = 8, .wrk = 3, .adr = 1, .ign = 23};
  /// q1..q3 are local DOFs 1..3, the hidden q4 the internal DOF 4.
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{0, 3}}};
  static constexpr element_help help{
      .title = "body-fixed torque on a spatial rotational node",
      .name = "Source of a moment P0 + A sin(2 pi f t + phase) given in the axes of a rotational node [N m]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - rotation potential q1 (flow: moment about X) [-]\n"
              "2 - rotation potential q2 (flow: moment about Y) [-]\n"
              "3 - rotation potential q3 (flow: moment about Z) [-]",
      .parameters = detail::spatial_load_parameter_help,
      .work = "1 - current moment about global X [N m]\n2 - about global Y [N m]\n3 - about global Z [N m]",
      .special = "code 100 if f < 0 or a parameter is not finite; code 75 if the quaternion norm comes near zero; "
                 "recommends a step of at most 1/(20 f)"};
  using parameters = spatial_load_parameters;
  parameters p;
  explicit body_torque_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.5, 0.2, -0.3, 0.1, 0.0, 0.2, 1.0, 0.0}; }
  static body_torque from_parameters(std::span<const double> v) { return body_torque(parameters::from(v)); }
  void new_integration(element_context& ctx) const { p.check(ctx); }
  void evaluate(const local_input<body_torque>& in, local_output<body_torque>& out, element_context& ctx) const {
    using namespace spatial;
    const quaternion q = in.u.head<4>();
    const double s = q.squaredNorm();
    if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    const vec3 n = rotation_matrix(q) * p.at(in.t);
    out.f.setZero();
    out.f.head<3>() = -n;
    for (int k = 0; k < 3; ++k) ctx.work[static_cast<std::size_t>(k)] = n(k);
    p.recommend(ctx);
    if (!out.want_jacobian) return;
    out.K.setZero();
    out.K.block<3, 4>(0, 0) = skew(n) * ((2.0 / s) * e_matrix(q));
  }
  /// Its moment -R(q) n(t) turns with its node (core/element.hpp, HasBodyFixedFlows).
  bool body_fixed_flows() const noexcept { return true; }
  /// States the checks may use: the quaternion norm is not near zero.
  bool admissible(const local_input<body_torque>& in) const { return in.u.head<4>().norm() > 0.2; }
};

}  // namespace pradis::elements
