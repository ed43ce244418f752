#pragma once
/// \file
/// BELT: a belt (rope) wrapped around a fixed drum, with the capstan friction
/// law between its two ends; docs/friction.md.

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct belt_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using belt = belt_t<>;
/// BELT: a belt wrapped at the angle theta around a fixed drum with the friction
/// coefficient mu. DOF 1 is end 1, DOF 2 end 2; each displacement is positive
/// when its end moves away from the drum. The belt slides on the drum by s
/// (positive towards end 1, kept in the state vector); the two free parts are
/// elastic with the stiffness k (tension per unit of stretch):
///   T1 = k (u1 - s),  T2 = k (u2 + s).
/// Capstan (Euler-Eytelwein) law, E = exp(mu theta): the belt holds (s keeps its
/// accepted value) while T1 <= E T2 and T2 <= E T1; beyond that it slips, and s
/// takes the value at which the tight side carries exactly E times the slack
/// side (a return mapping, as in rate-independent plasticity):
///   slip towards end 1 (T1 > E T2):  s = (u1 - E u2) / (1 + E),
///     T1 = E k (u1 + u2) / (1 + E), T2 = k (u1 + u2) / (1 + E);
///   slip towards end 2 (T2 > E T1):  s = (E u1 - u2) / (1 + E), the same with 1 and 2 exchanged.
/// The forces are continuous in u1, u2 (piecewise linear); the flows are T1, T2
/// (the belt pulls each end towards the drum). The law is meant for a belt under
/// tension: a compressed part (T < 0) pushes like a spring.
template <class>
struct belt_t {
  static constexpr pradis::passport passport{.name = "BELT", .ext = 2, .par = 3, .str = 1, .wrk = 4, .adr = 1, .ign = 23};
  static constexpr std::array<pradis::domain, 2> domains{pradis::domain::mechanical, pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "belt or rope on a fixed drum with capstan friction",
      .name = "Belt wrapped at angle theta around a fixed drum, friction mu: holds while T1/T2 is within "
              "[exp(-mu theta), exp(mu theta)], slips with T_tight = exp(mu theta) T_slack otherwise",
      .field = "mechanics",
      .dofs = "1 - displacement of end 1 away from the drum [m]\n"
              "2 - displacement of end 2 away from the drum [m]",
      .parameters = "1 - friction coefficient mu (>= 0)\n"
                    "2 - wrap angle theta [rad] (>= 0)\n"
                    "3 - belt stiffness k [N/m] (> 0), tension per unit stretch of each free part",
      .work = "1 - tension T1 at end 1 [N]\n"
              "2 - tension T2 at end 2 [N]\n"
              "3 - slip s of the belt on the drum towards end 1 [m]\n"
              "4 - slip flag: 1 slipping towards end 1, -1 towards end 2, 0 holding",
      .special = "code 100 if mu < 0, theta < 0, k <= 0 or a parameter is not finite. State vector (STR = 1): "
                 "the slip s of the last accepted step. Meant for a belt under tension (T1, T2 > 0); a compressed "
                 "part pushes like a spring. docs/friction.md"};
  /// Typed parameters, in PAR order.
  struct parameters {
    double mu = 0;     ///< friction coefficient
    double theta = 0;  ///< wrap angle [rad]
    double k = 0;      ///< belt stiffness [N/m]
  };
  parameters p;
  explicit belt_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.3, 3.0, 2e3}; }
  static belt from_parameters(std::span<const double> v) { return belt({v[0], v[1], v[2]}); }

  void new_integration(element_context& ctx) const {
    if (!std::isfinite(p.mu) || !(p.mu >= 0))
      ctx.invalid_parameter("friction coefficient mu = " + to_text(p.mu) + " must be finite and >= 0");
    if (!std::isfinite(p.theta) || !(p.theta >= 0))
      ctx.invalid_parameter("wrap angle theta = " + to_text(p.theta) + " must be finite and >= 0");
    if (!std::isfinite(p.mu * p.theta) || !std::isfinite(std::exp(p.mu * p.theta)))
      ctx.invalid_parameter("mu theta = " + to_text(p.mu * p.theta) + " is too large: exp(mu theta) overflows");
    if (!std::isfinite(p.k) || !(p.k > 0))
      ctx.invalid_parameter("belt stiffness k = " + to_text(p.k) + " must be finite and > 0");
  }

  /// The capstan ratio E = exp(mu theta).
  double ratio() const { return std::exp(p.mu * p.theta); }

  void evaluate(const local_input<belt>& in, local_output<belt>& out, element_context& ctx) const {
    const double e = ratio(), k = p.k, u1 = in.u(0), u2 = in.u(1);
    const double s_old = ctx.old_state.empty() ? 0.0 : ctx.old_state[0];
    double s = s_old, flag = 0;
    if (k * (u1 - s_old) > e * k * (u2 + s_old)) {
      s = (u1 - e * u2) / (1 + e);
      flag = 1;
    } else if (k * (u2 + s_old) > e * k * (u1 - s_old)) {
      s = (e * u1 - u2) / (1 + e);
      flag = -1;
    }
    const double t1 = k * (u1 - s), t2 = k * (u2 + s);
    if (!ctx.new_state.empty()) ctx.new_state[0] = s;
    out.f << t1, t2;
    ctx.work[0] = t1;
    ctx.work[1] = t2;
    ctx.work[2] = s;
    ctx.work[3] = flag;
    if (!out.want_jacobian) return;
    if (flag == 0) {
      out.K << k, 0, 0, k;
    } else {
      // T_tight = E k (u1 + u2) / (1 + E), T_slack = k (u1 + u2) / (1 + E).
      const double a = k / (1 + e), r0 = flag > 0 ? e * a : a, r1 = flag > 0 ? a : e * a;
      out.K << r0, r0, r1, r1;
    }
  }

  /// The all-elements check (accepted slip 0) stays 1e-3 m away from the slip
  /// thresholds u1 = E u2 and u2 = E u1, where the law has kinks.
  bool admissible(const local_input<belt>& in) const {
    const double e = ratio();
    return std::abs(in.u(0) - e * in.u(1)) > 1e-3 && std::abs(in.u(1) - e * in.u(0)) > 1e-3;
  }
};

}  // namespace pradis::elements
