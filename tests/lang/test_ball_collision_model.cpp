// examples/models/ball_collision.prd: three equal steel balls (BODY3) in a row, 1 mm apart, collide through
// CSPHSP with the Hertz law: ball 1 (1 m/s) hits ball 2, which hits ball 3.
//
// Closed forms.
// - Hertz (Johnson, Contact Mechanics, 1985, section 11.4): k = 4/3 E* sqrt(R*) with 1/E* = 2 (1 - nu^2) / E and
//   R* = R / 2 for two equal spheres of one material (section 4.2); with m* = m / 2 and the approach speed v0:
//   delta* = (5 m* v0^2 / (4 k))^(2/5), P* = k delta*^1.5,
//   t_c = 2 (delta* / v0) int_0^1 dx / sqrt(1 - x^2.5) = 2 (delta* / v0) Gamma(1.4) Gamma(0.5) / Gamma(0.9).
// - A central elastic collision of equal masses exchanges the velocities (Goldstein, Classical Mechanics, 3rd ed.,
//   section 3.10): after both contacts v1 = v2 = 0, v3 = v0. Contact 1 starts at gap / v0; the pair's centre of
//   mass moves at v0 / 2, so ball 2 leaves it v0 t_c / 2 ahead of its start and contact 2 starts at
//   2 gap / v0 + t_c / 2. The momentum m v0 holds at every instant (internal forces), the energy 1/2 m v0^2 with
//   the contact energy U = 2/5 k delta^2.5 counted.
//
// Tolerances, from the run's settings (NEWMARK, average acceleration: BETA = 1/4, GAMMA = 1/2; fixed step
// h = 0.5 us, outputs at every step).
// - Momentum. The residuals of the balls' X equations are m a_i -+ N: their sum m (a1 + a2 + a3) is linear in the
//   unknowns and the contact's Jacobian rows cancel in it, so each Newton update zeroes it; the trapezoidal
//   velocity update then keeps the momentum to round-off: at most a few ulps of m v0 per ball and step,
//   bcol_steps * 3 * 4 eps m v0 in all.
// - Energy. The rule gives exactly Delta T = -(N_n + N_{n+1}) / 2 Delta delta over a step (x_{n+1} - x_n =
//   h (v_n + v_{n+1}) / 2): the kinetic energy changes by the trapezoidal quadrature of the contact's work, which
//   misses the exact U(delta_{n+1}) - U(delta_n) by at most Delta delta^2 (N'(delta_{n+1}) - N'(delta_n)) / 8 for
//   the convex N(delta) = k delta^1.5 (the trapezoid bound for a convex function). With |Delta delta| <= h v0 and
//   N' rising to 1.5 k sqrt(delta*) and back, one contact moves T + U by at most
//   B_E = (h v0)^2 / 8 * 3 k sqrt(delta*) (B_E / 2 up to the peak). The residual speed u that a contact leaves
//   behind follows from the momentum (exact) and the energy: m u v0 = -Delta E, |u| <= B_E / (m v0).
// - The peak. At the output nearest the peak the relative speed is at most |delta''| h / 2 = P* h / (2 m*): a
//   kinetic energy P*^2 h^2 / (8 m*) not yet in the spring; with the energy error B_E / 2 the sampled peak overlap
//   lies within (B_E / 2 + P*^2 h^2 / (8 m*)) / P* of delta* (dU/d delta = N), the force within 1.5 times that
//   relatively (N ~ delta^1.5).
// - The duration. The trapezoidal rule lengthens the period of an oscillator of frequency w by (w h)^2 / 12
//   (Hughes, The Finite Element Method, section 9.3); the contact is never stiffer than dN/d delta at delta*,
//   w_max = sqrt(1.5 k sqrt(delta*) / m*), and we allow t_c (w_max h)^2 / 12. The crossings of delta = 0 are
//   interpolated linearly: near it delta'' = N / m* <= k (h v0)^1.5 / m* over a step, h^2 / 8 of that in delta.
// A second test runs the model at h / 2: the errors fall as h^2 (at least by 3).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {

constexpr double bcol_m = 0.25, bcol_radius = 0.02, bcol_v0 = 1, bcol_gap = 1e-3;  // the model's data
constexpr double bcol_young = 210e9, bcol_poisson = 0.3;                          // steel
constexpr double bcol_h = 5e-7, bcol_end = 2.5e-3;                                // the run's step and end
constexpr double bcol_steps = bcol_end / bcol_h;
constexpr double bcol_eps = std::numeric_limits<double>::epsilon();
constexpr const char* bcol_run_line = "'NEWMARK (END=2.5E-3, OUT=5E-7, SMAX=5E-7, DABSU=1E-12, DRLTU=0, DABSI=1E-6, DRLTI=0)";
constexpr const char* bcol_half_line = "'NEWMARK (END=2.5E-3, OUT=2.5E-7, SMAX=2.5E-7, DABSU=1E-12, DRLTU=0, DABSI=1E-6, DRLTI=0)";

std::string bcol_file() { return lang_test::slurp(lang_test::models_dir() / "ball_collision.prd"); }

/// Hertz's closed forms for the model's pair.
struct bcol_hertz {
  double k, ms, delta, force, tc, wmax;
  bcol_hertz() {
    const double estar = bcol_young / (2 * (1 - bcol_poisson * bcol_poisson)), rstar = bcol_radius / 2;
    k = 4.0 / 3.0 * estar * std::sqrt(rstar);
    ms = bcol_m / 2;
    delta = std::pow(5 * ms * bcol_v0 * bcol_v0 / (4 * k), 0.4);
    force = k * std::pow(delta, 1.5);
    tc = 2 * delta / bcol_v0 * std::tgamma(1.4) * std::tgamma(0.5) / std::tgamma(0.9);
    wmax = std::sqrt(1.5 * k * std::sqrt(delta) / ms);
  }
  /// B_E: the bound on the energy error of one contact at step h.
  double energy_bound(double h) const { return (h * bcol_v0) * (h * bcol_v0) / 8 * 3 * k * std::sqrt(delta); }
};

/// One contact read from the outputs: its start and end (delta = 0, interpolated), peak overlap and force.
struct bcol_contact {
  double t_in = -1, t_out = -1, overlap = 0, force = 0;
};

bcol_contact bcol_read(const io::table& t, const char* overlap, const char* force) {
  const std::size_t o = lang_test::column(t, overlap), f = lang_test::column(t, force);
  bcol_contact c;
  for (std::size_t i = 1; i < t.rows(); ++i) {
    const double a = t.at(i - 1, o), b = t.at(i, o);
    const double cross = t.at(i - 1, 0) + (t.at(i, 0) - t.at(i - 1, 0)) * a / (a - b);
    if (c.t_in < 0 && a <= 0 && b > 0) c.t_in = cross;
    if (c.t_in >= 0 && c.t_out < 0 && a > 0 && b <= 0) c.t_out = cross;
    c.overlap = std::max(c.overlap, b);
    c.force = std::max(c.force, t.at(i, f));
  }
  return c;
}

/// The largest |E - 1/2 m v0^2| over the rows (kinetic energies and the contacts' U = 2/5 k delta^2.5) from time
/// `from` on.
double bcol_energy_error(const io::table& t, double k, double from) {
  const std::size_t t1 = lang_test::column(t, "Kinetic 1"), t2 = lang_test::column(t, "Kinetic 2"),
                    t3 = lang_test::column(t, "Kinetic 3"), d12 = lang_test::column(t, "Overlap 12"),
                    d23 = lang_test::column(t, "Overlap 23");
  double e = 0;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (t.at(i, 0) < from) continue;
    const double u = 0.4 * k * (std::pow(std::max(0.0, t.at(i, d12)), 2.5) + std::pow(std::max(0.0, t.at(i, d23)), 2.5));
    e = std::max(e, std::abs(t.at(i, t1) + t.at(i, t2) + t.at(i, t3) + u - 0.5 * bcol_m * bcol_v0 * bcol_v0));
  }
  return e;
}

}  // namespace

TEST_SUITE("lang/ball collision") {
  TEST_CASE("examples/models/ball_collision.prd: CSPHSP passes the velocity along the row with Hertz's peak force "
            "and contact time, keeping the momentum and the energy") {
    const std::string text = bcol_file();
    REQUIRE(text.find(bcol_run_line) != std::string::npos);  // the settings the tolerances come from
    const bcol_hertz hz;
    // The file's k is the steel pair's 4/3 E* sqrt(R*) to its 17 digits.
    REQUIRE(text.find("0.02, 1, 1.5384615384615385E10, 0, 0.125, 0, 0") != std::string::npos);
    CHECK(1.5384615384615385e10 == doctest::Approx(hz.k).epsilon(4 * bcol_eps));
    lang::session s(lang::parse_file((lang_test::models_dir() / "ball_collision.prd").string()));
    s.run({.write_files = false});
    const io::table& t = s.results();
    REQUIRE(t.rows() == static_cast<std::size_t>(bcol_steps) + 1);

    // Momentum at every output, and the lateral motion and spin of ball 2, which no force or moment reaches (the
    // line of centres is the X axis exactly, the spheres are centred on the bodies' reference points).
    const std::size_t v1 = lang_test::column(t, "v1"), v2 = lang_test::column(t, "v2"), v3 = lang_test::column(t, "v3");
    const double p_tol = bcol_steps * 3 * 4 * bcol_eps * bcol_m * bcol_v0;
    double p_err = 0, lateral = 0;
    for (std::size_t i = 0; i < t.rows(); ++i) {
      p_err = std::max(p_err, std::abs(bcol_m * (t.at(i, v1) + t.at(i, v2) + t.at(i, v3)) - bcol_m * bcol_v0));
      lateral = std::max({lateral, std::abs(t.at(i, lang_test::column(t, "Lateral 2"))),
                          std::abs(t.at(i, lang_test::column(t, "Spin 2")))});
    }
    MESSAGE("momentum off m v0 by at most ", p_err, " N s (tolerance ", p_tol, "); lateral motion and spin ", lateral);
    CHECK(p_err <= p_tol);
    CHECK(lateral == 0.0);

    // Energy: up to B_E / 2 off in contact 1 (rising to its peak), at most B_E per contact in all.
    const double be = hz.energy_bound(bcol_h);
    const bcol_contact c1 = bcol_read(t, "Overlap 12", "Force 12"), c2 = bcol_read(t, "Overlap 23", "Force 23");
    REQUIRE(c1.t_out > c1.t_in);
    REQUIRE(c2.t_in > c1.t_out);
    REQUIRE(c2.t_out > c2.t_in);
    const double e_all = bcol_energy_error(t, hz.k, 0), e_after = bcol_energy_error(t, hz.k, c2.t_out + bcol_h);
    MESSAGE("energy: off 1/2 m v0^2 = ", 0.5 * bcol_m * bcol_v0 * bcol_v0, " J by at most ", e_all,
            " J over the run, ", e_after, " J after both contacts (bound B_E = ", be, " J per contact)");
    CHECK(e_all <= 2 * be);
    CHECK(e_after <= 2 * be);
    // In contact 1, up to its end: within B_E / 2 while compressing, B_E in all.
    {
      double e1 = 0;
      const std::size_t t1 = lang_test::column(t, "Kinetic 1"), t2 = lang_test::column(t, "Kinetic 2"),
                        d12 = lang_test::column(t, "Overlap 12");
      for (std::size_t i = 0; i < t.rows() && t.at(i, 0) <= c1.t_out; ++i)
        e1 = std::max(e1, std::abs(t.at(i, t1) + t.at(i, t2) + 0.4 * hz.k * std::pow(std::max(0.0, t.at(i, d12)), 2.5) -
                                   0.5 * bcol_m * bcol_v0 * bcol_v0));
      MESSAGE("contact 1: energy off by at most ", e1, " J (B_E / 2 = ", be / 2, " J at the peak)");
      CHECK(e1 <= be);
    }

    // The exchange: balls 1 and 2 at rest, ball 3 at v0, each to the residual speed the energy bound allows.
    const std::size_t last = t.rows() - 1;
    const double u_tol = 2 * be / (bcol_m * bcol_v0);
    MESSAGE("final velocities ", t.at(last, v1), ", ", t.at(last, v2), ", ", t.at(last, v3),
            " m/s (residual speed allowed ", u_tol, ")");
    CHECK(std::abs(t.at(last, v1)) <= u_tol);
    CHECK(std::abs(t.at(last, v2)) <= u_tol);
    CHECK(std::abs(t.at(last, v3) - bcol_v0) <= u_tol);

    // Hertz: peak overlap and force, duration, and the start times of both contacts. Contact 2 starts from ball 2's
    // speed after contact 1, off v0 by u <= B_E / (m v0): delta* ~ v^(4/5), P* ~ v^(6/5), t_c ~ v^(-1/5).
    const double sampling = hz.force * hz.force * bcol_h * bcol_h / (8 * hz.ms);
    const double d_tol = (be / 2 + sampling) / hz.force / hz.delta, du = be / (bcol_m * bcol_v0 * bcol_v0);
    const double tc_tol = hz.tc * (hz.wmax * bcol_h) * (hz.wmax * bcol_h) / 12;
    const double edge = bcol_h * bcol_h / 8 * hz.k * std::pow(bcol_h * bcol_v0, 1.5) / hz.ms / bcol_v0;
    for (const auto& [c, extra] : {std::pair{c1, 0.0}, std::pair{c2, du}}) {
      MESSAGE("contact: peak overlap ", c.overlap, " m (Hertz ", hz.delta, ", rel. ", c.overlap / hz.delta - 1,
              ", tolerance ", d_tol + 0.8 * extra, "), peak force ", c.force, " N (Hertz ", hz.force, ", rel. ",
              c.force / hz.force - 1, "), duration ", c.t_out - c.t_in, " s (Hertz ", hz.tc, ", rel. ",
              (c.t_out - c.t_in) / hz.tc - 1, ", tolerance ", tc_tol / hz.tc + 0.2 * extra, ")");
      CHECK(std::abs(c.overlap / hz.delta - 1) <= d_tol + 0.8 * extra);
      CHECK(std::abs(c.force / hz.force - 1) <= 1.5 * d_tol + 1.2 * extra);
      CHECK(std::abs(c.t_out - c.t_in - hz.tc) <= tc_tol + 0.2 * extra * hz.tc + 2 * edge);
    }
    // Contact 1 starts after free flight (exact under the rule) at gap / v0; contact 2 at 2 gap / v0 + t_c / 2, off
    // by half of contact 1's duration error and ball 2's speed error over the gap.
    const double start2 = 2 * bcol_gap / bcol_v0 + hz.tc / 2;
    const double start2_tol = tc_tol / 2 + edge + bcol_gap / bcol_v0 * du;
    MESSAGE("contact starts ", c1.t_in, " s (", bcol_gap / bcol_v0, "), ", c2.t_in, " s (", start2, ", off by ",
            c2.t_in - start2, ", tolerance ", start2_tol, ")");
    CHECK(std::abs(c1.t_in - bcol_gap / bcol_v0) <= edge + 4 * bcol_eps * bcol_gap / bcol_v0);
    CHECK(std::abs(c2.t_in - start2) <= start2_tol);
  }

  TEST_CASE("examples/models/ball_collision.prd at half the step: the energy and duration errors fall as h^2") {
    // Two runs at the fine step take minutes under the sanitizers (-O0); the dev preset runs them.
    if (pradis_test::sanitized) return;
    std::string half = bcol_file();
    const auto p = half.find(bcol_run_line);
    REQUIRE(p != std::string::npos);
    half.replace(p, std::string(bcol_run_line).size(), bcol_half_line);
    const auto a = lang_test::run(bcol_file()), b = lang_test::run(half);
    const bcol_hertz hz;
    const bcol_contact ca = bcol_read(a->results(), "Overlap 12", "Force 12"),
                       cb = bcol_read(b->results(), "Overlap 12", "Force 12");
    const double ea = bcol_energy_error(a->results(), hz.k, 0), eb = bcol_energy_error(b->results(), hz.k, 0);
    const double da = std::abs(ca.t_out - ca.t_in - hz.tc), db = std::abs(cb.t_out - cb.t_in - hz.tc);
    MESSAGE("h = 0.5 us -> 0.25 us: energy error ", ea, " -> ", eb, " J; duration error ", da, " -> ", db, " s");
    CHECK(eb <= ea / 3);
    CHECK(db <= da / 3);
    CHECK(eb > 0);
  }
}
