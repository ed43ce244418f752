#pragma once
/// \file
/// Hydraulic valves: HV22 (2/2 proportional), HV43 (4/3 proportional/servo), HRELIEF
/// (pressure relief) and HCHECK (check valve). Every flow path is a turbulent orifice
/// with the regularised root of HORT, q = Cd a sqrt(2/rho) r(dp), r(dp) = dp / (dp^2 + dpt^2)^(1/4),
/// and an opening area a = Al + Amax y between the leakage area Al and Al + Amax.
/// The opening y = c(s) is the C1 clamp of the normalised stroke s to [0, 1] with rounded
/// corners inside the interval, w = 0.02 (docs/domains.md):
///   c(s) = (ramp(s - w) - ramp(s - 1 + w)) / (1 - 2 w),
///   ramp(z) = 0 (z <= -w), (z + w)^2 / (4 w) (|z| < w), z (z >= w);
/// exactly 0 (closed: leakage only) for s <= 0 and 1 for s >= 1, c(1/2) = 1/2.
/// The spool of HV22 and HV43 is an external mechanical DOF (its displacement is the spool
/// position; the valve exerts no force on it): drive it by XSRC, or model the spool
/// dynamics with mechanical elements, e.g. a first-order lag tau x' + x = xc as SPRING k
/// from a command DOF (XSRC xc) and DAMPER c = k tau to the ground.

#include <array>
#include <cmath>
#include <span>

#include "pradis/core/domain.hpp"
#include "pradis/elements/hydraulic/common.hpp"

namespace pradis::elements {

namespace hydraulic_detail {
/// Common orifice parameters of a valve.
inline void check_valve_orifice(element_context& ctx, double cd, double amax, double rho, double dpt, double al) {
  require_positive(ctx, "discharge coefficient Cd", cd);
  require_positive(ctx, "maximum area Amax", amax);
  require_positive(ctx, "density rho", rho);
  require_positive(ctx, "transition pressure dpt", dpt);
  require_nonnegative(ctx, "leakage area Al", al);
}
/// Adds a flow path from local DOF i to j with area `a` whose derivative by the displacement of
/// local DOF x is `da_dx` (x < 0: no spool), to the flows and the K and C blocks; returns q.
template <class E>
double add_path(const local_input<E>& in, local_output<E>& out, int i, int j, double alpha, double a, double dpt,
                int x, double da_dx) {
  const reg_root r(in.v(i) - in.v(j), dpt);
  const double q = alpha * a * r.value;
  out.f(i) += q;
  out.f(j) -= q;
  if (out.want_jacobian) {
    const double g = alpha * a * r.slope;
    out.C(i, i) += g;
    out.C(i, j) -= g;
    out.C(j, i) -= g;
    out.C(j, j) += g;
    if constexpr (element_traits<E>::has_k) {
      if (x >= 0) {
        out.K(i, x) += alpha * r.value * da_dx;
        out.K(j, x) -= alpha * r.value * da_dx;
      }
    }
  }
  return q;
}
}  // namespace hydraulic_detail

/// Orifice parameters shared by the spool valves HV22 and HV43.
struct spool_valve_parameters {
  double cd = 0.7;          ///< discharge coefficient [-]
  double max_area = 0;      ///< Amax [m^2], the area of a fully open path
  double density = 850;     ///< rho [kg/m^3]
  double transition = 1e3;  ///< dpt [Pa]
  double stroke = 0;        ///< xmax [m], the spool displacement that opens a path fully
  double leakage_area = 0;  ///< Al [m^2]
};

template <class = void>
struct valve_22_t;
/// The element type valve_22_t<> (a class template so that a unit compiles its members only if it uses them).
using valve_22 = valve_22_t<>;
/// HV22: 2/2 proportional valve: q = Cd (Al + Amax c(x / xmax)) sqrt(2/rho) r(p1 - p2).
template <class>
struct valve_22_t {
  static constexpr pradis::passport passport{.name = "HV22", .ext = 3, .par = 6, .wrk = 2, .adr = 1, .ign = 3};
  static constexpr std::array<domain, 3> domains{domain::hydraulic, domain::hydraulic, domain::mechanical};
  static constexpr element_help help{
      .title = "2/2 proportional valve with a spool DOF",
      .name = "2/2 valve: q = Cd (Al + Amax c(x / xmax)) sqrt(2/rho) dp / (dp^2 + dpt^2)^(1/4)",
      .field = "hydraulics",
      .dofs = "1 - pressure of port 1 [Pa]\n2 - pressure of port 2 [Pa]\n3 - spool displacement x [m]",
      .parameters = "1 - discharge coefficient Cd [-] (> 0)\n2 - area when fully open Amax [m^2] (> 0)\n"
                    "3 - density rho [kg/m^3] (> 0)\n4 - transition pressure difference dpt [Pa] (> 0)\n"
                    "5 - spool stroke for full opening xmax [m] (> 0)\n6 - leakage area Al [m^2] (>= 0)",
      .work = "1 - flow from port 1 to port 2 [m^3/s]\n2 - opening c(x / xmax) [-]",
      .special = "code 100 if Cd, Amax, rho, dpt or xmax is not positive or Al is negative; the spool DOF has no "
                 "equation from the valve (drive it or give it dynamics)"};
  using parameters = spool_valve_parameters;
  parameters p;
  explicit valve_22_t(parameters q) : p(q) {}
  /// Example parameters (scaled units).
  static parameters example() { return {0.7, 0.5, 2.0, 1.0, 2.0, 0.05}; }
  static valve_22 from_parameters(std::span<const double> v) { return valve_22({v[0], v[1], v[2], v[3], v[4], v[5]}); }
  void new_integration(element_context& ctx) const {
    hydraulic_detail::check_valve_orifice(ctx, p.cd, p.max_area, p.density, p.transition, p.leakage_area);
    hydraulic_detail::require_positive(ctx, "spool stroke xmax", p.stroke);
  }
  void evaluate(const local_input<valve_22>& in, local_output<valve_22>& out, element_context& ctx) const {
    using namespace hydraulic_detail;
    const double alpha = p.cd * std::sqrt(2 / p.density);
    const clamp01 y(in.u(2) / p.stroke, opening_corner);
    out.clear();
    ctx.work[0] = add_path(in, out, 0, 1, alpha, p.leakage_area + p.max_area * y.value, p.transition, 2,
                           p.max_area * y.slope / p.stroke);
    ctx.work[1] = y.value;
  }
};

template <class = void>
struct valve_43_t;
/// The element type valve_43_t<> (a class template so that a unit compiles its members only if it uses them).
using valve_43 = valve_43_t<>;
/// HV43: 4/3 proportional (servo) valve, critical centre, ports P, T, A, B and spool x.
/// With s = x / xmax: for s > 0 the paths P->A and B->T open with c(s), for s < 0 the paths
/// P->B and A->T with c(-s); every path has the leakage area Al at every position.
template <class>
struct valve_43_t {
  static constexpr pradis::passport passport{.name = "HV43", .ext = 5, .par = 6, .wrk = 5, .adr = 1, .ign = 3};
  static constexpr std::array<domain, 5> domains{domain::hydraulic, domain::hydraulic, domain::hydraulic,
                                                 domain::hydraulic, domain::mechanical};
  static constexpr element_help help{
      .title = "4/3 proportional (servo) valve, critical centre, with a spool DOF",
      .name = "4/3 valve: paths P-A, B-T open for x > 0, P-B, A-T for x < 0; turbulent orifices with leakage",
      .field = "hydraulics",
      .dofs = "1 - pressure of port P [Pa]\n2 - pressure of port T [Pa]\n3 - pressure of port A [Pa]\n"
              "4 - pressure of port B [Pa]\n5 - spool displacement x [m]",
      .parameters = "1 - discharge coefficient Cd [-] (> 0)\n2 - area of a fully open path Amax [m^2] (> 0)\n"
                    "3 - density rho [kg/m^3] (> 0)\n4 - transition pressure difference dpt [Pa] (> 0)\n"
                    "5 - spool stroke for full opening xmax [m] (> 0)\n6 - leakage area of each path Al [m^2] (>= 0)",
      .work = "1 - flow P->A [m^3/s]\n2 - flow B->T [m^3/s]\n3 - flow P->B [m^3/s]\n4 - flow A->T [m^3/s]\n"
              "5 - normalised spool position x / xmax [-]",
      .special = "code 100 if Cd, Amax, rho, dpt or xmax is not positive or Al is negative; the spool DOF has no "
                 "equation from the valve (drive it or give it dynamics)"};
  using parameters = spool_valve_parameters;
  parameters p;
  explicit valve_43_t(parameters q) : p(q) {}
  /// Example parameters (scaled units).
  static parameters example() { return {0.7, 0.5, 2.0, 1.0, 2.0, 0.05}; }
  static valve_43 from_parameters(std::span<const double> v) { return valve_43({v[0], v[1], v[2], v[3], v[4], v[5]}); }
  void new_integration(element_context& ctx) const {
    hydraulic_detail::check_valve_orifice(ctx, p.cd, p.max_area, p.density, p.transition, p.leakage_area);
    hydraulic_detail::require_positive(ctx, "spool stroke xmax", p.stroke);
  }
  void evaluate(const local_input<valve_43>& in, local_output<valve_43>& out, element_context& ctx) const {
    using namespace hydraulic_detail;
    constexpr int P = 0, T = 1, A = 2, B = 3, X = 4;
    const double alpha = p.cd * std::sqrt(2 / p.density), s = in.u(X) / p.stroke;
    const clamp01 yp(s, opening_corner), ym(-s, opening_corner);
    const double ap = p.leakage_area + p.max_area * yp.value, am = p.leakage_area + p.max_area * ym.value;
    const double dap = p.max_area * yp.slope / p.stroke, dam = -p.max_area * ym.slope / p.stroke;
    out.clear();
    ctx.work[0] = add_path(in, out, P, A, alpha, ap, p.transition, X, dap);
    ctx.work[1] = add_path(in, out, B, T, alpha, ap, p.transition, X, dap);
    ctx.work[2] = add_path(in, out, P, B, alpha, am, p.transition, X, dam);
    ctx.work[3] = add_path(in, out, A, T, alpha, am, p.transition, X, dam);
    ctx.work[4] = s;
  }
};

/// Parameters of the pressure-operated valves HRELIEF and HCHECK.
struct pressure_valve_parameters {
  double cd = 0.7;          ///< discharge coefficient [-]
  double max_area = 0;      ///< Amax [m^2]
  double density = 850;     ///< rho [kg/m^3]
  double transition = 1e3;  ///< dpt [Pa]
  double crack = 0;         ///< cracking pressure difference pc [Pa]
  double band = 0;          ///< pressure rise from cracking to fully open dpo [Pa]
  double leakage_area = 0;  ///< Al [m^2]
};

namespace hydraulic_detail {
/// The pressure-operated valve of HRELIEF and HCHECK: opening y = c((p1 - p2 - pc) / dpo),
/// q = Cd (Al + Amax y) sqrt(2/rho) r(p1 - p2); only the viscous block (dq/dp).
template <class E>
void pressure_valve(const pressure_valve_parameters& p, const local_input<E>& in, local_output<E>& out,
                    element_context& ctx) {
  const double alpha = p.cd * std::sqrt(2 / p.density), dp = in.v(0) - in.v(1);
  const clamp01 y((dp - p.crack) / p.band, opening_corner);
  const reg_root r(dp, p.transition);
  const double a = p.leakage_area + p.max_area * y.value, q = alpha * a * r.value;
  out.f << q, -q;
  ctx.work[0] = q;
  ctx.work[1] = y.value;
  if (!out.want_jacobian) return;
  const double g = alpha * (a * r.slope + p.max_area * y.slope / p.band * r.value);
  out.C << g, -g, -g, g;
}
inline void check_pressure_valve(element_context& ctx, const pressure_valve_parameters& p) {
  check_valve_orifice(ctx, p.cd, p.max_area, p.density, p.transition, p.leakage_area);
  require_nonnegative(ctx, "cracking pressure pc", p.crack);
  require_positive(ctx, "opening band dpo", p.band);
}
}  // namespace hydraulic_detail

template <class = void>
struct relief_valve_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using relief_valve = relief_valve_t<>;
/// HRELIEF: pressure relief valve from port 1 (protected line) to port 2 (tank): closed up to
/// the cracking pressure difference pc (leakage Al only), opening proportionally over dpo.
template <class>
struct relief_valve_t {
  static constexpr pradis::passport passport{.name = "HRELIEF", .ext = 2, .par = 7, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::hydraulic, domain::hydraulic};
  static constexpr element_help help{
      .title = "pressure relief valve with a smooth proportional opening",
      .name = "Relief valve: q = Cd (Al + Amax c((p1 - p2 - pc) / dpo)) sqrt(2/rho) r(p1 - p2)",
      .field = "hydraulics",
      .dofs = "1 - pressure of the protected port [Pa]\n2 - pressure of the tank port [Pa]",
      .parameters = "1 - discharge coefficient Cd [-] (> 0)\n2 - area when fully open Amax [m^2] (> 0)\n"
                    "3 - density rho [kg/m^3] (> 0)\n4 - transition pressure difference dpt [Pa] (> 0)\n"
                    "5 - cracking pressure difference pc [Pa] (>= 0)\n6 - pressure rise to full opening dpo [Pa] (> 0)\n"
                    "7 - leakage area Al [m^2] (>= 0)",
      .work = "1 - flow from port 1 to port 2 [m^3/s]\n2 - opening [-]",
      .special = "code 100 if Cd, Amax, rho, dpt or dpo is not positive or pc, Al is negative"};
  using parameters = pressure_valve_parameters;
  parameters p;
  explicit relief_valve_t(parameters q) : p(q) {}
  /// Example parameters (scaled units: cracks at 4, fully open at 7).
  static parameters example() { return {0.7, 0.5, 2.0, 1.0, 4.0, 3.0, 0.01}; }
  static relief_valve from_parameters(std::span<const double> v) {
    return relief_valve({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
  }
  void new_integration(element_context& ctx) const { hydraulic_detail::check_pressure_valve(ctx, p); }
  void evaluate(const local_input<relief_valve>& in, local_output<relief_valve>& out, element_context& ctx) const {
    hydraulic_detail::pressure_valve(p, in, out, ctx);
  }
};

template <class = void>
struct check_valve_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using check_valve = check_valve_t<>;
/// HCHECK: check (non-return) valve from port 1 to port 2: opens when p1 - p2 exceeds the
/// cracking pressure pc (fully open at pc + dpo); in reverse only the leakage area Al passes.
template <class>
struct check_valve_t {
  static constexpr pradis::passport passport{.name = "HCHECK", .ext = 2, .par = 7, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 2> domains{domain::hydraulic, domain::hydraulic};
  static constexpr element_help help{
      .title = "check valve with a smooth opening",
      .name = "Check valve: q = Cd (Al + Amax c((p1 - p2 - pc) / dpo)) sqrt(2/rho) r(p1 - p2), free flow 1 -> 2",
      .field = "hydraulics",
      .dofs = "1 - pressure of the inlet port [Pa]\n2 - pressure of the outlet port [Pa]",
      .parameters = "1 - discharge coefficient Cd [-] (> 0)\n2 - area when fully open Amax [m^2] (> 0)\n"
                    "3 - density rho [kg/m^3] (> 0)\n4 - transition pressure difference dpt [Pa] (> 0)\n"
                    "5 - cracking pressure difference pc [Pa] (>= 0)\n6 - pressure rise to full opening dpo [Pa] (> 0)\n"
                    "7 - leakage area in reverse (and closed) Al [m^2] (>= 0)",
      .work = "1 - flow from port 1 to port 2 [m^3/s]\n2 - opening [-]",
      .special = "code 100 if Cd, Amax, rho, dpt or dpo is not positive or pc, Al is negative"};
  using parameters = pressure_valve_parameters;
  parameters p;
  explicit check_valve_t(parameters q) : p(q) {}
  /// Example parameters (scaled units: cracks at 0.5, fully open at 2.5).
  static parameters example() { return {0.7, 0.5, 2.0, 0.5, 0.5, 2.0, 0.01}; }
  static check_valve from_parameters(std::span<const double> v) {
    return check_valve({v[0], v[1], v[2], v[3], v[4], v[5], v[6]});
  }
  void new_integration(element_context& ctx) const { hydraulic_detail::check_pressure_valve(ctx, p); }
  void evaluate(const local_input<check_valve>& in, local_output<check_valve>& out, element_context& ctx) const {
    hydraulic_detail::pressure_valve(p, in, out, ctx);
  }
};

}  // namespace pradis::elements
