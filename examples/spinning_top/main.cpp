// The heavy symmetric top (Lagrange top): a rigid body (BODY3) symmetric about its
// Z axis, its tip held at the origin by a spherical joint (SPH3, penalty stiffness
// 1e6 N/m), under gravity (a constant F3 on the centre of mass), spinning at
// w3 = 30 rad/s about its axis, released at 30 degrees from the vertical with no
// precession or nutation rate. The axis nods between 30 degrees and the turning
// point of Goldstein's cubic f(u) (Classical Mechanics, 3rd ed., section 5.7;
// 33.63 degrees for these data) while it precesses at a mean 1.717 rad/s; the
// test tests/spatial/test_joints.cpp checks both against the analytic values.
//
// Writes the trajectory of the top's axis tip (the body point 2 l from the pivot
// along the axis), the polar and azimuth angles of the axis and the joint gap, as
// CSV, an animation every 10 ms as a VTK time series (<dir>/vtk/spinning_top.pvd:
// pivot, axis and a disc; open it in ParaView), and a plot (PNG, with gnuplot)
// unless --no-plot.
//
// Usage: spinning_top [output-directory] [--no-plot] [--quick] [--k STIFFNESS] [--exact] [--pivot]
//        (--quick: 0.5 s instead of 5 s, for the ctest smoke run; --k: the penalty
//        stiffness of SPH3 [N/m], default 1e6; --exact: the exact joint SPH3X instead;
//        --pivot: a ground pivot instead, SPH3X's reduced form without multipliers,
//        pradis::elements::add_ground_pivot)

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "top_model.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/table.hpp"
#include "pradis/io/vtk_series.hpp"
#include "common/gnuplot.hpp"
#include "pradis/spatial/node_state.hpp"

int main(int argc, char** argv) try {
  using namespace pradis;
  using namespace pradis::elements;
  using spatial::vec3;
  std::string dir = "out";
  bool plot = true, quick = false;
  pradis_examples::top_parameters params;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-plot") plot = false;
    else if (a == "--quick") quick = true;
    else if (a == "--exact") params.exact_joint = true;
    else if (a == "--pivot") params.exact_joint = params.ground_pivot = true;
    else if (a == "--k") {
      std::size_t used = 0;
      const std::string v = i + 1 < argc ? argv[++i] : "";
      try {
        params.k = std::stod(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (v.empty() || used != v.size() || !(params.k > 0) || !std::isfinite(params.k)) {
        std::cerr << "spinning_top: --k needs a finite stiffness > 0 [N/m], got '" << v << "'\n";
        return 2;
      }
    } else if (a == "--help" || a == "-h") {
      std::cout << "usage: spinning_top [output-directory] [--no-plot] [--quick] [--k STIFFNESS] [--exact] [--pivot]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);

  const double pi = std::numbers::pi;
  pradis_examples::spinning_top top(params);
  auto& m = top.m;
  const rotation_node r = top.r;
  const double l = top.l;

  io::table out({"axis tip X [m]", "axis tip Y [m]", "axis tip Z [m]", "polar angle [deg]", "azimuth [deg]",
                 "joint gap [m]"});
  // Animation (ParaView): the pivot, the axis from the tip through the centre of
  // mass to its top, and a disc of 8 triangles at the centre of mass.
  io::vtk_scene scene;
  const vec3 c0 = l * top.axis0();
  const int pivot = scene.point({0, 0, 0}, {m.ground(), m.ground(), m.ground()});
  const std::array<dof, 3> xc{top.x[0], top.x[1], top.x[2]};
  const int centre = scene.body_point(c0, xc, r, vec3::Zero());
  const int head = scene.body_point(c0, xc, r, {0, 0, l});
  scene.line(pivot, centre);
  scene.line(centre, head);
  std::vector<int> rim;
  for (int k = 0; k < 8; ++k)
    rim.push_back(scene.body_point(c0, xc, r, {0.05 * std::cos(k * pi / 4), 0.05 * std::sin(k * pi / 4), 0}));
  for (std::size_t k = 0; k < 8; ++k) scene.triangle(centre, rim[k], rim[(k + 1) % 8]);
  io::vtk_series vtk(dir + "/vtk", "spinning_top", scene);
  long output = 0;
  simulation sim(m);
  double max_gap = 0;
  sim.on_output([&](const auto& s) {
    if (output++ % 5 == 0) vtk.write(s);  // every 10 ms
    // The joint gap: W(1) of SPH3 / SPH3X; with the ground pivot, the tip's distance from the origin.
    const vec3 c = c0 + vec3(s.u(top.x[0]), s.u(top.x[1]), s.u(top.x[2]));
    const double gap = params.ground_pivot ? (c + spatial::node_rotation(s, r) * vec3(0, 0, -l)).norm()
                                           : s.get_model().work("tip")[0];
    max_gap = std::max(max_gap, gap);
    const vec3 ax = spatial::node_rotation(s, r).col(2);
    const vec3 tip = 2 * l * ax;  // the pivot stays at the origin (up to the joint gap)
    out.add_row(s.time(), {tip.x(), tip.y(), tip.z(), std::acos(ax.z()) * 180 / pi,
                           std::atan2(ax.y(), ax.x()) * 180 / pi, gap});
  });
  const double end = quick ? 0.5 : 5.0;
  sim.run({.end = end, .out = 0.002, .smax = 1e-3,
           .newton = {.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-10, .drlti = 0}});

  const std::string csv = dir + "/spinning_top.csv";
  out.write_csv(csv);
  std::cout << "spinning_top: " << out.rows() << " output rows to " << csv << "\n";
  std::cout << "animation: " << vtk.frames() << " frames, " << vtk.collection().string() << " (ParaView)\n";
  const auto& st = sim.statistics();
  std::cout << (params.ground_pivot  ? "joint: ground pivot (SPH3X's reduced form)"
                : params.exact_joint ? "joint: SPH3X (exact)"
                                     : "joint: SPH3, k = " + std::to_string(params.k) + " N/m")
            << "; largest joint gap " << max_gap << " m\n";
  std::cout << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations "
            << st.newton_iterations << "\n";
  if (plot) {
    const std::string png = dir + "/spinning_top.png";
    const std::string why = pradis_apps::plot_png(out.names(), csv, png,
                                                  "heavy symmetric top on SPH3: tip trajectory and angles");
    if (!why.empty())
      std::cerr << "warning: " << why << "\n";
    else
      std::cout << "plot: " << png << "\n";
  }
  return 0;
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
