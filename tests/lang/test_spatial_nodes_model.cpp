// Rotational nodes placed from model files: BODY3, ROT0 and M3 by node numbers (the hidden q4 created by
// itself), and the outputs 'W (a node's global angular velocity) and 'LQ (its quaternion norm). References:
// Euler's equation about a fixed principal axis (theta = w0 t + M t^2 / (2 Jz)); the trapezoidal rule's phase
// error and the drift of Lq (docs/rotations.md); examples/models/compound_pendulum.prd (F3A) against the exact
// large-amplitude period. The same scenes in C++: tests/spatial/test_spatial_elements.cpp.
// (In tests/lang so that only this unit compiles the whole language.)

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "lang_test_support.hpp"
#include "pradis/lang/lang.hpp"
#include "pradis/spatial/node_state.hpp"
#include "pradis/spatial/quaternion.hpp"

using namespace pradis;

namespace {
/// A model file: a body spinning about Z at 2 rad/s (Jz = 2) under a moment of 1 N m
/// about Z, NEWMARK for 1 s at h = 1e-3, with more elements and the outputs given.
std::string spin_model(const std::string& more_elements, const std::string& outputs,
                       const std::string& stage = "'NEWMARK (END=1, OUT=0.1, SMAX=1E-3, DABSU=1E-12, DRLTU=0, "
                                                  "DABSI=1E-10, DRLTI=0)") {
  return "$DATA:\n"
         "    Body = 1, 1, 1, 2, 0, 0, 0, 0, 0, 0\n"
         "    Spin = 0, 0, 1, 0, 0, 0, 2\n"
         "    Drive = 0, 0, 1, 0, 0, 0, 0, 0\n"
         "$FRAGMENT:\n"
         "#STRUCTURE:\n"
         "    Body 'BODY3 (1 2 3 4 5 6; Body)\n"
         "    Start 'ROT0 (4 5 6; Spin)\n"
         "    Motor 'M3 (4 5 6; Drive)\n" +
         more_elements + "#OUTPUT:\n" + outputs +
         "$RUN:\n"
         "    Spin up " + stage + "\n$END\n";
}
/// Angle of the rotation between two quaternions [rad] (0 when they are the same rotation).
double rotation_angle_between(const spatial::quaternion& a, const spatial::quaternion& b) {
  return spatial::to_axis_angle(spatial::relative_rotation(a, b)).angle;
}
}  // namespace

TEST_SUITE("lang/spatial nodes") {
  TEST_CASE("the model language places BODY3, ROT0 and M3 by node numbers; the hidden q4 is created by itself") {
    // A body spinning about Z at 2 rad/s with Jz = 2 and a moment 1 N m about Z:
    // theta = 2 t + t^2 / 4 (Euler's equation about a fixed principal axis).
    const std::string text = spin_model("", "    Q3 'X (6; 1)\n");
    lang::session s(lang::parse_string(text, "spin.prd", lang::read_file));
    s.run({.write_files = false});
    REQUIRE(s.model().rotation_nodes().size() == 1);
    const auto node = s.model().find_rotation_node(dof{s.dof_of_node(4)});
    REQUIRE(node.has_value());
    REQUIRE(s.simulation_ptr() != nullptr);
    const double theta = 2.0 + 0.25;
    CHECK(rotation_angle_between(spatial::node_quaternion(*s.simulation_ptr(), *node),
                                 spatial::from_axis_angle(spatial::vec3::UnitZ(), theta)) < 1e-6);
  }

  TEST_CASE("the outputs 'W and 'LQ give a node's global angular velocity and quaternion norm in model files") {
    // The spinning body above: omega_z = 2 + t / 2 exactly (Jz = 2, M = 1 N m about Z);
    // omega_x = omega_y = 0, up to the trapezoidal rule's phase error on the quaternion, which
    // turns at w / 2: relative (w h / 2)^2 / 12, at most 2.5 (1.25e-3)^2 / 12 = 3.3e-7 rad/s.
    // Lq moves by h^2 D|w|^2 / 32 (docs/rotations.md), D|w|^2 = 2.5^2 - 2^2 = 2.25 here. A second node with q1 and q2 fixed
    // (nodes 0 0 9) turns about Z under the same moment.
    const std::string flat = "    Flat 'BODY3 (0 0 0 0 0 9; Body)\n    Motor2 'M3 (0 0 9; Drive)\n";
    const std::string text =
        spin_model(flat, "    Wx 'W (4 5 6; 1)\n    Wz 'W (4 5 6; 3)\n    'LQ (4 5 6)\n    Flat wz 'W (0 0 9; 3)\n");
    lang::session s(lang::parse_string(text, "spin.prd", lang::read_file));
    s.run({.write_files = false});
    const auto& r = s.results();
    REQUIRE(r.rows() == 11);
    REQUIRE(r.names().size() == 4);
    CHECK(r.names()[2] == "LQ(4 5 6)");
    double worst_w = 0, worst_lq = 0;
    for (std::size_t i = 0; i < r.rows(); ++i) {
      const double t = r.at(i, 0);  // column 0 is the time
      worst_w = std::max({worst_w, std::abs(r.at(i, 1)), std::abs(r.at(i, 2) - (2 + t / 2)),
                          std::abs(r.at(i, 4) - t / 2)});
      worst_lq = std::max(worst_lq, std::abs(r.at(i, 3) - 1));
    }
    MESSAGE("'W max error ", worst_w, " rad/s; 'LQ max |Lq - 1| ", worst_lq);
    CHECK(worst_w < 2.5 * (2.5e-3 / 2) * (2.5e-3 / 2) / 12);
    CHECK(worst_lq == doctest::Approx(2.25 * 1e-6 / 32).epsilon(1e-3));

    // Bad uses: located errors.
    struct bad {
      const char* output;
      const char* mention;
    };
    for (const bad b : {bad{"    'W (4 5 6)\n", "'W needs (q1 q2 q3; k)"}, bad{"    'W (4 5 6; 4)\n", "axis"},
                        bad{"    'LQ (4 5)\n", "'LQ needs (q1 q2 q3)"}, bad{"    'LQ (1 2 3)\n", "not the q1 q2 q3"},
                        bad{"    'LQ (5 4 6)\n", "not the q1 q2 q3"}, bad{"    'LQ (0 0 0)\n", "the ground"},
                        bad{"    'W (4 5 7; 1)\n", "node 7 is not connected"}}) {
      CAPTURE(b.output);
      try {
        lang::session bad_session(lang::parse_string(spin_model(flat, b.output), "bad.prd", lang::read_file));
        bad_session.run({.write_files = false});
        FAIL("no error for ", b.output);
      } catch (const lang::lang_error& e) {
        CHECK(std::string(e.what()).find(b.mention) != std::string::npos);
        CHECK(std::string(e.what()).find("bad.prd:") != std::string::npos);
      }
    }
  }

  TEST_CASE("LQBAND of a BDF stage brings the quaternion norm back to 1; the motion stays that of the body") {
    // The spinning body above under BDF: omega_z = 2 + t / 2 exactly. LQBAND = 0 scales the node
    // back to Lq = 1 after every step; LQBAND = 1 never does, and Lq keeps the drift of BDF's
    // steps (docs/bdf.md, "Rotational nodes"). The scaling is exact (every rotational formula is
    // invariant under q -> l q), so both runs follow the exact motion alike; they differ only by
    // their integration errors (measured: 1.4e-7 rad/s off the exact omega_z, 9e-8 apart; the
    // scaling drops the kept factorisation, so the Newton iterates differ).
    auto run = [](const std::string& band) {
      auto s = std::make_unique<lang::session>(lang::parse_string(
          spin_model("", "    Wz 'W (4 5 6; 3)\n    'LQ (4 5 6)\n",
                     "'BDF (END=1, OUT=0.1, SMAX=0.1, DRLTX=1E-8, LQBAND=" + band + ")"),
          "spin.prd", lang::read_file));
      s->run({.write_files = false});
      return s;
    };
    const auto every = run("0"), never = run("1");
    REQUIRE(every->bdf_active());
    CHECK(every->bdf_ptr()->options().lq_renormalise == 0.0);
    CHECK(never->bdf_ptr()->options().lq_renormalise == 1.0);
    const auto &a = every->results(), &b = never->results();
    REQUIRE(a.rows() == 11);
    REQUIRE(b.rows() == 11);
    double worst_w = 0, lq_every = 0, lq_never = 0, diff_w = 0;
    for (std::size_t i = 0; i < a.rows(); ++i) {
      const double t = a.at(i, 0);
      worst_w = std::max({worst_w, std::abs(a.at(i, 1) - (2 + t / 2)), std::abs(b.at(i, 1) - (2 + t / 2))});
      diff_w = std::max(diff_w, std::abs(a.at(i, 1) - b.at(i, 1)));
      lq_every = std::max(lq_every, std::abs(a.at(i, 2) - 1));
      lq_never = std::max(lq_never, std::abs(b.at(i, 2) - 1));
    }
    MESSAGE("BDF spin-up: omega_z error ", worst_w, ", runs differ by ", diff_w, "; |Lq - 1| ", lq_every,
            " (LQBAND = 0) and ", lq_never, " (LQBAND = 1)");
    CHECK(worst_w < 1e-6);
    CHECK(diff_w < 1e-6);
    CHECK(lq_every < 1e-12);
    CHECK(lq_never > 100 * lq_every);
  }

  TEST_CASE("examples/models/compound_pendulum.prd: F3A swings a body pivoted at its node with the exact period") {
    // m = 2 kg, l = 0.5 m, I = Jxx + m l^2 = 0.55 kg m^2 about the pivot, released at rest at 90 degrees:
    // T = 4 sqrt(I / (m g l)) K(sin 45 deg) = 1.7560385869 s (the simple pendulum of length I / (m l):
    // Landau & Lifshitz, Mechanics, section 11, problem 1). Outputs every T/16: at T/4 and 3T/4 the bottom,
    // |w_x| = sqrt(2 m g l / I) (energy), at T/2 and T the turning points, w = 0; the weight's moment
    // about the pivot is m g l sin(theta): +9.81 N m at -90 degrees (T/2), -9.81 N m at +90 degrees.
    lang::session s(lang::parse_file((lang_test::models_dir() / "compound_pendulum.prd").string()));
    s.run({.write_files = false});
    const auto& r = s.results();
    REQUIRE(r.rows() == 17);
    const double peak = std::sqrt(2 * 2.0 * 9.81 * 0.5 / 0.55), mgl = 2.0 * 9.81 * 0.5;
    MESSAGE("compound pendulum: w_x at T/4, T/2, 3T/4, T: ", r.at(4, 1), ", ", r.at(8, 1), ", ", r.at(12, 1), ", ",
            r.at(16, 1), " rad/s (peak ", peak, ")");
    CHECK(r.at(4, 1) == doctest::Approx(-peak).epsilon(1e-6));
    CHECK(r.at(12, 1) == doctest::Approx(peak).epsilon(1e-6));
    // At h = 1e-3 the trapezoidal period error, (w h)^2 / 12 = 1.5e-6 of T, leaves about 2e-5 rad/s at the
    // turning points (the same scene in C++: tests/spatial/test_spatial_elements.cpp).
    CHECK(std::abs(r.at(8, 1)) < 2e-4);
    CHECK(std::abs(r.at(16, 1)) < 4e-4);
    CHECK(r.at(0, 2) == doctest::Approx(-mgl).epsilon(1e-12));
    CHECK(r.at(8, 2) == doctest::Approx(mgl).epsilon(1e-6));
  }
}
