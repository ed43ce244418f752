#pragma once
/// \file
/// TSPRING: spring-damper between two DOFs whose elastic force is a table of
/// (deformation, force) points, plus linear damping.

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
struct table_spring_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using table_spring = table_spring_t<>;
/// TSPRING: nonlinear spring-damper between DOFs 1 and 2 with the force
/// F = f(d) + c d', d = u2 - u1 (elongation), F positive in tension; flows -F, F.
/// f is interpolated in a table of (d_k, F_k) points (tabular_law: piecewise
/// linear or monotone cubic, linear extrapolation with the end slope). The
/// Jacobian is exact: K = f'(d) [1 -1; -1 1], C = c [1 -1; -1 1] (ADR=1, IGN=3).
///
/// Flat parameters (VPR = 21, an even count of at least 6): interpolation
/// (0 linear, 1 monotone cubic), damping c, then d1, F1, d2, F2, ...
template <class>
struct table_spring_t {
  static constexpr pradis::passport passport{
      .name = "TSPRING", .ext = 2, .par = 6, .vpr = 21, .wrk = 2, .adr = 1, .ign = 3};
  static constexpr std::array<pradis::domain, 2> domains{pradis::domain::mechanical, pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "tabulated spring-damper between two DOFs",
      .name = "Spring with a force-deformation table and linear damping: F = f(u2 - u1) + c (v2 - v1)",
      .field = "mechanics",
      .dofs = "1 - displacement of end 1 [m]\n2 - displacement of end 2 [m]",
      .parameters = "1 - interpolation: 0 piecewise linear, 1 monotone cubic (PCHIP)\n"
                    "2 - damping coefficient c [N s/m] (>= 0)\n"
                    "3 - deformation d1 = u2 - u1 of point 1 [m]\n4 - force F1 at d1 [N]\n"
                    "5 - deformation d2 (> d1) [m]\n6 - force F2 [N]\n(more pairs d_k, F_k may follow)",
      .work = "1 - force F = f(d) + c d' [N], positive in tension\n2 - deformation d = u2 - u1 [m]",
      .special = "code 100 if the table count is not even, it has fewer than 2 points, a value is not finite, the "
                 "deformations do not increase strictly, the interpolation is not 0 or 1 or c < 0 (an odd flat "
                 "count is code 101). Piecewise linear: at a table point the slope of the segment to its right; "
                 "monotone cubic: value and slope continuous. Beyond the table: linear with the end slope. Tables "
                 "can come from a CSV file (FILE(\"name.csv\") in $DATA, io::read_table_csv in C++)"};
  /// The parameters, in PAR order.
  struct parameters {
    double interpolation = 0;    ///< 0 piecewise linear, 1 monotone cubic (PCHIP)
    double damping = 0;          ///< c [N s/m]
    std::vector<double> table{};  ///< d1, F1, d2, F2, ... [m, N]
  };
  /// Stores the parameters and builds the interpolant (allocates here, never in evaluate).
  explicit table_spring_t(parameters q)
      : p(std::move(q)), law_(p.table, p.interpolation == 1 ? interpolation::monotone_cubic : interpolation::linear) {}
  /// Example parameters (used by `pradis check` and the all-elements test): a
  /// stiffening piecewise-linear law with damping.
  static parameters example() { return {0.0, 2.0, {-1.0, -30.0, 0.0, 0.0, 0.5, 10.0, 1.0, 40.0}}; }
  static table_spring from_parameters(std::span<const double> v) {
    return table_spring({v[0], v[1], std::vector<double>(v.begin() + 2, v.end())});
  }
  /// The parameters (read-only: a changed table needs a new element, as `$REPLACE` builds).
  const parameters& params() const noexcept { return p; }
  /// The interpolant of the elastic force f(d).
  const tabular_law& law() const noexcept { return law_; }
  /// Finite-difference checks stay 1e-3 away from the table points (where the
  /// piecewise-linear slope jumps).
  bool admissible(const local_input<table_spring>& in) const {
    return law_.distance_to_point(in.u(1) - in.u(0)) > 1e-3;
  }
  void new_integration(element_context& ctx) const {
    if (const std::string why = law_.problem("deformation", "force"); !why.empty()) ctx.invalid_parameter(why);
    if (p.interpolation != 0 && p.interpolation != 1)
      ctx.invalid_parameter("interpolation = " + to_text(p.interpolation) +
                            " must be 0 (piecewise linear) or 1 (monotone cubic)");
    if (!(p.damping >= 0) || !std::isfinite(p.damping))
      ctx.invalid_parameter("damping coefficient c = " + to_text(p.damping) + " must be finite and >= 0");
  }
  void evaluate(const local_input<table_spring>& in, local_output<table_spring>& out, element_context& ctx) const {
    const double d = in.u(1) - in.u(0), dv = in.v(1) - in.v(0);
    const law_sample f = law_.at(d);
    const double force = f.value + p.damping * dv;
    out.f << -force, force;
    ctx.work[0] = force;
    ctx.work[1] = d;
    if (out.want_jacobian) {
      out.K << f.slope, -f.slope, -f.slope, f.slope;
      out.C << p.damping, -p.damping, -p.damping, p.damping;
    }
  }

 private:
  parameters p;
  tabular_law law_;
};

}  // namespace pradis::elements
