#pragma once
/// \file
/// HCYL: double-acting hydraulic cylinder coupling two chambers to a 1D translation.

#include <array>
#include <cmath>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

template <class = void>
struct hydraulic_cylinder_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using hydraulic_cylinder = hydraulic_cylinder_t<>;
/// HCYL: double-acting cylinder with a fixed housing. DOF 1: pressure pA of the cap-side
/// chamber (area AA), DOF 2: pressure pB of the rod-side chamber (area AB), DOF 3: piston
/// displacement x (positive extends, enlarging chamber A). Piston position s = s0 + x in
/// [0, stroke]; chamber volumes VA = VA0 + AA s, VB = VB0 + AB (stroke - s), compressible
/// with bulk modulus B. Flows:
///   fA = AA dx/dt + VA / B dpA/dt,   fB = -AB dx/dt + VB / B dpB/dt,
///   fx = -(AA pA - AB pB + Fs)  (minus the force of fluid and end stops on the piston).
/// End stops: a stiff spring-damper that engages smoothly over the penetration width w,
///   Fs = ke r(-s) - ce r'(-s) dx/dt - ke r(s - stroke) - ce r'(s - stroke) dx/dt,
/// r(d) = 0 (d <= -w), (d + w)^2 / (4 w) (|d| < w), d (d >= w): a C1 penalty contact.
template <class>
struct hydraulic_cylinder_t {
  static constexpr pradis::passport passport{.name = "HCYL", .ext = 3, .par = 10, .wrk = 5, .adr = 1};
  static constexpr std::array<domain, 3> domains{domain::hydraulic, domain::hydraulic, domain::mechanical};
  static constexpr element_help help{
      .title = "double-acting hydraulic cylinder with compressible chambers and end stops",
      .name = "Double-acting cylinder: chamber flows A dx/dt + V(x)/B dp/dt, piston force AA pA - AB pB",
      .field = "hydraulics",
      .dofs = "1 - pressure of chamber A (cap side) [Pa]\n2 - pressure of chamber B (rod side) [Pa]\n"
              "3 - piston displacement x, positive extending [m]",
      .parameters = "1 - piston area of chamber A, AA [m^2] (> 0)\n2 - annulus area of chamber B, AB [m^2] (> 0)\n"
                    "3 - stroke [m] (> 0)\n4 - initial piston position s0 [m] (0 <= s0 <= stroke)\n"
                    "5 - dead volume of chamber A, VA0 [m^3] (> 0)\n6 - dead volume of chamber B, VB0 [m^3] (> 0)\n"
                    "7 - bulk modulus B [Pa] (> 0)\n8 - end-stop stiffness ke [N/m] (>= 0)\n"
                    "9 - end-stop damping ce [N s/m] (>= 0)\n10 - end-stop engagement width w [m] (> 0)",
      .work = "1 - piston position s = s0 + x [m]\n2 - force on the piston AA pA - AB pB + Fs [N]\n"
              "3 - volume of chamber A [m^3]\n4 - volume of chamber B [m^3]\n5 - end-stop force Fs [N]",
      .special = "code 100 if an area, the stroke, a dead volume, B or w is not positive, ke or ce is negative or "
                 "s0 is outside [0, stroke]; code 75 if a chamber volume reaches zero (the piston went through an "
                 "end stop)"};
  struct parameters {
    double area_a = 0, area_b = 0;              ///< AA, AB [m^2]
    double stroke = 0, s0 = 0;                  ///< [m]
    double dead_a = 0, dead_b = 0;              ///< VA0, VB0 [m^3]
    double bulk_modulus = 0;                    ///< B [Pa]
    double stop_stiffness = 0, stop_damping = 0;  ///< ke [N/m], ce [N s/m]
    double stop_width = 1e-3;                   ///< w [m]
  };
  parameters p;
  explicit hydraulic_cylinder_t(parameters q) : p(q) {}
  /// Example parameters (scaled units; the all-elements test's +-3 reaches both end stops).
  static parameters example() { return {0.5, 0.3, 4.0, 2.0, 2.0, 2.0, 20.0, 100.0, 5.0, 0.1}; }
  static hydraulic_cylinder from_parameters(std::span<const double> v) {
    return hydraulic_cylinder({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9]});
  }
  void new_integration(element_context& ctx) const {
    using namespace hydraulic_detail;
    require_positive(ctx, "area AA", p.area_a);
    require_positive(ctx, "area AB", p.area_b);
    require_positive(ctx, "stroke", p.stroke);
    if (!(p.s0 >= 0 && p.s0 <= p.stroke))
      ctx.invalid_parameter("initial position s0 = " + to_text(p.s0) + " must be in [0, stroke]");
    require_positive(ctx, "dead volume VA0", p.dead_a);
    require_positive(ctx, "dead volume VB0", p.dead_b);
    require_positive(ctx, "bulk modulus B", p.bulk_modulus);
    require_nonnegative(ctx, "end-stop stiffness ke", p.stop_stiffness);
    require_nonnegative(ctx, "end-stop damping ce", p.stop_damping);
    require_positive(ctx, "end-stop width w", p.stop_width);
  }
  void evaluate(const local_input<hydraulic_cylinder>& in, local_output<hydraulic_cylinder>& out,
                element_context& ctx) const {
    using hydraulic_detail::ramp;
    const double s = p.s0 + in.u(2), xd = in.v(2);
    const double va = p.dead_a + p.area_a * s, vb = p.dead_b + p.area_b * (p.stroke - s);
    if (!(va > 0)) ctx.singular("the volume of chamber A has reached zero (piston position " + to_text(s) + " m)");
    if (!(vb > 0)) ctx.singular("the volume of chamber B has reached zero (piston position " + to_text(s) + " m)");
    const ramp lo(-s, p.stop_width), hi(s - p.stroke, p.stop_width);
    const double ke = p.stop_stiffness, ce = p.stop_damping;
    const double fs = ke * (lo.value - hi.value) - ce * (lo.slope + hi.slope) * xd;
    const double force = p.area_a * in.v(0) - p.area_b * in.v(1) + fs;
    const double b = p.bulk_modulus;
    out.f << p.area_a * xd + va / b * in.a(0), -p.area_b * xd + vb / b * in.a(1), -force;
    ctx.work[0] = s;
    ctx.work[1] = force;
    ctx.work[2] = va;
    ctx.work[3] = vb;
    ctx.work[4] = fs;
    if (!out.want_jacobian) return;
    // dFs/ds: lo depends on -s, hi on s.
    const double dfs_ds = -ke * (lo.slope + hi.slope) - ce * (-lo.curvature + hi.curvature) * xd;
    const double dfs_dv = -ce * (lo.slope + hi.slope);
    out.K << 0, 0, p.area_a / b * in.a(0), 0, 0, -p.area_b / b * in.a(1), 0, 0, -dfs_ds;
    out.C << 0, 0, p.area_a, 0, 0, -p.area_b, -p.area_a, p.area_b, -dfs_dv;
    out.M << va / b, 0, 0, 0, vb / b, 0, 0, 0, 0;
  }
  /// The all-elements test keeps both chamber volumes positive.
  bool admissible(const local_input<hydraulic_cylinder>& in) const {
    const double s = p.s0 + in.u(2);
    return p.dead_a + p.area_a * s > 0 && p.dead_b + p.area_b * (p.stroke - s) > 0;
  }
};

}  // namespace pradis::elements
