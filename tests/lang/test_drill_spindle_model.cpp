// examples/models/drill_spindle.prd: a horizontal spindle in an exact cylindrical bearing CYL3X (axis X), wound
// up by a body-fixed drive torque M3B against a torsion spring-damper RSD3 to the ground and fed along its axis by
// a body-fixed force F3B whose radial part turns with it. Checked against closed forms and exact balances:
//
// The spin about the fixed principal axis X (Euler's equations, Goldstein, Classical Mechanics, 3rd ed., section
// 5.5: w x J w = 0) is the damped oscillator Ja theta'' + c theta' + k theta = Md from rest, the step response
// (Thomson and Dahleh, Theory of Vibration with Applications, 5th ed., sections 2.4 and 4.2):
//     theta(t) = theta_eq (1 - exp(-z w t) (cos(wd t) + z w / wd sin(wd t))),   theta_eq = Md / k,
//     theta'(t) = theta_eq w / sqrt(1 - z^2) exp(-z w t) sin(wd t),
//     w = sqrt(k / Ja), z = c / (2 sqrt(k Ja)), wd = w sqrt(1 - z^2).
// The slide along the axis under the feed's constant axial part Ff: x = Ff t^2 / (2 m) (Newton's second law).
// The loads in global axes: the feed (Ff, Fr cos theta, Fr sin theta), the drive (Md, -Mr sin theta,
// Mr cos theta) (a body-fixed vector turned by theta about X), the torsion spring's moment on the spindle
// -(k theta + c theta') X. The bearing carries the rest (d'Alembert, Goldstein section 1.4; no lateral
// acceleration, no angular acceleration across the axis): the force f = -(m g_vec + Fr (0, cos, sin)) and the
// moment about B, m = -M_lat - (B - G) x f, M_lat = Mr (0, -sin, cos); none along the axis.
//
// Reading the angle. 'X gives q1..q3 of the non-normalised quaternion q = Lq (sin(theta / 2) X, cos(theta / 2))
// and 'LQ its norm: theta = 2 atan2(q1 / Lq, sqrt(1 - |q_vec|^2 / Lq^2)), with cos(theta / 2) > 0.69 since
// theta stays below 1.63 rad (checked).
//
// Tolerances, from the run's BDF settings DRLTX = DABSX = 1e-9 (docs/bdf.md, "Error control and tolerances").
// The local error test is an RMS norm over at most N = 2 x (the model's DOFs) components, each weighted by
// DRLTX |x| + DABSX, so one component's local error is at most sqrt(N) times its weight: for the quaternion
// components (|q| <= 1 + LQBAND = 1.01) eps_q = sqrt(N) (DRLTX 1.01 + DABSX), for their rates (|q'| <=
// 1.01 w_max / 2) eps_qd = sqrt(N) (DRLTX 1.01 w_max / 2 + DABSX). The read-off theta = 2 atan2(q1, q4) and
// theta' = 2 (q4 q1' - q1 q4') / Lq^2 (Lq >= 0.99) turn them into
//     d_theta = 4 eps_q / 0.99,   d_omega = 4.04 (eps_qd + w_max eps_q / 2) / 0.99^2
// per step. The damped mode does not amplify an error in its energy norm sqrt(theta^2 + theta'^2 / w^2), so
// the global errors are at most the sums over the run's NSTEP steps:
//     D_theta <= NSTEP (d_theta + d_omega / w),   D_omega <= NSTEP (w d_theta + d_omega).
// The slide is a free motion: D_x <= NSTEP (eps_x + eps_v END) (a velocity error grows into the displacement).
// A load or reaction that depends on theta is then within its magnitude times D_theta (the spring's moment
// within k D_theta + c D_omega): the reactions balance the loads at a state within these bounds. This is a
// worst case (each local error at its limit, all of one sign); the errors are also required to fall with DRLTX
// (the model against a run at DRLTX / 10), as a discretisation error does. The constraint rows (the distance
// from the axis, the misalignment, the turn across the axis) are met to the Newton weights DRLTX |x| + DABSX
// per coordinate (|x| <= 1 m, |q| <= 1.01): a distance of two points to twice that, an angle from two
// quaternions to four times. Where a work entry is compared with the angle read off the same output row, the
// entry comes from the driver's last evaluation of the step, within a Newton correction (below d_theta) of it.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {

constexpr double drsp_pi = 3.14159265358979323846;
constexpr double drsp_m = 3, drsp_ja = 0.005, drsp_g = 9.81;  // the file's $DATA
constexpr double drsp_k = 2, drsp_c = 0.03;                   // RSD3
constexpr double drsp_md = 2, drsp_mr = 0.6;                  // M3B: about the axis, about the spindle's z
constexpr double drsp_ff = 1.5, drsp_fr = 8;                  // F3B: along the axis, along the spindle's y
constexpr double drsp_arm = -0.15;                            // B - G along X
constexpr double drsp_end = 1.5;
constexpr double drsp_drltx = 1e-9, drsp_dabsx = 1e-9;  // the model's BDF settings
constexpr const char* drsp_run_line = "'BDF (END=1.5, OUT=0.01, DRLTX=1E-9, DABSX=1E-9)";

using drsp_vec = std::array<double, 3>;
double drsp_dist(const drsp_vec& a, const drsp_vec& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

/// The closed form of the spin.
struct drsp_spin {
  double w = std::sqrt(drsp_k / drsp_ja), z = drsp_c / (2 * std::sqrt(drsp_k * drsp_ja)), wd = w * std::sqrt(1 - z * z);
  double theta_eq = drsp_md / drsp_k;
  double theta(double t) const {
    return theta_eq * (1 - std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t)));
  }
  double omega(double t) const {
    return theta_eq * w / std::sqrt(1 - z * z) * std::exp(-z * w * t) * std::sin(wd * t);
  }
  double theta_max() const { return theta_eq * (1 + std::exp(-z * drsp_pi / std::sqrt(1 - z * z))); }
  double omega_max() const { return theta_eq * w / std::sqrt(1 - z * z); }
};

/// The bearing's force and moment on the spindle at the angle theta.
std::pair<drsp_vec, drsp_vec> drsp_bearing(double theta) {
  const drsp_vec f{0, -drsp_fr * std::cos(theta), drsp_m * drsp_g - drsp_fr * std::sin(theta)};
  // (B - G) x f with B - G = (arm, 0, 0): (0, -arm f_z, arm f_y).
  const drsp_vec m{0, drsp_mr * std::sin(theta) + drsp_arm * f[2], -drsp_mr * std::cos(theta) - drsp_arm * f[1]};
  return {f, m};
}

/// The largest deviations of one run.
struct drsp_errors {
  double steps = 0, n_norm = 0, theta_top = 0, read_cos = 1;
  double theta = 0, omega = 0, slide = 0;                  // against the closed forms
  double bearing_f = 0, bearing_m = 0, spring = 0, loads = 0;  // reactions and loads at the closed-form angle
  double bearing_f_read = 0, bearing_m_read = 0;           // the bearing at the angle read off the row
  double spring_read = 0, loads_read = 0, angle_read = 0;  // RSD3, F3B, M3B at the angle read off the row
  double axial = 0, across = 0, turn = 0, residual = 0, tilt = 0, lateral = 0;
  double f_max = 0, m_max = 0;
};

drsp_errors drsp_measure(lang::session& s) {
  const drsp_spin cf;
  const io::table& t = s.results();
  auto c = [&](const char* label) { return lang_test::column(t, label); };
  drsp_errors r;
  r.n_norm = 2.0 * s.model().dof_count();
  r.steps = t.at(t.rows() - 1, c("Steps"));
  for (std::size_t i = 0; i < t.rows(); ++i) {
    auto at = [&](const char* label) { return t.at(i, c(label)); };
    auto at3 = [&](const char* x, const char* y, const char* z) { return drsp_vec{at(x), at(y), at(z)}; };
    const double time = t.at(i, 0), th = cf.theta(time), om = cf.omega(time);
    const double lq = at("Lq"), q1 = at("q1"), q2 = at("q2"), q3 = at("q3");
    const double cos_half = std::sqrt(std::max(0.0, 1 - (q1 * q1 + q2 * q2 + q3 * q3) / (lq * lq)));
    const double read = 2 * std::atan2(q1 / lq, cos_half), spin = at("Spin");
    r.read_cos = std::min(r.read_cos, cos_half);
    r.theta_top = std::max(r.theta_top, read);
    r.theta = std::max(r.theta, std::abs(read - th));
    r.omega = std::max(r.omega, std::abs(spin - om));
    const double x = drsp_ff / (2 * drsp_m) * time * time;
    r.slide = std::max({r.slide, std::abs(at("X") - x), std::abs(at("Slide") - x)});

    const drsp_vec f = at3("Bearing Fx", "Bearing Fy", "Bearing Fz"), m = at3("Bearing Mx", "Bearing My", "Bearing Mz");
    r.f_max = std::max(r.f_max, std::hypot(f[0], f[1], f[2]));
    r.m_max = std::max(r.m_max, std::hypot(m[0], m[1], m[2]));
    const auto [fc, mc] = drsp_bearing(th);
    const auto [fr, mr] = drsp_bearing(read);
    r.bearing_f = std::max(r.bearing_f, drsp_dist(f, fc));
    r.bearing_m = std::max(r.bearing_m, drsp_dist(m, mc));
    r.bearing_f_read = std::max(r.bearing_f_read, drsp_dist(f, fr));
    r.bearing_m_read = std::max(r.bearing_m_read, drsp_dist(m, mr));
    r.axial = std::max({r.axial, std::abs(f[0]), std::abs(m[0])});

    // The loads: F3B and M3B turned with the spindle, RSD3's moment from the angle and the spin.
    const drsp_vec tor = at3("Torsion Mx", "Torsion My", "Torsion Mz");
    r.spring = std::max(r.spring, drsp_dist(tor, {-(drsp_k * th + drsp_c * om), 0, 0}));
    r.spring_read = std::max(r.spring_read, drsp_dist(tor, {-(drsp_k * read + drsp_c * spin), 0, 0}));
    r.angle_read = std::max(r.angle_read, std::abs(at("Torsion angle") - read));
    const drsp_vec feed = at3("Feed Fx", "Feed Fy", "Feed Fz"), drive = at3("Drive Mx", "Drive My", "Drive Mz");
    r.loads = std::max({r.loads, drsp_dist(feed, {drsp_ff, drsp_fr * std::cos(th), drsp_fr * std::sin(th)}),
                        drsp_dist(drive, {drsp_md, -drsp_mr * std::sin(th), drsp_mr * std::cos(th)})});
    r.loads_read =
        std::max({r.loads_read, drsp_dist(feed, {drsp_ff, drsp_fr * std::cos(read), drsp_fr * std::sin(read)}),
                  drsp_dist(drive, {drsp_md, -drsp_mr * std::sin(read), drsp_mr * std::cos(read)})});

    // The bearing holds: no turn across the axis, on the axis, aligned.
    r.turn = std::max({r.turn, std::abs(q2), std::abs(q3)});
    r.across = std::max({r.across, std::abs(at("wy")), std::abs(at("wz"))});
    r.lateral = std::max({r.lateral, std::abs(at("Y")), std::abs(at("Z"))});
    r.residual = std::max(r.residual, std::abs(at("Off axis")));
    r.tilt = std::max(r.tilt, std::abs(at("Tilt")));
  }
  return r;
}

/// The worst-case global error bounds from the run's settings and step count (see the top).
struct drsp_bounds {
  double d_theta = 0, d_omega = 0, theta = 0, omega = 0, x = 0;
};
drsp_bounds drsp_bound(const drsp_errors& r, double drltx, double dabsx) {
  const drsp_spin cf;
  const double root = std::sqrt(r.n_norm), wmax = cf.omega_max();
  const double eps_q = root * (drltx * 1.01 + dabsx), eps_qd = root * (drltx * 1.01 * wmax / 2 + dabsx);
  drsp_bounds b;
  b.d_theta = 4 * eps_q / 0.99;
  b.d_omega = 4.04 * (eps_qd + wmax * eps_q / 2) / (0.99 * 0.99);
  b.theta = r.steps * (b.d_theta + b.d_omega / cf.w);
  b.omega = r.steps * (cf.w * b.d_theta + b.d_omega);
  const double x_max = drsp_ff * drsp_end * drsp_end / (2 * drsp_m), v_max = drsp_ff * drsp_end / drsp_m;
  b.x = r.steps * root * ((drltx * x_max + dabsx) + (drltx * v_max + dabsx) * drsp_end);
  return b;
}

std::string drsp_file() { return lang_test::slurp(lang_test::models_dir() / "drill_spindle.prd"); }

}  // namespace

TEST_SUITE("lang/drill spindle") {
  TEST_CASE("examples/models/drill_spindle.prd: CYL3X lets the spindle wind up against RSD3 under M3B and slide "
            "under F3B by the closed forms, and carries the turning loads across the axis") {
    const std::string text = drsp_file();
    REQUIRE(text.find(drsp_run_line) != std::string::npos);  // the settings the tolerances come from
    lang::session s(lang::parse_file((lang_test::models_dir() / "drill_spindle.prd").string()));
    s.run({.write_files = false});
    REQUIRE(s.bdf_active());
    REQUIRE(s.results().rows() == 151);
    // CYL3X's multipliers: two line rows and two axis rows (the hidden q4 are the nodes').
    const auto& m = s.model();
    int n = 0;
    for (int d = 0; d < m.dof_count(); ++d)
      if (m.dof_name(d).rfind("Bearing.internal", 0) == 0) ++n;
    CHECK(n == 4);

    const drsp_spin cf;
    const drsp_errors r = drsp_measure(s);
    const drsp_bounds b = drsp_bound(r, drsp_drltx, drsp_dabsx);
    MESSAGE("drill spindle: ", r.steps, " steps; theta peak ", r.theta_top, " rad (closed form ", cf.theta_max(),
            "); off the closed forms: theta ", r.theta, " rad (bound ", b.theta, "), spin ", r.omega,
            " rad/s (bound ", b.omega, "), slide ", r.slide, " m (bound ", b.x, "); bearing force ", r.bearing_f,
            " N of ", r.f_max, " (bound ", drsp_fr * b.theta, "), moment ", r.bearing_m, " N m of ", r.m_max,
            "; RSD3 ", r.spring, " N m, F3B/M3B ", r.loads, "; at the angle read off each row: bearing ",
            r.bearing_f_read, " N, ", r.bearing_m_read, " N m, RSD3 ", r.spring_read, " N m and angle ",
            r.angle_read, " rad, F3B/M3B ", r.loads_read, " (per-step bound on the angle ", b.d_theta,
            "); along the axis ", r.axial, "; across: turn ", r.turn, ", spin ", r.across, " rad/s, off axis ",
            r.residual, " m, tilt ", r.tilt, " rad, Y/Z ", r.lateral, " m");

    // The read-off is clear of cos(theta / 2) = 0, and the mode is exercised up to its first peak.
    REQUIRE(r.read_cos > 0.5);
    CHECK(r.theta_top == doctest::Approx(cf.theta_max()).epsilon(0.01));
    CHECK(r.theta <= b.theta);
    CHECK(r.omega <= b.omega);
    CHECK(r.slide <= b.x);
    // Loads and reactions at the closed-form angle: their turning parts times the angle's bound.
    CHECK(r.bearing_f <= drsp_fr * b.theta);
    CHECK(r.bearing_m <= (drsp_mr + std::abs(drsp_arm) * drsp_fr) * b.theta);
    CHECK(r.spring <= drsp_k * b.theta + drsp_c * b.omega);
    CHECK(r.loads <= std::max(drsp_fr, drsp_mr) * b.theta);
    CHECK(r.f_max > drsp_m * drsp_g);  // the weight and the radial force: not trivial
    CHECK(r.m_max > 1);
    // At the angle read off the same row: F3B, M3B and RSD3 are functions of the state (within a Newton
    // correction of the row's); the bearing's multipliers carry BDF's acceleration error as the trajectory.
    CHECK(r.angle_read <= b.d_theta);
    CHECK(r.loads_read <= std::max(drsp_fr, drsp_mr) * b.d_theta);
    CHECK(r.spring_read <= drsp_k * b.d_theta + drsp_c * b.d_omega);
    CHECK(r.bearing_f_read <= drsp_fr * b.theta);
    CHECK(r.bearing_m_read <= (drsp_mr + std::abs(drsp_arm) * drsp_fr) * b.theta);
    // CYL3X carries nothing along or about its axis: its force is a sum of the line rows' normals, its moment
    // of the axis rows' (both perpendicular to X).
    CHECK(r.axial <= 16 * std::numeric_limits<double>::epsilon() * std::max(r.f_max, r.m_max));
    // The bearing holds: no turn across the axis, no spin across it, on the axis and aligned.
    CHECK(r.turn <= drsp_drltx * 1.01 + drsp_dabsx);
    CHECK(r.across <= b.d_omega);
    CHECK(r.lateral <= drsp_drltx + drsp_dabsx);
    CHECK(r.residual <= 2 * (drsp_drltx + drsp_dabsx));
    CHECK(r.tilt <= 4 * (drsp_drltx * 1.01 + drsp_dabsx));
  }

  TEST_CASE("examples/models/drill_spindle.prd: the errors of the spin and of the bearing's reactions fall with "
            "DRLTX") {
    const std::string text = drsp_file();
    const auto p = text.find(drsp_run_line);
    REQUIRE(p != std::string::npos);
    std::string fine = text;
    fine.replace(p, std::string(drsp_run_line).size(), "'BDF (END=1.5, OUT=0.01, DRLTX=1E-10, DABSX=1E-10)");
    const auto model_run = lang_test::run(text), fine_run = lang_test::run(fine);
    const drsp_errors a = drsp_measure(*model_run), f = drsp_measure(*fine_run);
    const drsp_bounds bf = drsp_bound(f, 1e-10, 1e-10);
    MESSAGE("at DRLTX = 1e-9 / 1e-10: theta ", a.theta, " / ", f.theta, " rad, spin ", a.omega, " / ", f.omega,
            " rad/s, bearing force ", a.bearing_f, " / ", f.bearing_f, " N (at the read angle ", a.bearing_f_read,
            " / ", f.bearing_f_read, "), RSD3 ", a.spring, " / ", f.spring, " N m; steps ", a.steps, " / ", f.steps);
    // A tenfold tighter tolerance: a discretisation error falls by more than 3 (BDF's order is 2..5).
    CHECK(f.theta <= a.theta / 3);
    CHECK(f.omega <= a.omega / 3);
    CHECK(f.bearing_f <= a.bearing_f / 3);
    CHECK(f.bearing_f_read <= a.bearing_f_read / 3);
    CHECK(f.spring <= a.spring / 3);
    CHECK(f.theta <= bf.theta);
  }
}
