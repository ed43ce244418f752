#pragma once
/// \file
/// CAM: a rotating cam with a tabulated lift pushing a translating follower
/// through a one-sided contact; the follower lifts off when its spring cannot
/// keep it on the profile.

#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/mech1d/periodic_spline.hpp"

namespace pradis::elements {

template <class = void>
struct cam_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using cam = cam_t<>;
/// CAM: cam rotation theta (DOF 1, rad) and follower displacement y (DOF 2, m,
/// positive away from the cam). The lift s(theta) is a table over one period,
/// interpolated by the periodic cubic spline (value, slope and curvature
/// continuous, so the follower's acceleration is too). The contact is a stiff,
/// damped, one-sided spring on the interference delta = s(theta) - y:
///
///     F = max(0, k delta + c delta')   while delta > 0, else 0,
///     delta' = s'(theta) theta' - y'
///
/// F pushes the follower (flow -F on y) and brakes the cam with the moment
/// F s'(theta) (flow F s' on theta): the power F delta' balances. With delta <= 0
/// the follower has lifted off. Jacobian exact (ADR=1, IGN=3).
template <class>
struct cam_t {
  static constexpr pradis::passport passport{.name = "CAM", .ext = 2, .par = 10, .vpr = 21, .wrk = 3, .adr = 1,
                                             .ign = 3};
  static constexpr std::array<pradis::domain, 2> domains{pradis::domain::mechanical, pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "cam with a tabulated lift and a follower that can lift off",
      .name = "Cam and translating follower: one-sided contact on the interference s(theta) - y, lift s(theta) "
              "from a periodic table",
      .field = "mechanics",
      .dofs = "1 - cam rotation theta [rad]\n2 - follower displacement y [m] (positive away from the cam)",
      .parameters = "1 - contact stiffness k [N/m] (> 0)\n2 - contact damping c [N s/m] (>= 0)\n"
                    "3 - angle theta_1 of the first table point [rad]\n4 - lift s_1 [m]\n"
                    "5, 6 - theta_2, s_2\n7, 8 - theta_3, s_3\n9, 10 - theta_4, s_4\n"
                    "(more pairs may follow; the last lift must equal the first: the table spans one period "
                    "theta_m - theta_1)",
      .work = "1 - contact force F [N] (0 after lift-off)\n"
              "2 - interference s(theta) - y [m] (negative: the follower's gap)\n3 - lift s(theta) [m]",
      .special = "code 100 if k <= 0, c < 0, a value is not finite, the table has fewer than 4 points, the "
                 "angles do not increase strictly or the last lift differs from the first (code 101 for an odd "
                 "flat count). The lift is a periodic cubic spline (C2). The contact force is zero while the "
                 "follower is off the profile and never pulls"};
  /// The parameters, in PAR order.
  struct parameters {
    double k = 0;                 ///< contact stiffness [N/m]
    double c = 0;                 ///< contact damping [N s/m]
    std::vector<double> table{};  ///< theta_1, s_1, theta_2, s_2, ... [rad, m]
  };
  explicit cam_t(parameters q) : p(std::move(q)), lift_(p.table) {}
  /// Example parameters: a harmonic lift of 8 mm sampled every 30 degrees, a soft contact.
  static parameters example() {
    parameters q{1e4, 50.0, {}};
    for (int i = 0; i <= 12; ++i) {
      const double th = i * 3.141592653589793 / 6;
      q.table.insert(q.table.end(), {th, 0.004 * (1 - std::cos(th))});
    }
    return q;
  }
  static cam from_parameters(std::span<const double> v) {
    return cam({v[0], v[1], std::vector<double>(v.begin() + 2, v.end())});
  }
  const parameters& params() const noexcept { return p; }
  /// The lift s(theta).
  const periodic_spline& lift() const noexcept { return lift_; }
  /// Finite-difference checks stay away from the contact's edge and the force's clamp.
  bool admissible(const local_input<cam>& in) const {
    const spline_sample s = lift_.at(in.u(0));
    const double delta = s.value - in.u(1), rate = s.slope * in.v(0) - in.v(1);
    return std::abs(delta) > 1e-5 && std::abs(p.k * delta + p.c * rate) > 1e-3 * p.k * 1e-3;
  }
  void new_integration(element_context& ctx) const {
    if (!(p.k > 0) || !std::isfinite(p.k))
      ctx.invalid_parameter("contact stiffness k = " + to_text(p.k) + " must be > 0");
    if (!(p.c >= 0) || !std::isfinite(p.c))
      ctx.invalid_parameter("contact damping c = " + to_text(p.c) + " must be >= 0");
    if (const std::string why = lift_.problem("angle", "lift"); !why.empty()) ctx.invalid_parameter(why);
  }
  void evaluate(const local_input<cam>& in, local_output<cam>& out, element_context& ctx) const {
    const spline_sample s = lift_.at(in.u(0));
    const double delta = s.value - in.u(1), rate = s.slope * in.v(0) - in.v(1);
    const double force = delta > 0 ? std::max(0.0, p.k * delta + p.c * rate) : 0.0;
    out.f << force * s.slope, -force;
    if (ctx.work.size() >= 3) {
      ctx.work[0] = force;
      ctx.work[1] = delta;
      ctx.work[2] = s.value;
    }
    if (!out.want_jacobian) return;
    if (force > 0) {
      const double df_dth = p.k * s.slope + p.c * s.curvature * in.v(0), df_dy = -p.k;
      out.K << s.slope * df_dth + force * s.curvature, s.slope * df_dy, -df_dth, -df_dy;
      out.C << p.c * s.slope * s.slope, -p.c * s.slope, -p.c * s.slope, p.c;
    } else {
      out.K.setZero();
      out.C.setZero();
    }
  }

 private:
  parameters p;
  periodic_spline lift_;
};

}  // namespace pradis::elements
