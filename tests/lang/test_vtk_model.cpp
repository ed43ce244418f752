// The 'VTK display of the model language: a model file's spatial elements draw
// themselves (io/model_scene.hpp) and the session writes the motion as a VTK
// time series. A cantilever of two BEAM3 (with BEAMI3 on the same nodes) carries
// an SD3 spring to a fixed point. Checked against the run's own outputs: one
// frame per output row between START and END with its time; shared points and
// cells drawn once (the beams' common node, BEAM3 and BEAMI3 on one line, the
// spring's attachment at the tip node); the tip at x0 + u of its DOFs; the
// spring's body point A at tip + R(q) a with R from the tip's quaternion (PRADIS
// convention p = X0 + x + R(q) a, docs/rotations.md), so |A - tip| = |a|;
// the clamped root and the fixed point do not move; velocities as the outputs.
// Error paths: output labels, a model with nothing to draw, a key VTK does not
// have, and an unusable vtk directory.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../io/vtk_reader.hpp"
#include "lang_test_support.hpp"
#include "pradis/spatial/quaternion.hpp"

using namespace pradis;

namespace {
const std::string cantilever = R"(* Cantilever of two beams with a spring from the tip to a fixed point
$DATA:
    Steel = 2.1E11, 8.1E10, 1E-4, 1E-8, 1E-8, 2E-8
    Seg 1 = 0, 0, 0, 1, 0, 0, 0, 1, 0
    Seg 2 = 1, 0, 0, 2, 0, 0, 0, 1, 0
    Mass section = 7800, 1E-4, 1E-8, 1E-8, 2E-8
    Spring = 2, 0, 0, 0, 0, -0.2, 2, 0, -1, 0, 0, 0, 400, 0.8, 0.5
    Load = 0, 3, -20, 0, 0, 0, 0, 0
$FRAGMENT:
#STRUCTURE:
    Beam 1 'BEAM3 (0 0 0 0 0 0 1 2 3 4 5 6; Steel, Seg 1)
    Beam 2 'BEAM3 (1 2 3 4 5 6 7 8 9 10 11 12; Steel, Seg 2)
    Mass 1 'BEAMI3 (0 0 0 0 0 0 1 2 3 4 5 6; Mass section, Seg 1)
    Mass 2 'BEAMI3 (1 2 3 4 5 6 7 8 9 10 11 12; Mass section, Seg 2)
    Stay 'SD3 (7 8 9 10 11 12 0 0 0 0 0 0; Spring)
    Tip load 'F3 (7 8 9; Load)
#OUTPUT:
    X 'X (7; 1)
    Y 'X (8; 1)
    Z 'X (9; 1)
    VX 'X (7; 2)
    VY 'X (8; 2)
    VZ 'X (9; 2)
    Q1 'X (10; 1)
    Q2 'X (11; 1)
    Q3 'X (12; 1)
    Norm 'LQ (10 11 12)
$RUN:
    Load 'HHT (END=0.03, OUT=0.005, SMAX=1E-4)
$PRINT:
    Motion 'VTK (START=0.01, END=0.03)
$END
)";

/// Index of the point nearest to (x, y, z) in a flat list of positions, if it
/// is within 0.05 m (the beam deflects by millimetres), else -1.
int find_point(const std::vector<double>& pos, double x, double y, double z) {
  int best = -1;
  double d_best = 0.05;
  for (std::size_t i = 0; 3 * i + 2 < pos.size(); ++i) {
    const double d = std::hypot(pos[3 * i] - x, pos[3 * i + 1] - y, pos[3 * i + 2] - z);
    if (d < d_best) best = static_cast<int>(i), d_best = d;
  }
  return best;
}
}  // namespace

TEST_SUITE("lang/vtk") {
  TEST_CASE("'VTK writes one frame per output row in its window, the shared geometry once, the exact positions") {
    const auto dir = lang_test::scratch_dir("vtk");
    auto s = lang_test::build(cantilever);
    s->run({.output_dir = dir.string(), .stem = "m", .plot = false});
    const io::table& t = s->results();
    const auto pvd = dir / "vtk" / "m.Motion.pvd";
    REQUIRE(std::filesystem::exists(pvd));
    const auto times = vtk_test::attributes(vtk_test::slurp(pvd), "DataSet", "timestep");
    const auto files = vtk_test::attributes(vtk_test::slurp(pvd), "DataSet", "file");
    std::vector<std::size_t> rows;  // the output rows in [START, END]
    for (std::size_t r = 0; r < t.rows(); ++r)
      if (t.at(r, 0) >= 0.01 && t.at(r, 0) <= 0.03) rows.push_back(r);
    CHECK(rows.size() == 5);  // 0.01, 0.015, ..., 0.03 with OUT = 0.005
    REQUIRE(times.size() == rows.size());
    const auto col = [&](const char* name) { return lang_test::column(t, name); };
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const std::size_t r = rows[k];
      CHECK(std::stod(times[k]) == t.at(r, 0));
      const std::string xml = vtk_test::slurp(dir / "vtk" / files[k]);
      // Points: root, middle and tip of the beams (the tip is also the spring's
      // body a), the spring's point A and its fixed end: 5. Cells: two beam lines
      // (BEAMI3 draws the same ones), the tip-to-A arm and the spring: 4.
      CHECK(vtk_test::attribute_int(xml, "NumberOfPoints") == 5);
      CHECK(vtk_test::attribute_int(xml, "NumberOfCells") == 4);
      for (double type : vtk_test::data_array(xml, "types")) CHECK(type == 3);
      const auto pos = vtk_test::data_array(xml, "position");
      const auto disp = vtk_test::data_array(xml, "displacement");
      const auto vel = vtk_test::data_array(xml, "velocity");
      REQUIRE(pos.size() == 15);
      REQUIRE(disp.size() == 15);
      REQUIRE(vel.size() == 15);
      if (k == 0)
        for (double d : disp) CHECK(d == 0);  // displacements are from the first frame written
      const int root = find_point(pos, 0, 0, 0), tip = find_point(pos, 2, 0, 0);
      const int a = find_point(pos, 2, 0, -0.2), fixed = find_point(pos, 2, 0, -1);
      REQUIRE(root >= 0);
      REQUIRE(tip >= 0);
      REQUIRE(a >= 0);
      REQUIRE(fixed >= 0);
      const auto at = [&](const std::vector<double>& v, int i) {
        return spatial::vec3(v[3 * static_cast<std::size_t>(i)], v[3 * static_cast<std::size_t>(i) + 1],
                             v[3 * static_cast<std::size_t>(i) + 2]);
      };
      CHECK(at(pos, root).norm() == 0);
      CHECK((at(pos, fixed) - spatial::vec3(2, 0, -1)).norm() == 0);
      // The tip: x0 + u of nodes 7, 8, 9 (written with 17 digits).
      const spatial::vec3 u(t.at(r, col("X")), t.at(r, col("Y")), t.at(r, col("Z")));
      CHECK((at(pos, tip) - (spatial::vec3(2, 0, 0) + u)).norm() <= 1e-15);
      CHECK(u.norm() > 1e-4);  // the load has moved it
      CHECK((at(vel, tip) - spatial::vec3(t.at(r, col("VX")), t.at(r, col("VY")), t.at(r, col("VZ")))).norm() <=
            1e-14);
      // Point A: tip + R(q) (0, 0, -0.2), q4 from the norm output.
      const double q1 = t.at(r, col("Q1")), q2 = t.at(r, col("Q2")), q3 = t.at(r, col("Q3"));
      const double lq = t.at(r, col("Norm"));
      const double q4 = std::sqrt(lq * lq - q1 * q1 - q2 * q2 - q3 * q3);
      const spatial::vec3 a_exact =
          at(pos, tip) + spatial::rotation_matrix(spatial::quaternion(q1, q2, q3, q4)) * spatial::vec3(0, 0, -0.2);
      CHECK((at(pos, a) - a_exact).norm() <= 1e-12);
      CHECK(std::abs((at(pos, a) - at(pos, tip)).norm() - 0.2) <= 1e-12);
      CHECK(std::abs(q1) + std::abs(q2) + std::abs(q3) > 1e-6);  // the tip has turned
    }
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("'VTK errors: output labels, nothing to draw, unknown keys, an unusable directory; no files in tests") {
    const auto with = [](const std::string& display) {
      std::string m = cantilever;
      const std::string old = "    Motion 'VTK (START=0.01, END=0.03)";
      m.replace(m.find(old), old.size(), display);
      return m;
    };
    std::string e = lang_test::error_of(with("    Motion 'VTK (X)"));
    CHECK(e.find("test.prd:31:") != std::string::npos);
    CHECK(e.find("takes no output labels") != std::string::npos);
    e = lang_test::error_of(with("    Motion 'VTK (EVERY=2)"));
    CHECK(e.find("test.prd:31:") != std::string::npos);
    CHECK(e.find("unknown key EVERY of VTK") != std::string::npos);
    e = lang_test::error_of(R"($FRAGMENT:
#STRUCTURE:
    Mass 'MASS (1; 2)
    Spring 'SPRING (1 0; 100)
$RUN:
    Go 'SHTERM (END=0.1)
$PRINT:
    Anim 'VTK ()
$END
)");
    CHECK(e.find("test.prd:8:5") != std::string::npos);
    CHECK(e.find("VTK has nothing to draw") != std::string::npos);

    // The vtk directory cannot be made: a file of that name is in the way.
    const auto dir = lang_test::scratch_dir("vtkbad");
    std::ofstream(dir / "vtk") << "in the way\n";
    auto s = lang_test::build(cantilever);
    try {
      s->run({.output_dir = dir.string(), .stem = "m", .plot = false});
      FAIL("no error");
    } catch (const pradis::error& x) {
      CHECK(x.code() == error_code::io_error);
      CHECK(std::string(x.message()).find("vtk") != std::string::npos);
    }
    // The results up to the display are kept.
    CHECK(std::filesystem::exists(dir / "m.csv"));
    std::filesystem::remove_all(dir);

    // write_files = false: the display writes nothing.
    const auto quiet = lang_test::scratch_dir("vtkquiet");
    auto q = lang_test::build(cantilever);
    q->run({.output_dir = quiet.string(), .write_files = false});
    CHECK(!std::filesystem::exists(quiet / "vtk"));
    std::filesystem::remove_all(quiet);
  }
}
