// The crankshaft of the PRADIS paper (Fig. 3): a single-cylinder crank mechanism
// (crankshaft of BEAM3 + BEAMI3 elements in two main bearings, flywheel, pulley,
// connecting rod, piston, gas force, camshaft resistance, belt load) driven through
// an elastic coupling (SHC3) from rest to 5000 rev/min; the result is the radial
// runout of the main journals in their bearings against the engine speed. The model
// and all its numbers are in crankshaft_model.hpp.
//
// Writes CSV (time, speed, runout of both main journals, piston position, drive
// torque, big-end force), an animation every 2 ms as a VTK time series
// (<dir>/vtk/crankshaft.pvd: shaft nodes and beams, rod, piston; open it in
// ParaView) and, unless --no-plot, a plot (PNG, with gnuplot).
//
// Usage: crankshaft [output-directory] [--no-plot] [--quick] [--no-gas] [--cb] [--bdf]
//        (--quick: the first 0.04 s of the run-up, for the ctest smoke run;
//         --no-gas: without the gas force, to see the inertia forces alone;
//         --cb: the shaft as one Craig-Bampton body, FLEX3, instead of the beams;
//         --bdf: the variable-order BDF driver under error control, DRLTX = DABSX = 1e-4,
//         with the angular DOFs at the nominal potential 100 rad/s (crankshaft::
//         scale_angular_dofs; docs/bdf.md, "Stiff, excited modes: the crankshaft"),
//         instead of the default one-step scheme at fixed steps of 0.1 ms)

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
#include <type_traits>

#include "crankshaft_model.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/table.hpp"
#include "pradis/io/vtk_series.hpp"
#include "pradis/spatial/node_state.hpp"

namespace {

/// Runs the example on a model of type Model (crankshaft::model_type or cb_model_type),
/// with the BDF driver when Bdf, else with the default one-step scheme.
template <class Model, bool Bdf>
int run(const std::string& dir, bool plot, bool quick, bool gas) {
  using namespace pradis;
  const double pi = std::numbers::pi, rpm = 60 / (2 * pi);
  crankshaft::parameters P;
  if (!gas) P.p_peak = 0;
  Model m;
  const crankshaft::handles h = crankshaft::build(m, P);
  if constexpr (Bdf) crankshaft::scale_angular_dofs(m, h, 100.0);
  const double y_tdc = P.r + P.l;  // piston pin at top dead centre

  io::table out({"speed [rev/min]", "drive speed [rev/min]", "runout bearing 1 [um]", "runout bearing 2 [um]",
                 "piston position [m]", "drive torque [N m]", "big-end force [N]"});
  // Animation (ParaView): the shaft's nodes joined by its beams, the rod, the piston.
  io::vtk_scene scene;
  std::vector<int> node;
  for (std::size_t i = 0; i < h.pos.size(); ++i)
    if (h.present[i])  // with --cb the inner nodes are condensed: the line joins the boundary nodes
      node.push_back(scene.body_point({h.pos[i][0], h.pos[i][1], h.pos[i][2]}, h.x[i], h.r[i], spatial::vec3::Zero()));
  for (std::size_t i = 0; i + 1 < node.size(); ++i) scene.line(node[i], node[i + 1]);
  const spatial::vec3 rod0(h.rod_pos[0], h.rod_pos[1], h.rod_pos[2]);
  const int big = scene.body_point(rod0, h.rod_x, h.rod_r, {0, -P.l / 2, 0});
  const int small = scene.body_point(rod0, h.rod_x, h.rod_r, {0, P.l / 2, 0});
  scene.line(big, small);
  scene.vertex(scene.point({h.rod_pos[0], y_tdc, 0}, {m.ground(), h.py, m.ground()}));
  scene.vertex(node.back());  // the flywheel
  io::vtk_series vtk(dir + "/vtk", "crankshaft", scene);
  long output = 0;
  double next_frame = 0;  // BDF: the time of the next animation frame
  auto make = [&] {
    if constexpr (Bdf) return bdf_simulation(m);
    else return simulation(m);
  };
  auto sim = make();
  double peak1 = 0, peak2 = 0, peak_speed1 = 0, worst_lag = 0, worst_law = 0;
  std::array<double, 10> band{};  // peak runout of bearing 1 per 500 rev/min band of the speed
  sim.on_output([&](const auto& s) {
    const double w = spatial::node_angular_velocity(s, h.r[1]).x();
    auto runout = [&](int i) {
      const auto& x = h.x[static_cast<std::size_t>(i)];
      return std::hypot(s.u(x[1]), s.u(x[2]));
    };
    const double r1 = runout(1), r2 = runout(7);
    if (r1 > peak1) peak1 = r1, peak_speed1 = w * rpm;
    peak2 = std::max(peak2, r2);
    const auto b1 = m.work(h.bearing1);  // gap, force on the journal
    if (b1[0] > 10e-6)  // bearing law: force = k gap (+ the damping c gap', small)
      worst_law = std::max(worst_law, std::abs(std::hypot(b1[1], b1[2], b1[3]) / (P.k_bearing * b1[0]) - 1));
    worst_lag = std::max(worst_lag, std::abs(w - s.v(h.phi)) * rpm);
    const int k = std::clamp(static_cast<int>(w * rpm / 500), 0, 9);
    band[static_cast<std::size_t>(k)] = std::max(band[static_cast<std::size_t>(k)], r1);
    if constexpr (Bdf) {  // the steps vary: the first output at or after every 2 ms
      if (s.time() >= next_frame - 1e-12) {
        vtk.write(s);
        next_frame += 2e-3;
      }
    } else if (output++ % 20 == 0) {
      vtk.write(s);  // every 2 ms
    }
    const auto fb = m.work(h.big_end);
    out.add_row(s.time(), {w * rpm, s.v(h.phi) * rpm, r1 * 1e6, r2 * 1e6, y_tdc + s.u(h.py), m.work(h.drive)[2],
                           std::hypot(fb[1], fb[2], fb[3])});
  });
  const double end = quick ? 0.04 : P.t_run, step = 1e-4;
  const auto t0 = std::chrono::steady_clock::now();
  run_options o{.end = end, .out = 0, .smax = step};
  if constexpr (Bdf) {
    o.smax = 1e-3;
    o.smin = 1e-12;
    o.error_control = true;
    o.drltx = 1e-4;
    o.dabsx = 1e-4;
  }
  sim.run(o);
  const double cpu = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::string csv = dir + "/crankshaft.csv";
  out.write_csv(csv);
  const auto& st = sim.statistics();
  std::cout << "crankshaft: " << out.rows() << " output rows to " << csv << "\n"
            << "shaft: "
            << (std::is_same_v<Model, crankshaft::cb_model_type> ? "one Craig-Bampton body (FLEX3, 5 boundary nodes, 6 modes)"
                                                                 : "8 BEAM3 + BEAMI3")
            << "\n"
            << "animation: " << vtk.frames() << " frames, " << vtk.collection().string() << " (ParaView)\n"
            << "simulated " << end << " s (run-up to " << P.w_end * rpm * std::sin(pi / 2 * end / P.t_run)
            << " rev/min), ";
  if constexpr (Bdf)
    std::cout << "driver: BDF, DRLTX = DABSX = 1e-4, angular DOFs at 100 rad/s";
  else
    std::cout << "driver: one-step scheme, step " << step << " s";
  std::cout << ", " << m.dof_count() << " DOFs\n"
            << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations "
            << st.newton_iterations << "\n"
            << "CPU (wall) time " << cpu << " s, " << cpu / end << " s per simulated second\n"
            << "peak runout: bearing 1 " << peak1 * 1e6 << " um (at " << peak_speed1 << " rev/min), bearing 2 "
            << peak2 * 1e6 << " um\n"
            << "speed - drive speed: max |difference| " << worst_lag << " rev/min; bearing 1: max | |F| / (k gap) - 1 | "
            << worst_law << " (gap > 10 um)\npeak runout of bearing 1 per speed band:\n";
  for (std::size_t k = 0; k < band.size(); ++k)
    if (band[k] > 0) std::cout << "  " << 500 * k << "-" << 500 * (k + 1) << " rev/min: " << band[k] * 1e6 << " um\n";
  if (plot) {
    // Runout against speed (the figure of the example) and the time histories.
    const std::string png = dir + "/crankshaft.png", script = png + ".gp";
    if ((csv + png).find_first_of("'\"\n\\`$") != std::string::npos)
      throw error(error_code::io_error, "cannot plot to '" + png + "': the path contains a quote or special character");
    {
      std::ofstream g(script);
      if (!g) throw error(error_code::io_error, "cannot write '" + script + "'");
      g << "set datafile separator ','\nset terminal pngcairo size 900,1000 font 'sans,10'\n"
        << "set output '" << png << "'\nset grid\n"
        << "set multiplot layout 3,1 title 'crankshaft run-up to 5000 rev/min'\n"
        << "set xrange [0:*]\nset xlabel 'speed [rev/min]'\nset ylabel 'radial runout [um]'\n"
        << "plot '" << csv << "' using 2:4 every ::1 with lines title 'main bearing 1 (pulley side)', '' using 2:5 "
        << "every ::1 with lines title 'main bearing 2 (flywheel side)'\n"
        << "set autoscale x\nset xlabel 't [s]'\nset ylabel 'speed [rev/min]'\n"
        << "plot '" << csv << "' using 1:2 every ::1 with lines title 'crankshaft', '' using 1:3 every ::1 with lines "
        << "dt 2 title 'drive'\n"
        << "set ylabel 'drive torque [N m]'\nplot '" << csv << "' using 1:7 every ::1 with lines notitle\n"
        << "unset multiplot\n";
    }
    const std::string cmd = "gnuplot '" + script + "' 2>/dev/null";
    if (std::system(cmd.c_str()) == 0)
      std::cout << "plot: " << png << "\n";
    else
      std::cout << "gnuplot failed or is missing: plot with  gnuplot '" << script << "'  (runout: columns 4 and 5 "
                << "of " << csv << " against column 2)\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string dir = "out";
  bool plot = true, quick = false, gas = true, cb = false, bdf = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-plot") plot = false;
    else if (a == "--quick") quick = true;
    else if (a == "--no-gas") gas = false;
    else if (a == "--cb") cb = true;
    else if (a == "--bdf") bdf = true;
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: crankshaft [output-directory] [--no-plot] [--quick] [--no-gas] [--cb] [--bdf]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);
  if (cb)
    return bdf ? run<crankshaft::cb_model_type, true>(dir, plot, quick, gas)
               : run<crankshaft::cb_model_type, false>(dir, plot, quick, gas);
  return bdf ? run<crankshaft::model_type, true>(dir, plot, quick, gas)
             : run<crankshaft::model_type, false>(dir, plot, quick, gas);
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
