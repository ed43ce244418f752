// What accuracy costs on a model: the tolerance ladder (pradis/integrators/
// tolerance_ladder.hpp) on the two-body system of the PRADIS element developer's
// manual (Fig. 3.3, section 3.6.9; as in examples/two_bodies): two bodies in plane
// motion (MD) joined by an elastic link (LINKD), a force of 1e3 N on body 2, to
// END = 1 s. The model is run with error control at DRLTX = 1e-2 ... 1e-6 (and
// DABSX equal to it), against a reference at 1e-8, with Newmark and with
// generalized-alpha; the table shows the error each tolerance achieves, its cost,
// and the CPU-time factor each extra digit costs.
//
// Usage: tolerance_ladder [--quick]   (--quick: DRLTX = 1e-2, 1e-3 only, Newmark only)

#include <iostream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/integrators/statistics_io.hpp"
#include "pradis/integrators/tolerance_ladder.hpp"

int main(int argc, char** argv) try {
  using namespace pradis;
  using namespace pradis::elements;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") quick = true;
    else {
      std::cout << "usage: tolerance_ladder [--quick]\n";
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }

  // The user's model, built once; the ladder runs copies of it.
  model<planar_inertia, planar_link, constant_force> m;
  const auto d = m.add_dofs(6, "DOF ");
  m.add<planar_inertia>("Body 1", {.m = 1.0, .j = 0.1}, d[0], d[1], d[2]);
  m.add<planar_inertia>("Body 2", {.m = 2.0, .j = 0.1}, d[3], d[4], d[5]);
  m.add<planar_link>("Connection", {1, 1, 2, 2, 5e3}, d[0], d[1], d[3], d[4]);
  m.add<constant_force>("Force", {.force = -1e3}, d[4]);

  // The run: one stage to END = 1 s; the ladder switches error control on and
  // sets DRLTX, DABSX and the Newton tolerances per rung.
  const run_options run{.end = 1.0, .smax = 0.05, .smin = 1e-12};
  ladder_options lo;
  lo.tolerances = quick ? std::vector<double>{1e-2, 1e-3} : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
  lo.reference_factor = 1e-2;  // reference at (tightest rung) / 100
  lo.repeats = quick ? 1 : 3;  // CPU time: minimum of 3 runs

  tolerance_ladder(m, run, newmark{}, lo).print(std::cout);
  if (!quick) {
    std::cout << "\n";
    tolerance_ladder(m, run, generalized_alpha(0.8), lo).print(std::cout);
  }

  // The statistics of a single run print in one call as well.
  simulation sim(m, newmark{});
  sim.run({.end = 1.0, .smax = 1e-4});
  std::cout << "\nfixed step 1e-4, Newmark: " << sim.statistics() << "\n";
  return 0;
} catch (const pradis::error& e) {
  std::cerr << e.what() << "\n";
  return 1;
}
