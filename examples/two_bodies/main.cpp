// The two-body system of the PRADIS element developer's manual, Fig. 3.3 and
// section 3.6.9: two bodies in plane motion (MD), joined at their centres of
// gravity by an ideal elastic link (LINKD, k = 5e3 N/m), with a force of 1e3 N
// acting vertically downward on body 2. Body 1 starts at (1, 1) with mass 1 kg
// and J = 0.1 kg m^2; body 2 at (2, 2) with mass 2 kg and J = 0.1 kg m^2.
// Integrated with the Stoermer scheme (SHTERM) to END = 1 s.
//
// Writes the manual's outputs: body 2 X and Y displacement, link length W(2)
// and link force W(3), as CSV, and a plot (PNG, with gnuplot) unless --no-plot.
//
// Usage: two_bodies [output-directory] [--no-plot]

#include <filesystem>
#include <iostream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/table.hpp"
#include "common/gnuplot.hpp"

int main(int argc, char** argv) try {
  using namespace pradis;
  using namespace pradis::elements;
  std::string dir = "out";
  bool plot = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-plot") plot = false;
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: two_bodies [output-directory] [--no-plot]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);

  // Only the element types this scene uses are compiled in.
  model<planar_inertia, planar_link, constant_force> m;
  const auto d = m.add_dofs(6, "DOF ");  // body 1: DOFs 1 2 3, body 2: DOFs 4 5 6
  m.add<planar_inertia>("Body 1", {.m = 1.0, .j = 0.1}, d[0], d[1], d[2]);
  m.add<planar_inertia>("Body 2", {.m = 2.0, .j = 0.1}, d[3], d[4], d[5]);
  const auto link = m.add<planar_link>("Connection", {1, 1, 2, 2, 5e3}, d[0], d[1], d[3], d[4]);
  m.add<constant_force>("Force", {.force = -1e3}, d[4]);  // 1e3 N downward on DOF 5

  io::table out({"body 2 X displacement [m]", "body 2 Y displacement [m]", "link length [m]", "link force [N]"});
  simulation sim(m, stoermer{});
  sim.on_output([&](const auto& s) {
    const auto w = s.get_model().work("Connection");
    out.add_row(s.time(), {s.u(d[3]), s.u(d[4]), w[1], w[2]});
  });
  sim.run({.end = 1.0, .out = 0.005, .smax = 1e-4,
           .newton = {.dabsu = 1e-8, .drltu = 1e-8, .dabsi = 1e-6, .drlti = 1e-8}});
  (void)link;

  const std::string csv = dir + "/two_bodies.csv";
  out.write_csv(csv);
  std::cout << "two_bodies: " << out.rows() << " output rows to " << csv << "\n";
  const auto& st = sim.statistics();
  std::cout << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations "
            << st.newton_iterations << ", factorisations " << st.factorizations << "\n";
  std::cout << "at t = 1 s: body 2 X = " << sim.u(d[3]) << " m, Y = " << sim.u(d[4])
            << " m, link length = " << m.work("Connection")[1] << " m, link force = " << m.work("Connection")[2]
            << " N\n";
  if (plot) {
    const std::string png = dir + "/two_bodies.png";
    const std::string why = pradis_apps::plot_png(out.names(), csv, png,
                                                  "two bodies joined by LINKD (manual Fig. 3.3)");
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
