// The BDF integration program of the model language: a damped oscillator
// m x'' + c x' + k x = 0 against its exact solution (x(t) = e^(-z w t) (cos wd t
// + z w / wd sin wd t), wd = w sqrt(1 - z^2)); stages of BDF and of the one-step
// schemes following each other from the state the previous stage reached; a
// $SAVE / $RESTORE between two BDF stages reproducing the uninterrupted run
// bit for bit (both drivers write the same checkpoint format and BDF starts
// every stage at order 1); OPTIM, CONTROL, LQBAND, INDEX2, TURN, TURNMAX, RATES and REFORM on a BDF stage; the keys
// BDF refuses and bad values.

#include <cmath>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {
// m = 1, k = 4 pi^2 (w = 2 pi), c = 0.4 (z = c / (2 w) = 0.0318), x(0) = 1.
const double w = 2 * M_PI, z = 0.4 / (2 * w), wd = w * std::sqrt(1 - z * z);
double exact(double t) { return std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t)); }

/// The oscillator model followed by `actions` (sections from $RUN on).
std::string model_then(const std::string& actions) {
  return "$DATA:\n    K = 39.47841760435743\n$FRAGMENT:\n#STRUCTURE:\n    Mass 'MASS (1; 1)\n"
         "    Spring 'SPRING (1 0; K)\n    Damper 'DAMPER (1 0; 0.4)\n    Start 'X0 (1; 1)\n#OUTPUT:\n"
         "    X 'X (1; 1)\n    Steps 'NSTEP ()\n" +
         actions + "$END\n";
}
/// The oscillator model with the stage lines `stages` under $RUN (the first stage at line 13).
std::string oscillator(const std::string& stages) { return model_then("$RUN:\n" + stages); }
/// The largest |x - exact| over the output rows.
double max_error(const lang::session& s) {
  const io::table& t = s.results();
  double e = 0;
  for (std::size_t r = 0; r < t.rows(); ++r) e = std::max(e, std::abs(t.at(r, 1) - exact(t.at(r, 0))));
  return e;
}
}  // namespace

TEST_SUITE("lang/bdf") {
  TEST_CASE("'BDF integrates the damped oscillator to its tolerance with far fewer steps than NEWMARK") {
    auto b = lang_test::run(oscillator("    Calc 'BDF (END=4, OUT=0.05, SMAX=0.1, DRLTX=1E-8, DABSX=1E-8)\n"));
    auto n = lang_test::run(oscillator("    Calc 'NEWMARK (END=4, OUT=0.05, SMAX=0.1, DRLTX=1E-8, DABSX=1E-8)\n"));
    const double eb = max_error(*b), en = max_error(*n);
    CAPTURE(eb);
    CAPTURE(en);
    // Local error control: the global error is a modest multiple of the tolerance
    // over 4 periods (docs/bdf.md: about N steps times DRLTX at worst).
    CHECK(eb < 2e-5);
    CHECK(b->bdf_active());
    REQUIRE(b->bdf_ptr() != nullptr);
    CHECK(b->bdf_ptr()->order() >= 3);  // it has raised its order
    const double steps_b = b->results().at(b->results().rows() - 1, 2);
    const double steps_n = n->results().at(n->results().rows() - 1, 2);
    CAPTURE(steps_b);
    CAPTURE(steps_n);
    CHECK(steps_b * 5 < steps_n);
    REQUIRE(b->stages().size() == 1);
    CHECK(b->stages()[0].program == "BDF");
  }

  TEST_CASE("BDF and one-step stages continue from each other's state") {
    auto s = lang_test::run(oscillator("    A 'NEWMARK (END=1, OUT=0.05, SMAX=1E-3)\n"
                                       "    B 'BDF (END=2, OUT=0.05, SMAX=0.1, DRLTX=1E-9, DABSX=1E-9)\n"
                                       "    C 'HHT (END=3, OUT=0.05, SMAX=1E-3, ALPHA=-0.01)\n"
                                       "    D 'BDF (END=4, OUT=0.05, SMAX=0.1, DRLTX=1E-9, DABSX=1E-9, MAXORD=3)\n"));
    REQUIRE(s->stages().size() == 4);
    CHECK(s->stages()[1].program == "BDF");
    CHECK(s->stages()[1].t0 == 1.0);
    CHECK(s->stages()[3].t0 == 3.0);
    // Newmark at h = 1e-3 has a phase error of about (w h)^2 / 12 per radian:
    // ~3.3e-6 rad per period; the other stages add less. A stage that started
    // from a wrong state (e.g. at rest, or at t = 0) would be off by O(1).
    const double e = max_error(*s);
    CAPTURE(e);
    CHECK(e < 5e-5);
    CHECK(s->bdf_ptr()->options().max_order == 3);
    CHECK(s->bdf_ptr()->order() <= 3);
  }

  TEST_CASE("$SAVE and $RESTORE between two BDF stages reproduce the uninterrupted run bit for bit") {
    const auto dir = lang_test::scratch_dir("bdfsave");
    const std::string first = "$RUN:\n    A 'BDF (END=1, OUT=0.1, SMAX=0.1, DRLTX=1E-7)\n";
    const std::string second = "$RUN:\n    B 'BDF (END=2, OUT=0.1, SMAX=0.1, DRLTX=1E-7)\n";
    auto whole = lang_test::build(model_then(first + second));
    whole->run({.output_dir = dir.string(), .write_files = false});
    auto saved = lang_test::build(model_then(first + "$SAVE \"bdf.chk\"\n"));
    saved->run({.output_dir = dir.string(), .stem = "a", .plot = false});
    auto again = lang_test::build(model_then("$RESTORE \"bdf.chk\"\n" + second));
    again->run({.output_dir = dir.string(), .write_files = false});
    REQUIRE(again->bdf_active());
    CHECK(again->bdf_ptr()->time() == 2.0);
    const global_state& a = again->bdf_ptr()->state();
    const global_state& b = whole->bdf_ptr()->state();
    for (Eigen::Index k = 0; k < b.u.size(); ++k) {
      CHECK(a.u(k) == b.u(k));
      CHECK(a.v(k) == b.v(k));
    }
    CHECK(again->bdf_ptr()->statistics().steps == whole->bdf_ptr()->statistics().steps);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("OPTIM picks the ordering of a BDF stage") {
    auto s = lang_test::run(oscillator("    Calc 'BDF (END=0.1, OPTIM=3)\n"));
    CHECK(s->bdf_ptr()->solver().ordering().level == 3);
  }

  TEST_CASE("CONTROL holds a BDF stage's steps at or above it (the error test gives way)") {
    // DRLTX = 1E-10 would take hundreds of steps over END = 1 (the first test: 4 periods at
    // 1E-8); CONTROL = 0.05 keeps every step but the one clipped at END at 0.05 or more.
    auto tight = lang_test::run(oscillator("    Calc 'BDF (END=1, SMAX=0.1, DRLTX=1E-10)\n"));
    auto held = lang_test::run(oscillator("    Calc 'BDF (END=1, SMAX=0.1, DRLTX=1E-10, CONTROL=0.05)\n"));
    REQUIRE(held->bdf_active());
    const long n_held = held->bdf_ptr()->statistics().steps, n_tight = tight->bdf_ptr()->statistics().steps;
    CAPTURE(n_held);
    CAPTURE(n_tight);
    CHECK(n_held <= 21);
    CHECK(n_tight > 5 * n_held);
    CHECK(held->stages()[0].program == "BDF");
  }

  TEST_CASE("LQBAND, INDEX2, TURN, TURNMAX and RATES set the BDF driver's options; a stage with other options gets "
            "its own "
            "driver") {
    auto s = lang_test::run(oscillator("    A 'BDF (END=0.5, OUT=0.1, SMAX=0.1, DRLTX=1E-9, LQBAND=0.05, INDEX2=0, "
                                       "TURN=0, RATES=1)\n"
                                       "    B 'BDF (END=1, OUT=0.1, SMAX=0.1, DRLTX=1E-9)\n"));
    REQUIRE(s->stages().size() == 2);
    // The session keeps the last driver: stage B's options are the defaults again.
    CHECK(s->bdf_ptr()->options() == bdf_options{});
    auto a = lang_test::run(oscillator("    A 'BDF (END=0.5, OUT=0.1, SMAX=0.1, DRLTX=1E-9, LQBAND=0.05, INDEX2=0, "
                                       "TURN=0, RATES=1)\n"));
    CHECK(a->bdf_ptr()->options().lq_renormalise == 0.05);
    CHECK(a->bdf_ptr()->options().turn_refresh == bdf_options{}.turn_refresh);
    CHECK_FALSE(a->bdf_ptr()->options().stabilised_index2);
    CHECK_FALSE(a->bdf_ptr()->options().rotated_jacobian);
    CHECK(a->bdf_ptr()->options().rotation_rates);
    CHECK(a->bdf_ptr()->options().max_order == 5);
    // TURN = 1: turned in the global frame only; TURN = 2 (the default): body frames too.
    auto turn1 = lang_test::run(oscillator("    A 'BDF (END=0.5, OUT=0.1, SMAX=0.1, DRLTX=1E-9, TURN=1)\n"));
    CHECK(turn1->bdf_ptr()->options().rotated_jacobian);
    CHECK_FALSE(turn1->bdf_ptr()->options().body_frame);
    auto turn2 = lang_test::run(oscillator("    A 'BDF (END=0.5, OUT=0.1, SMAX=0.1, DRLTX=1E-9, TURN=2)\n"));
    CHECK(turn2->bdf_ptr()->options() == bdf_options{});
    auto turnmax = lang_test::run(oscillator("    A 'BDF (END=0.5, OUT=0.1, SMAX=0.1, DRLTX=1E-9, TURNMAX=0.25)\n"));
    CHECK(turnmax->bdf_ptr()->options().turn_refresh == 0.25);
    CHECK(turnmax->bdf_ptr()->options().rotated_jacobian);
    // The oscillator has no rotational node and no exact joint: the keys change nothing
    // of its motion (exact solution as in the first test).
    CHECK(max_error(*s) < 1e-6);
  }

  TEST_CASE("REFORM sets reform_jacobian: with it the kept matrix is formed again at a new c from its element blocks") {
    // The linear oscillator's K, C and M are constant, so the matrix formed again from
    // the kept blocks is the one a fresh evaluation gives: REFORM = 1 (the default)
    // evaluates the Jacobian only when the driver must (start, failures), REFORM = 0 at
    // every factorisation (measured: 3 against 91 Jacobian evaluations for 90
    // factorisations); both follow the exact solution of the first test.
    auto on = lang_test::run(oscillator("    A 'BDF (END=2, OUT=0.1, SMAX=0.1, DRLTX=1E-9)\n"));
    auto off = lang_test::run(oscillator("    A 'BDF (END=2, OUT=0.1, SMAX=0.1, DRLTX=1E-9, REFORM=0)\n"));
    CHECK(on->bdf_ptr()->options().reform_jacobian);
    CHECK_FALSE(off->bdf_ptr()->options().reform_jacobian);
    const run_statistics& a = on->stages()[0].stats;
    const run_statistics& b = off->stages()[0].stats;
    CAPTURE(a.jacobian_evaluations);
    CAPTURE(a.factorizations);
    CAPTURE(b.jacobian_evaluations);
    CAPTURE(b.factorizations);
    CHECK(a.factorizations > 3);
    CHECK(a.jacobian_evaluations < a.factorizations);
    CHECK(b.jacobian_evaluations >= b.factorizations);
    CHECK(max_error(*on) < 1e-6);
    CHECK(max_error(*off) < 1e-6);
  }

  TEST_CASE("keys BDF refuses, MAXORD, LQBAND, INDEX2, TURN, TURNMAX, RATES and REFORM out of range, are located "
            "errors") {
    std::string e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, BETA=0.3)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("key BETA belongs to NEWMARK, not to BDF") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, PREDICT=1)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("key PREDICT does not apply to BDF") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, CONTROL=-1)\n"));
    CHECK(e.find("CONTROL = -1 must be >= 0") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, MAXORD=6)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("MAXORD") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'NEWMARK (END=1, MAXORD=2)\n"));
    CHECK(e.find("key MAXORD belongs to BDF, not to NEWMARK") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, LQBAND=-0.5)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("LQBAND = -0.5 must be a number >= 0") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, INDEX2=2)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("INDEX2 must be a whole number from 0 to 1") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'GALPHA (END=1, LQBAND=0.05)\n"));
    CHECK(e.find("key LQBAND belongs to BDF, not to GALPHA") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'HHT (END=1, INDEX2=0)\n"));
    CHECK(e.find("key INDEX2 belongs to BDF, not to HHT") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, TURN=3)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("TURN must be a whole number from 0 to 2") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, TURNMAX=-0.1)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("TURNMAX = -0.1 must be a number >= 0") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'NEWMARK (END=1, TURNMAX=1)\n"));
    CHECK(e.find("key TURNMAX belongs to BDF, not to NEWMARK") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, RATES=-1)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("RATES must be a whole number from 0 to 1") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'NEWMARK (END=1, RATES=1)\n"));
    CHECK(e.find("key RATES belongs to BDF, not to NEWMARK") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (END=1, REFORM=2)\n"));
    CHECK(e.find("test.prd:13:") != std::string::npos);
    CHECK(e.find("REFORM must be a whole number from 0 to 1") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'HHT (END=1, REFORM=0)\n"));
    CHECK(e.find("key REFORM belongs to BDF, not to HHT") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'SHTERM (END=1, TURN=0)\n"));
    CHECK(e.find("key TURN belongs to BDF, not to SHTERM") != std::string::npos);
    e = lang_test::error_of(oscillator("    Calc 'BDF (OUT=1)\n"));
    CHECK(e.find("BDF needs END=<end time>") != std::string::npos);
  }
}
