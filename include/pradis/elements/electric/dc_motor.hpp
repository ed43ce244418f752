#pragma once
/// \file
/// DCM: permanent-magnet DC motor coupling an electric circuit to a 1D rotation.

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct dc_motor_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using dc_motor = dc_motor_t<>;
/// DCM: DC motor with armature resistance R and inductance L and motor constant k
/// (back-EMF k w, torque k i). Terminals: nodes 1 (+) and 2 (-); shaft: a 1D
/// rotation DOF whose v is the angular speed w. The armature current i (from node 1
/// through the armature to node 2) is the internal DOF's v, with the armature
/// equation as its row:
///     F_i = (v1 - v2) - k w - R i - L di/dt = 0
/// Flows: i on node 1, -i on node 2, -k i on the shaft (the motor drives the shaft
/// with the torque k i). Electric power (v1 - v2) i = R i^2 + L i i' + k i w: the
/// converted power k i w is the mechanical power. Blocks C and M (ADR=2, IGN=0).
template <class>
struct dc_motor_t {
  static constexpr pradis::passport passport{.name = "DCM", .ext = 3, .ent = 1, .par = 3, .wrk = 3, .adr = 2};
  static constexpr std::array<domain, 4> domains{domain::electric, domain::electric, domain::mechanical,
                                                 domain::electric};
  static constexpr element_help help{
      .title = "permanent-magnet DC motor",
      .name = "DC motor: armature R and L, back-EMF k w, torque k i on a 1D rotation",
      .field = "electromechanics",
      .dofs = "1 - positive terminal [V]\n2 - negative terminal [V]\n3 - shaft rotation (v = angular speed) [rad]",
      .parameters = "1 - armature resistance R [Ohm] (>= 0)\n2 - armature inductance L [H] (>= 0, R + L > 0)\n"
                    "3 - motor constant k [V s/rad = N m/A] (> 0)",
      .work = "1 - armature current i [A]\n2 - torque on the shaft k i [N m]\n3 - back-EMF k w [V]",
      .special = "code 100 if R < 0, L < 0, both are zero, k <= 0 or a parameter is not finite. The armature "
                 "current is an internal DOF (0 at t = 0)"};
  struct parameters {
    double r = 1;  ///< armature resistance [Ohm]
    double l = 0;  ///< armature inductance [H]
    double k = 1;  ///< motor constant [V s/rad]
  };
  parameters p;
  explicit dc_motor_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {1.2, 0.05, 0.8}; }
  static dc_motor from_parameters(std::span<const double> v) { return dc_motor({v[0], v[1], v[2]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.r >= 0) || !std::isfinite(p.r)) ctx.invalid_parameter("armature resistance R = " + to_text(p.r) + " must be finite and >= 0");
    if (!(p.l >= 0) || !std::isfinite(p.l)) ctx.invalid_parameter("armature inductance L = " + to_text(p.l) + " must be finite and >= 0");
    if (!(p.r + p.l > 0)) ctx.invalid_parameter("armature resistance R and inductance L are both zero");
    if (!(p.k > 0) || !std::isfinite(p.k)) ctx.invalid_parameter("motor constant k = " + to_text(p.k) + " must be finite and > 0");
  }
  void evaluate(const local_input<dc_motor>& in, local_output<dc_motor>& out, element_context& ctx) const {
    const double i = in.v(3), w = in.v(2);
    out.f << i, -i, -p.k * i, (in.v(0) - in.v(1)) - p.k * w - p.r * i - p.l * in.a(3);
    ctx.work[0] = i;
    ctx.work[1] = p.k * i;
    ctx.work[2] = p.k * w;
    if (!out.want_jacobian) return;
    out.C << 0, 0, 0, 1,  //
        0, 0, 0, -1,      //
        0, 0, 0, -p.k,    //
        1, -1, -p.k, -p.r;
    out.M.setZero();
    out.M(3, 3) = -p.l;
  }
};

}  // namespace pradis::elements
