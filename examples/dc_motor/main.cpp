// A DC motor run-up: a tabulated voltage source (VTAB: a 50 ms ramp to 24 V, a step
// down to 12 V at 0.6 s) feeds a permanent-magnet DC motor (DCM: R = 1.2 Ohm,
// L = 3 mH, k = 0.08 V s/rad) that drives an inertia (MASS, J = 1e-4 kg m^2) against
// a constant load torque (F, 0.05 N m) and viscous friction (DAMPER, 1e-5 N m s).
// The speed settles at w = (k V - R T) / (k^2 + R b) after each voltage change
// (steady state of V = R i + k w, k i = T + b w), which the program prints next to
// the simulated value.
//
// Writes voltage, armature current, speed and torque as CSV.
//
// Usage: dc_motor [output-directory] [--quick]
//        (--quick: 0.3 s instead of 1.2 s, for the ctest smoke run)

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/table.hpp"

int main(int argc, char** argv) try {
  using namespace pradis;
  using namespace pradis::elements;
  std::string dir = "out";
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: dc_motor [output-directory] [--quick]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);

  const double r = 1.2, l = 3e-3, k = 0.08, j = 1e-4, load = 0.05, b = 1e-5;
  model<voltage_table, dc_motor, point_mass, constant_force, linear_damper> m;
  const dof supply = m.add_dof("supply"), shaft = m.add_dof("shaft");
  m.add<voltage_table>("V", {{0.0, 0.0, 0.05, 24.0, 0.6, 24.0, 0.601, 12.0}}, supply);
  m.add<dc_motor>("M", {r, l, k}, supply, m.ground(), shaft);
  m.add<point_mass>("J", {j}, shaft);
  m.add<constant_force>("load", {-load}, shaft);
  m.add<linear_damper>("friction", {b}, shaft, m.ground());

  io::table out({"voltage [V]", "current [A]", "speed [rad/s]", "torque [N m]"});
  simulation sim(m);
  sim.on_output([&](const auto& s) {
    const auto w = s.get_model().work("M");
    out.add_row(s.time(), {s.v(supply), w[0], s.v(shaft), w[1]});
  });
  const auto steady = [&](double v) { return (k * v - r * load) / (k * k + r * b); };
  const auto report = [&](double v) {
    std::printf("t = %.3f s: speed %.6f rad/s, steady state (k V - R T)/(k^2 + R b) = %.6f rad/s\n", sim.time(),
                sim.v(shaft), steady(v));
  };
  const run_options opt{.end = 0.3, .out = 1e-3, .smax = 1e-4};
  sim.run(opt);
  report(24.0);
  if (!quick) {
    run_options o2 = opt;
    o2.end = 0.6;
    sim.run(o2);
    report(24.0);
    o2.end = 1.2;
    sim.run(o2);
    report(12.0);
  }
  const std::string csv = dir + "/dc_motor.csv";
  out.write_csv(csv);
  std::cout << "dc_motor: " << out.rows() << " output rows to " << csv << "\n";
  const auto& st = sim.statistics();
  std::cout << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations "
            << st.newton_iterations << "\n";
  return 0;
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
