#pragma once
/// \file
/// HACC: gas-charged hydraulic accumulator with a polytropic gas law.

#include <array>
#include <cmath>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

template <class = void>
struct accumulator_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using accumulator = accumulator_t<>;
/// HACC: accumulator with gas volume V0 pre-charged to the absolute pressure p0. Above the
/// pre-charge the gas is compressed polytropically, p_abs V_gas^n = p0 V0^n (p_abs = pa + p),
/// so the stored liquid volume is V0 g(p), g(p) = 1 - (p0 / p_abs)^(1/n). Below the pre-charge
/// the accumulator is empty; the C1 ramp of width 0.01 (in g) joins the two. A liquid dead
/// volume Vd of bulk modulus B at the port keeps a capacitance when empty. Flow:
///   q = dVf/dt = C(p) dp/dt,  Vf(p) = V0 ramp(g(p)) + Vd p / B,  C = V0 ramp'(g) g' + Vd / B
/// (inertia block C, viscous block dC/dp dp/dt).
template <class>
struct accumulator_t {
  static constexpr pradis::passport passport{.name = "HACC", .ext = 1, .par = 6, .wrk = 3, .adr = 2, .ign = 0};
  static constexpr std::array<domain, 1> domains{domain::hydraulic};
  static constexpr element_help help{
      .title = "gas-charged accumulator (polytropic gas)",
      .name = "Accumulator: stored volume V0 (1 - (p0 / (pa + p))^(1/n)) above the pre-charge, plus Vd p / B",
      .field = "hydraulics",
      .dofs = "1 - pressure node [Pa]",
      .parameters = "1 - gas volume V0 [m^3] (> 0)\n2 - absolute pre-charge pressure p0 [Pa] (> 0)\n"
                    "3 - polytropic exponent n [-] (> 0)\n4 - ambient (absolute) pressure pa [Pa] (> 0)\n"
                    "5 - liquid dead volume Vd [m^3] (> 0)\n6 - bulk modulus of the liquid B [Pa] (> 0)",
      .work = "1 - stored liquid volume Vf [m^3]\n2 - absolute gas pressure [Pa]\n3 - capacitance C [m^3/Pa]",
      .special = "code 100 if a parameter is not positive; code 75 if the absolute pressure pa + p reaches zero"};
  struct parameters {
    double gas_volume = 0;     ///< V0 [m^3]
    double precharge = 0;      ///< p0 [Pa], absolute
    double polytropic = 1.4;   ///< n [-]
    double ambient = 1e5;      ///< pa [Pa]
    double dead_volume = 0;    ///< Vd [m^3]
    double bulk_modulus = 0;   ///< B [Pa]
  };
  parameters p;
  explicit accumulator_t(parameters q) : p(q) {}
  /// Example parameters (scaled units: the pre-charge lies at p = 5, inside the test's +-10).
  static parameters example() { return {2.0, 25.0, 1.4, 20.0, 0.5, 40.0}; }
  static accumulator from_parameters(std::span<const double> v) {
    return accumulator({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  void new_integration(element_context& ctx) const {
    using namespace hydraulic_detail;
    require_positive(ctx, "gas volume V0", p.gas_volume);
    require_positive(ctx, "pre-charge pressure p0", p.precharge);
    require_positive(ctx, "polytropic exponent n", p.polytropic);
    require_positive(ctx, "ambient pressure pa", p.ambient);
    require_positive(ctx, "dead volume Vd", p.dead_volume);
    require_positive(ctx, "bulk modulus B", p.bulk_modulus);
  }
  /// Width of the ramp at the pre-charge (in units of the stored fraction g).
  static constexpr double corner = 0.01;
  void evaluate(const local_input<accumulator>& in, local_output<accumulator>& out, element_context& ctx) const {
    const double pabs = p.ambient + in.v(0);
    if (!(pabs > 0)) ctx.singular("the absolute pressure pa + p = " + to_text(pabs) + " Pa is not positive");
    const double k = 1 / p.polytropic, r = std::pow(p.precharge / pabs, k);
    const double g = 1 - r, g1 = k * r / pabs, g2 = -(1 + k) * g1 / pabs;
    const hydraulic_detail::ramp f(g, corner);
    const double c0 = p.dead_volume / p.bulk_modulus;
    const double c = p.gas_volume * f.slope * g1 + c0;
    out.f(0) = c * in.a(0);
    ctx.work[0] = p.gas_volume * f.value + c0 * in.v(0);
    ctx.work[1] = pabs;
    ctx.work[2] = c;
    if (!out.want_jacobian) return;
    out.M(0, 0) = c;
    out.C(0, 0) = p.gas_volume * (f.curvature * g1 * g1 + f.slope * g2) * in.a(0);
  }
};

}  // namespace pradis::elements
