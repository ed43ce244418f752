// examples/models/slider_table.prd: a machine table on an inclined exact slider PRI3X, driven by a body-fixed
// force F3B and held by a spring-damper SD3 along the slide; a vise welded to it with FIX3X, a frictionless puck
// on its top held by PTP3X (body a the moving table). Checked against closed forms and exact balances:
//
// The slide (Newton's second law with ideal, workless constraints: Goldstein, Classical Mechanics, 3rd ed.,
// sections 1.3-1.4). With e = (cos a, 0, sin a) the slide axis, n = Z the table's top normal, the table and the
// vise (m1 + m2) moving as one along e by s(t), the puck riding the top (its height s sin a, so its normal force
// is lambda = mp (g + s'' sin a), pushing the table by -lambda n):
//     M s'' + c s' + k s = F,   M = m1 + m2 + mp sin^2 a,   F = Fb . e - (m1 + m2 + mp) g sin a,
// from rest at the spring's unstressed length: the step response of the damped oscillator (Thomson and Dahleh,
// Theory of Vibration with Applications, 5th ed., section 2.4 and 4.2; Meirovitch, Elements of Vibration
// Analysis, section 3.2):
//     s(t) = s_eq (1 - exp(-z w t) (cos(wd t) + z w / wd sin(wd t))),   s_eq = F / k,
//     s'(t) = s_eq w / sqrt(1 - z^2) exp(-z w t) sin(wd t),   s'' = (F - k s - c s') / M,
//     w = sqrt(k / M), z = c / (2 sqrt(k M)), wd = w sqrt(1 - z^2).
// The puck: no force in the plane of the top, so its horizontal velocity stays (0.25, 0.15) m/s (Newton's first
// law) and its spin about the vertical (a principal axis, no moment: Euler's equations, Goldstein section 5.5)
// stays 6 rad/s. The reactions (d'Alembert, Goldstein section 1.4): on the vise f_w = m2 (s'' e - g) and
// m_w = -(B - G2) x f_w (it does not turn); on the puck lambda n; on the table the slider carries everything
// across the axis, f_s = -[(m1 + m2) g + Fb - lambda n] projected off e (constant but for lambda), and the
// moment about its centre m_s = (G2 - G1) x f_w + (P - G1) x f_p (P the puck's contact point).
//
// Tolerances, from the run's BDF settings DRLTX = DABSX = 1e-9 (docs/bdf.md, "Error control and tolerances").
// The local error test is an RMS norm over at most N = 2 x (the model's DOFs) components, each weighted by
// DRLTX |x| + DABSX: one component's local error is at most sqrt(N) times its weight, eps_u = sqrt(N) (DRLTX
// s_max + DABSX) for the table's displacements and eps_v = sqrt(N) (DRLTX v_max + DABSX) for its velocities
// (s_max, v_max bounds of the closed form). The slide takes e . (X, Y, Z): at most (cos a + sin a) of them. The
// damped oscillator does not amplify an error in its energy norm sqrt(s^2 + s'^2 / w^2) (its energy only decays),
// so the global error is at most the sum of the local ones over the run's NSTEP steps:
//     ds <= NSTEP (cos a + sin a) (eps_u + eps_v / w),   dv <= NSTEP (cos a + sin a) (w eps_u + eps_v),
//     da <= (k ds + c dv) / M,
// and each reaction, which balances the loads at a state within these bounds, is within its mass times da
// (arms times that for moments, and the forces times ds for the moving arms). This is a worst case (each local
// error at its limit and all of one sign); the errors are also required to fall with DRLTX (the model against a
// run at DRLTX / 10), as a discretisation error does. The joint residuals (the distance from the axis and the
// plane, the weld's gap, the misalignment and twist angles) and the table's and vise's rotation are held by the
// constraint rows, which BDF meets to the Newton weights: DRLTX |x| + DABSX per coordinate, |x| <= 1 m (every
// displacement) and |q| <= 1 + LQBAND = 1.01 (the quaternion components); a gap, a difference of two points,
// to twice that, an angle from two quaternions to four times.

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

constexpr double sltb_pi = 3.14159265358979323846;
constexpr double sltb_g = 9.81, sltb_m1 = 20, sltb_m2 = 8, sltb_mp = 0.5;  // the file's $DATA
constexpr double sltb_k = 1120, sltb_c = 35;                                // SD3's stiffness and damping
const double sltb_sa = std::sin(sltb_pi / 6), sltb_ca = std::cos(sltb_pi / 6);  // the slide's incline, 30 deg
constexpr std::array<double, 3> sltb_fb{300, 40, 0};       // F3B's force in the table's (= global) axes
constexpr std::array<double, 3> sltb_vise_b{0, 0, -0.06};  // the weld point B from the vise's centre
constexpr std::array<double, 3> sltb_g2_0{0.1, 0.15, 0.1}, sltb_p_0{-0.2, -0.1, 0.04};  // G2, P at t = 0
constexpr double sltb_v0x = 0.25, sltb_v0y = 0.15, sltb_spin = 6;  // the puck's start
constexpr double sltb_drltx = 1e-9, sltb_dabsx = 1e-9;              // the model's BDF settings
constexpr const char* sltb_run_line = "'BDF (END=2, OUT=0.01, DRLTX=1E-9, DABSX=1E-9)";

using sltb_vec = std::array<double, 3>;
sltb_vec sltb_cross(const sltb_vec& a, const sltb_vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double sltb_dist(const sltb_vec& a, const sltb_vec& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }
double sltb_norm(const sltb_vec& a) { return std::hypot(a[0], a[1], a[2]); }

/// The closed form of the slide.
struct sltb_slide {
  double mass = sltb_m1 + sltb_m2 + sltb_mp * sltb_sa * sltb_sa;
  double force = sltb_fb[0] * sltb_ca + sltb_fb[2] * sltb_sa - (sltb_m1 + sltb_m2 + sltb_mp) * sltb_g * sltb_sa;
  double w = std::sqrt(sltb_k / mass), z = sltb_c / (2 * std::sqrt(sltb_k * mass)), wd = w * std::sqrt(1 - z * z);
  double s_eq = force / sltb_k;
  double s(double t) const {
    return s_eq * (1 - std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t)));
  }
  double v(double t) const { return s_eq * w / std::sqrt(1 - z * z) * std::exp(-z * w * t) * std::sin(wd * t); }
  double a(double t) const { return (force - sltb_k * s(t) - sltb_c * v(t)) / mass; }
  /// Bounds of |s| and |s'|: the first overshoot and the envelope.
  double s_max() const { return s_eq * (1 + std::exp(-z * sltb_pi / std::sqrt(1 - z * z))); }
  double v_max() const { return s_eq * w / std::sqrt(1 - z * z); }
};

/// The largest deviations of one run from the closed forms and balances.
struct sltb_errors {
  double steps = 0, n_norm = 0;
  double slide = 0, velocity = 0, accel = 0, lateral = 0;  // s (work 10 and the table's X, Z), s', s'', Y
  double spring = 0;                                       // SD3's tension against k s + c s'
  double slider_force = 0, slider_along = 0, slider_moment = 0, slider_balance = 0;
  double weld_force = 0, weld_moment = 0, weld_balance = 0, top_force = 0, top_in_plane = 0;
  double puck_plane = 0, puck_height = 0, puck_spin = 0;
  double turn = 0, residual = 0, angles = 0, together = 0, drive = 0;
  double f_w_max = 0, f_p_max = 0, f_s_max = 0, m_s_max = 0, s_top = 0;
};

sltb_errors sltb_measure(lang::session& s) {
  const sltb_slide cf;
  const io::table& t = s.results();
  auto c = [&](const char* label) { return lang_test::column(t, label); };
  sltb_errors r;
  r.n_norm = 2.0 * s.model().dof_count();
  r.steps = t.at(t.rows() - 1, c("Steps"));
  const sltb_vec e{sltb_ca, 0, sltb_sa}, gv{0, 0, -sltb_g};
  for (std::size_t i = 0; i < t.rows(); ++i) {
    auto at = [&](const char* label) { return t.at(i, c(label)); };
    auto at3 = [&](const char* x, const char* y, const char* z) { return sltb_vec{at(x), at(y), at(z)}; };
    const double time = t.at(i, 0), sc = cf.s(time), vc = cf.v(time), ac = cf.a(time);
    r.s_top = std::max(r.s_top, at("Slide s"));
    r.slide = std::max({r.slide, std::abs(at("Slide s") - sc), std::abs(at("Table X") - sc * sltb_ca),
                        std::abs(at("Table Z") - sc * sltb_sa)});
    r.lateral = std::max(r.lateral, std::abs(at("Table Y")));
    r.velocity = std::max({r.velocity, std::abs(at("Table vX") - vc * sltb_ca), std::abs(at("Table vZ") - vc * sltb_sa)});
    r.accel = std::max({r.accel, std::abs(at("Table aX") - ac * sltb_ca), std::abs(at("Table aZ") - ac * sltb_sa)});
    r.spring = std::max(r.spring, std::abs(at("Spring tension") - (sltb_k * sc + sltb_c * vc)));

    // The reactions: the vise's and the puck's against their closed forms and against m a - F of the run.
    const sltb_vec fw = at3("Weld Fx", "Weld Fy", "Weld Fz"), mw = at3("Weld Mx", "Weld My", "Weld Mz");
    const sltb_vec fp = at3("Top Fx", "Top Fy", "Top Fz");
    const sltb_vec fs = at3("Slide Fx", "Slide Fy", "Slide Fz"), ms = at3("Slide Mx", "Slide My", "Slide Mz");
    r.f_w_max = std::max(r.f_w_max, sltb_norm(fw));
    r.f_p_max = std::max(r.f_p_max, sltb_norm(fp));
    r.f_s_max = std::max(r.f_s_max, sltb_norm(fs));
    r.m_s_max = std::max(r.m_s_max, sltb_norm(ms));
    const double lambda = sltb_mp * (sltb_g + ac * sltb_sa);
    r.weld_force = std::max(r.weld_force, sltb_dist(fw, {sltb_m2 * ac * sltb_ca, 0, sltb_m2 * (ac * sltb_sa + sltb_g)}));
    const sltb_vec rb_x_fw = sltb_cross(sltb_vise_b, fw);
    r.weld_moment = std::max(r.weld_moment, sltb_dist(mw, {-rb_x_fw[0], -rb_x_fw[1], -rb_x_fw[2]}));
    const sltb_vec aw = at3("Vise aX", "Vise aY", "Vise aZ");
    r.weld_balance = std::max(r.weld_balance, sltb_dist(fw, {sltb_m2 * aw[0], sltb_m2 * aw[1], sltb_m2 * (aw[2] + sltb_g)}));
    r.top_force = std::max(r.top_force, std::abs(fp[2] - lambda));
    r.top_in_plane = std::max(r.top_in_plane, std::hypot(fp[0], fp[1]));
    // The slider's force: everything on the table and vise across the axis (the spring acts along it).
    sltb_vec across{};
    for (int j = 0; j < 3; ++j) across[j] = (sltb_m1 + sltb_m2) * gv[j] + sltb_fb[j] - (j == 2 ? lambda : 0.0);
    const double along = across[0] * e[0] + across[1] * e[1] + across[2] * e[2];
    for (int j = 0; j < 3; ++j) across[j] = -(across[j] - along * e[j]);
    r.slider_force = std::max(r.slider_force, sltb_dist(fs, across));
    r.slider_along = std::max(r.slider_along, std::abs(fs[0] * e[0] + fs[1] * e[1] + fs[2] * e[2]));
    // The table's Newton equation with the run's acceleration: f_s = m1 a1 - m1 g - Fb + T e + f_w + f_p.
    const sltb_vec a1 = at3("Table aX", "Table aY", "Table aZ");
    const double tension = at("Spring tension");
    sltb_vec bal{};
    for (int j = 0; j < 3; ++j)
      bal[j] = sltb_m1 * (a1[j] - gv[j]) - sltb_fb[j] + tension * e[j] + fw[j] + fp[j];
    r.slider_balance = std::max(r.slider_balance, sltb_dist(fs, bal));
    // The table's moment about its centre: the vise's and the puck's reactions at their arms.
    const sltb_vec g1 = at3("Table X", "Table Y", "Table Z");
    const sltb_vec g2{sltb_g2_0[0] + at("Vise X"), sltb_g2_0[1] + at("Vise Y"), sltb_g2_0[2] + at("Vise Z")};
    const sltb_vec p{sltb_p_0[0] + at("Puck X"), sltb_p_0[1] + at("Puck Y"), sltb_p_0[2] + at("Puck Z")};
    const sltb_vec m1 = sltb_cross({g2[0] - g1[0], g2[1] - g1[1], g2[2] - g1[2]}, fw);
    const sltb_vec m2 = sltb_cross({p[0] - g1[0], p[1] - g1[1], p[2] - g1[2]}, fp);
    r.slider_moment = std::max(r.slider_moment, sltb_dist(ms, {m1[0] + m2[0], m1[1] + m2[1], m1[2] + m2[2]}));

    // The puck glides: its horizontal motion uniform, its height the table's, its spin kept.
    r.puck_plane = std::max({r.puck_plane, std::abs(at("Puck X") - sltb_v0x * time),
                             std::abs(at("Puck Y") - sltb_v0y * time), std::abs(at("Puck vX") - sltb_v0x),
                             std::abs(at("Puck vY") - sltb_v0y)});
    r.puck_height = std::max(r.puck_height, std::abs(at("Puck Z") - sc * sltb_sa));
    r.puck_spin = std::max({r.puck_spin, std::abs(at("Puck wz") - sltb_spin), std::abs(at("Puck wx")),
                            std::abs(at("Puck wy"))});

    // The joints hold: no turn of the table and the vise, the residuals, the vise with the table.
    r.turn = std::max({r.turn, std::abs(at("Table q1")), std::abs(at("Table q2")), std::abs(at("Table q3")),
                       std::abs(at("Vise q1")), std::abs(at("Vise q2")), std::abs(at("Vise q3"))});
    r.residual = std::max({r.residual, std::abs(at("Off axis")), std::abs(at("Weld gap")), std::abs(at("Off plane"))});
    r.angles = std::max({r.angles, std::abs(at("Slide tilt")), std::abs(at("Slide twist")),
                         std::abs(at("Weld tilt")), std::abs(at("Weld twist"))});
    r.together = std::max({r.together, std::abs(at("Vise X") - at("Table X")), std::abs(at("Vise Y") - at("Table Y")),
                           std::abs(at("Vise Z") - at("Table Z"))});
    // F3B turns with the table, which does not turn: the force stays Fb in global axes.
    r.drive = std::max(r.drive, sltb_dist(at3("Drive Fx", "Drive Fy", "Drive Fz"), sltb_fb));
  }
  return r;
}

/// The worst-case global error bounds of the slide from the run's settings and step count (see the top).
struct sltb_bounds {
  double ds = 0, dv = 0, da = 0;
};
sltb_bounds sltb_bound(const sltb_errors& r, double drltx, double dabsx) {
  const sltb_slide cf;
  const double root = std::sqrt(r.n_norm);
  const double eps_u = root * (drltx * cf.s_max() + dabsx), eps_v = root * (drltx * cf.v_max() + dabsx);
  sltb_bounds b;
  b.ds = r.steps * (sltb_ca + sltb_sa) * (eps_u + eps_v / cf.w);
  b.dv = r.steps * (sltb_ca + sltb_sa) * (cf.w * eps_u + eps_v);
  b.da = (sltb_k * b.ds + sltb_c * b.dv) / cf.mass;
  return b;
}

std::string sltb_file() { return lang_test::slurp(lang_test::models_dir() / "slider_table.prd"); }

}  // namespace

TEST_SUITE("lang/slider table") {
  TEST_CASE("examples/models/slider_table.prd: PRI3X slides the table as a damped oscillator, FIX3X carries the "
            "vise with it, PTP3X lets the puck glide, and the reactions balance the loads") {
    const std::string text = sltb_file();
    REQUIRE(text.find(sltb_run_line) != std::string::npos);  // the settings the tolerances come from
    lang::session s(lang::parse_file((lang_test::models_dir() / "slider_table.prd").string()));
    s.run({.write_files = false});
    REQUIRE(s.bdf_active());
    REQUIRE(s.results().rows() == 201);
    // The multipliers are the joints' internal DOFs: PRI3X 5 (two line rows, three frame rows), FIX3X 6 (the
    // point, three frame rows), PTP3X 1.
    const auto& m = s.model();
    struct joint {
      const char* name;
      int multipliers;
    };
    for (const joint j : {joint{"Slide", 5}, joint{"Weld", 6}, joint{"Top", 1}}) {
      CAPTURE(j.name);
      int n = 0;
      for (int d = 0; d < m.dof_count(); ++d)
        if (m.dof_name(d).rfind(std::string(j.name) + ".internal", 0) == 0) ++n;
      CHECK(n == j.multipliers);  // the hidden q4 are the nodes'
    }

    const sltb_slide cf;
    const sltb_errors r = sltb_measure(s);
    const sltb_bounds b = sltb_bound(r, sltb_drltx, sltb_dabsx);
    MESSAGE("slider table: ", r.steps, " steps; slide s_eq = ", cf.s_eq, " m, peak ", r.s_top, " m (closed form ",
            cf.s_max(), "); off the closed form: s ", r.slide, " m (bound ", b.ds, "), s' ", r.velocity,
            " m/s (bound ", b.dv, "), s'' ", r.accel, " m/s^2 (bound ", b.da, "); spring tension ", r.spring,
            " N; reactions: slider ", r.slider_force, " N of ", r.f_s_max, ", weld ", r.weld_force, " N of ",
            r.f_w_max, ", top ", r.top_force, " N of ", r.f_p_max, ", slider moment ", r.slider_moment, " N m of ",
            r.m_s_max, ", weld moment ", r.weld_moment, " N m; balances with the run's accelerations: table ",
            r.slider_balance, " N, vise ", r.weld_balance, " N; puck: plane ", r.puck_plane, ", height ",
            r.puck_height, " m, spin ", r.puck_spin, " rad/s; turn ", r.turn, ", residuals ", r.residual,
            " m, angles ", r.angles, " rad, vise off the table ", r.together, " m");

    // The slide: the closed form, exercised (it overshoots to its first peak).
    CHECK(r.s_top == doctest::Approx(cf.s_max()).epsilon(0.01));
    CHECK(r.slide <= b.ds);
    CHECK(r.velocity <= b.dv);
    CHECK(r.accel <= b.da);
    CHECK(r.spring <= sltb_k * b.ds + sltb_c * b.dv);
    // Nothing moves the table off the axis: Y stays at the constraint's weight.
    CHECK(r.lateral <= sltb_drltx + sltb_dabsx);

    // The reactions: each within its mass times da of the closed form; the arms of the slider's moment move
    // with the trajectory (ds) and carry the vise's and the puck's force errors (at most 0.6 m).
    CHECK(r.weld_force <= sltb_m2 * b.da);
    CHECK(r.top_force <= sltb_mp * sltb_sa * b.da);
    CHECK(r.slider_force <= sltb_mp * sltb_sa * b.da);
    CHECK(r.weld_balance <= 2 * sltb_m2 * b.da);  // both the weld force and the vise's acceleration within da
    CHECK(r.slider_balance <= 2 * (sltb_m1 + sltb_m2 + sltb_mp) * b.da + sltb_k * b.ds + sltb_c * b.dv);
    CHECK(r.weld_moment <= sltb_norm(sltb_vise_b) * sltb_m2 * b.da);
    CHECK(r.slider_moment <= 0.6 * (sltb_m2 + sltb_mp) * b.da + 2 * b.ds * (r.f_w_max + r.f_p_max));
    // Structural: PRI3X's force is a sum of the line rows' normals, PTP3X's lies along the top's normal (Z as
    // long as the table does not turn: its in-plane part is the force times the turn's bound).
    CHECK(r.slider_along <= 16 * std::numeric_limits<double>::epsilon() * r.f_s_max);
    CHECK(r.top_in_plane <= r.f_p_max * 4 * (sltb_drltx * 1.01 + sltb_dabsx));
    CHECK(r.f_w_max > 80);   // the vise's weight and more: the checks are not trivial
    CHECK(r.m_s_max > 10);

    // The puck: uniform in the plane, on the table's top, spinning on. A free motion: each step's local errors
    // (eps of the displacement, |x| <= 0.5 m, and of the velocity, |v| <= 0.3 m/s) add up, the velocity's
    // growing into the displacement over the rest of the run (END = 2 s). Its height is the table's Z
    // (sin a times the slide) on the top (the plane's residual). Its spin (|q'| <= 3 rad/s, |q| <= 1.01): the
    // spin's local error at most 2 (DRLTX 3 + DABSX) + 2 spin (DRLTX 1.01 + DABSX) times sqrt(N).
    const double root = std::sqrt(r.n_norm);
    CHECK(r.puck_plane <=
          r.steps * root * ((sltb_drltx * 0.5 + sltb_dabsx) + 2.0 * (sltb_drltx * 0.3 + sltb_dabsx)));
    CHECK(r.puck_height <= sltb_sa * b.ds + 2 * (sltb_drltx + sltb_dabsx));
    CHECK(r.puck_spin <= r.steps * root *
                             (2 * (sltb_drltx * 3 + sltb_dabsx) + 2 * sltb_spin * (sltb_drltx * 1.01 + sltb_dabsx)));

    // The joints hold: the table and the vise do not turn, the residuals and angles stay at the weights.
    CHECK(r.turn <= sltb_drltx * 1.01 + sltb_dabsx);
    CHECK(r.residual <= 2 * (sltb_drltx + sltb_dabsx));
    CHECK(r.angles <= 4 * (sltb_drltx * 1.01 + sltb_dabsx));
    CHECK(r.together <= 2 * (sltb_drltx + sltb_dabsx));
    CHECK(r.drive <= sltb_norm(sltb_fb) * 4 * (sltb_drltx * 1.01 + sltb_dabsx));
  }

  TEST_CASE("examples/models/slider_table.prd: the errors of the slide and of the reactions fall with DRLTX") {
    const std::string text = sltb_file();
    const auto p = text.find(sltb_run_line);
    REQUIRE(p != std::string::npos);
    std::string fine = text;
    fine.replace(p, std::string(sltb_run_line).size(), "'BDF (END=2, OUT=0.01, DRLTX=1E-10, DABSX=1E-10)");
    const auto model_run = lang_test::run(text), fine_run = lang_test::run(fine);
    const sltb_errors a = sltb_measure(*model_run), f = sltb_measure(*fine_run);
    const sltb_bounds bf = sltb_bound(f, 1e-10, 1e-10);
    MESSAGE("at DRLTX = 1e-9 / 1e-10: s ", a.slide, " / ", f.slide, " m, s' ", a.velocity, " / ", f.velocity,
            " m/s, weld force ", a.weld_force, " / ", f.weld_force, " N, slider moment ", a.slider_moment, " / ",
            f.slider_moment, " N m; steps ", a.steps, " / ", f.steps);
    // A tenfold tighter tolerance: a discretisation error falls by more than 3 (BDF's order is 2..5).
    CHECK(f.slide <= a.slide / 3);
    CHECK(f.velocity <= a.velocity / 3);
    CHECK(f.weld_force <= a.weld_force / 3);
    CHECK(f.slider_moment <= a.slider_moment / 3);
    CHECK(f.slide <= bf.ds);
    CHECK(f.weld_force <= sltb_m2 * bf.da);
  }
}
