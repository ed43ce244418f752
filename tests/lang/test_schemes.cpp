// The integration programs 'HHT and 'GALPHA of the model language: their
// algorithmic period error and damping on an undamped oscillator against the
// published values, their keys and ranges, and changes of program between
// stages.

#include <cmath>
#include <string>
#include <vector>

#include "lang_test_support.hpp"
#include "pradis/pradis.hpp"

using namespace pradis;
using namespace pradis::elements;
using lang_test::small_with;

namespace {

/// Mass 1 on spring 1 (omega = 1), released from u = 1 at rest; one stage `stage`.
std::string free_oscillator(const std::string& stage) {
  return "$FRAGMENT\n"
         "#STRUCTURE\n"
         "  Body 'MASS (1; 1)\n"
         "  Spring 'SPRING (0 1; 1)\n"
         "  Start 'X0 (1; 1)\n"
         "#OUTPUT\n"
         "  U 'X (1; 1)\n"
         "$RUN\n"
         "  " + stage + "\n"
         "$END\n";
}

/// Relative period error Tbar/T - 1 and damping ratio xi of a fixed-step run of
/// the undamped oscillator (omega = 1, step h = Omega). For a linear problem the
/// scheme is a linear recurrence; once the spurious roots have died out the
/// displacements obey u_{n+1} = a u_n + c u_{n-1} with a = 2 r cos(theta),
/// c = -r^2 for the principal roots r exp(+-i theta). a and c are found by
/// least squares over the samples; then Omegabar = theta, Tbar/T = Omega / theta,
/// xi = -ln(r) / theta.
struct measured {
  double period_error, xi;
};
measured period_and_damping(const io::table& t, double omega_h) {
  const std::size_t first = 100, last = t.rows() - 5;  // skip the start (spurious roots) and the last, shorter steps
  double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
  for (std::size_t n = first; n + 1 < last; ++n) {
    const double u0 = t.at(n - 1, 1), u1 = t.at(n, 1), u2 = t.at(n + 1, 1);
    s11 += u1 * u1;
    s12 += u1 * u0;
    s22 += u0 * u0;
    r1 += u2 * u1;
    r2 += u2 * u0;
  }
  const double det = s11 * s22 - s12 * s12;
  const double a = (r1 * s22 - r2 * s12) / det, c = (s11 * r2 - s12 * r1) / det;
  const double r = std::sqrt(-c), theta = std::acos(a / (2 * r));
  return {omega_h / theta - 1, -std::log(r) / theta};
}

}  // namespace

TEST_SUITE("lang/schemes") {
  TEST_CASE("'GALPHA: period error and damping ratio of the undamped oscillator are Chung-Hulbert's") {
    // Generalized-alpha (J. Chung, G. M. Hulbert, J. Appl. Mech. 60 (1993)
    // 371-375) at Omega = omega h = 0.1: the exact values of the principal roots
    // of its amplification matrix are Tbar/T - 1 = 1.24809e-3, xi = 1.84187e-5 for
    // rho_inf = 0.5 and 8.79024e-4, 6.84445e-7 for rho_inf = 0.8 (computed in
    // high-precision arithmetic; leading terms (11 rho^2 - 14 rho + 11) Omega^2 /
    // (24 (1 + rho)^2) and (1 - rho)^3 Omega^3 / (2 (1 + rho)^3)).
    struct row {
      const char* rho;
      double period_error, xi;
    };
    for (const row& c : {row{"0.5", 1.24809e-3, 1.84187e-5}, row{"0.8", 8.79024e-4, 6.84445e-7}}) {
      CAPTURE(c.rho);
      auto s = lang_test::run(free_oscillator(std::string("Free 'GALPHA (END=300, SMAX=0.1, RHOINF=") + c.rho + ")"));
      REQUIRE(s->results().rows() > 2990);
      const measured m = period_and_damping(s->results(), 0.1);
      CHECK(m.period_error == doctest::Approx(c.period_error).epsilon(1e-5));
      CHECK(m.xi == doctest::Approx(c.xi).epsilon(1e-5));
    }
  }

  TEST_CASE("'HHT: period error and damping ratio of the undamped oscillator are Hilber-Hughes-Taylor's") {
    // HHT-alpha (H. M. Hilber, T. J. R. Hughes, R. L. Taylor, Earthquake Eng.
    // Struct. Dyn. 5 (1977) 283-292): Tbar/T - 1 = (2 - 6 alpha - 9 alpha^2)
    // Omega^2 / 24 and xi = -alpha (1 + alpha)^2 Omega^3 / 8 to leading order. At
    // Omega = 0.05 the next terms change them by a relative O(Omega^2): less than
    // 4e-4 and 1.4e-3 for alpha in [-1/3, 0) (exact roots of the amplification
    // matrix, high-precision arithmetic), hence the tolerances 1e-3 and 3e-3.
    const double omega_h = 0.05;
    for (const char* alpha : {"-0.1", "-0.3", "-0.33333333333333333"}) {
      CAPTURE(alpha);
      const double al = std::stod(alpha);
      auto s = lang_test::run(free_oscillator(std::string("Free 'HHT (END=600, SMAX=0.05, ALPHA=") + alpha + ")"));
      REQUIRE(s->results().rows() > 11990);
      const measured m = period_and_damping(s->results(), omega_h);
      const double w2 = omega_h * omega_h;
      CHECK(m.period_error == doctest::Approx((2 - 6 * al - 9 * al * al) * w2 / 24).epsilon(1e-3));
      CHECK(m.xi == doctest::Approx(-al * (1 + al) * (1 + al) * w2 * omega_h / 8).epsilon(3e-3));
    }
  }

  TEST_CASE("'HHT with ALPHA=0 is 'NEWMARK average acceleration, bit for bit; defaults are ALPHA=-0.05, RHOINF=0.8") {
    // alpha = 0 gives beta = 1/4, gamma = 1/2, alpha_f = 0: Newmark's parameters.
    auto hht0 = lang_test::run(free_oscillator("Free 'HHT (END=5, SMAX=0.1, ALPHA=0)"));
    auto nm = lang_test::run(free_oscillator("Free 'NEWMARK (END=5, SMAX=0.1)"));
    REQUIRE(hht0->results().rows() == nm->results().rows());
    for (std::size_t r = 0; r < nm->results().rows(); ++r) CHECK(hht0->results().at(r, 1) == nm->results().at(r, 1));
    // Omitted keys take the library's defaults.
    auto hd = lang_test::run(free_oscillator("Free 'HHT (END=1, SMAX=0.1)"));
    auto he = lang_test::run(free_oscillator("Free 'HHT (END=1, SMAX=0.1, ALPHA=-0.05)"));
    auto gd = lang_test::run(free_oscillator("Free 'GALPHA (END=1, SMAX=0.1)"));
    auto ge = lang_test::run(free_oscillator("Free 'GALPHA (END=1, SMAX=0.1, RHOINF=0.8)"));
    CHECK(hd->simulation_ptr()->scheme().coefficients_set().alpha_f == 0.05);
    CHECK(gd->simulation_ptr()->scheme().coefficients_set().alpha_f == 0.8 / 1.8);
    for (std::size_t r = 0; r < hd->results().rows(); ++r) {
      CHECK(hd->results().at(r, 1) == he->results().at(r, 1));
      CHECK(gd->results().at(r, 1) == ge->results().at(r, 1));
    }
  }

  TEST_CASE("stages switch between all four programs; each stage keeps equilibrium and its scheme's relations") {
    // Mass 2 on spring 100 with load 10: every accepted step solves
    // m a + k u = F at its end, whatever the scheme (the residual is evaluated at
    // t_{n+1} with the true acceleration).
    std::string text = small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n",
                                  "  S 'SHTERM (END=0.05, SMAX=1E-3)\n"
                                  "  G 'GALPHA (END=0.1, SMAX=1E-3, RHOINF=0.5)\n"
                                  "  N 'NEWMARK (END=0.15, SMAX=1E-3)\n"
                                  "  H 'HHT (END=0.2, SMAX=1E-3, ALPHA=-0.2)\n"
                                  "  G2 'GALPHA (END=0.25, SMAX=1E-3, RHOINF=0)\n");
    text = text.replace(text.find("  Spring force"), 0, "  V 'X (1; 2)\n  A 'X (1; 3)\n");
    auto s = lang_test::run(text);
    REQUIRE(s->stages().size() == 5);
    const auto& t = s->results();
    REQUIRE(t.names() == std::vector<std::string>{"Position", "V", "A", "Spring force"});
    CHECK(t.at(t.rows() - 1, 0) == doctest::Approx(0.25));
    for (std::size_t r = 0; r < t.rows(); ++r) CHECK(2 * t.at(r, 3) + 100 * t.at(r, 1) == doctest::Approx(10).epsilon(1e-9));
    // Newmark's own relations (beta = 1/4, gamma = 1/2) with the true accelerations
    // hold on every step of the NEWMARK stage, also on its first step after the
    // GALPHA stage: a change of program starts the new scheme afresh (its
    // pseudo-acceleration is the acceleration, as at t = 0).
    int checked = 0;
    for (std::size_t r = 1; r < t.rows(); ++r) {
      const double t0 = t.at(r - 1, 0), t1 = t.at(r, 0);
      if (!(t0 >= 0.1 - 1e-12 && t1 <= 0.15 + 1e-12)) continue;
      const double h = t1 - t0, u0 = t.at(r - 1, 1), v0 = t.at(r - 1, 2), a0 = t.at(r - 1, 3);
      const double u1 = t.at(r, 1), v1 = t.at(r, 2), a1 = t.at(r, 3);
      CHECK(v1 == doctest::Approx(v0 + h * (0.5 * a0 + 0.5 * a1)).epsilon(1e-12));
      CHECK(u1 == doctest::Approx(u0 + h * v0 + h * h * (0.25 * a0 + 0.25 * a1)).epsilon(1e-12));
      ++checked;
    }
    CHECK(checked >= 50);
  }

  TEST_CASE("example stiff_pair.prd: HHT and GALPHA damp the unresolved fast mode and keep the slow one") {
    // Masses M = 1, m = 1e-3; springs k1 = 1 (to the ground), k2 = 1000 (between
    // them); start at rest from u = (1, 1.01). Exact solution: the modes of
    // K - w^2 M, i.e. m w^4 - (k2 M + (k1 + k2) m) w^2 + k1 k2 = 0 (M = 1), and
    // u(t) = sum_i c_i phi_i cos(w_i t) with phi_i = (1, (k1 + k2 - w_i^2) / k2).
    auto s = std::make_unique<lang::session>(
        lang::parse_file((lang_test::models_dir() / "stiff_pair.prd").string()));
    s->run({.write_files = false});
    const double m = 1e-3, k1 = 1, k2 = 1000;
    const double b = k2 + (k1 + k2) * m, disc = std::sqrt(b * b - 4 * m * k1 * k2);
    const double w2[2] = {(b - disc) / (2 * m), (b + disc) / (2 * m)};  // slow, fast
    const double r[2] = {(k1 + k2 - w2[0]) / k2, (k1 + k2 - w2[1]) / k2};
    // c0 + c1 = 1, c0 r0 + c1 r1 = 1.01.
    const double c1 = (1.01 - r[0]) / (r[1] - r[0]), c0 = 1 - c1;
    const auto& t = s->results();
    REQUIRE(t.names() == std::vector<std::string>{"Heavy X", "Light X", "Link force"});
    REQUIRE(t.at(t.rows() - 1, 0) == doctest::Approx(4));
    double worst_slow = 0, worst_stretch = 0, exact_fast = 0;
    for (std::size_t row = 0; row < t.rows(); ++row) {
      const double time = t.at(row, 0);
      if (time < 0.5) continue;
      const double slow = c0 * std::cos(std::sqrt(w2[0]) * time), fast = c1 * std::cos(std::sqrt(w2[1]) * time);
      // The heavy mass follows the slow mode (the fast one moves it by |c1| < 1e-5).
      worst_slow = std::max(worst_slow, std::abs(t.at(row, 1) - slow));
      // The stretch of the stiff link is the slow mode's alone: the fast mode is gone.
      worst_stretch = std::max(worst_stretch, std::abs(t.at(row, 2) - t.at(row, 1) - slow * (r[0] - 1)));
      exact_fast = std::max(exact_fast, std::abs(fast * (r[1] - 1)));
    }
    CHECK(exact_fast > 9e-3);        // undamped, the fast mode would stretch the link by about 0.01 ...
    CHECK(worst_stretch < 1e-7);     // ... but the schemes remove it,
    CHECK(worst_slow < 2e-4);        // while the slow mode keeps amplitude and phase (second order).
    // The link force is k2 times the stretch.
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, 3) == doctest::Approx(k2 * (t.at(last, 2) - t.at(last, 1))).epsilon(1e-9));
  }

  TEST_CASE("simulation::restart_scheme() starts the pseudo-acceleration afresh (p = a)") {
    // What the session does when a stage changes the program.
    model<point_mass, linear_spring, initial_displacement> m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {.m = 1.0}, x);
    m.add<linear_spring>("spring", {.k = 4.0}, x, m.ground());
    m.add<initial_displacement>("x0", {.u0 = 1.0}, x);
    simulation sim(m, generalized_alpha(0.5));
    sim.run({.end = 0.5, .smax = 0.05});
    // Generalized-alpha's p differs from a by O(h) during the run.
    CHECK(std::abs(sim.state().p(x.index) - sim.state().a(x.index)) > 1e-3);
    const double u = sim.u(x), v = sim.v(x), a = sim.a(x);
    sim.restart_scheme();
    CHECK(sim.state().p(x.index) == a);
    CHECK(sim.u(x) == u);
    CHECK(sim.v(x) == v);
    CHECK(sim.a(x) == a);
  }

  TEST_CASE("ALPHA, RHOINF out of range and keys of another program are located errors") {
    using lang_test::error_of;
    auto expect = [](const std::string& text, const std::string& where, std::initializer_list<const char*> parts) {
      const std::string e = error_of(text);
      CAPTURE(e);
      CHECK(e.rfind("test.prd:" + where + ": error: ", 0) == 0);
      for (const char* p : parts) CHECK(e.find(p) != std::string::npos);
    };
    expect(small_with("'SHTERM (", "'HHT (ALPHA=0.1, "), "14:14",
           {"HHT: ALPHA = 0.1 is outside its valid range -1/3 <= ALPHA <= 0"});
    expect(small_with("'SHTERM (", "'HHT (ALPHA=-0.34, "), "14:14", {"ALPHA = -0.34 is outside", "-1/3 <= ALPHA <= 0"});
    expect(small_with("'SHTERM (", "'GALPHA (RHOINF=1.5, "), "14:17",
           {"GALPHA: RHOINF = 1.5 is outside its valid range 0 <= RHOINF <= 1"});
    expect(small_with("'SHTERM (", "'GALPHA (RHOINF=-0.1, "), "14:17", {"RHOINF = -0.1 is outside"});
    expect(small_with("'SHTERM (", "'GALPHA (ALPHA=-0.1, "), "14:17", {"key ALPHA belongs to HHT, not to GALPHA"});
    expect(small_with("'SHTERM (", "'HHT (RHOINF=0.5, "), "14:14", {"key RHOINF belongs to GALPHA, not to HHT"});
    expect(small_with("'SHTERM (", "'HHT (BETA=0.3, "), "14:14", {"key BETA belongs to NEWMARK, not to HHT"});
    expect(small_with("'SHTERM (", "'NEWMARK (ALPHA=-0.1, "), "14:18", {"key ALPHA belongs to HHT"});
    expect(small_with("SMAX=1E-3", "SMAX=1E-3, RHOINF=0.5"), "14:37", {"key RHOINF belongs to GALPHA, not to SHTERM"});
    expect(small_with("'SHTERM (", "'GALPHA (SCHEME=1, "), "14:17",
           {"key SCHEME of GALPHA is not implemented", "CONTROL PREDICT SAVE OPTIM NSTEPMAX RHOINF)"});
    expect(small_with("'SHTERM (", "'HALPHA ("), "14:9", {"unknown integration program 'HALPHA'", "did you mean"});
    // A run-time option error names the program of the stage.
    expect(small_with("'SHTERM (END=0.1, SMAX=1E-3", "'GALPHA (END=0.1, SMAX=-1"), "14:3", {"GALPHA: SMAX = -1 must be > 0"});
  }
}
