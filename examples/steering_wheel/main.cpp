// The steering-wheel impact of the PRADIS paper: a rigid head (6.8 kg, 165 mm)
// hits the junction of a spoke and the rim of a steel steering wheel at 7 m/s. The
// rim and the spokes are BEAM3 + BEAMI3 elements, the hub is fixed, the head is a
// BODY3 touching the wheel through CSPHSP sphere contacts at the wheel's nodes near
// the impact point (a penalty approximation). The model and its numbers are in
// steering_wheel_model.hpp; docs/steering_wheel.md describes it and the results.
//
// Prints the head's peak deceleration, the longest time and the total time it
// stays above 80 g (pradis/io/post.hpp), the rebound speed, the energy balance and
// the spring-mass estimate a_max = v0 sqrt(k/m) with the wheel's static stiffness
// k measured in the same model. Writes CSV, an animation (<dir>/vtk/steering_wheel.pvd:
// rim and spokes as lines, the head as an octahedron; open it in ParaView) and,
// unless --no-plot, a plot (PNG, with gnuplot).
//
// Usage: steering_wheel [output-directory] [--no-plot] [--quick] [--elastic] [--rim N]
//        (--quick: the first 2 ms, for the ctest smoke run;
//         --elastic: contact damping 0, to check the energy balance;
//         --rim N: N beam elements around the rim, a multiple of 4 (default 16))

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "pradis/integrators/simulation.hpp"
#include "pradis/io/post.hpp"
#include "pradis/io/table.hpp"
#include "pradis/io/vtk_series.hpp"
#include "steering_wheel_model.hpp"

int main(int argc, char** argv) try {
  using namespace pradis;
  std::string dir = "out";
  bool plot = true, quick = false, elastic = false;
  int rim = 16;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-plot") plot = false;
    else if (a == "--quick") quick = true;
    else if (a == "--elastic") elastic = true;
    else if (a == "--rim") rim = i + 1 < argc ? std::atoi(argv[++i]) : 0;
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: steering_wheel [output-directory] [--no-plot] [--quick] [--elastic] [--rim N]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);

  const double g = 9.81, threshold = 80;  // [m/s^2]; the deceleration threshold [g]
  steering_wheel::parameters P;
  if (elastic) P.c_contact = 0;
  if (rim < 4 || rim % 4 != 0) throw error(error_code::invalid_option, "--rim " + std::to_string(rim) + ": a multiple of 4 is needed");
  P.rim_segments = rim;
  steering_wheel::model_type m;
  const steering_wheel::handles h = steering_wheel::build(m, P);

  // Animation: the wheel's nodes joined by its members, the head as an octahedron.
  io::vtk_scene scene;
  std::vector<int> point;
  for (const auto& n : h.nodes) {
    const spatial::vec3 x0(n.pos[0], n.pos[1], n.pos[2]);
    point.push_back(n.ground ? scene.point(x0, n.x) : scene.body_point(x0, n.x, n.r, spatial::vec3::Zero()));
  }
  for (const auto& mb : h.members) scene.line(point[static_cast<std::size_t>(mb.a)], point[static_cast<std::size_t>(mb.b)]);
  const spatial::vec3 head0(h.head_pos[0], h.head_pos[1], h.head_pos[2]);
  const double rh = P.head_radius();
  std::array<int, 6> tip{};  // +x, -x, +y, -y, +z, -z
  for (int k = 0; k < 6; ++k) {
    spatial::vec3 o = spatial::vec3::Zero();
    o(k / 2) = k % 2 == 0 ? rh : -rh;
    tip[static_cast<std::size_t>(k)] = scene.body_point(head0, h.head_x, h.head_r, o);
  }
  for (int a : {0, 1})
    for (int b : {2, 3})
      for (int c : {4, 5}) scene.triangle(tip[static_cast<std::size_t>(a)], tip[static_cast<std::size_t>(b)], tip[static_cast<std::size_t>(c)]);
  scene.vertex(scene.body_point(head0, h.head_x, h.head_r, spatial::vec3::Zero()));
  io::vtk_series vtk(dir + "/vtk", "steering_wheel", scene);

  io::table out({"head deceleration [g]", "head displacement [mm]", "head velocity [m/s]", "contact force [N]",
                 "junction deflection [mm]", "kinetic energy [J]", "elastic energy [J]", "contact energy [J]",
                 "total energy [J]"});
  std::vector<double> t, decel, fz;
  double e_min = 1e300, e_max = 0;
  const auto& hit = h.nodes[static_cast<std::size_t>(h.impact)];
  long output = 0;
  simulation sim(m);  // Newmark's average acceleration: no numerical damping
  sim.on_output([&](const auto& s) {
    const auto f = steering_wheel::head_force(s, m, h);
    const double a = f[2] / P.head_mass / g;  // deceleration: the force against the motion (+Z)
    const auto e = steering_wheel::energy(m, h, P);
    e_min = std::min(e_min, e.total());
    e_max = std::max(e_max, e.total());
    t.push_back(s.time());
    decel.push_back(a);
    fz.push_back(f[2]);
    if (output++ % 50 == 0) vtk.write(s);  // every 0.5 ms
    out.add_row(s.time(), {a, -s.u(h.head_x[2]) * 1e3, s.v(h.head_x[2]), std::hypot(f[0], f[1], f[2]),
                           -s.u(hit.x[2]) * 1e3, e.kinetic, e.elastic, e.contact, e.total()});
  });
  const double end = quick ? 0.002 : 0.025, step = 1e-5;
  const auto t0 = std::chrono::steady_clock::now();
  sim.run({.end = end, .out = 0, .smax = step});
  const double cpu = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::string csv = dir + "/steering_wheel.csv";
  out.write_csv(csv);
  const auto& st = sim.statistics();
  const post::peak_value pk = post::peak(t, decel);
  const post::interval above = post::longest_above(t, decel, threshold);
  const double total_above = post::cumulative_above(t, decel, threshold);
  const double e0 = 0.5 * P.head_mass * P.v0 * P.v0;
  double impulse = 0;  // of the contact forces on the head along Z (trapezoidal rule over the steps)
  for (std::size_t i = 1; i < t.size(); ++i) impulse += 0.5 * (t[i] - t[i - 1]) * (fz[i] + fz[i - 1]);
  // The spring-mass estimate: the head on the wheel's static stiffness at the junction in
  // series with the contact spring: a_max = v0 sqrt(k/m), contact time pi sqrt(m/k).
  const double k_wheel = steering_wheel::static_stiffness(P, 10.0);
  const double k = k_wheel * P.k_contact / (k_wheel + P.k_contact), w = std::sqrt(k / P.head_mass);
  std::cout << "steering wheel: " << out.rows() << " output rows to " << csv << "\n"
            << "animation: " << vtk.frames() << " frames, " << vtk.collection().string() << " (ParaView)\n"
            << "simulated " << end << " s, step " << step << " s, " << m.dof_count() << " DOFs, " << h.contacts.size()
            << " contact spheres" << (elastic ? ", elastic contact (c = 0)" : "") << "\n"
            << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations " << st.newton_iterations
            << "; CPU (wall) time " << cpu << " s\n"
            << "peak head deceleration " << pk.value << " g at " << pk.time * 1e3 << " ms\n";
  if (above.found())
    std::cout << "longest time above " << threshold << " g: " << above.duration * 1e3 << " ms (" << above.start * 1e3
              << " to " << above.end * 1e3 << " ms); in total " << total_above * 1e3 << " ms\n";
  else
    std::cout << "the deceleration stays below " << threshold << " g\n";
  std::cout << "head velocity at the end " << sim.v(h.head_x[2]) << " m/s (impact " << -P.v0 << " m/s); momentum change "
            << P.head_mass * (sim.v(h.head_x[2]) + P.v0) << " N s, impulse of the contact forces " << impulse << " N s\n"
            << "energy: initial " << e0 << " J, total over the run " << e_min << " .. " << e_max << " J, at the end "
            << steering_wheel::energy(m, h, P).total() << " J\n"
            << "spring-mass estimate: wheel stiffness " << k_wheel << " N/m (static, at the junction), with the "
            << "contact spring " << k << " N/m: a_max = v0 sqrt(k/m) = " << P.v0 * w / g << " g, contact time "
            << std::numbers::pi / w * 1e3 << " ms\n";
  if (plot) {
    const std::string png = dir + "/steering_wheel.png", script = png + ".gp";
    if ((csv + png).find_first_of("'\"\n\\`$") != std::string::npos)
      throw error(error_code::io_error, "cannot plot to '" + png + "': the path contains a quote or special character");
    {
      std::ofstream gp(script);
      if (!gp) throw error(error_code::io_error, "cannot write '" + script + "'");
      // The spring-mass half sine a_max sin(w t') from the first touch (the gap closes at v0).
      const double t_touch = P.gap / P.v0;
      gp << "set datafile separator ','\nset terminal pngcairo size 900,800 font 'sans,10'\n"
         << "set output '" << png << "'\nset grid\n"
         << "set multiplot layout 2,1 title 'head (6.8 kg, 165 mm) hitting a steering wheel at 7 m/s'\n"
         << "set xrange [0:" << end * 1e3 << "]\nset xlabel 't [ms]'\nset ylabel 'head deceleration [g]'\n"
         << "am = " << P.v0 * w / g << "; w = " << w << "; t0 = " << t_touch << "\n"
         << "sm(x) = (x/1e3 > t0 && x/1e3 < t0 + pi/w) ? am*sin(w*(x/1e3 - t0)) : 0\n"
         << "set samples 500\n"
         << "plot '" << csv << "' using ($1*1e3):2 every ::1 with lines lw 2 title 'pradis', sm(x) with lines dt 2 "
         << "title 'spring-mass estimate', " << threshold << " with lines lc rgb 'red' dt 3 title '" << threshold << " g'\n"
         << "set ylabel 'displacement [mm]'\n"
         << "plot '" << csv << "' using ($1*1e3):3 every ::1 with lines title 'head', '' using ($1*1e3):6 every ::1 "
         << "with lines title 'spoke-rim junction'\n"
         << "unset multiplot\n";
    }
    const std::string cmd = "gnuplot '" + script + "' 2>/dev/null";
    if (std::system(cmd.c_str()) == 0)
      std::cout << "plot: " << png << "\n";
    else
      std::cout << "gnuplot failed or is missing: plot with  gnuplot '" << script << "'  (deceleration: column 2 of "
                << csv << " against column 1)\n";
  }
  return 0;
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
