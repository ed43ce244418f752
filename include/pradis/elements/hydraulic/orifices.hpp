#pragma once
/// \file
/// HORL and HORT: laminar and turbulent orifices between two hydraulic nodes.

#include <array>
#include <cmath>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

template <class = void>
struct laminar_orifice_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using laminar_orifice = laminar_orifice_t<>;
/// HORL: laminar orifice (linear resistance) q = (p1 - p2) / R from node 1 to node 2.
/// Pure viscosity: flows q, -q; dF/dv = [1 -1; -1 1] / R.
template <class>
struct laminar_orifice_t {
  static constexpr pradis::passport passport{.name = "HORL", .ext = 2, .par = 1, .wrk = 1, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::hydraulic, domain::hydraulic};
  static constexpr element_help help{.title = "laminar orifice (linear hydraulic resistance)",
                                     .name = "Laminar orifice: q = (p1 - p2) / R",
                                     .field = "hydraulics",
                                     .dofs = "1 - pressure node 1 [Pa]\n2 - pressure node 2 [Pa]",
                                     .parameters = "1 - resistance R [Pa s/m^3] (> 0)",
                                     .work = "1 - volume flow q from node 1 to node 2 [m^3/s]",
                                     .special = "code 100 if R is not positive"};
  struct parameters {
    double resistance = 0;  ///< R [Pa s/m^3]
  };
  parameters p;
  explicit laminar_orifice_t(parameters q) : p(q) {}
  /// Example parameters (scaled units).
  static parameters example() { return {4.0}; }
  static laminar_orifice from_parameters(std::span<const double> v) { return laminar_orifice({v[0]}); }
  void new_integration(element_context& ctx) const {
    hydraulic_detail::require_positive(ctx, "resistance R", p.resistance);
  }
  void evaluate(const local_input<laminar_orifice>& in, local_output<laminar_orifice>& out,
                element_context& ctx) const {
    const double g = 1 / p.resistance, q = g * (in.v(0) - in.v(1));
    out.f << q, -q;
    ctx.work[0] = q;
    if (out.want_jacobian) out.C << g, -g, -g, g;
  }
};

template <class = void>
struct turbulent_orifice_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using turbulent_orifice = turbulent_orifice_t<>;
/// HORT: turbulent (sharp-edged) orifice q = Cd A sqrt(2 |dp| / rho) sign(dp), dp = p1 - p2,
/// regularised near dp = 0 with the transition pressure dpt:
///   q = Cd A sqrt(2 / rho) dp / (dp^2 + dpt^2)^(1/4)
/// (finite slope Cd A sqrt(2 / rho) / sqrt(dpt) at dp = 0; relative deviation from the
/// square-root law below dpt^2 / (4 dp^2); docs/domains.md).
template <class>
struct turbulent_orifice_t {
  static constexpr pradis::passport passport{.name = "HORT", .ext = 2, .par = 4, .wrk = 1, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::hydraulic, domain::hydraulic};
  static constexpr element_help help{
      .title = "turbulent orifice with a smooth laminar transition",
      .name = "Turbulent orifice: q = Cd A sqrt(2/rho) dp / (dp^2 + dpt^2)^(1/4), dp = p1 - p2",
      .field = "hydraulics",
      .dofs = "1 - pressure node 1 [Pa]\n2 - pressure node 2 [Pa]",
      .parameters = "1 - discharge coefficient Cd [-] (> 0)\n2 - orifice area A [m^2] (> 0)\n"
                    "3 - density rho [kg/m^3] (> 0)\n4 - transition pressure difference dpt [Pa] (> 0)",
      .work = "1 - volume flow q from node 1 to node 2 [m^3/s]",
      .special = "code 100 if Cd, A, rho or dpt is not positive"};
  struct parameters {
    double cd = 0.7;           ///< discharge coefficient [-]
    double area = 0;           ///< A [m^2]
    double density = 850;      ///< rho [kg/m^3]
    double transition = 1e3;   ///< dpt [Pa]
  };
  parameters p;
  explicit turbulent_orifice_t(parameters q) : p(q) {}
  /// Example parameters (scaled units: the all-elements test's pressures of +-10 cross the transition at 1).
  static parameters example() { return {0.7, 0.5, 2.0, 1.0}; }
  static turbulent_orifice from_parameters(std::span<const double> v) {
    return turbulent_orifice({v[0], v[1], v[2], v[3]});
  }
  void new_integration(element_context& ctx) const {
    using namespace hydraulic_detail;
    require_positive(ctx, "discharge coefficient Cd", p.cd);
    require_positive(ctx, "area A", p.area);
    require_positive(ctx, "density rho", p.density);
    require_positive(ctx, "transition pressure dpt", p.transition);
  }
  void evaluate(const local_input<turbulent_orifice>& in, local_output<turbulent_orifice>& out,
                element_context& ctx) const {
    const double k = p.cd * p.area * std::sqrt(2 / p.density);
    const hydraulic_detail::reg_root r(in.v(0) - in.v(1), p.transition);
    const double q = k * r.value, g = k * r.slope;
    out.f << q, -q;
    ctx.work[0] = q;
    if (out.want_jacobian) out.C << g, -g, -g, g;
  }
};

}  // namespace pradis::elements
