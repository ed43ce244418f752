// A hydraulic drive: a fixed-displacement pump (HPUMP, 10 cm^3/rev at 150 rad/s, about
// 14 l/min) feeds the supply line (HVOL, 0.5 l) protected by a relief valve (HRELIEF,
// cracking at 100 bar, fully open at 110 bar). A 4/3 servo valve (HV43) drives a
// double-acting cylinder (HCYL, bore 40 mm, rod 22 mm, stroke 0.5 m) that moves a mass of
// 200 kg against viscous friction. The spool follows a sinusoidal command (0.5 Hz, full
// stroke) through a first-order lag of 10 ms, built from mechanical elements: SPRING k from
// the command DOF (XSRC) to the spool and DAMPER k tau from the spool to the ground.
// When the valve is closed or the piston stands at an end stop, the pump flow goes over the
// relief valve and the supply pressure rises to its setting.
//
// Writes hydraulic_cylinder.csv: spool position, supply and chamber pressures, piston
// position and speed, relief flow.
//
// Usage: hydraulic_cylinder [output-directory] [--quick]

#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
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
      std::cout << "usage: hydraulic_cylinder [output-directory] [--quick]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);

  constexpr double pi = std::numbers::pi, oil_b = 1.5e9, oil_rho = 850, dpt = 1e3;
  const double bore = 0.04, rod = 0.022;
  const double area_a = pi * bore * bore / 4, area_b = area_a - pi * rod * rod / 4;
  const double xmax = 1e-3, k_spool = 1e3, tau = 0.01;

  model<hydraulic_pump, hydraulic_volume, relief_valve, valve_43, hydraulic_cylinder, point_mass, linear_spring,
        linear_damper, velocity_source, displacement_source>
      m;
  const dof shaft = m.add_dof("shaft"), p = m.add_dof("P"), a = m.add_dof("A"), b = m.add_dof("B");
  const dof x = m.add_dof("piston"), spool = m.add_dof("spool"), command = m.add_dof("command");
  m.add<velocity_source>("drive", {.offset = 150.0}, shaft);
  m.add<hydraulic_pump>("pump", {1e-5 / (2 * pi), 1e-13, 0.0}, m.ground(), p, shaft);
  m.add<hydraulic_volume>("supply line", {.volume = 5e-4, .bulk_modulus = oil_b}, p);
  m.add<relief_valve>("relief", {0.7, 2e-5, oil_rho, dpt, 100e5, 10e5, 0.0}, p, m.ground());
  m.add<valve_43>("servo valve", {0.7, 2e-5, oil_rho, dpt, xmax, 1e-9}, p, m.ground(), a, b, spool);
  m.add<displacement_source>("command", {.amplitude = xmax, .frequency = 0.5}, command);
  m.add<linear_spring>("spool lag spring", {k_spool}, command, spool);
  m.add<linear_damper>("spool lag damper", {k_spool * tau}, spool, m.ground());
  m.add<hydraulic_cylinder>("cylinder", {area_a, area_b, 0.5, 0.25, 5e-5, 5e-5, oil_b, 1e8, 1e5, 1e-4}, a, b, x);
  m.add<point_mass>("load", {200.0}, x);
  m.add<linear_damper>("friction", {2000.0}, x, m.ground());

  io::table out({"spool [m]", "supply pressure [Pa]", "pressure A [Pa]", "pressure B [Pa]", "piston position [m]",
                 "piston speed [m/s]", "relief flow [m^3/s]"});
  simulation sim(m);
  sim.on_output([&](const auto& s) {
    const auto& md = s.get_model();
    out.add_row(s.time(), {s.u(spool), s.v(p), s.v(a), s.v(b), md.work("cylinder")[0], s.v(x), md.work("relief")[0]});
  });
  sim.run({.end = quick ? 0.5 : 4.0, .out = 0.005, .smax = 5e-4});

  const std::string csv = dir + "/hydraulic_cylinder.csv";
  out.write_csv(csv);
  std::cout << "hydraulic_cylinder: " << out.rows() << " output rows to " << csv << "\n";
  const auto& st = sim.statistics();
  std::cout << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations "
            << st.newton_iterations << "\n";
  std::cout << "at t = " << sim.time() << " s: supply " << sim.v(p) / 1e5 << " bar, A " << sim.v(a) / 1e5 << " bar, B "
            << sim.v(b) / 1e5 << " bar, piston at " << m.work("cylinder")[0] << " m\n";
  return 0;
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
