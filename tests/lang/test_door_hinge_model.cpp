// examples/models/door_hinge.prd: a door on the penalty revolute joint REV3, in a frame 3 degrees out of plumb, swings
// from 90 degrees open about its closed position as a compound pendulum under g sin(3 deg).
//
// Closed forms.
// - The period of the compound pendulum released at rest at theta0 (Landau and Lifshitz, Mechanics, section 11,
//   problem 1; the reduced length I / (m d)): T = 4 K(sin(theta0 / 2)) / w0, w0^2 = m g sin(b) d / I, with K the
//   complete elliptic integral of the first kind, computed by the arithmetic-geometric mean,
//   K(k) = pi / (2 AGM(1, sqrt(1 - k^2))) (Abramowitz and Stegun, Handbook of Mathematical Functions, 17.6).
//   The door passes theta = 0 at T/4 and 3T/4; energy: theta'^2 = 2 w0^2 (cos(theta) - cos(theta0)).
// - The hinge force (Newton's law for the centre of mass on a circle of radius d about the hinge line):
//   F = m a_c - m g_vec, a_c = d theta'' e_t - d theta'^2 e_r, theta'' = -w0^2 sin(theta).
// - Euler's equations about the centre of mass (the door turns about its principal axis z): the moments normal to
//   the hinge balance, so the hinge carries the constant moment m g cos(b) d (its axial force m g cos(b) at the
//   lever d), and the penalty joint's kr sin(phi) equals it; the centre of mass sits m g cos(b) / k (the axial gap)
//   + d sin(phi) (the sag) low. Penalty: gap = |F - c gap'| / k (the joint's law, joints.hpp).
// - The energy T + V + U (V = -m g_vec . x_c, U = k gap^2 / 2 + kr (1 - cos(phi))) is constant but for what the
//   joint's dampers take while the joint settles at its deflection after the release, its strain energy there,
//   D = |F0|^2 / (2 k) + M0^2 / (2 kr), F0 and M0 the hinge force and moment at release.
//
// Tolerances, from the run's settings: NEWMARK with the average acceleration rule (no numerical damping), fixed step
// h = 1 ms, outputs at every step, Newton on the velocity corrections to DABSU = 1e-10 m/s.
// - The swing: the rule's phase error for an oscillator of frequency w is (w h)^2 / 12 of the elapsed time (Hughes,
//   The Finite Element Method, section 9.3); the swing through 90 degrees is anharmonic, and we allow (w0 h)^2 of the
//   elapsed time (12 times the harmonic constant) and an energy error of (w0 h)^2 of the swing's energy m g sin(b) d;
//   a second test confirms that both errors fall as h^2. The penalty joint moves the hinge point by the gap: the
//   pendulum's length changes by at most F_r / k, the period by half of that relatively.
// - The hinge force from the closed form at the run's angle: off by m d Delta(theta'^2), Delta(theta'^2) = 2 Delta E
//   / I from the energy error. The gap is |F + c v| / k, v the relative velocity of the joint points: c |F'| / k
//   from the slow change of the deflection F / k (F' the closed form's rate along the swing), and the rule's
//   velocity of the door's joint point, x' + omega x rho from the trapezoidal velocities of the translation and of
//   the quaternion, which follows the point's motion only to O(h^2): we allow (theta'max h)^2 of its speed
//   d theta'max (measured: about 1 % of that, and falling as h^2, second test).
// - The sag and the drop: what the balance above leaves out, the moment of the in-plane force at the gap and at the
//   tilted lever (|F_in| (F_max / k + d phi)) and the gyroscopic moment of the tilted door (phi (Jyy - Jzz) theta'^2),
//   and the position's resolution (h / 2) DABSU; after the dampers settled the joint (t >= 0.5 s: the stiff modes,
//   at about half of critical damping, lose a factor 0.9 per step under the rule at w h of 10 to 18).

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {

constexpr double dhng_pi = 3.14159265358979323846;
constexpr double dhng_m = 30, dhng_w = 0.8, dhng_height = 2, dhng_thick = 0.04, dhng_d = 0.4, dhng_g = 9.81;
const double dhng_b = 3 * dhng_pi / 180, dhng_theta0 = dhng_pi / 2;
constexpr double dhng_k = 1e10, dhng_c = 5e5, dhng_kr = 1e9;  // the hinge's penalty parameters
constexpr double dhng_h = 1e-3, dhng_dabsu = 1e-10;         // the run's step and Newton tolerance
constexpr double dhng_settled = 0.5;                        // the joint's stiff modes have died out
constexpr const char* dhng_run_line = "'NEWMARK (END=6, OUT=1E-3, SMAX=1E-3, DABSU=1E-10, DRLTU=0, DABSI=1E-6, DRLTI=0)";
constexpr const char* dhng_half_line = "'NEWMARK (END=6, OUT=5E-4, SMAX=5E-4, DABSU=1E-10, DRLTU=0, DABSI=1E-6, DRLTI=0)";

std::string dhng_file() { return lang_test::slurp(lang_test::models_dir() / "door_hinge.prd"); }

/// The plate's moments of inertia about its centre of mass (body x along the width, y the thickness, z the height).
const double dhng_jxx = dhng_m * (dhng_height * dhng_height + dhng_thick * dhng_thick) / 12;
const double dhng_jyy = dhng_m * (dhng_w * dhng_w + dhng_height * dhng_height) / 12;
const double dhng_jzz = dhng_m * (dhng_w * dhng_w + dhng_thick * dhng_thick) / 12;
const double dhng_i = dhng_jzz + dhng_m * dhng_d * dhng_d;  // about the hinge line
const double dhng_gp = dhng_g * std::sin(dhng_b), dhng_gz = dhng_g * std::cos(dhng_b);
const double dhng_w0 = std::sqrt(dhng_m * dhng_gp * dhng_d / dhng_i);
const double dhng_swing_energy = dhng_m * dhng_gp * dhng_d * (1 - std::cos(dhng_theta0));
const double dhng_moment = dhng_m * dhng_gz * dhng_d;  // the hinge's moment normal to the axis

/// K(k) by the arithmetic-geometric mean.
double dhng_ellk(double k) {
  double a = 1, b = std::sqrt(1 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double an = (a + b) / 2;
    b = std::sqrt(a * b);
    a = an;
  }
  return dhng_pi / (2 * a);
}
const double dhng_period = 4 * dhng_ellk(std::sin(dhng_theta0 / 2)) / dhng_w0;

/// theta'^2 at the angle theta (energy).
double dhng_rate2(double theta) { return 2 * dhng_w0 * dhng_w0 * (std::cos(theta) - std::cos(dhng_theta0)); }
/// The hinge force on the door at the angle theta (closed form), the swing towards theta = 0 or past it.
std::array<double, 3> dhng_force(double theta) {
  const double acc = -dhng_w0 * dhng_w0 * std::sin(theta), r2 = std::max(0.0, dhng_rate2(theta));
  const double c = std::cos(theta), s = std::sin(theta);
  return {dhng_m * dhng_d * (-acc * s - r2 * c) - dhng_m * dhng_gp, dhng_m * dhng_d * (acc * c - r2 * s),
          dhng_m * dhng_gz};
}
double dhng_norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/// The swing angle theta about Z from the quaternion Lq (sin(theta/2) e, cos(theta/2)): |theta| < pi throughout, so
/// cos(theta/2) > 0 and follows from the norm.
double dhng_angle(const io::table& t, std::size_t i) {
  const double q1 = t.at(i, lang_test::column(t, "q1")), q2 = t.at(i, lang_test::column(t, "q2")),
               q3 = t.at(i, lang_test::column(t, "q3")), lq = t.at(i, lang_test::column(t, "Lq"));
  return 2 * std::atan2(q3, std::sqrt(std::max(0.0, lq * lq - q1 * q1 - q2 * q2 - q3 * q3)));
}

/// The times at which theta passes 0 (interpolated linearly: theta'' = 0 there) and the swing rate then.
struct dhng_crossing {
  double t, rate;
};
std::vector<dhng_crossing> dhng_crossings(const io::table& t) {
  std::vector<dhng_crossing> out;
  const std::size_t w = lang_test::column(t, "Swing rate");
  for (std::size_t i = 1; i < t.rows(); ++i) {
    const double a = dhng_angle(t, i - 1), b = dhng_angle(t, i);
    if ((a > 0) == (b > 0)) continue;
    const double f = a / (a - b);
    out.push_back({t.at(i - 1, 0) + f * (t.at(i, 0) - t.at(i - 1, 0)), t.at(i - 1, w) + f * (t.at(i, w) - t.at(i - 1, w))});
  }
  return out;
}

/// The largest |E + D| from t = dhng_settled on (E = T + V + U, D the joint's strain energy at release).
double dhng_energy_error(const io::table& t) {
  const std::size_t kin = lang_test::column(t, "Kinetic"), x = lang_test::column(t, "Centre X"),
                    z = lang_test::column(t, "Centre Z"), gap = lang_test::column(t, "Gap"),
                    sag = lang_test::column(t, "Sag");
  const std::array<double, 3> f0 = dhng_force(dhng_theta0);
  const double d = dhng_norm(f0) * dhng_norm(f0) / (2 * dhng_k) + dhng_moment * dhng_moment / (2 * dhng_kr);
  double e = 0;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (t.at(i, 0) < dhng_settled) continue;
    const double v = -(dhng_m * dhng_gp * t.at(i, x) - dhng_m * dhng_gz * t.at(i, z));
    const double u = dhng_k * t.at(i, gap) * t.at(i, gap) / 2 + dhng_kr * (1 - std::cos(t.at(i, sag)));
    e = std::max(e, std::abs(t.at(i, kin) + v + u + d));
  }
  return e;
}

/// The largest |k gap - |F|| from t = dhng_settled on, F the joint force of the work entries: the damper's share
/// c v . (gap direction).
double dhng_damper_share(const io::table& t) {
  const std::size_t fx = lang_test::column(t, "Hinge Fx"), fy = lang_test::column(t, "Hinge Fy"),
                    fz = lang_test::column(t, "Hinge Fz"), gap = lang_test::column(t, "Gap");
  double e = 0;
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.at(i, 0) >= dhng_settled)
      e = std::max(e, std::abs(dhng_k * t.at(i, gap) - dhng_norm({t.at(i, fx), t.at(i, fy), t.at(i, fz)})));
  return e;
}

}  // namespace

TEST_SUITE("lang/door hinge") {
  TEST_CASE("examples/models/door_hinge.prd: a door on REV3 swings with the compound pendulum's exact period, keeps "
            "its energy, and the hinge gives way by force / stiffness") {
    const std::string text = dhng_file();
    REQUIRE(text.find(dhng_run_line) != std::string::npos);  // the settings the tolerances come from
    // The file's data are the plate's inertia, the tilted weight and the joint's parameters used here.
    REQUIRE(text.find("Door = 30, 10.004, 11.6, 1.604, 0, 0, 0, 0, 0, 0") != std::string::npos);
    REQUIRE(text.find("Weight = 15.402471922298371, 0, -293.8966720782711, 0") != std::string::npos);
    REQUIRE(text.find("0, 0, 1, 0, 0, 1, 1E10, 5E5, 1E9, 1E5") != std::string::npos);
    CHECK(10.004 == doctest::Approx(dhng_jxx).epsilon(1e-15));
    CHECK(11.6 == doctest::Approx(dhng_jyy).epsilon(1e-15));
    CHECK(1.604 == doctest::Approx(dhng_jzz).epsilon(1e-15));
    CHECK(15.402471922298371 == doctest::Approx(dhng_m * dhng_gp).epsilon(1e-15));
    CHECK(293.8966720782711 == doctest::Approx(dhng_m * dhng_gz).epsilon(1e-15));

    lang::session s(lang::parse_file((lang_test::models_dir() / "door_hinge.prd").string()));
    s.run({.write_files = false});
    const io::table& t = s.results();
    REQUIRE(t.rows() == 6001);

    // The in-plane hinge force is at most m (g sin b + d (theta'max^2 + w0^2)), the whole at most that and the
    // axial m g cos b.
    const double rate_max = std::sqrt(dhng_rate2(0));
    const double f_in = dhng_m * (dhng_gp + dhng_d * (rate_max * rate_max + dhng_w0 * dhng_w0));
    const double f_max = std::hypot(f_in, dhng_m * dhng_gz);
    const double scheme = (dhng_w0 * dhng_h) * (dhng_w0 * dhng_h);

    // The period: theta = 0 at T/4 and 3T/4, passed at sqrt(2) w0.
    const std::vector<dhng_crossing> x = dhng_crossings(t);
    REQUIRE(x.size() == 2);
    const double length_part = f_in / dhng_k / dhng_d / 2;
    for (std::size_t j = 0; j < 2; ++j) {
      const double when = (2 * static_cast<double>(j) + 1) * dhng_period / 4;
      const double sign = j == 0 ? -1 : 1;  // closing (theta falls) at T/4, opening again at 3T/4
      MESSAGE("theta = 0 at ", x[j].t, " s (exact ", when, " s, rel. ", x[j].t / when - 1, ", tolerance ",
              scheme + length_part, "), rate ", x[j].rate, " rad/s (exact ", sign * rate_max, ", rel. ",
              x[j].rate / (sign * rate_max) - 1, ")");
      CHECK(std::abs(x[j].t / when - 1) <= scheme + length_part);
      // theta'^2 carries the relative energy error, at most (w0 h)^2: theta' half of it.
      CHECK(std::abs(x[j].rate / (sign * rate_max) - 1) <= scheme / 2 + length_part);
    }

    // The energy, once the joint has settled.
    const double e = dhng_energy_error(t), e_tol = scheme * dhng_swing_energy;
    MESSAGE("energy: off its start less the joint's settling loss by at most ", e, " J (tolerance ", e_tol,
            " J of the swing's ", dhng_swing_energy, " J)");
    CHECK(e <= e_tol);

    // The hinge force against the closed form at the run's angle, the gap against force / stiffness, the sag angle
    // and the drop of the centre of mass.
    const std::size_t fx = lang_test::column(t, "Hinge Fx"), fy = lang_test::column(t, "Hinge Fy"),
                      fz = lang_test::column(t, "Hinge Fz"), gap = lang_test::column(t, "Gap"),
                      sag = lang_test::column(t, "Sag"), cz = lang_test::column(t, "Centre Z");
    double f_rate = 0;  // max |F'| along the swing (closed form: dF/dtheta theta')
    for (int i = 0; i <= 1000; ++i) {
      const double th = dhng_theta0 * (1 - 2 * i / 1000.0), dt = 1e-6;
      const std::array<double, 3> a = dhng_force(th + dt), b = dhng_force(th - dt);
      const double df = std::hypot(a[0] - b[0], a[1] - b[1]) / (2 * dt);
      f_rate = std::max(f_rate, df * std::sqrt(std::max(0.0, dhng_rate2(th))));
    }
    const double f_tol = dhng_m * dhng_d * 2 * scheme * dhng_swing_energy / dhng_i + f_max * f_max / dhng_k / dhng_d;
    const double gap_tol =
        dhng_c * (f_rate / dhng_k + dhng_d * rate_max * (rate_max * dhng_h) * (rate_max * dhng_h)) / dhng_k;
    const double phi = std::asin(dhng_moment / dhng_kr);
    const double sag_tol = (f_in * (f_max / dhng_k + dhng_d * phi) + phi * (dhng_jyy - dhng_jzz) * rate_max * rate_max) /
                           dhng_moment;
    const double drop = dhng_m * dhng_gz / dhng_k + dhng_d * std::sin(phi);
    const double drop_tol = drop * sag_tol + dhng_h / 2 * dhng_dabsu;
    double f_err = 0, gap_err = 0, gap_max = 0, sag_err = 0, drop_err = 0;
    for (std::size_t i = 0; i < t.rows(); ++i) {
      if (t.at(i, 0) < dhng_settled) continue;
      const std::array<double, 3> f = dhng_force(dhng_angle(t, i));
      const std::array<double, 3> w{t.at(i, fx), t.at(i, fy), t.at(i, fz)};
      f_err = std::max(f_err, dhng_norm({w[0] - f[0], w[1] - f[1], w[2] - f[2]}));
      gap_err = std::max(gap_err, std::abs(t.at(i, gap) - dhng_norm(f) / dhng_k) - f_err / dhng_k);
      gap_max = std::max(gap_max, t.at(i, gap));
      sag_err = std::max(sag_err, std::abs(t.at(i, sag) / phi - 1));
      drop_err = std::max(drop_err, std::abs(t.at(i, cz) + drop));
    }
    MESSAGE("hinge force off the closed form by at most ", f_err, " N (tolerance ", f_tol, "); gap up to ", gap_max,
            " m, off |F| / k (beyond the force's own error / k) by ", gap_err, " m (tolerance ", gap_tol, "); sag ", phi, " rad to rel. ", sag_err, " (tolerance ", sag_tol, "); centre of mass ", drop,
            " m low, to ", drop_err, " m (tolerance ", drop_tol, ")");
    CHECK(f_err <= f_tol);
    CHECK(gap_err <= gap_tol);
    CHECK(gap_max > 0.99 * dhng_m * dhng_gz / dhng_k);  // the axial load alone opens it by m g cos(b) / k
    CHECK(sag_err <= sag_tol);
    CHECK(drop_err <= drop_tol);
  }

  TEST_CASE("examples/models/door_hinge.prd at half the step: the period and energy errors fall as h^2") {
    // Two runs at the fine step take minutes under the sanitizers (-O0); the dev preset runs them.
    if (pradis_test::sanitized) return;
    std::string half = dhng_file();
    const auto p = half.find(dhng_run_line);
    REQUIRE(p != std::string::npos);
    half.replace(p, std::string(dhng_run_line).size(), dhng_half_line);
    const auto a = lang_test::run(dhng_file()), b = lang_test::run(half);
    const std::vector<dhng_crossing> xa = dhng_crossings(a->results()), xb = dhng_crossings(b->results());
    REQUIRE(xa.size() == 2);
    REQUIRE(xb.size() == 2);
    const double ta = std::abs(xa[1].t - xa[0].t - dhng_period / 2), tb = std::abs(xb[1].t - xb[0].t - dhng_period / 2);
    const double ea = dhng_energy_error(a->results()), eb = dhng_energy_error(b->results());
    const double ga = dhng_damper_share(a->results()), gb = dhng_damper_share(b->results());
    MESSAGE("h = 1 ms -> 0.5 ms: half-period error ", ta, " -> ", tb, " s; energy error ", ea, " -> ", eb,
            " J; the damper's share |k gap - |F|| ", ga, " -> ", gb, " N");
    CHECK(tb <= ta / 3);
    CHECK(eb <= ea / 3);
    CHECK(gb <= ga / 3);
    CHECK(tb > 0);
  }
}
