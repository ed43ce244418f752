// model_scene: a model's spatial elements draw themselves (io/model_scene.hpp).
// A double pendulum of two rigid bodies on exact spherical joints (SPH3X), with
// a spring between them (SD3) and a sphere contact on the second body (CSPHPL,
// its plane far below), falls from the horizontal. The scene has exactly the
// points and cells the elements draw, with shared points merged; while the
// bodies swing, the joint points that SPH3X holds together coincide in the
// drawing (to the constraint's round-off), the drawn arms keep their lengths
// (rigid bodies), and vtk_series::write(t, motions) refuses a wrong count. A
// body on a ground pivot draws its arm, whose joint end stays on the ground point. A draw
// hook that asks for a local DOF its element does not have is an error naming the element.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/elements/spatial/plate_mesh.hpp"
#include "pradis/io/model_scene.hpp"

using namespace pradis;
using namespace pradis::elements;
using spatial::vec3;

TEST_SUITE("io/vtk") {
  TEST_CASE("model_scene: a double pendulum draws its joints, spring and sphere once, and the joints stay closed") {
    using scene_model = model<rigid_body, exact_spherical_joint, spatial_spring_damper, sphere_plane_contact,
                              spatial_force>;
    scene_model m;
    const dof G = m.ground();
    const auto x1 = m.add_dofs(3, "x1");
    const auto x2 = m.add_dofs(3, "x2");
    const rotation_node r1 = m.add_rotation_node("r1"), r2 = m.add_rotation_node("r2");
    const double mass = 1.0, j = 0.1, g = 9.81;
    m.add<rigid_body>("body 1", {mass, j, j, j, 0, 0, 0, 0, 0, 0}, x1[0], x1[1], x1[2], r1);
    m.add<rigid_body>("body 2", {mass, j, j, j, 0, 0, 0, 0, 0, 0}, x2[0], x2[1], x2[2], r2);
    // Pivot at the origin; body 1's centre at (0.5, 0, 0), body 2's at (1.5, 0, 0).
    m.add<exact_spherical_joint>("pivot", {{0, 0, 0, 0, 0, 0, 0.5, 0, 0, -0.5, 0, 0}}, G, G, G, G, G, G, x1[0], x1[1],
                                 x1[2], r1);
    m.add<exact_spherical_joint>("elbow", {{0.5, 0, 0, 0.5, 0, 0, 1.5, 0, 0, -0.5, 0, 0}}, x1[0], x1[1], x1[2], r1,
                                 x2[0], x2[1], x2[2], r2);
    m.add<spatial_spring_damper>("spring", {0.5, 0, 0, 0, 0.1, 0, 1.5, 0, 0, 0, 0.1, 0, 10, 1, 0}, x1[0], x1[1],
                                 x1[2], r1, x2[0], x2[1], x2[2], r2);
    m.add<sphere_plane_contact>("ball", {1.5, 0, 0, 0.5, 0, 0, 0.1, 0, 0, -10, 0, 0, 1, 0, 1e5, 0, 0, 0, 0}, x2[0],
                                x2[1], x2[2], r2);
    m.add<spatial_force>("weight 1", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x1[0], x1[1], x1[2]);
    m.add<spatial_force>("weight 2", {0, 0, -mass * g, 0, 0, 0, 0, 0}, x2[0], x2[1], x2[2]);

    const io::vtk_scene scene = io::model_scene(m);
    // Points: the pivot, body 1's centre and its two joint points and spring
    // point, body 2's centre, its joint point, spring point and sphere centre: 9.
    // Cells: 6 arms (the pivot's own arm has zero length and is left out), the
    // spring, and the sphere's centre as a vertex: 8.
    CHECK(scene.points() == 9);
    CHECK(scene.cells() == 8);
    int vertices = 0, lines = 0;
    for (int t : scene.types()) (t == io::vtk_scene::vertex_cell ? vertices : lines) += 1;
    CHECK(vertices == 1);
    CHECK(lines == 7);

    simulation<scene_model, alpha_family> sim(m, alpha_family(hht{-0.05}));
    std::vector<vec3> start;
    double joint_gap = 0, arm_error = 0, travel = 0;
    const auto index_of = [&](const vec3& p) {
      for (std::size_t i = 0; i < start.size(); ++i)
        if ((start[i] - p).norm() < 1e-12) return i;
      FAIL("no point at " << p.transpose());
      return std::size_t{0};
    };
    const auto at = [&](std::size_t i) { return scene.motion(sim, i).position; };
    sim.on_output([&](const auto& s) {
      if (start.empty()) {
        for (std::size_t i = 0; i < scene.points(); ++i) start.push_back(scene.motion(s, i).position);
        return;
      }
      // Two points start at each joint (one per body), and one at the pivot.
      std::vector<std::size_t> pivot, elbow;
      for (std::size_t i = 0; i < start.size(); ++i) {
        if (start[i].norm() < 1e-12) pivot.push_back(i);
        if ((start[i] - vec3(1, 0, 0)).norm() < 1e-12) elbow.push_back(i);
      }
      REQUIRE(pivot.size() == 2);
      REQUIRE(elbow.size() == 2);
      joint_gap = std::max({joint_gap, (at(pivot[0]) - at(pivot[1])).norm(), (at(elbow[0]) - at(elbow[1])).norm()});
      const vec3 c1 = at(index_of({0.5, 0, 0})), c2 = at(index_of({1.5, 0, 0}));
      const vec3 ball = at(index_of({2, 0, 0})), s2 = at(index_of({1.5, 0.1, 0}));
      arm_error = std::max({arm_error, std::abs((ball - c2).norm() - 0.5), std::abs((s2 - c2).norm() - 0.1),
                            std::abs((c1 - at(index_of({0.5, 0.1, 0}))).norm() - 0.1)});
      travel = std::max(travel, (c2 - vec3(1.5, 0, 0)).norm());
    });
    run_options o;
    o.end = 0.4;
    o.out = 0.01;
    o.smax = 1e-3;
    (void)sim.run(o);
    CHECK(travel > 0.5);  // the pendulum has swung well down
    CHECK(joint_gap < 1e-9);
    CHECK(arm_error < 1e-12);

    // A frame with a wrong number of point motions.
    io::vtk_series vtk(std::filesystem::temp_directory_path() / "pradis_scene_test", "s", scene);
    std::vector<spatial::point_motion> few(3);
    try {
      vtk.write(0.0, few);
      FAIL("no error");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_model);
      CHECK(std::string(e.message()).find("3 point motions") != std::string::npos);
    }
    std::filesystem::remove_all(std::filesystem::temp_directory_path() / "pradis_scene_test");
  }

  TEST_CASE("model_scene: a ground pivot draws its body's arm, whose joint end stays on the ground point") {
    // The compound pendulum of examples/models/pivot_pendulum.prd in code: BODY3 at its centre of mass,
    // (0, 0.5, 0) at the start, hung 0.5 m below the ground point A = 0 by a ground pivot (add_ground_pivot),
    // released level. The pivot draws the arm from the centre to B: 2 points, 1 line. B stays on A and the
    // arm keeps its length while the body swings (the node's equation holds B on A exactly).
    using pivot_model = model<rigid_body, exact_spherical_joint, spatial_force, initial_rotation>;
    pivot_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node r = m.add_rotation_node("r");
    m.add<rigid_body>("body", {2, 0.05, 0.05, 0.02, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
    add_ground_pivot(m, "tip", {0, 0, 0, 0, 0, 0, 0, 0.5, 0, 0, 0, 0.5}, x[0], x[1], x[2], r);
    m.add<spatial_force>("weight", {0, 0, -19.62, 0, 0, 0, 0, 0}, x[0], x[1], x[2]);
    m.add<initial_rotation>("release", {1, 0, 0, 90, 0, 0, 0}, r);
    const io::vtk_scene scene = io::model_scene(m);
    CHECK(scene.points() == 2);
    CHECK(scene.cells() == 1);
    bdf_simulation sim(m);
    double off = 0, arm = 0, drop = 0;
    sim.on_output([&](const auto& s) {
      const vec3 c = scene.motion(s, 0).position, b = scene.motion(s, 1).position;
      off = std::max(off, b.norm());
      arm = std::max(arm, std::abs((b - c).norm() - 0.5));
      drop = std::max(drop, -c.z());
    });
    (void)sim.run({.end = 0.44, .out = 0.02, .smax = 0.01});
    MESSAGE("ground pivot arm: B off A by ", off, " m, length error ", arm, " m, centre dropped ", drop, " m");
    CHECK(drop > 0.45);  // near the bottom at T/4 = 0.439 s, 0.5 m below the pivot
    CHECK(off < 1e-12);
    CHECK(arm < 1e-12);
  }

  TEST_CASE("model_scene: a draw hook that asks for a DOF its element or node lacks is code 110 naming it") {
    // A hook of a one-DOF element (MASS) asking for a point on local DOFs 0, 1, 2, and a node's hook
    // asking for DOF 3 of three: programming errors in a hook, reported instead of read past the DOFs.
    io::scene_builder b;
    const element_instance<point_mass> in{point_mass({1.0}), "slider", {0}};
    io::element_drawer<point_mass> d(b, in);
    try {
      (void)d.point(vec3::Zero(), 0);
      FAIL("no error for a draw hook that asks for local DOF 1 of a one-DOF element");
    } catch (const pradis::error& e) {
      CHECK(e.code() == error_code::invalid_model);
      CHECK(e.message() ==
            "the draw hook of MASS 'slider' asks for local DOF 1, which is not one of its 1 DOFs (0..0)");
    }
    const std::array<int, 3> dofs{0, 1, 2};
    io::dof_drawer nd(b, dofs, "node 'tip'");
    CHECK_NOTHROW((void)nd.point(vec3::Zero(), 0));
    try {
      (void)nd.point_at(vec3::Zero(), {0, 1, 3});
      FAIL("no error for a node's draw hook that asks for local DOF 3 of three");
    } catch (const pradis::error& e) {
      CHECK(e.code() == error_code::invalid_model);
      CHECK(e.message() == "the draw hook of node 'tip' asks for local DOF 3, which is not one of its 3 DOFs (0..2)");
    }
    CHECK(b.scene().points() == 1);  // the failed calls added nothing
  }

  TEST_CASE("model_scene: a plate mesh draws one triangle per TRIPL on shared vertices that move with their DOFs") {
    // A 4 x 2 mesh (15 vertices, 16 triangles), simply supported, under a sudden
    // pressure: every triangle is a cell, every vertex one point (shared by up to
    // six triangles), at x0 + u of its three DOFs.
    model<triangle_plate> m;
    const plate_mesh mesh = rectangular_plate_mesh(2.0, 1.0, 4, 2);
    const plate_sides sides = find_plate_sides(mesh);
    const plate_dofs d = add_plate_mesh(m, mesh, sides, {2e9, 0.3, 0.01, 1000, 5e3}, {});
    const io::vtk_scene scene = io::model_scene(m);
    CHECK(scene.points() == 15);
    CHECK(scene.cells() == 16);
    for (int t : scene.types()) CHECK(t == io::vtk_scene::triangle_cell);
    // The same mesh simply supported: the three interior vertices move.
    model<triangle_plate, initial_displacement> held;
    const plate_dofs h = add_plate_mesh(held, mesh, sides, {2e9, 0.3, 0.01, 1000, 5e3},
                                        boundary_fixity(mesh, sides, false));
    const io::vtk_scene hs = io::model_scene(held);
    REQUIRE(hs.points() == 15);
    simulation<decltype(held), alpha_family> sim(held, alpha_family(newmark{}));
    (void)sim.run({.end = 2e-3, .smax = 1e-4});
    std::size_t matched = 0, moved = 0;
    for (std::size_t i = 0; i < hs.points(); ++i) {
      const vec3 p = hs.motion(sim, i).position;
      for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const auto& x = h.vertex[v];
        const vec3 u(sim.u(x[0]), sim.u(x[1]), sim.u(x[2]));
        if ((p - (mesh.vertices[v] + u)).norm() <= 1e-15 && (p - mesh.vertices[v]).norm() < 1e-2) {
          ++matched;
          if (u.norm() > 1e-7) ++moved;
        }
      }
    }
    CHECK(matched == 15);  // each drawn point is exactly one vertex moved by its DOFs
    CHECK(moved == 3);     // the interior ones
    (void)d;
  }
}
