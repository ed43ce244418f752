// vtk_series: a spinning, drifting rigid body written as a VTK time series.
// The files are read back with a small XML reader: the collection lists one
// DataSet per output with its time, each frame has the scene's point and cell
// counts, the positions equal the simulation's to full precision and follow the
// torque-free uniform rotation x = R_z(w t) a + v t (an axisymmetric body
// spinning about its axis; Goldstein, Classical Mechanics, 5.6), and bad scenes
// or directories are refused with their codes.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/vtk_series.hpp"
#include "vtk_reader.hpp"

using namespace pradis;
using namespace pradis::elements;
using spatial::vec3;

using namespace vtk_test;

TEST_SUITE("io/vtk") {
  TEST_CASE("a spinning body's VTK series lists every frame and each frame holds the exact point positions") {
    const double w = 3.0, vx = 0.5, a = 0.2;
    model<rigid_body, initial_rotation, initial_velocity> m;
    const std::array<dof, 3> x{m.add_dof("x"), m.add_dof("y"), m.add_dof("z")};
    const rotation_node r = m.add_rotation_node("r");
    m.add<rigid_body>("body", {1.0, 1.0, 1.0, 2.0, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    m.add<initial_rotation>("spin", {0, 0, 1, 0, 0, 0, w}, r);
    m.add<initial_velocity>("drift", {vx}, x[0]);

    io::vtk_scene scene;
    const vec3 x0(1.0, 2.0, 3.0);
    const int fixed = scene.point({0, 0, 0}, {m.ground(), m.ground(), m.ground()});
    const int ref = scene.body_point(x0, x, r, vec3::Zero());
    const int p1 = scene.body_point(x0, x, r, vec3(a, 0, 0));
    const int p2 = scene.body_point(x0, x, r, vec3(0, a, 0));
    scene.vertex(ref);
    scene.line(fixed, ref);
    scene.triangle(ref, p1, p2);
    const auto dir = std::filesystem::temp_directory_path() / "pradis_vtk_test";
    std::filesystem::remove_all(dir);
    io::vtk_series vtk(dir, "body", scene);
    simulation sim(m);
    std::vector<double> times;
    std::vector<std::vector<double>> expected;
    sim.on_output([&](const auto& s) {
      vtk.write(s);
      times.push_back(s.time());
      std::vector<double> e;
      for (std::size_t i = 0; i < scene.points(); ++i) {
        const vec3 p = scene.motion(s, i).position;
        e.insert(e.end(), {p.x(), p.y(), p.z()});
      }
      expected.push_back(e);
    });
    sim.run({.end = 1.0, .out = 0.1, .smax = 1e-3, .newton = {.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-10, .drlti = 0}});
    REQUIRE(vtk.frames() == times.size());
    CHECK(times.size() == 11);  // t = 0 and ten outputs

    const std::string pvd = slurp(vtk.collection());
    CHECK(pvd.find("type=\"Collection\"") != std::string::npos);
    const auto steps = attributes(pvd, "DataSet", "timestep"), files = attributes(pvd, "DataSet", "file");
    REQUIRE(steps.size() == times.size());
    REQUIRE(files.size() == times.size());
    double worst_exact = 0;
    for (std::size_t k = 0; k < times.size(); ++k) {
      CAPTURE(k);
      CHECK(std::stod(steps[k]) == times[k]);
      const std::string vtu = slurp(dir / files[k]);
      CHECK(vtu.find("type=\"UnstructuredGrid\"") != std::string::npos);
      CHECK(attribute_int(vtu, "NumberOfPoints") == 4);
      CHECK(attribute_int(vtu, "NumberOfCells") == 3);
      CHECK(data_array(vtu, "connectivity") == std::vector<double>{1, 0, 1, 1, 2, 3});
      CHECK(data_array(vtu, "offsets") == std::vector<double>{1, 3, 6});
      CHECK(data_array(vtu, "types") == std::vector<double>{1, 3, 5});
      const auto pos = data_array(vtu, "position");
      CHECK(pos == expected[k]);  // %.17g round-trips doubles exactly
      const auto disp = data_array(vtu, "displacement");
      REQUIRE(disp.size() == 12);
      for (std::size_t i = 0; i < 12; ++i) CHECK(disp[i] == doctest::Approx(pos[i] - expected[0][i]).epsilon(1e-15));
      // Uniform rotation about Z and drift along X.
      const double t = times[k], c = std::cos(w * t), s = std::sin(w * t);
      const vec3 centre = x0 + vec3(vx * t, 0, 0);
      const std::array<vec3, 4> exact{vec3::Zero(), centre, centre + a * vec3(c, s, 0), centre + a * vec3(-s, c, 0)};
      for (std::size_t i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j) worst_exact = std::max(worst_exact, std::abs(pos[3 * i + j] - exact[i](j)));
      const auto vel = data_array(vtu, "velocity");
      CHECK(vel[9] == doctest::Approx(vx - a * w * c).epsilon(1e-5));  // point p2: v = v_x e_x + w e_z x a R e_y
    }
    // The trapezoidal rule's phase error of the rotation (w h)^2 w t / 12 ~ 2e-6 rad at t = 1.
    CHECK(worst_exact < 1e-6);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("bad VTK scenes, names and directories are refused with their codes") {
    io::vtk_scene scene;
    const dof g{};
    const int p = scene.point({0, 0, 0}, {g, g, g});
    auto code = [](auto f) -> int {
      try {
        f();
      } catch (const pradis::error& e) {
        return e.number();
      }
      return 0;
    };
    CHECK(code([&] { scene.line(p, 1); }) == static_cast<int>(error_code::invalid_model));
    CHECK(code([&] { scene.triangle(-1, p, p); }) == static_cast<int>(error_code::invalid_model));
    CHECK(code([&] { scene.point({NAN, 0, 0}, {g, g, g}); }) == static_cast<int>(error_code::invalid_model));
    const auto dir = std::filesystem::temp_directory_path() / "pradis_vtk_bad";
    CHECK(code([&] { io::vtk_series s(dir, "", scene); }) == static_cast<int>(error_code::invalid_option));
    CHECK(code([&] { io::vtk_series s(dir, "a/b", scene); }) == static_cast<int>(error_code::invalid_option));
    // A directory path that is an existing file.
    const auto file = std::filesystem::temp_directory_path() / "pradis_vtk_not_a_dir";
    std::ofstream(file) << "x";
    CHECK(code([&] { io::vtk_series s(file / "sub", "x", scene); }) == static_cast<int>(error_code::io_error));
    std::filesystem::remove(file);
  }
}
