// PIVOT, the ground pivot (elements::add_ground_pivot) in the model language: examples/models/pivot_pendulum.prd
// against the exact large-amplitude period of the compound pendulum, the same body on SPH3X, `pradis help PIVOT`,
// and every error of a PIVOT statement with its file:line:column. The C++ side: tests/spatial/test_ground_pivot.cpp.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;

namespace pivot_model_tests {
/// examples/models/pivot_pendulum.prd with the first `from` replaced by `to` (empty `from`: unchanged).
std::string pendulum_with(const std::string& from = {}, const std::string& to = {}) {
  std::string s = lang_test::slurp(lang_test::models_dir() / "pivot_pendulum.prd");
  if (from.empty()) return s;
  const auto p = s.find(from);
  REQUIRE_MESSAGE(p != std::string::npos, from);
  s.replace(p, from.size(), to);
  return s;
}
/// The line:column of the first `what` in `text` (1-based, as lang_error reports it).
std::string where(const std::string& text, const std::string& what) {
  const auto p = text.find(what);
  REQUIRE_MESSAGE(p != std::string::npos, what);
  const auto nl = text.rfind('\n', p);
  const auto line = static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(p), '\n'));
  const std::size_t col = nl == std::string::npos ? p + 1 : p - nl;
  return std::to_string(line + 1) + ":" + std::to_string(col);
}
}  // namespace pivot_model_tests

namespace pm = pivot_model_tests;

TEST_SUITE("lang/pivot") {
  TEST_CASE("examples/models/pivot_pendulum.prd: a body on a PIVOT swings with the compound pendulum's exact period") {
    // m = 2 kg, l = 0.5 m, I = Jxx + m l^2 = 0.55 kg m^2 about the pivot, released at rest at 90 degrees:
    // T = 4 sqrt(I / (m g l)) K(sin 45 deg) = 1.7560385869 s (Landau & Lifshitz, Mechanics, section 11,
    // problem 1). Outputs every T/16: at T/4 and 3T/4 the bottom, |w_x| = sqrt(2 m g l / I) (energy), the
    // centre of mass moved by (0, -0.5, -0.5) from its start (0, 0.5, 0); at T/2 the other turning point,
    // w = 0, moved by (0, -1, 0); at T back at the start.
    lang::session s(lang::parse_file((lang_test::models_dir() / "pivot_pendulum.prd").string()));
    s.run({.write_files = false});
    const auto& r = s.results();
    REQUIRE(r.rows() == 17);
    const double peak = std::sqrt(2 * 2.0 * 9.81 * 0.5 / 0.55);
    MESSAGE("pivot pendulum (BDF, DRLTX = 1e-9): w_x at T/4, T/2, 3T/4, T: ", r.at(4, 1), ", ", r.at(8, 1), ", ",
            r.at(12, 1), ", ", r.at(16, 1), " rad/s (peak ", peak, ")");
    CHECK(r.at(4, 1) == doctest::Approx(-peak).epsilon(1e-6));
    CHECK(r.at(12, 1) == doctest::Approx(peak).epsilon(1e-6));
    CHECK(std::abs(r.at(8, 1)) < 1e-5);
    CHECK(std::abs(r.at(16, 1)) < 1e-5);
    // The translations follow the rotation exactly (the node's equation): the centre of mass stays 0.5 m
    // from the pivot at every output, |(0, 0.5 + y, z)| = 0.5, whatever the error of the phase.
    for (std::size_t i = 0; i < r.rows(); ++i)
      CHECK(std::hypot(0.5 + r.at(i, 2), r.at(i, 3)) == doctest::Approx(0.5).epsilon(1e-12));
    CHECK(r.at(4, 2) == doctest::Approx(-0.5).epsilon(1e-6));
    CHECK(r.at(4, 3) == doctest::Approx(-0.5).epsilon(1e-12));
    CHECK(r.at(8, 2) == doctest::Approx(-1.0).epsilon(1e-9));
    CHECK(std::abs(r.at(16, 2)) < 1e-9);
    // The pivot's force on the body, W:Tip(3) (vertical). With the arm level at rest the angular
    // acceleration is m g l / I, the centre falls at m g l^2 / I, and the pivot carries
    // m g (1 - m l^2 / I); at the bottom it carries the weight and the centripetal force m l w^2. It is
    // the force of the last Newton iterate of a step, whose correction is below DRLTX.
    const double mg = 2.0 * 9.81, at_rest = mg * (1 - 2.0 * 0.25 / 0.55), bottom = mg + 2.0 * 0.5 * peak * peak;
    MESSAGE("pivot force Z at 0, T/4, T/2, 3T/4: ", r.at(0, 4), ", ", r.at(4, 4), ", ", r.at(8, 4), ", ", r.at(12, 4),
            " N (", at_rest, " at rest, ", bottom, " at the bottom)");
    CHECK(r.at(0, 4) == doctest::Approx(at_rest).epsilon(1e-6));
    CHECK(r.at(4, 4) == doctest::Approx(bottom).epsilon(1e-6));
    CHECK(r.at(8, 4) == doctest::Approx(at_rest).epsilon(1e-5));
    CHECK(r.at(12, 4) == doctest::Approx(bottom).epsilon(1e-6));
  }

  TEST_CASE("a PIVOT gives the motion of SPH3X to the ground without its multipliers") {
    // The same body on SPH3X (body a the ground, the same 12 parameters) under the same BDF stage: the
    // ground pivot is SPH3X's reduced form, so both follow the same exact motion; the model has no
    // multipliers (3 internal DOFs fewer) and no fixed rotational node of the ground.
    // The pivot's force output is SPH3X's joint force on body b along Z, its work entry 4.
    std::string joint =
        pm::pendulum_with("Tip 'PIVOT (1 2 3 4 5 6; Hold)", "Tip 'SPH3X (0 0 0 0 0 0 1 2 3 4 5 6; Hold)");
    joint.replace(joint.find("(W:Tip(3); 1)"), 13, "(W:Tip(4); 1)");
    auto a = lang_test::run(pm::pendulum_with());
    auto b = lang_test::run(joint);
    CHECK(b->model().dof_count() - a->model().dof_count() >= 3);
    double worst = 0;
    for (std::size_t i = 0; i < a->results().rows(); ++i)
      for (std::size_t c = 1; c <= 3; ++c)
        worst = std::max(worst, std::abs(a->results().at(i, c) - b->results().at(i, c)));
    double force = 0;
    for (std::size_t i = 0; i < a->results().rows(); ++i)
      force = std::max(force, std::abs(a->results().at(i, 4) - b->results().at(i, 4)));
    MESSAGE("PIVOT against SPH3X: largest difference of the motion outputs ", worst, ", of the force ", force, " N");
    CHECK(worst < 1e-5);
    // The forces come from the accelerations of the two runs' own steps (measured 2.2e-4 N): within
    // 1e-5 of the largest, m g + m l w^2 = 55.3 N.
    CHECK(force < 1e-5 * (2 * 9.81 + 2 * 0.5 * 2 * 2 * 9.81 * 0.5 / 0.55));
  }

  TEST_CASE("a PIVOT may come before the elements on its nodes, and inside a fragment instance") {
    // The rotational node is made by the PIVOT and shared by BODY3 and ROT0 placed after it.
    std::string first = pm::pendulum_with("    Tip 'PIVOT (1 2 3 4 5 6; Hold)\n", "");
    const auto at = first.find("    Body 'BODY3");
    first.insert(at, "    Tip 'PIVOT (1 2 3 4 5 6; Hold)\n");
    auto s = lang_test::run(first);
    CHECK(s->model().rotation_nodes().size() == 1);
    CHECK(s->results().at(4, 1) == doctest::Approx(-std::sqrt(2 * 2.0 * 9.81 * 0.5 / 0.55)).epsilon(1e-6));
    // Unlabelled, a PIVOT is named "PIVOT <n>"; in an instance, after the instance's prefix. The fragment
    // SWING holds the body and its pivot; its external nodes are the rotation's, so that ROT0 and 'W of the
    // main model reach it.
    std::string sub = pm::pendulum_with();
    const std::string frag = "$FRAGMENT SWING:\n#EXTERNAL 4 5 6\n#STRUCTURE:\n"
                             "    Body 'BODY3 (1 2 3 4 5 6; Body)\n    Weight 'F3 (1 2 3; Weight)\n"
                             "    'PIVOT (1 2 3 4 5 6; Hold)\n"
                             "$FRAGMENT:\n#STRUCTURE:\n    Arm 'SWING (4 5 6)\n    Start 'ROT0 (4 5 6; Release)\n";
    const auto f = sub.find("$FRAGMENT:");
    sub.replace(f, sub.find("#OUTPUT:") - f, frag);
    const std::string centre = "    Centre Y 'X (2; 1)\n    Centre Z 'X (3; 1)\n    Pivot force Z 'X (W:Tip(3); 1)\n";
    sub.replace(sub.find(centre), centre.size(), "    Arm force Z 'X (W:Arm.PIVOT 1(3); 1)\n");
    sub.replace(sub.find(", Centre Y, Centre Z, Pivot force Z;"), 36, ";");
    auto t = lang_test::run(sub);
    CHECK(t->results().at(4, 1) == doctest::Approx(-std::sqrt(2 * 2.0 * 9.81 * 0.5 / 0.55)).epsilon(1e-6));
    const auto& pivots = t->model().nodes<elements::ground_pivot_kind>();
    REQUIRE(pivots.size() == 1);
    CHECK(pivots.front().name == "Arm.PIVOT 1");
  }

  TEST_CASE("`pradis help PIVOT` and `pradis list` show the node program with SPH3X's parameters; `pradis check` "
            "says it is not an element") {
    std::ostringstream os, err, list;
    CHECK(lang::print_reference(os, err, "pivot"));
    CHECK(os.str().find("PIVOT - ground pivot") != std::string::npos);
    CHECK(os.str().find("node program") != std::string::npos);
    CHECK(os.str().find("12 - z of B, body b frame [m]") != std::string::npos);
    std::ostringstream check_out, check_err;
    CHECK(lang::check_by_name(check_out, check_err, "PIVOT", {}) == 1);  // not an element: exit status 1
    CHECK(check_err.str().find("PIVOT is a node program, not an element") != std::string::npos);
    lang::print_catalog(list);
    CHECK(list.str().find("Nodes with an equation") != std::string::npos);
    CHECK(list.str().find("  PIVOT    ground pivot") != std::string::npos);
  }

  TEST_CASE("every error of a PIVOT statement names its file:line:column") {
    using lang_test::expect_error;
    const std::string base = pm::pendulum_with();
    const std::string stmt = "'PIVOT (1 2 3 4 5 6; Hold)";
    // The PIVOT statement replaced by `to`: the error is at the first `at` of the file and names `what`
    // and `also` (empty: nothing more).
    const auto bad = [&](const std::string& to, const std::string& at, const char* what, const char* also = "",
                         int line = __builtin_LINE()) {
      const std::string t = pm::pendulum_with(stmt, to);
      expect_error(t, pm::where(t, at), {what, also}, line);
    };
    bad("'PIVOT (1 2 3 4 5; Hold)", "1 2 3 4 5;", "'PIVOT needs 6 nodes", "got 5");
    bad("'PIVOT (1 2 3 4 5 6)", "(1 2 3 4 5 6)", "a PIVOT needs (nodes; parameters)", "no ';'");
    bad("'PIVOT (1 0 3 4 5 6; Hold)", "0 3 4 5 6;", "its node 2 cannot be the ground");
    bad("'PIVOT (1 2 3 4 5 6; Hold, 1)", "Hold, 1)", "'PIVOT takes 12 parameters", "got 13");
    // The body's translations already slaved by another pivot (code 110 from add_ground_pivot).
    bad("'PIVOT (1 2 3 4 5 6; Hold)\n    Tip2 'PIVOT (1 2 3 4 5 6; Hold)", "Tip2", "PIVOT 'Tip2'", "already");
    bad("'PIVOT (1 2 3 5 4 6; Hold)", "5 4 6;", "nodes 5 4 6 are not the q1 q2 q3 of one spatial rotational node");
    bad("'PIVOT (1 2 3 7 5 8; Hold)", "Tip 'PIVOT", "PIVOT 'Tip'", "already belongs to rotational node");
    bad("'PIVOT (1 2 3 4 5 6; Hold)\n    Tip 'PIVOT (7 8 9 10 11 12; Hold)", "Tip 'PIVOT (7",
        "'Tip' is already defined at test.prd:");
    bad("'PIVTO (1 2 3 4 5 6; Hold)", "PIVTO", "unknown element model 'PIVTO'", "did you mean 'PIVOT'?");
    {
      const std::string t = pm::pendulum_with("(W:Tip(3); 1)", "(W:Tip(4); 1)");
      expect_error(t, pm::where(t, "4); 1)"), {"PIVOT 'Tip' has 3 outputs", "W:Tip(4) does not exist"});
    }
    {
      const std::string t = pm::pendulum_with("$FRAGMENT:", "$FRAGMENT PIVOT:\n#STRUCTURE:\n$FRAGMENT:");
      expect_error(t, pm::where(t, "$FRAGMENT PIVOT"), {"fragment name PIVOT is the name of a node program"});
    }
    CHECK(lang_test::error_of(base).empty());
    // The pivot draws the body's arm (io/model_scene.hpp), so a VTK display of a model whose only spatial
    // items are BODY3 and a PIVOT has something to draw.
    const std::string vtk = pm::pendulum_with("$END", "    Animation 'VTK ()\n$END");
    CHECK(lang_test::error_of(vtk).empty());
    std::string free_body = vtk;  // the same body without its pivot: BODY3 alone draws nothing
    for (const std::string cut : {"    Tip 'PIVOT (1 2 3 4 5 6; Hold)\n", "    Pivot force Z 'X (W:Tip(3); 1)\n",
                                  ", Pivot force Z"})
      free_body.erase(free_body.find(cut), cut.size());
    CHECK(lang_test::error_of(free_body).find("VTK has nothing to draw") != std::string::npos);
  }
}
