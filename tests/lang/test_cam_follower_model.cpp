// examples/models/cam_follower.prd: a harmonic cam (CAM) driven at a constant speed by VSRC pushes a follower
// (MASS) held against it by a preload (F) and a shock absorber with a return spring (TDAMPER); at 150 rad/s the
// follower leaves the profile before the top of the lift, flies, lands and bounces, and the cycle repeats.
//
// The laws checked:
// - The lift. CAM interpolates its table by the periodic cubic spline (cam.hpp, periodic_spline.hpp; de Boor,
//   A Practical Guide to Splines, 1978, chapter IV). On the file's uniform table of s(theta) = H/2 (1 - cos theta),
//   spacing D = pi/12, the spline's second derivatives are those of the harmonic times a constant: the cyclic
//   system D/6 (M_j-1 + 4 M_j + M_j+1) = (f_j+1 - 2 f_j + f_j-1) / D is solved for f = cos by
//   M_j = lambda cos(theta_j), lambda = 6 (cos D - 1) / (D^2 (2 + cos D)). That closed form must give the element's
//   lift (work entry 3) to round-off, and it lies within the bound of Hall and Meyer (J. Approx. Theory 16 (1976)
//   105; de Boor, chapter V) (5/384) D^4 max|s''''| of the harmonic profile.
// - The contact law of cam.hpp at every sample: F = max(0, k delta + c delta') while delta = S(theta) - y > 0,
//   else 0, with delta' = S'(theta) omega - y'; and the moment F S'(theta) on the cam, which the drive (VSRC)
//   supplies: its reaction equals it (the power F S' omega that the drive puts in is the power F delta' + F y'
//   that the contact takes and passes on).
// - The table damper. TDAMPER's force is g(y') + k y with g the monotone cubic (PCHIP) through the file's
//   (speed, force) table: Fritsch and Carlson, SIAM J. Numer. Anal. 17 (1980) 238, with the node slopes of
//   Fritsch and Butland as in Moler, Numerical Computing with MATLAB, 2004, section 3.4 ("pchip"), implemented
//   here independently; its speed entry is the follower's speed.
// - Newton's second law on the follower: m y'' = F - F_damper - P at every sample.
// - The jump of a force-closed follower. A rigid follower stays on the profile while the contact force that
//   its motion y = s(theta) needs is positive (the kinetostatic force):
//       F_req(theta) = m s''(theta) omega^2 + k s(theta) + P + g(s'(theta) omega),
//   and leaves it where F_req falls to zero (R. L. Norton, Design of Machinery, chapter on cam dynamics, the
//   force-closed cam-follower system and follower jump; Norton, Cam Design and Manufacturing Handbook, 2nd ed.,
//   2009, chapter on cam dynamics). The contact of CAM is compliant (k_c, c_c): the force rings about F_req
//   (its period 2 pi sqrt(m / k_c), excited at every knot of the spline, whose jerk jumps) and the follower lags
//   the profile by F / k_c. So the run is compared with the closed form in the rigid limit: with a contact
//   100 times stiffer (c_c scaled with sqrt(k_c), the same damping ratio; step and output interval divided by 10
//   to resolve it as well) the force comes closer to F_req (the ringing scales like 1/omega_n = sqrt(m / k_c),
//   so by a factor 10 predicted; 3 required), and in both runs the first lift-off lies at the root of F_req within
//   the sample spacing omega OUT plus the force deviation found near it divided by |dF_req/dtheta|.
//
// Tolerances follow from the run's settings. Newton (NEWMARK, fixed step) accepts a step when the residual of
// every DOF is at most DABSI * 1 N + DRLTI * (sum of |flows| on the DOF) (include/pradis/integrators/newton.hpp;
// 1 N is the mechanical nominal flow): that bounds the follower's balance. The element laws are evaluated at the
// sampled state, so the work entries agree with the closed forms up to round-off, bounded as 64 eps times the
// magnitude of the terms (the spline's cyclic solve and the PCHIP slopes are computed in another order here).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {
// The file's $DATA.
constexpr double camf_omega = 150;                    // cam speed [rad/s] (VSRC constant part)
constexpr double camf_kc = 1e7, camf_cc = 900;        // contact stiffness [N/m] and damping [N s/m]
constexpr double camf_lift = 0.01;                    // stroke H of s = H/2 (1 - cos theta) [m]
constexpr int camf_intervals = 24;                    // table spacing pi/12
constexpr double camf_m = 0.5, camf_ks = 2000;        // follower mass [kg], return spring [N/m]
constexpr double camf_preload = 20;                   // F (2; -20): 20 N towards the cam
constexpr double camf_speeds[] = {-1, -0.5, -0.2, 0, 0.2, 0.5, 1};   // shock absorber table [m/s]
constexpr double camf_forces[] = {-30, -18, -9, 0, 14, 28, 45};      // [N]
// $RUN: the fixed step (= OUT) and Newton's residual test.
constexpr double camf_h = 5e-5, camf_dabsi = 1e-9, camf_drlti = 1e-12;
constexpr const char* camf_contact_line = "Contact = 1E7, 900";
constexpr const char* camf_start_line = "Start = -7.623475304939012E-6";
constexpr const char* camf_run_line = "'NEWMARK (END=0.084, OUT=5E-5, SMAX=5E-5, ITR=20,";
constexpr double camf_eps = std::numeric_limits<double>::epsilon();

/// The periodic cubic spline S of the file's table and its first two derivatives (closed form, see above).
struct camf_spline_value {
  double s = 0, s1 = 0, s2 = 0;
};
camf_spline_value camf_spline(double theta) {
  const double d = 2 * std::numbers::pi / camf_intervals;
  const double lambda = 6 * (std::cos(d) - 1) / (d * d * (2 + std::cos(d)));
  double r = std::fmod(theta, 2 * std::numbers::pi);
  if (r < 0) r += 2 * std::numbers::pi;
  const int j = std::min(static_cast<int>(r / d), camf_intervals - 1);
  const double xj = j * d, a = xj + d - r, t = r - xj;
  const double f0 = std::cos(xj), f1 = std::cos(xj + d), m0 = lambda * f0, m1 = lambda * f1;
  // The spline C of cos; S = H/2 (1 - C).
  const double c = m0 * a * a * a / (6 * d) + m1 * t * t * t / (6 * d) + (f0 / d - m0 * d / 6) * a +
                   (f1 / d - m1 * d / 6) * t;
  const double c1 = -m0 * a * a / (2 * d) + m1 * t * t / (2 * d) + (f1 - f0) / d - (m1 - m0) * d / 6;
  const double c2 = (m0 * a + m1 * t) / d;
  return {camf_lift / 2 * (1 - c), -camf_lift / 2 * c1, -camf_lift / 2 * c2};
}

/// The shock absorber's PCHIP g(v) and its slope (Moler's pchip; linear extrapolation with the end slopes).
struct camf_pchip {
  static constexpr std::size_t n = std::size(camf_speeds);
  double slope[n] = {};
  static double sign(double a) { return a > 0 ? 1.0 : (a < 0 ? -1.0 : 0.0); }
  static double secant(std::size_t k) {
    return (camf_forces[k + 1] - camf_forces[k]) / (camf_speeds[k + 1] - camf_speeds[k]);
  }
  static double width(std::size_t k) { return camf_speeds[k + 1] - camf_speeds[k]; }
  static double end(double h0, double h1, double d0, double d1) {
    double s = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (sign(s) != sign(d0)) return 0;
    if (sign(d0) != sign(d1) && std::abs(s) > std::abs(3 * d0)) return 3 * d0;
    return s;
  }
  camf_pchip() {
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double d0 = secant(k - 1), d1 = secant(k);
      if (sign(d0) * sign(d1) <= 0) continue;
      const double w1 = 2 * width(k) + width(k - 1), w2 = width(k) + 2 * width(k - 1);
      slope[k] = (w1 + w2) / (w1 / d0 + w2 / d1);
    }
    slope[0] = end(width(0), width(1), secant(0), secant(1));
    slope[n - 1] = end(width(n - 2), width(n - 3), secant(n - 2), secant(n - 3));
  }
  /// Value, slope, and the magnitude of the terms summed (for the round-off bound).
  void at(double v, double& value, double& dvalue, double& scale) const {
    if (v < camf_speeds[0] || v >= camf_speeds[n - 1]) {
      const std::size_t e = v < camf_speeds[0] ? 0 : n - 1;
      value = camf_forces[e] + slope[e] * (v - camf_speeds[e]);
      dvalue = slope[e];
      scale = std::abs(camf_forces[e]) + std::abs(slope[e] * (v - camf_speeds[e]));
      return;
    }
    std::size_t k = 0;
    while (!(v < camf_speeds[k + 1])) ++k;
    const double hk = width(k), t = (v - camf_speeds[k]) / hk, t2 = t * t, t3 = t2 * t;
    const double m0 = slope[k] * hk, m1 = slope[k + 1] * hk;
    value = (2 * t3 - 3 * t2 + 1) * camf_forces[k] + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * camf_forces[k + 1] +
            (t3 - t2) * m1;
    dvalue = ((6 * t2 - 6 * t) * camf_forces[k] + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * camf_forces[k + 1] +
              (3 * t2 - 2 * t) * m1) /
             hk;
    scale = std::abs(camf_forces[k]) + std::abs(camf_forces[k + 1]) + std::abs(m0) + std::abs(m1);
  }
  double operator()(double v) const {
    double g = 0, dg = 0, sc = 0;
    at(v, g, dg, sc);
    return g;
  }
};

/// The kinetostatic contact force of the rigid follower on the spline profile.
double camf_required(const camf_pchip& g, double theta) {
  const camf_spline_value s = camf_spline(theta);
  return camf_m * s.s2 * camf_omega * camf_omega + camf_ks * s.s + camf_preload + g(s.s1 * camf_omega);
}

/// The first root of F_req after the top of its rise, by bisection on [pi/2, pi] (F_req > 0 at pi/2, < 0 at pi).
double camf_jump_angle(const camf_pchip& g) {
  double lo = std::numbers::pi / 2, hi = std::numbers::pi;
  REQUIRE(camf_required(g, lo) > 0);
  REQUIRE(camf_required(g, hi) < 0);
  for (int i = 0; i < 200 && hi - lo > 4 * camf_eps * hi; ++i) {
    const double mid = (lo + hi) / 2;
    (camf_required(g, mid) > 0 ? lo : hi) = mid;
  }
  return lo;
}

/// A run's contact phase before its first lift-off compared with the kinetostatic force.
struct camf_jump_result {
  double theta_off = 0;   ///< the cam angle of the first sample without contact force [rad]
  double dev_arc = 0;     ///< max |F - F_req| over pi/4 <= theta <= theta_jump - 0.1 [N]
  double dev_near = 0;    ///< max |F - F_req| over the 0.2 rad before the lift-off sample [N]
  double f_peak = 0;      ///< the largest F_req on the arc [N]
};
camf_jump_result camf_jump(const io::table& t, const camf_pchip& g, double theta_jump) {
  const std::size_t th = lang_test::column(t, "Cam angle"), f = lang_test::column(t, "Contact force");
  camf_jump_result out;
  std::size_t off = t.rows();
  for (std::size_t r = 0; r < t.rows() && off == t.rows(); ++r)
    if (t.at(r, f) == 0) off = r;
  REQUIRE(off < t.rows());
  out.theta_off = t.at(off, th);
  for (std::size_t r = 0; r < off; ++r) {
    const double theta = t.at(r, th), dev = std::abs(t.at(r, f) - camf_required(g, theta));
    if (theta >= std::numbers::pi / 4 && theta <= theta_jump - 0.1) {
      out.dev_arc = std::max(out.dev_arc, dev);
      out.f_peak = std::max(out.f_peak, camf_required(g, theta));
    }
    if (theta >= out.theta_off - 0.2) out.dev_near = std::max(out.dev_near, dev);
  }
  return out;
}

std::string camf_replaced(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  REQUIRE_MESSAGE(p != std::string::npos, from);
  return text.replace(p, from.size(), to);
}
}  // namespace

TEST_SUITE("lang/cam follower") {
  TEST_CASE("examples/models/cam_follower.prd: CAM's spline lift and contact law, TDAMPER's PCHIP table, the drive's "
            "moment and Newton's law on the follower") {
    const std::string text = lang_test::slurp(lang_test::models_dir() / "cam_follower.prd");
    REQUIRE(text.find(camf_run_line) != std::string::npos);  // the settings the tolerances come from
    REQUIRE(text.find(camf_contact_line) != std::string::npos);
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "cam_follower.prd").string()));
    s->run({.write_files = false});
    const io::table& t = s->results();
    const auto col = [&](const char* label) { return lang_test::column(t, label); };
    const std::size_t th = col("Cam angle"), w = col("Cam speed"), y = col("Follower lift"), v = col("Follower speed"),
                      a = col("Follower acceleration"), fc = col("Contact force"), dl = col("Interference"),
                      lift = col("Cam lift"), torque = col("Drive torque"), fd = col("Damper force"),
                      vd = col("Damper speed"), steps = col("Steps");
    const std::size_t last = t.rows() - 1;
    REQUIRE(t.rows() == 1681);           // t = 0 and every 50 us to 84 ms
    REQUIRE(t.at(last, steps) == 1680);  // the fixed step throughout: no step was cut
    // The start: the static deflection of the contact under the force the follower needs at theta = 0,
    // y0 = -(m H/2 omega^2 + P) / (k_c + k), set by X0.
    const double y0 = -(camf_m * camf_lift / 2 * camf_omega * camf_omega + camf_preload) / (camf_kc + camf_ks);
    CHECK(std::abs(t.at(0, y) - y0) <= 4 * camf_eps * std::abs(y0));

    // The spline of the table against the harmonic profile (Hall and Meyer's bound), on a fine grid.
    const double d = 2 * std::numbers::pi / camf_intervals;
    const double hall_meyer = 5.0 / 384 * std::pow(d, 4) * camf_lift / 2;
    double e_profile = 0;
    for (int i = 0; i <= 2400; ++i) {
      const double theta = 2 * std::numbers::pi * i / 2400;
      e_profile = std::max(e_profile, std::abs(camf_spline(theta).s - camf_lift / 2 * (1 - std::cos(theta))));
    }
    CHECK(e_profile <= hall_meyer);

    const camf_pchip g;
    double e_lift = 0, e_delta = 0, e_law = 0, e_torque = 0, e_damper = 0, newton_ratio = 0;
    std::size_t contact_rows = 0, free_rows = 0, speed_mismatch = 0, rebound_rows = 0, compression_rows = 0;
    double v_min = 0, v_max = 0;
    for (std::size_t r = 0; r <= last; ++r) {
      const double theta = t.at(r, th), yr = t.at(r, y), vr = t.at(r, v);
      CHECK(t.at(r, w) == camf_omega);
      const camf_spline_value sp = camf_spline(theta);
      // Lift and interference: the spline at the sampled angle, S - y.
      e_lift = std::max(e_lift, std::abs(t.at(r, lift) - sp.s) / (64 * camf_eps * camf_lift));
      e_delta = std::max(e_delta, std::abs(t.at(r, dl) - (sp.s - yr)) / (64 * camf_eps * camf_lift));
      // The contact law on the element's interference.
      const double delta = t.at(r, dl), rate = sp.s1 * camf_omega - vr;
      const double push = camf_kc * delta + camf_cc * rate;
      const double law = delta > 0 ? std::max(0.0, push) : 0.0;
      const double law_tol =
          64 * camf_eps * (camf_kc * camf_lift + camf_cc * (std::abs(sp.s1 * camf_omega) + std::abs(vr)));
      e_law = std::max(e_law, std::abs(t.at(r, fc) - law) / law_tol);
      if (t.at(r, fc) > 0)
        ++contact_rows;
      else {
        ++free_rows;
        CHECK(t.at(r, fc) == 0);  // the contact never pulls
      }
      // The drive's reaction: the moment F S'(theta) (only CAM acts on the cam's DOF).
      const double fs = t.at(r, fc) * sp.s1;
      if (t.at(r, fc) > 0)
        e_torque = std::max(e_torque, std::abs(t.at(r, torque) - fs) /
                                          (64 * camf_eps * (std::abs(fs) + t.at(r, fc) * camf_lift)));
      else
        CHECK(t.at(r, torque) == 0);
      // The shock absorber: g(y') + k y, its speed entry y'.
      speed_mismatch += t.at(r, vd) != vr;
      double gv = 0, dg = 0, gscale = 0;
      g.at(vr, gv, dg, gscale);
      e_damper = std::max(e_damper, std::abs(t.at(r, fd) - (gv + camf_ks * yr)) /
                                        (64 * camf_eps * (gscale + camf_ks * std::abs(yr))));
      v_min = std::min(v_min, vr);
      v_max = std::max(v_max, vr);
      rebound_rows += vr > camf_speeds[4];
      compression_rows += vr < camf_speeds[2];
      // Newton's law on the follower: m y'' + F_damper + P - F = 0 to Newton's residual test.
      const double ma = camf_m * t.at(r, a);
      const double flows = std::abs(ma) + std::abs(t.at(r, fd)) + camf_preload + t.at(r, fc);
      newton_ratio = std::max(newton_ratio, std::abs(ma + t.at(r, fd) + camf_preload - t.at(r, fc)) /
                                                (camf_dabsi + camf_drlti * flows));
    }
    MESSAGE("cam follower: lift ", e_lift, ", interference ", e_delta, ", contact law ", e_law, ", drive moment ",
            e_torque, ", damper ", e_damper, " of their round-off bounds; Newton's law at ", newton_ratio,
            " of the residual tolerance; spline off the harmonic by ", e_profile, " m (bound ", hall_meyer,
            "); follower speeds ", v_min, " .. ", v_max, " m/s; ", contact_rows, " samples in contact, ", free_rows,
            " off");
    CHECK(e_lift <= 1);
    CHECK(e_delta <= 1);
    CHECK(e_law <= 1);
    CHECK(e_torque <= 1);
    CHECK(e_damper <= 1);
    CHECK(speed_mismatch == 0);
    CHECK(newton_ratio <= 1);
    // The run exercises both sides of the table and both regimes of the contact.
    CHECK(rebound_rows > 100);
    CHECK(compression_rows > 100);
    CHECK(contact_rows > 400);
    CHECK(free_rows > 400);
  }

  TEST_CASE("examples/models/cam_follower.prd: the follower jumps where the kinetostatic force of the rigid follower "
            "vanishes, and the run tends to it as the contact stiffens") {
    const std::string text = lang_test::slurp(lang_test::models_dir() / "cam_follower.prd");
    const auto model_run = lang_test::run(text);
    // 100 times stiffer, the same damping ratio, the same static start, a step 10 times shorter; to 25 ms.
    const double kc_stiff = 100 * camf_kc, cc_stiff = 10 * camf_cc, h_stiff = camf_h / 10;
    char start[80];
    std::snprintf(start, sizeof start, "Start = %.17g",
                  -(camf_m * camf_lift / 2 * camf_omega * camf_omega + camf_preload) / (kc_stiff + camf_ks));
    std::string stiff = camf_replaced(text, camf_contact_line, "Contact = 1E9, 9000");
    stiff = camf_replaced(stiff, camf_start_line, start);
    stiff = camf_replaced(stiff, camf_run_line, "'NEWMARK (END=0.025, OUT=5E-6, SMAX=5E-6, ITR=20,");
    REQUIRE(kc_stiff == 1e9);
    REQUIRE(cc_stiff == 9000);
    const auto stiff_run = lang_test::run(stiff);

    const camf_pchip g;
    const double theta_jump = camf_jump_angle(g);
    // The smallest |dF_req/dtheta| within 0.2 rad of the root (F_req falls steadily there).
    double slope = std::numeric_limits<double>::infinity();
    for (int i = -20; i <= 20; ++i) {
      const double x = theta_jump + 0.01 * i, e = 1e-5;
      slope = std::min(slope, std::abs(camf_required(g, x + e) - camf_required(g, x - e)) / (2 * e));
    }
    const camf_jump_result j = camf_jump(model_run->results(), g, theta_jump);
    const camf_jump_result js = camf_jump(stiff_run->results(), g, theta_jump);
    const double tol = camf_omega * camf_h + j.dev_near / slope, tol_s = camf_omega * h_stiff + js.dev_near / slope;
    MESSAGE("jump: F_req = 0 at ", theta_jump, " rad (", theta_jump * 180 / std::numbers::pi, " deg), |dF_req/dtheta| >= ",
            slope, " N/rad; the run leaves the profile at ", j.theta_off, " rad (tolerance ", tol, "), with a contact "
            "100 times stiffer at ", js.theta_off, " (", tol_s, "); |F - F_req| on the arc ", j.dev_arc, " N and ",
            js.dev_arc, " N of a peak ", j.f_peak, " N");
    CHECK(j.theta_off >= theta_jump - tol);
    CHECK(j.theta_off <= theta_jump + tol);
    CHECK(js.theta_off >= theta_jump - tol_s);
    CHECK(js.theta_off <= theta_jump + tol_s);
    CHECK(js.dev_arc <= j.dev_arc / 3);
    CHECK(std::abs(js.theta_off - theta_jump) <= std::abs(j.theta_off - theta_jump));
    CHECK(j.f_peak > 80);  // the arc carries the load: F_req peaks at 92 N
  }
}
