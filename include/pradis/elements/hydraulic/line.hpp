#pragma once
/// \file
/// HLINE: one lumped segment of a hydraulic line (pi model).

#include <array>
#include <cmath>
#include <numbers>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

template <class = void>
struct hydraulic_line_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using hydraulic_line = hydraulic_line_t<>;
/// HLINE: a pipe segment of length l and inner diameter d as a lumped pi model: half
/// its capacitance C = A l / B at each end, and between the ends an inertance
/// L = rho l / A in series with the laminar (Hagen-Poiseuille) resistance
/// R = 128 mu l / (pi d^4), joined at an internal node m (A = pi d^2 / 4).
///   f1 = C/2 dp1/dt + qL,   fm = -qL + qR,   f2 = C/2 dp2/dt - qR,
///   qL = (u1 - um) / L  (the inertance: a stiffness block; u is the pressure impulse),
///   qR = (pm - p2) / R.
/// The segment starts at rest (qL = 0 with u = 0 at t = 0). Chain segments for a long line.
template <class>
struct hydraulic_line_t {
  static constexpr pradis::passport passport{.name = "HLINE", .ext = 2, .ent = 1, .par = 5, .wrk = 4, .adr = 1};
  static constexpr std::array<domain, 3> domains{domain::hydraulic, domain::hydraulic, domain::hydraulic};
  static constexpr element_help help{
      .title = "lumped hydraulic line segment (capacitance, inertance, laminar resistance)",
      .name = "Line segment, pi model: C/2 at each end, inertance L and resistance R in series",
      .field = "hydraulics",
      .dofs = "1 - pressure at end 1 [Pa]\n2 - pressure at end 2 [Pa]",
      .parameters = "1 - length l [m] (> 0)\n2 - inner diameter d [m] (> 0)\n3 - bulk modulus B [Pa] (> 0)\n"
                    "4 - density rho [kg/m^3] (> 0)\n5 - dynamic viscosity mu [Pa s] (> 0)",
      .work = "1 - flow through the segment from end 1 to end 2 [m^3/s]\n2 - capacitance C = A l / B [m^3/Pa]\n"
              "3 - inertance L = rho l / A [kg/m^4]\n4 - resistance R = 128 mu l / (pi d^4) [Pa s/m^3]",
      .special = "code 100 if a parameter is not positive; one internal DOF (the pressure between L and R)"};
  struct parameters {
    double length = 0;        ///< l [m]
    double diameter = 0;      ///< d [m]
    double bulk_modulus = 0;  ///< B [Pa]
    double density = 850;     ///< rho [kg/m^3]
    double viscosity = 0.03;  ///< mu [Pa s]
  };
  parameters p;
  explicit hydraulic_line_t(parameters q) : p(q) {}
  /// Example parameters (scaled units).
  static parameters example() { return {2.0, 0.8, 30.0, 3.0, 0.05}; }
  static hydraulic_line from_parameters(std::span<const double> v) {
    return hydraulic_line({v[0], v[1], v[2], v[3], v[4]});
  }
  void new_integration(element_context& ctx) const {
    using namespace hydraulic_detail;
    require_positive(ctx, "length l", p.length);
    require_positive(ctx, "diameter d", p.diameter);
    require_positive(ctx, "bulk modulus B", p.bulk_modulus);
    require_positive(ctx, "density rho", p.density);
    require_positive(ctx, "viscosity mu", p.viscosity);
    const double area = std::numbers::pi * p.diameter * p.diameter / 4;
    ctx.work[1] = area * p.length / p.bulk_modulus;
    ctx.work[2] = p.density * p.length / area;
    ctx.work[3] = 128 * p.viscosity * p.length / (std::numbers::pi * std::pow(p.diameter, 4));
  }
  void evaluate(const local_input<hydraulic_line>& in, local_output<hydraulic_line>& out,
                element_context& ctx) const {
    const double c2 = ctx.work[1] / 2, kl = 1 / ctx.work[2], gr = 1 / ctx.work[3];
    const double ql = kl * (in.u(0) - in.u(2)), qr = gr * (in.v(2) - in.v(1));
    out.f << c2 * in.a(0) + ql, c2 * in.a(1) - qr, -ql + qr;
    ctx.work[0] = ql;
    if (!out.want_jacobian) return;
    out.K << kl, 0, -kl, 0, 0, 0, -kl, 0, kl;
    out.C << 0, 0, 0, 0, gr, -gr, 0, -gr, gr;
    out.M << c2, 0, 0, 0, c2, 0, 0, 0, 0;
  }
};

}  // namespace pradis::elements
