// The model language: what each section does, the example models in
// examples/models (every one runs; the two-body model gives exactly the results
// of the C++ example), stages, $REPLACE, $SAVE/$RESTORE, $INCLUDE, fragments.

#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "lang_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using lang_test::small_model;
using lang_test::small_with;

namespace {
using lang_test::scratch_dir;
using lang_test::slurp;
using lang_test::column;
}  // namespace

TEST_SUITE("lang/language") {
  TEST_CASE("lexer: words, punctuation, sections, comments, strings") {
    auto src = std::make_shared<const lang::source_file>(lang::source_file{
        "x", "* a comment line\n$data: A b = 1.5D2, -c // trailing comment\n  # structure\nP 'X (W:N(2); 1) \"s t\""});
    const auto t = lang::lex(src);
    std::vector<lang::tok> kinds;
    for (const auto& k : t) kinds.push_back(k.kind);
    using lang::tok;
    const std::vector<tok> expected{tok::newline, tok::section, tok::colon, tok::word,    tok::word,       tok::equals,
                                    tok::word,    tok::comma,   tok::word,  tok::newline, tok::subsection, tok::newline,
                                    tok::word,    tok::quote,   tok::word,  tok::lparen,  tok::word,       tok::colon,
                                    tok::word,    tok::lparen,  tok::word,  tok::rparen,  tok::semicolon,  tok::word,
                                    tok::rparen,  tok::string,  tok::eof};
    CHECK(kinds == expected);
    CHECK(t[1].text == "DATA");
    CHECK(t[10].text == "STRUCTURE");
    CHECK(t[25].text == "s t");
    CHECK(t[6].loc.line == 2);
    CHECK(t[6].loc.col == 14);
  }

  TEST_CASE("numbers: Fortran forms, D exponents, signs; names are not numbers") {
    CHECK(lang::parse_number("5E3") == 5000.0);
    CHECK(lang::parse_number("1.E3") == 1000.0);
    CHECK(lang::parse_number("-.5") == -0.5);
    CHECK(lang::parse_number("+2.5d-1") == 0.25);
    CHECK(lang::parse_number("1e+2") == 100.0);
    CHECK_FALSE(lang::parse_number("1.2.3"));
    CHECK_FALSE(lang::parse_number("."));
    CHECK_FALSE(lang::parse_number("1e"));
    CHECK_FALSE(lang::parse_number("1e400"));
    CHECK_FALSE(lang::parse_number("0x10"));
    CHECK(lang::looks_numeric("-1"));
    CHECK_FALSE(lang::looks_numeric("-Force"));
  }

  TEST_CASE("$DATA: names with blanks (normalised), lists expanded in place, negation, references") {
    auto s = lang_test::build(
        "$DATA\n"
        "  Centre   of body  1 = 1, 2\n"
        "  Twice = Centre of body 1, Centre of body 1,\n"
        "          5\n"
        "  Down = -Twice\n"
        "$FRAGMENT\n#STRUCTURE\n  M 'MASS (1; 1)\n$RUN\n  C 'SHTERM (END=0.01)\n$END\n");
    CHECK(s->data("Centre of body 1") == std::vector<double>{1, 2});
    CHECK(s->data("Twice") == std::vector<double>{1, 2, 1, 2, 5});
    CHECK(s->data("Down") == std::vector<double>{-1, -2, -1, -2, -5});
  }

  TEST_CASE("keywords and model names are case-insensitive; '*' and '//' comments; ':' optional") {
    auto s = lang_test::run(
        "* comment\n$data\n  k = 100 // stiffness\n$fragment:\n# structure:\n  m 'mass (1; 1)\n"
        "  s 'Spring (0 1; k)\n  x0 'X0 (1; 0.1)\n#Output\n  x 'x (1; 1)\n$run\n  c 'shterm (end=0.5, "
        "smax=1e-3)\n$end\n"
        "anything after $END is ignored \x01\n");
    CHECK(s->results().rows() > 10);
    CHECK(s->results().at(0, 1) == doctest::Approx(0.1));
  }

  TEST_CASE("Windows line ends and a UTF-8 byte-order mark are accepted") {
    std::string crlf;
    for (char c : std::string(small_model)) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    auto s = lang_test::run("\xEF\xBB\xBF" + crlf);
    CHECK(s->results().names() == std::vector<std::string>{"Position", "Spring force"});
    const std::string e = lang_test::error_of("\xEF\xBB\xBF" + small_with("Mass = 2", "Mass = 2x"));
    CHECK(e.rfind("test.prd:2:10: error: unparsable number '2x'", 0) == 0);
  }

  TEST_CASE("outputs: displacement, velocity, acceleration, work entries and solver statistics") {
    auto s = lang_test::run(small_with("  Spring force",
                                       "  V 'X (1; 2)\n  A 'X (1; 3)\n  N 'NSTEP ()\n  I 'NITER ()\n"
                                       "  H 'STEP ()\n  R 'NREJ ()\n  'X (1; 1)\n  Spring force"));
    const auto& t = s->results();
    REQUIRE(t.names() == std::vector<std::string>{"Position", "V", "A", "N", "I", "H", "R", "X(1;1)", "Spring force"});
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, 0) == doctest::Approx(0.1));
    CHECK(t.at(last, 4) == doctest::Approx(static_cast<double>(s->stages().back().stats.steps)));
    CHECK(t.at(last, 1) == t.at(last, 8));
    // Spring force W(1) = k (u2 - u1), here nodes (0 1): k u.
    CHECK(t.at(last, 9) == doctest::Approx(100 * t.at(last, 1)));
    // Mass on a spring under a constant force: m a + k u = F at every output.
    for (std::size_t r = 1; r < t.rows(); ++r)
      CHECK(2 * t.at(r, 3) + 100 * t.at(r, 1) == doctest::Approx(10).epsilon(1e-6));
  }

  TEST_CASE("the two-body model file gives exactly the results of the C++ example") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "two_bodies.prd").string()));
    s->run({.write_files = false});
    // examples/two_bodies/main.cpp, same parameters and options.
    using namespace pradis::elements;
    model<planar_inertia, planar_link, constant_force> m;
    const auto d = m.add_dofs(6, "DOF ");
    m.add<planar_inertia>("Body 1", {.m = 1.0, .j = 0.1}, d[0], d[1], d[2]);
    m.add<planar_inertia>("Body 2", {.m = 2.0, .j = 0.1}, d[3], d[4], d[5]);
    m.add<planar_link>("Connection", {1, 1, 2, 2, 5e3}, d[0], d[1], d[3], d[4]);
    m.add<constant_force>("Force", {.force = -1e3}, d[4]);
    std::vector<std::array<double, 5>> ref;
    simulation sim(m, stoermer{});
    sim.on_output([&](const auto& x) {
      const auto w = x.get_model().work("Connection");
      ref.push_back({x.time(), x.u(d[3]), x.u(d[4]), w[1], w[2]});
    });
    sim.run({.end = 1.0,
             .out = 0.005,
             .smax = 1e-4,
             .newton = {.dabsu = 1e-8, .drltu = 1e-8, .dabsi = 1e-6, .drlti = 1e-8}});
    const auto& t = s->results();
    REQUIRE(t.rows() == ref.size());
    REQUIRE(t.rows() == 201);
    double worst = 0;
    for (std::size_t r = 0; r < t.rows(); ++r)
      for (std::size_t c = 0; c < 5; ++c)
        worst = std::max(worst, std::abs(t.at(r, c) - ref[r][c]) / std::max(1.0, std::abs(ref[r][c])));
    CHECK(worst <= 1e-12);
    CHECK(t.at(200, 2) == doctest::Approx(-167.179).epsilon(1e-5));
  }

  TEST_CASE("the built-in example of `pradis run` is examples/models/two_bodies.prd") {
    CHECK(slurp(lang_test::models_dir() / "two_bodies.prd") == std::string(lang::builtin_example));
  }

  TEST_CASE("every example model runs") {
    // Under the sanitizers (-O0, some 200x slower) the models that a test of their own runs in
    // full anyway are left out here; the dev preset runs every one.
    const std::set<std::string> own_test = {
        "accumulator_charge.prd", "ball_collision.prd", "bouncing_ball.prd", "cam_follower.prd", "capstan.prd",
        "cardan_shaft.prd", "door_hinge.prd", "eccentric_shaker.prd",
        "compound_pendulum.prd", "coulomb_oscillator.prd", "crank_throw.prd", "crank_throw_rod.prd",
        "drill_spindle.prd", "slider_table.prd",
        "flex_cantilever.prd", "gear_backlash.prd", "hydraulic_motor.prd", "large_deflection.prd",
        "pivot_pendulum.prd", "plate_strip.prd", "pneumatic_cylinder.prd", "pneumatic_fill.prd",
        "rectifier.prd", "rigid_pendulum.prd", "source_bench.prd", "rlc_circuit.prd", "rolling_ball.prd", "simple_pendulum.prd",
        "slider_crank.prd", "spring_pendulum.prd", "stiff_pair.prd", "tabular_spring.prd", "two_bodies.prd"};
    for (const std::string& name : own_test) CHECK(std::filesystem::exists(lang_test::models_dir() / name));
    int count = 0;
    for (const auto& e : std::filesystem::directory_iterator(lang_test::models_dir())) {
      if (e.path().extension() != ".prd") continue;
      if (pradis_test::sanitized && own_test.contains(e.path().filename().string())) continue;
      CAPTURE(e.path().string());
      auto s = std::make_unique<lang::session>(lang::parse_file(e.path().string()));
      CHECK_NOTHROW(s->run({.write_files = false}));
      CHECK(s->results().rows() > 10);
      ++count;
    }
    CHECK(count >= 3);
  }

  TEST_CASE("spring pendulum: Newmark keeps the total energy") {
    auto s =
        std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "spring_pendulum.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t uy = column(t, "Y displacement"), vx = column(t, "X velocity"), vy = column(t, "Y velocity"),
                      len = column(t, "Spring length");
    auto energy = [&](std::size_t r) {
      const double y = -0.8660254037844386 + t.at(r, uy);
      const double v2 = t.at(r, vx) * t.at(r, vx) + t.at(r, vy) * t.at(r, vy);
      return 9.81 * y + 0.5 * v2 + 0.5 * 100 * (t.at(r, len) - 1) * (t.at(r, len) - 1);
    };
    const double e0 = energy(0);
    double drift = 0;
    for (std::size_t r = 0; r < t.rows(); ++r) drift = std::max(drift, std::abs(energy(r) - e0));
    CHECK(drift < 2e-3 * 9.81);  // relative to m g L
    CHECK(t.at(t.rows() - 1, 0) == doctest::Approx(5.0));
  }

  TEST_CASE("simple pendulum: the period of small oscillations") {
    auto s =
        std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "simple_pendulum.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t ux = column(t, "X displacement");
    std::size_t rmin = 0;
    for (std::size_t r = 0; r < t.rows() && t.at(r, 0) < 1.5; ++r)
      if (t.at(r, ux) < t.at(rmin, ux)) rmin = r;
    const double theta0 = 5.0 * M_PI / 180.0;
    const double period = 2 * M_PI * std::sqrt(1.0 / 9.81) * (1 + theta0 * theta0 / 16);
    CHECK(t.at(rmin, 0) == doctest::Approx(period / 2).epsilon(0.01));
    CHECK(t.at(rmin, ux) == doctest::Approx(-2 * std::sin(theta0)).epsilon(0.01));
    REQUIRE(s->stages().size() == 2);
    CHECK(s->stages()[1].t0 == 1.0);
  }

  TEST_CASE("rigid pendulum (LINKX): bottom at a quarter period with speed sqrt(2 g L) and rod force 3 m g") {
    // examples/models/rigid_pendulum.prd: m = 2, L = 1.5, released from the
    // horizontal; quarter period sqrt(L / g) K(1 / sqrt 2), K(1/sqrt 2) =
    // 1.8540746773013719 (Abramowitz and Stegun, table 17.1).
    auto s =
        std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "rigid_pendulum.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t ux = column(t, "X displacement"), vx = column(t, "X velocity"), vy = column(t, "Y velocity");
    const std::size_t len = column(t, "Rod length"), force = column(t, "Rod force");
    const double l = 1.5, g = 9.81, quarter = std::sqrt(l / g) * 1.8540746773013719;
    std::size_t r = 1;
    while (r < t.rows() && l + t.at(r, ux) > 0) ++r;  // first output past the bottom (x = 0)
    REQUIRE(r < t.rows());
    // Linear interpolation of the crossing between outputs 1 ms apart.
    const double x0 = l + t.at(r - 1, ux), x1 = l + t.at(r, ux);
    const double tc = t.at(r - 1, 0) + (t.at(r, 0) - t.at(r - 1, 0)) * x0 / (x0 - x1);
    CHECK(tc == doctest::Approx(quarter).epsilon(1e-5));
    CHECK(std::hypot(t.at(r, vx), t.at(r, vy)) == doctest::Approx(std::sqrt(2 * g * l)).epsilon(1e-4));
    CHECK(t.at(r, force) == doctest::Approx(3 * 2 * g).epsilon(1e-3));
    double gap = 0;
    for (std::size_t k = 0; k < t.rows(); ++k) gap = std::max(gap, std::abs(t.at(k, len) - l));
    CHECK(gap < 1e-12);
  }

  TEST_CASE("slider-crank (PIN2X): the slider follows the closed form and the kinetic energy equals the work") {
    // examples/models/slider_crank.prd: crank r = 0.1 about the origin, rod l = 0.3,
    // slider on the X axis; slider x = r cos(phi) + sqrt(l^2 - r^2 sin(phi)^2) (the
    // triangle of crank, rod and axis); no gravity or friction, so the kinetic
    // energy equals the work M phi of the torque (energy theorem), here to the
    // scheme's O(h^2) error: measured 1.9e-5 of M phi at h = 1e-4 and 1.2e-4 at
    // h = 2.5e-4, alike under NEWMARK (no numerical dissipation) and HHT.
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "slider_crank.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t phi = column(t, "Crank angle"), w = column(t, "Crank speed"), xs = column(t, "Slider position"),
                      vs = column(t, "Slider speed"), cvx = column(t, "Crank vx"), cvy = column(t, "Crank vy"),
                      rvx = column(t, "Rod vx"), rvy = column(t, "Rod vy"), rw = column(t, "Rod speed"),
                      gap = column(t, "Wrist gap");
    const double r = 0.1, l = 0.3, torque = 0.5;
    double kin = 0, energy = 0, worst_gap = 0;
    for (std::size_t k = 0; k < t.rows(); ++k) {
      const double p = t.at(k, phi), sp = std::sin(p);
      kin = std::max(kin, std::abs(0.4 + t.at(k, xs) - (r * std::cos(p) + std::sqrt(l * l - r * r * sp * sp))));
      const double e = 0.5 * 1.0 * (std::pow(t.at(k, cvx), 2) + std::pow(t.at(k, cvy), 2)) +
                       0.5 * 8.333333333333333e-4 * std::pow(t.at(k, w), 2) +
                       0.5 * 2.0 * (std::pow(t.at(k, rvx), 2) + std::pow(t.at(k, rvy), 2)) +
                       0.5 * 0.015 * std::pow(t.at(k, rw), 2) + 0.5 * 0.5 * std::pow(t.at(k, vs), 2);
      energy = std::max(energy, std::abs(e - torque * p) / std::max(1.0, torque * p));
      worst_gap = std::max(worst_gap, t.at(k, gap));
    }
    CHECK(t.at(t.rows() - 1, phi) > 4 * 3.141592653589793);  // more than two turns
    CHECK(kin < 1e-12);
    CHECK(energy < 4e-5);
    CHECK(worst_gap < 1e-12);
  }

  TEST_CASE("bouncing ball (ELLPL): the bounces die out and the ball rolls on the flat part at v_x = -r w") {
    // examples/models/bouncing_ball.prd: a disc of radius r = 0.1 m thrown into a
    // valley. Once the bounces have died out it rolls on the flat part: the stick
    // state holds the contact point (rolling without slip, v_x = -r w: the disc's
    // kinematics) and it stays in contact near the Hertz depth (m g / k)^(2/3)
    // below r (N = k delta^1.5 = m g). The contact still rings there at about
    // 61 Hz (sqrt(1.5 k delta^0.5 / m)), weakly damped by the Hunt-Crossley term:
    // measured 4.7e-5 m and +-6 N about the rest values.
    auto s =
        std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "bouncing_ball.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t y = column(t, "y"), vx = column(t, "vx"), w = column(t, "w"), mode = column(t, "Flat part mode"),
                      normal = column(t, "Floor force");
    const double r = 0.1, depth = std::pow(9.81 / 1e7, 2.0 / 3.0);
    int rolling = 0;
    double slip = 0, height = 0;
    for (std::size_t k = 0; k < t.rows(); ++k) {
      if (t.at(k, 0) < 3.4 || t.at(k, 0) > 3.8) continue;
      ++rolling;
      CHECK(t.at(k, mode) == 1);  // stick
      slip = std::max(slip, std::abs(t.at(k, vx) + r * t.at(k, w)));
      height = std::max(height, std::abs(t.at(k, y) - (-1.4 - depth)));
      CHECK(t.at(k, normal) > 0);  // in contact, no more bouncing
    }
    CHECK(rolling >= 30);
    CHECK(slip < 5e-5);  // measured 2.5e-5 m/s
    CHECK(height < 1e-4);  // measured 4.7e-5 m
  }

  TEST_CASE("$REPLACE changes parameters for the following stages") {
    // Mass 2 on spring 100 with load 10, then load 30.
    std::string text = small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n",
                                  "  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n$REPLACE\n  Load = 30\n$RUN\n"
                                  "  Calc 2 'NEWMARK (END=0.2, SMAX=1E-3)\n");
    text = text.replace(text.find("  Spring force"), 0, "  A 'X (1; 3)\n");
    auto s = lang_test::run(text);
    CHECK(s->data("Load") == std::vector<double>{30});
    const auto& t = s->results();
    REQUIRE(t.names() == std::vector<std::string>{"Position", "A", "Spring force"});
    // m a + k u = F holds with F = 10 before and F = 30 after the replacement.
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, 0) == doctest::Approx(0.2));
    for (std::size_t r = 1; r < t.rows(); ++r) {
      const double f = t.at(r, 0) <= 0.1 + 1e-12 ? 10 : 30;
      CHECK(2 * t.at(r, 2) + 100 * t.at(r, 1) == doctest::Approx(f).epsilon(1e-6));
    }
    auto& loads = s->model().instances<elements::constant_force>();
    REQUIRE(loads.size() == 1);
    CHECK(loads[0].element.p.force == 30);
  }

  TEST_CASE("DABSX/DRLTX turn on error control: fewer, varying steps; tighter tolerance, more steps") {
    // The small model is a mass-spring under a constant load (w = 10 rad/s): the
    // fixed-step run takes END/SMAX = 100 steps; error control starts at SMIN,
    // grows, and takes more steps for a tighter tolerance.
    auto fixed = lang_test::run(small_model);
    auto loose = lang_test::run(small_with("SMAX=1E-3", "SMAX=1E-2, DABSX=1E-3, DRLTX=1E-3"));
    auto tight = lang_test::run(small_with("SMAX=1E-3", "SMAX=1E-2, DABSX=1E-6, DRLTX=1E-6"));
    const long nf = fixed->simulation_ptr()->statistics().steps;
    const long nl = loose->simulation_ptr()->statistics().steps;
    const long nt = tight->simulation_ptr()->statistics().steps;
    CHECK(nf == 100);
    CHECK(nl > 0);
    CHECK(nt > nl);
    CHECK(loose->simulation_ptr()->statistics().last_step != doctest::Approx(1e-2).epsilon(1e-12));
  }

  TEST_CASE("stages continue in time, also when the integration program changes") {
    auto s = lang_test::run(small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n",
                                       "  A 'SHTERM (END=0.1, SMAX=1E-3)\n  B 'NEWMARK (END=0.2, SMAX=1E-3)\n"
                                       "  C 'SHTERM (END=0.3, SMAX=1E-3)\n"));
    REQUIRE(s->stages().size() == 3);
    CHECK(s->stages()[2].t0 == doctest::Approx(0.2));
    const auto& t = s->results();
    for (std::size_t r = 1; r < t.rows(); ++r) CHECK(t.at(r, 0) > t.at(r - 1, 0));
    CHECK(t.at(t.rows() - 1, 0) == doctest::Approx(0.3));
    // NSTEP keeps counting across the change of program (statistics travel with the state).
    CHECK(s->simulation_ptr()->statistics().steps ==
          s->stages()[0].stats.steps + s->stages()[1].stats.steps + s->stages()[2].stats.steps);
  }

  TEST_CASE("$SAVE then $RESTORE in another run continues bit for bit") {
    const auto dir = scratch_dir("ckpt");
    const std::string two = "  A 'SHTERM (END=0.05, SMAX=1E-3)\n  B 'SHTERM (END=0.1, SMAX=1E-3)\n";
    auto whole = lang_test::build(small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n", two));
    whole->run({.output_dir = dir.string(), .write_files = false});
    auto first = lang_test::build(
        small_with("  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n", "  A 'SHTERM (END=0.05, SMAX=1E-3)\n$SAVE \"half.ckp\"\n"));
    first->run({.output_dir = dir.string(), .write_files = true});
    CHECK(std::filesystem::exists(dir / "half.ckp"));
    CHECK(std::filesystem::exists(dir / "model.csv"));
    auto second = lang_test::build(small_with("$RUN\n  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n",
                                              "$RESTORE \"half.ckp\"\n$RUN\n  B 'SHTERM (END=0.1, SMAX=1E-3)\n"));
    second->run({.output_dir = dir.string(), .write_files = false});
    const auto& a = whole->results();
    const auto& b = second->results();
    REQUIRE(b.rows() > 0);
    const std::size_t off = a.rows() - b.rows();
    for (std::size_t r = 0; r < b.rows(); ++r)
      for (std::size_t c = 0; c <= b.names().size(); ++c) CHECK(b.at(r, c) == a.at(off + r, c));
    // A checkpoint of a different model is refused at the $RESTORE line.
    std::string other = small_with("$RUN\n", "$RESTORE \"" + (dir / "half.ckp").string() + "\"\n$RUN\n");
    other.insert(other.find("  Push"), "  Extra 'MASS (2; 1)\n  S2 'SPRING (1 2; 1)\n");
    const std::string e = lang_test::error_of(other);
    CHECK(e.find("error: checkpoint") != std::string::npos);
    CHECK(e.find("different model") != std::string::npos);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("'TABL and 'DISP write tables of the chosen outputs (START/END) next to <stem>.csv") {
    const auto dir = scratch_dir("print");
    auto s =
        lang_test::build(small_with("$END", "$PRINT\n  Only position 'TABL (Position; START=0.05)\n  'DISP ()\n$END"));
    s->run({.output_dir = dir.string(), .stem = "m", .plot = false});
    const std::string tabl = slurp(dir / "m.Only_position.csv");
    CHECK(tabl.rfind("t,Position\n0.05", 0) == 0);
    CHECK(std::filesystem::exists(dir / "m.DISP2.csv"));
    CHECK(slurp(dir / "m.csv").rfind("t,Position,Spring force\n0,", 0) == 0);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("$INCLUDE reads a file relative to the including one") {
    const auto load =
        lang_test::memory_loader({{"dir/data.prd", "$DATA\n  Mass = 2\n  Stiffness = 100\n  Load = 10\n$END\nignored"},
                                  {"dir/structure.prd",
                                   "$FRAGMENT\n#STRUCTURE\n  Body 'MASS (1; Mass)\n  Spring 'SPRING (0 1; Stiffness)\n"
                                   "#OUTPUT\n  P 'X (1; 1)\n"}});
    auto prog = lang::parse_string(
        "$INCLUDE \"data.prd\"\n$INCLUDE \"structure.prd\"\n"
        "$RUN\n  C 'SHTERM (END=0.1)\n$END\n",
        "dir/main.prd", load);
    lang::session s(std::move(prog));
    CHECK(s.data("Mass") == std::vector<double>{2});
    CHECK(s.model().element_count() == 2);
    CHECK(s.outputs().size() == 1);
    // Errors in an included file name that file.
    const auto bad = lang_test::memory_loader({{"bad.prd", "$DATA\n  X = 1..2\n"}});
    const std::string e = lang_test::error_of("$INCLUDE \"bad.prd\"\n$END\n", bad);
    CHECK(e.rfind("bad.prd:2:7: error: unparsable number '1..2'", 0) == 0);
  }

  TEST_CASE("fragments instantiated as sub-structures equal the flat model") {
    const std::string sub =
        "$DATA\n  k = 100\n  m = 2\n"
        "$FRAGMENT OSC\n#EXTERNAL 1\n#STRUCTURE\n  Mass 'MASS (2; m)\n  Spring 'SPRING (1 2; k)\n  Start 'X0 (2; 0.1)\n"
        "#OUTPUT\n  U 'X (2; 1)\n  F 'X (W:Spring(1); 1)\n"
        "$FRAGMENT\n#STRUCTURE\n  Base 'MASS (1; 5)\n  Support 'SPRING (0 1; 1000)\n  Left 'OSC (1)\n  Right 'OSC (1)\n"
        "#OUTPUT\n  Base 'X (1; 1)\n"
        "$RUN\n  C 'NEWMARK (END=0.2, SMAX=1E-3)\n$END\n";
    const std::string flat =
        "$DATA\n  k = 100\n  m = 2\n"
        "$FRAGMENT\n#STRUCTURE\n  Base 'MASS (1; 5)\n  Support 'SPRING (0 1; 1000)\n"
        "  Left.Mass 'MASS (2; m)\n  Left.Spring 'SPRING (1 2; k)\n  Left.Start 'X0 (2; 0.1)\n"
        "  Right.Mass 'MASS (3; m)\n  Right.Spring 'SPRING (1 3; k)\n  Right.Start 'X0 (3; 0.1)\n"
        "#OUTPUT\n  Left.U 'X (2; 1)\n  Left.F 'X (W:Left.Spring(1); 1)\n  Right.U 'X (3; 1)\n"
        "  Right.F 'X (W:Right.Spring(1); 1)\n  Base 'X (1; 1)\n"
        "$RUN\n  C 'NEWMARK (END=0.2, SMAX=1E-3)\n$END\n";
    auto a = lang_test::run(sub);
    auto b = lang_test::run(flat);
    REQUIRE(a->results().names() == b->results().names());
    REQUIRE(a->results().rows() == b->results().rows());
    for (std::size_t r = 0; r < a->results().rows(); ++r)
      for (std::size_t c = 0; c <= a->results().names().size(); ++c)
        CHECK(a->results().at(r, c) == doctest::Approx(b->results().at(r, c)).epsilon(1e-12));
    CHECK(a->model().find("Right.Spring").has_value());
    // Mistakes in instances.
    std::string wrong = sub;
    wrong.replace(wrong.find("'OSC (1)"), 8, "'OSC (1 2)");
    CHECK(lang_test::error_of(wrong).find("fragment OSC has 1 external nodes (#EXTERNAL), got 2") != std::string::npos);
    std::string self = sub;
    self.replace(self.find("  Start 'X0 (2; 0.1)"), 0, "  Again 'OSC (2)\n");
    CHECK(lang_test::error_of(self).find("fragment OSC instantiates itself") != std::string::npos);
  }

  TEST_CASE("node numbers of the file map to model DOFs; node 0 is the ground") {
    auto s = lang_test::build(
        "$FRAGMENT\n#STRUCTURE\n  M 'MASS (70; 1)\n  S 'SPRING (0 70; 5)\n  M2 'MASS (3; 1)\n"
        "  S2 'SPRING (70 3; 5)\n$RUN\n  C 'SHTERM (END=0.1)\n$END\n");
    CHECK(s->model().dof_count() == 3);  // ground + two used nodes, whatever their numbers
    CHECK(s->model().dof_name(s->dof_of_node(70)) == "node 70");
    CHECK(s->model().dof_name(s->dof_of_node(3)) == "node 3");
  }
}
