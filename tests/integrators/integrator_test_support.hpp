#pragma once
// Helpers shared by the integrator tests (tests/integrators/*.cpp): closed forms
// of the methods' properties, the complete elliptic integral, a zero-crossing
// period estimator, tight Newton options and small test-only element types.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <vector>

#include "pradis/core/element.hpp"
#include "pradis/integrators/simulation.hpp"

namespace pradis_test {

/// Newton tolerances relative to the state (absolute ones would be unreachable
/// at small steps).
inline constexpr pradis::newton_options rel_newton{
    .dabsu = 1e-14, .drltu = 1e-12, .dabsi = 1e-14, .drlti = 1e-12, .itr = 8};

/// Newton options tight enough that the Newton error is far below every
/// discretisation error measured in these tests (the defaults DABSU = 0.01,
/// DABSI = 0.1 are engineering tolerances, not test tolerances). `dabsi` is the
/// absolute residual tolerance [N]: choose it above the roundoff of the flows
/// (about k * eps * L for a link of stiffness k).
inline pradis::newton_options tight_newton(double dabsi = 1e-9, double dabsu = 1e-11) {
  pradis::newton_options n;
  n.dabsu = dabsu;
  n.drltu = 1e-12;
  n.dabsi = dabsi;
  n.drlti = 1e-13;
  n.itr = 12;
  return n;
}

/// Complete elliptic integral of the first kind K(m), parameter m = k^2, by the
/// arithmetic-geometric mean: K(m) = pi / (2 AGM(1, sqrt(1 - m)))
/// (Abramowitz & Stegun 17.6; DLMF 19.8.5).
inline double elliptic_k(double m) {
  double a = 1.0, b = std::sqrt(1.0 - m);
  for (int i = 0; i < 60 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return std::numbers::pi / (2.0 * a);
}

/// Exact period of the simple pendulum released at rest from theta0 [rad]:
/// T = 4 K(k^2) / w, k = sin(theta0 / 2), w = sqrt(g / L) (e.g. Landau-Lifshitz, Mechanics, section 11, problem 1).
inline double pendulum_period(double theta0, double g, double l) {
  const double k = std::sin(0.5 * theta0);
  return 4.0 * elliptic_k(k * k) / std::sqrt(g / l);
}

/// First-order effect of a finite link stiffness k on the period of a pendulum
/// of mass m and length L released at rest from theta0 (derived for these
/// tests): T(k) / T(inf) - 1 = c(theta0) m g / (k L) + O(1/k^2), with
///     c(theta0) = (7.5 <cos theta> - 6.5 cos theta0) / 2,
/// <cos theta> the time average over the rigid pendulum's motion. Derivation:
/// the slaved stretch d = m (L theta'^2 + g cos theta) / k adds
/// m^2 (L theta'^2 + g cos theta)^2 / (2k) to the Lagrangian; solving its energy
/// integral for theta'^2 to first order in 1/k gives
/// theta'^2 = w0 (1 - (m/k)(c + 13 w0 / 4)), w0 = 2 (g/L)(cos theta - cos theta0)
/// in units g = L = 1, and 4 int dtheta / theta' expands to the formula.
/// The time average uses sin(theta/2) = k sin(phi): dt is proportional to
/// dphi / sqrt(1 - k^2 sin^2 phi); the midpoint rule in phi converges spectrally.
/// Returns c(theta0): 0.505 at 5 deg (-> 1/2 for small swings), 1.7135 at 90 deg.
inline double stiff_pendulum_period_shift(double theta0) {
  const double k = std::sin(0.5 * theta0);
  const int n = 4000;
  double num = 0, den = 0;
  for (int i = 0; i < n; ++i) {
    const double phi = (i + 0.5) * (0.5 * std::numbers::pi) / n;
    const double s = k * std::sin(phi);
    const double w = 1.0 / std::sqrt(1.0 - s * s);
    num += (1.0 - 2.0 * s * s) * w;  // cos(theta) = 1 - 2 sin^2(theta/2)
    den += w;
  }
  return 0.5 * (7.5 * num / den - 6.5 * std::cos(theta0));
}

/// Relative period error of average-acceleration Newmark (trapezoidal rule) on
/// u'' + w^2 u = 0: the amplification matrix is the Cayley transform of the
/// system matrix, its eigenvalues are exp(+-i theta) with tan(theta/2) = Omega/2,
/// so Tbar/T - 1 = Omega / (2 atan(Omega / 2)) - 1 exactly (Omega = w h).
/// (Hughes, The Finite Element Method, section 9.3; leading term Omega^2/12.)
inline double trapezoidal_period_error(double omega_h) { return omega_h / (2.0 * std::atan(0.5 * omega_h)) - 1.0; }

/// Spectral radius per step of PRADIS's Stoermer scheme (Newmark beta = 1/2,
/// gamma = 1) on u'' + w^2 u = 0. Derivation (ours): with beta = 1/2, gamma = 1
/// the scheme reads u1 = u0 + h v0 + (h^2/2) a1, v1 = v0 + h a1, a1 = -w^2 u1
/// (a0 drops out), so on (u, h v) the amplification matrix is
///     A = (1/D) [[1, 1], [-Omega^2, D - Omega^2]],   D = 1 + Omega^2 / 2,
/// with det A = 1/D and tr A = (2 - Omega^2/2)/D. The eigenvalues are complex for
/// Omega < 4 (rho = sqrt(det A) = 1/sqrt(1 + Omega^2/2)), real beyond
/// (rho = (|tr| + sqrt(tr^2 - 4 det)) / 2, tending to 1 as Omega grows).
struct stoermer_amplification {
  double trace, det;
  explicit stoermer_amplification(double omega_h) {
    const double d = 1.0 + 0.5 * omega_h * omega_h;
    trace = (2.0 - 0.5 * omega_h * omega_h) / d;
    det = 1.0 / d;
  }
  double spectral_radius() const {
    const double disc = trace * trace - 4.0 * det;
    if (disc < 0) return std::sqrt(det);
    return 0.5 * (std::abs(trace) + std::sqrt(disc));
  }
};

/// Times at which the sampled signal x(t) crosses zero (either direction, or
/// only upward when `upward_only`), located by a cubic Lagrange interpolant
/// through the four samples around the sign change and bisection. For a signal
/// resolved by n samples per period the location error is O((2 pi / n)^4) of
/// a period, far below the method errors measured here.
inline std::vector<double> zero_crossings(const std::vector<double>& t, const std::vector<double>& x,
                                          bool upward_only = false) {
  std::vector<double> out;
  const std::size_t n = std::min(t.size(), x.size());
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const bool up = x[i] < 0 && x[i + 1] >= 0;
    const bool down = x[i] > 0 && x[i + 1] <= 0;
    if (!(up || (down && !upward_only))) continue;
    // Four interpolation nodes i-1 .. i+2, shifted inside the sample range.
    std::size_t j0 = i > 0 ? i - 1 : 0;
    if (j0 + 4 > n) j0 = n >= 4 ? n - 4 : 0;
    const std::size_t m = std::min<std::size_t>(4, n - j0);
    auto p = [&](double s) {
      double sum = 0;
      for (std::size_t a = 0; a < m; ++a) {
        double l = 1;
        for (std::size_t b = 0; b < m; ++b)
          if (b != a) l *= (s - t[j0 + b]) / (t[j0 + a] - t[j0 + b]);
        sum += l * x[j0 + a];
      }
      return sum;
    };
    double lo = t[i], hi = t[i + 1];
    double flo = p(lo);
    for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++it) {
      const double mid = 0.5 * (lo + hi), fm = p(mid);
      if ((fm < 0) == (flo < 0)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    out.push_back(0.5 * (lo + hi));
  }
  return out;
}

/// Mean period from zero crossings. With `upward_only`, consecutive crossings
/// are one period apart (robust to an offset of the signal); otherwise they are
/// half a period apart (the signal must be symmetric about zero).
inline double period_from_crossings(const std::vector<double>& c, bool upward_only) {
  if (c.size() < 2) return std::nan("");
  const double span = c.back() - c.front();
  const double intervals = static_cast<double>(c.size() - 1);
  return upward_only ? span / intervals : 2.0 * span / intervals;
}

// ---------------------------------------------------------------------------
// Test-only element types
// ---------------------------------------------------------------------------

/// Counts NEWINT calls (new_integration) and commits; produces no flow.
struct newint_counter {
  static constexpr pradis::passport passport{.name = "NEWINTCOUNT", .ext = 1, .par = 0, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "test: counts NEWINT calls",
                                             .name = "Test element counting new_integration calls",
                                             .field = "tests",
                                             .dofs = "1 - any DOF",
                                             .parameters = "",
                                             .work = "",
                                             .special = "none"};
  struct parameters {};
  int newint_calls = 0;
  int commits = 0;
  double newint_time = -1;  // time at the last NEWINT
  explicit newint_counter(parameters) {}
  static newint_counter from_parameters(std::span<const double>) { return newint_counter(parameters{}); }
  void new_integration(pradis::element_context& ctx) {
    ++newint_calls;
    newint_time = ctx.time;
  }
  void commit(pradis::element_context&) { ++commits; }
  void evaluate(const pradis::local_input<newint_counter>&, pradis::local_output<newint_counter>& out,
                pradis::element_context&) const {
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

/// State-vector test element (STR = 1): integrates the velocity of its DOF over
/// time with the right-endpoint rule, written as the manual demands,
/// NEW = OLD + h v (never X = X + dX). If the kernel copied NEW to OLD on a
/// rejected step or on every Newton iteration, the integral would be wrong.
struct velocity_integrator {
  static constexpr pradis::passport passport{.name = "VINT", .ext = 1, .par = 0, .str = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "test: integrates v over time in its state vector",
                                             .name = "Test element with a state vector",
                                             .field = "tests",
                                             .dofs = "1 - any DOF",
                                             .parameters = "",
                                             .work = "",
                                             .special = "none"};
  struct parameters {};
  explicit velocity_integrator(parameters) {}
  static velocity_integrator from_parameters(std::span<const double>) { return velocity_integrator(parameters{}); }
  void evaluate(const pradis::local_input<velocity_integrator>& in, pradis::local_output<velocity_integrator>& out,
                pradis::element_context& ctx) const {
    ctx.new_state[0] = ctx.old_state[0] + ctx.step * in.v(0);
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

/// Rejects (singular situation, code 75) the first attempt of the first step
/// that ends after time t_reject, at its second Newton iteration, so that the
/// elements evaluated before it have already written NEW for that attempt.
/// W(1) counts the rejections it caused.
struct one_time_rejector {
  static constexpr pradis::passport passport{.name = "REJECT1", .ext = 1, .par = 1, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "test: rejects one step",
                                             .name = "Test element rejecting one step attempt",
                                             .field = "tests",
                                             .dofs = "1 - any DOF",
                                             .parameters = "1 - time after which the next step attempt is rejected",
                                             .work = "1 - number of rejections caused",
                                             .special = "code 75 once"};
  struct parameters {
    double t_reject = 0;
  };
  parameters p;
  explicit one_time_rejector(parameters q) : p(q) {}
  static one_time_rejector from_parameters(std::span<const double> v) { return one_time_rejector({v[0]}); }
  void evaluate(const pradis::local_input<one_time_rejector>&, pradis::local_output<one_time_rejector>& out,
                pradis::element_context& ctx) const {
    if (out.want_jacobian) out.K(0, 0) = 0.0;
    if (ctx.nstep > 0 && ctx.time > p.t_reject && ctx.work[0] == 0 && ctx.niter >= 1) {
      ctx.work[0] = 1;
      ctx.singular("test rejection of one step attempt");
    }
  }
};

/// Recommends a maximum step h_rec at every call (STEPMD); no flow.
struct step_recommender {
  static constexpr pradis::passport passport{.name = "STEPREC", .ext = 1, .par = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "test: recommends a step",
                                             .name = "Test element recommending a maximum step (STEPMD)",
                                             .field = "tests",
                                             .dofs = "1 - any DOF",
                                             .parameters = "1 - recommended step [s]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double h = 0;
  };
  parameters p;
  explicit step_recommender(parameters q) : p(q) {}
  static step_recommender from_parameters(std::span<const double> v) { return step_recommender({v[0]}); }
  void evaluate(const pradis::local_input<step_recommender>&, pradis::local_output<step_recommender>& out,
                pradis::element_context& ctx) const {
    ctx.recommend_step(p.h);
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

}  // namespace pradis_test
