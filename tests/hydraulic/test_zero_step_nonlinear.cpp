// The zero step on a node whose only blocks are nonlinear viscous ones (docs/domains.md,
// "The zero step"): a pump delivers a constant flow D w into node 2, which has no volume;
// a check valve joins it to an accumulator. The consistent start has the valve pass the
// pump flow: q(p2 - p3) = D w. The valve's flow law is nonlinear (closed below its
// cracking pressure, a turbulent orifice when open), so one linear solve from p2 = 0 at
// the closed valve's tiny slope lands at 2.2e8 Pa; the zero step iterates Newton with a
// line search on these DOFs until the flows balance.
// - Check valve fully open: q = Cd (Al + Amax) sqrt(2 / rho) r(dp), r the regularised
//   root dp / (dp^2 + dpt^2)^(1/4) (docs/domains.md, "Regularised root"; Merritt,
//   Hydraulic Control Systems, 1967, eq. 3-1, for the orifice).
// - Conservation of the liquid volume: node 2 stores nothing, so the accumulator's stored
//   volume (its work entry 1) grows by D w t.

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

#include "../elements/element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

namespace {
struct zsn_circuit {
  static constexpr double w = 150, d = 1.5915494e-6;  // shaft speed [rad/s], displacement [m^3/rad]
  const check_valve::parameters cp{0.7, 2e-5, oil_rho, 1e3, 0.5e5, 0.5e5, 1e-9};
  model<velocity_source, hydraulic_pump, check_valve, accumulator> md;
  dof shaft = md.add_dof("shaft"), p2 = md.add_dof("p2"), p3 = md.add_dof("p3");
  zsn_circuit() {
    md.add<velocity_source>("drive", {.offset = w}, shaft);
    md.add<hydraulic_pump>("pump", {d, 0, 0}, md.ground(), p2, shaft);
    md.add<check_valve>("check", cp, p2, p3);
    md.add<accumulator>("acc", {1e-3, 20e5, 1.4, 1e5, 1e-5, oil_b}, p3);
  }
  /// The valve's flow at pressure difference dp, fully open.
  double open_flow(double dp) const {
    return cp.cd * std::sqrt(2 / cp.density) * (cp.leakage_area + cp.max_area) * reg_root(dp, cp.transition);
  }
};
}  // namespace

TEST_SUITE("hydraulic/zero step") {
  TEST_CASE("a node without volume behind a check valve starts with the valve passing the pump flow") {
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      zsn_circuit c;
      std::ostringstream log;
      const double q = zsn_circuit::d * zsn_circuit::w, end = 0.2;
      double stored0 = 0, dp0 = 0;
      auto check_run = [&](auto& sim) {
        sim.log().to(log);
        sim.on_output([&](const auto& r) {
          if (r.time() == 0) stored0 = c.md.work("acc")[0], dp0 = r.v(c.p2) - r.v(c.p3);
        });
        run_options o;
        o.end = end;
        o.out = 0.01;
        o.error_control = true;
        o.drltx = 1e-7;
        o.dabsx = 1e-7;
        sim.run(o);
        CHECK(c.md.work("check")[0] == doctest::Approx(q).epsilon(1e-6));
        CHECK(c.md.work("acc")[0] - stored0 == doctest::Approx(q * end).epsilon(1e-6));
      };
      if (bdf) {
        bdf_simulation sim(c.md);
        check_run(sim);
      } else {
        simulation sim(c.md);
        check_run(sim);
      }
      // The start: the valve is fully open and passes the pump flow.
      CHECK(dp0 > c.cp.crack + c.cp.band);
      CHECK(c.open_flow(dp0) == doctest::Approx(q).epsilon(1e-9));
      CHECK(log.str().find("warning") == std::string::npos);
    }
  }
}
