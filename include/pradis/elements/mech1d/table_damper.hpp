#pragma once
/// \file
/// TDAMPER: damper between two DOFs whose force is a table of (relative
/// velocity, force) points, plus a linear spring: the characteristic of a shock
/// absorber or a viscous coupling, measured or designed.

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/mech1d/tabular_law.hpp"

namespace pradis::elements {

template <class = void>
struct table_damper_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using table_damper = table_damper_t<>;
/// TDAMPER: F = g(d') + k d between DOFs 1 and 2, d = u2 - u1, d' = v2 - v1,
/// F positive in tension; flows -F, F (the convention of SPRING and TSPRING).
/// g is interpolated in a table of (d'_k, F_k) points by tabular_law (piecewise
/// linear or monotone cubic, linear extrapolation with the end slope). The
/// Jacobian is exact: C = g'(d') [1 -1; -1 1], K = k [1 -1; -1 1] (ADR=1, IGN=3).
///
/// Flat parameters (VPR = 21, an even count of at least 6): interpolation
/// (0 linear, 1 monotone cubic), stiffness k, then v1, F1, v2, F2, ...
template <class>
struct table_damper_t {
  static constexpr pradis::passport passport{
      .name = "TDAMPER", .ext = 2, .par = 6, .vpr = 21, .wrk = 2, .adr = 1, .ign = 3};
  static constexpr std::array<pradis::domain, 2> domains{pradis::domain::mechanical, pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "tabulated damper between two DOFs",
      .name = "Damper with a force-velocity table and a linear spring: F = g(v2 - v1) + k (u2 - u1)",
      .field = "mechanics",
      .dofs = "1 - displacement of end 1 [m]\n2 - displacement of end 2 [m]",
      .parameters = "1 - interpolation: 0 piecewise linear, 1 monotone cubic (PCHIP)\n"
                    "2 - stiffness k [N/m] (>= 0)\n"
                    "3 - relative velocity v1 = v2 - v1 of point 1 [m/s]\n4 - force F1 at v1 [N]\n"
                    "5 - velocity of point 2 (> v1) [m/s]\n6 - force F2 [N]\n(more pairs may follow)",
      .work = "1 - force F = g(d') + k d [N], positive in tension\n2 - relative velocity d' = v2 - v1 [m/s]",
      .special = "code 100 if the table count is not even, it has fewer than 2 points, a value is not finite, the "
                 "velocities do not increase strictly, the interpolation is not 0 or 1 or k < 0 (an odd flat "
                 "count is code 101). Beyond the table: linear with the end slope. Tables can come from a CSV "
                 "file (FILE(\"name.csv\") in $DATA, io::read_table_csv in C++)"};
  /// The parameters, in PAR order.
  struct parameters {
    double interpolation = 0;     ///< 0 piecewise linear, 1 monotone cubic (PCHIP)
    double stiffness = 0;         ///< k [N/m]
    std::vector<double> table{};  ///< v1, F1, v2, F2, ... [m/s, N]
  };
  /// Stores the parameters and builds the interpolant (allocates here, never in evaluate).
  explicit table_damper_t(parameters q)
      : p(std::move(q)), law_(p.table, p.interpolation == 1 ? interpolation::monotone_cubic : interpolation::linear) {}
  /// Example parameters: a shock absorber, soft in compression, hard in rebound, with a spring.
  static parameters example() { return {1.0, 500.0, {-1.0, -400.0, -0.1, -80.0, 0.0, 0.0, 0.1, 200.0, 1.0, 1200.0}}; }
  static table_damper from_parameters(std::span<const double> v) {
    return table_damper({v[0], v[1], std::vector<double>(v.begin() + 2, v.end())});
  }
  const parameters& params() const noexcept { return p; }
  /// The interpolant of the damping force g(d').
  const tabular_law& law() const noexcept { return law_; }
  /// Finite-difference checks stay 1e-3 away from the table points.
  bool admissible(const local_input<table_damper>& in) const {
    return law_.distance_to_point(in.v(1) - in.v(0)) > 1e-3;
  }
  void new_integration(element_context& ctx) const {
    if (const std::string why = law_.problem("velocity", "force"); !why.empty()) ctx.invalid_parameter(why);
    if (p.interpolation != 0 && p.interpolation != 1)
      ctx.invalid_parameter("interpolation = " + to_text(p.interpolation) +
                            " must be 0 (piecewise linear) or 1 (monotone cubic)");
    if (!(p.stiffness >= 0) || !std::isfinite(p.stiffness))
      ctx.invalid_parameter("stiffness k = " + to_text(p.stiffness) + " must be finite and >= 0");
  }
  void evaluate(const local_input<table_damper>& in, local_output<table_damper>& out, element_context& ctx) const {
    const double d = in.u(1) - in.u(0), dv = in.v(1) - in.v(0);
    const law_sample g = law_.at(dv);
    const double force = g.value + p.stiffness * d;
    out.f << -force, force;
    if (ctx.work.size() >= 2) {
      ctx.work[0] = force;
      ctx.work[1] = dv;
    }
    if (out.want_jacobian) {
      out.K << p.stiffness, -p.stiffness, -p.stiffness, p.stiffness;
      out.C << g.slope, -g.slope, -g.slope, g.slope;
    }
  }

 private:
  parameters p;
  tabular_law law_;
};

}  // namespace pradis::elements
