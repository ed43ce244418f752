// A ball bouncing into a valley: a disc (MD with ELLPL, radius 0.1 m, 1 kg) is
// thrown at 1 m/s from (-0.5, 1.5) onto a polyline floor that slopes down, runs
// flat from x = 1 to 3 and slopes up again. Each impact is a Hunt-Crossley
// contact (Hertz exponent 1.5, k = 1e7 N/m^1.5, d = 1 s/m); Coulomb friction
// (mu_s = 0.4, mu_k = 0.3) with a stick state turns the sliding after each
// impact into rolling. The run is error-controlled (HHT); ELLPL's STEPMD brings
// every approach to the floor down to the contact's resolution, so no impact is
// stepped over. The bounces die out on the flat part and the ball then rolls.
//
// For each impact the program prints the normal approach and rebound speeds
// and the rebound speed that the Hunt-Crossley law gives for that approach
// speed (x - ln(1 + x) = -y - ln(1 - y), x = d v_in, y = d v_out; docs/contact.md);
// gravity and friction during the contact, and hits in a corner that touch two
// segments, make them differ.
//
// Writes x, y, rotation, normal force and contact mode as CSV, and a plot
// (PNG, with gnuplot) unless --no-plot. The same scene as a model file:
// examples/models/bouncing_ball.prd.
//
// Usage: bouncing_ball [output-directory] [--quick] [--no-plot]
//        (--quick: 0.8 s instead of 4 s, for the ctest smoke run)

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/gnuplot.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/io/table.hpp"

namespace {
/// The rebound speed of the Hunt-Crossley law for the approach speed v (bisection).
double hunt_crossley_rebound(double d, double v) {
  if (d <= 0) return v;
  const double x = d * v, c = x - std::log1p(x);
  double lo = 0, hi = x;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mid + std::log1p(-mid) + c > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) / d;
}
}  // namespace

int main(int argc, char** argv) try {
  using namespace pradis;
  using namespace pradis::elements;
  std::string dir = "out";
  bool quick = false, plot = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--no-plot") plot = false;
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: bouncing_ball [output-directory] [--quick] [--no-plot]\n";
      return 0;
    } else dir = a;
  }
  std::filesystem::create_directories(dir);

  const double m = 1.0, r = 0.1, j = 0.5 * m * r * r, g = 9.81, k = 1e7, d = 1.0, kt = 1e6;
  const std::vector<double> floor{-1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 5.0, 2.0};
  model<planar_inertia, ellipse_contact, constant_force, initial_velocity> md;
  const dof x = md.add_dof("x"), y = md.add_dof("y"), phi = md.add_dof("phi");
  md.add<planar_inertia>("ball", {m, j}, x, y, phi);
  md.add<constant_force>("weight", {-m * g}, y);
  md.add<initial_velocity>("throw", {1.0}, x);
  const auto contact = md.add<ellipse_contact>(
      "floor", {-0.5, 1.5, 0.0, r, r, k, 1.5, d, 0.4, 0.3, kt, 2 * std::sqrt(kt * m / 3), floor}, x, y, phi);

  io::table out({"x [m]", "y [m]", "rotation [rad]", "normal force [N]", "mode"});
  simulation<decltype(md), alpha_family> sim(md, alpha_family(hht{-0.1}));
  // Impacts: the normal speed on entering and on leaving contact with a segment.
  struct impact {
    double t, v_in, v_out;
  };
  std::vector<impact> impacts;
  std::vector<double> last_depth(3, -1.0);
  double v_in = 0;
  sim.on_output([&](const auto& s) {
    const auto w = md.work(contact);
    double normal = 0;
    int mode = 0;
    for (int i = 0; i < 3; ++i) {
      const double depth = w[5 + 4 * i];  // the normal force: > 0 in contact
      normal += w[5 + 4 * i];
      mode = std::max(mode, static_cast<int>(w[7 + 4 * i]));
      // Normal speed of the centre towards segment i: -(v . n).
      const double tx = floor[2 * i + 2] - floor[2 * i], ty = floor[2 * i + 3] - floor[2 * i + 1];
      const double l = std::hypot(tx, ty), vn = -(-ty / l * s.v(x) + tx / l * s.v(y));
      if (last_depth[i] <= 0 && depth > 0) v_in = vn;
      if (last_depth[i] > 0 && depth <= 0 && v_in > 0.05) impacts.push_back({s.time(), v_in, -vn});
      last_depth[i] = depth;
    }
    out.add_row(s.time(), {s.u(x), s.u(y), s.u(phi), normal, static_cast<double>(mode)});
  });
  sim.run({.end = quick ? 0.8 : 4.0, .smax = 0.01, .error_control = true, .drltx = 1e-5});

  for (const auto& i : impacts)
    std::printf("impact at t = %.4f s: approach %.4f m/s, rebound %.4f m/s, Hunt-Crossley law %.4f m/s\n", i.t, i.v_in,
                i.v_out, hunt_crossley_rebound(d, i.v_in));
  const std::string csv = dir + "/bouncing_ball.csv";
  out.write_csv(csv);
  std::cout << "bouncing_ball: " << out.rows() << " output rows to " << csv << "\n";
  const auto& st = sim.statistics();
  std::cout << "steps " << st.steps << ", rejected " << st.rejected_steps << ", Newton iterations "
            << st.newton_iterations << "\n";
  if (plot) {
    const std::string png = dir + "/bouncing_ball.png";
    const std::string why = pradis_apps::plot_png(out.names(), csv, png, "Ball bouncing into a valley (ELLPL)");
    if (why.empty()) std::cout << "plot: " << png << "\n";
    else std::cerr << "no plot: " << why << "\n";
  }
  return 0;
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
