// BEAM3C (include/pradis/elements/spatial/condensed_beam.hpp): a BEAM3 cut into N segments whose inner nodes are
// condensed. References: the cubic beam element is exact for end loads, so small deflections equal one BEAM3's; the
// condensation is exact, so large deflections equal the model with the same segments kept, to the Newton tolerance;
// the elastica of a cantilever under a dead tip load (tests/testing/elastica.hpp), which the segments approach at the
// second order of the corotational discretisation.

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "condensed_parts.hpp"
#include "element_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/spatial/node_state.hpp"
#include "pradis/spatial/quaternion.hpp"
#include "testing/elastica.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;
using pradis_condensed_tests::cond_context;

namespace {

/// The section of the large-deflection tests: E Iz = 2 (bending in the XY plane), E Iy = 4, G J = 1.2; E A = 1e5 so
/// that the axial strain (below 1e-4) leaves the inextensible elastica's tip within 1e-4 L.
elastic_beam::parameters slender(double xa, double xb) {
  return {1e4, 4e3, 10, 4e-4, 2e-4, 3e-4, xa, 0, 0, xb, 0, 0, 0, 1, 0};
}
constexpr double ei = 2.0;

/// What a large-deflection run gives: the tip (x, y) / L and the run's counts.
struct tip_result {
  double x = 0, y = 0;
  long steps = 0, failed = 0, newton = 0;
};

/// A cantilever of length 1 along X: A clamped at the origin, B free, under a dead tip load along Y ramped as
/// alpha E I sin(pi t / 2) to alpha E I at t = 1, in 20 static steps of generalized-alpha with rho_inf = 0 (a damped
/// scheme: the model has no mass, docs/rotations.md), or `scheme` up to `end`, its log to `log`, stopped at the first
/// accepted step after `stop_after_cuts` cut steps of this run (0: not stopped). The beam is one BEAM3C with N
/// segments or, if `kept`, N BEAM3 with their inner nodes as model DOFs. The run starts from the checkpoint `restore`
/// if given, and writes one to `save` at its end.
template <int N, class Scheme = generalized_alpha>
tip_result cantilever(double alpha, bool kept, Scheme scheme = generalized_alpha(0.0), double end = 1.0,
                      std::ostream* log = nullptr, long stop_after_cuts = 0, std::istream* restore = nullptr,
                      std::ostream* save = nullptr) {
  model<condensed_beam_t<N>, elastic_beam, spatial_force> m;
  const dof g = m.ground();
  const rotation_node root = m.add_rotation_node("r0", g, g, g);
  std::vector<dof> x;
  rotation_node r = root;
  std::vector<dof> prev = {g, g, g};
  for (int i = 1; i <= (kept ? N : 1); ++i) {
    x = m.add_dofs(3, "x" + std::to_string(i));
    const rotation_node ri = m.add_rotation_node("r" + std::to_string(i));
    if (kept)
      m.template add<elastic_beam>("segment " + std::to_string(i),
                                   condensed_beam_t<N>::segment(slender(0, 1), i - 1), prev[0], prev[1], prev[2], r,
                                   x[0], x[1], x[2], ri);
    else
      m.template add<condensed_beam_t<N>>("beam", slender(0, 1), g, g, g, root, x[0], x[1], x[2], ri);
    prev = x;
    r = ri;
  }
  m.template add<spatial_force>("load", {0, 0, 0, 0, alpha * ei, 0, 0.25, 0}, x[0], x[1], x[2]);
  simulation<decltype(m), Scheme> sim(m, scheme);
  if (log) sim.log().to(*log);
  if (restore) sim.load_checkpoint(*restore);
  const long cut_before = sim.statistics().rejected_steps;
  struct enough {};
  if (stop_after_cuts > 0)
    sim.on_step([&](const auto& s) {
      if (s.statistics().rejected_steps - cut_before >= stop_after_cuts) throw enough{};
    });
  try {
    sim.run({.end = end, .smax = 0.05, .newton = {.dabsu = 1e-11, .drltu = 0, .dabsi = 1e-7, .drlti = 0, .itr = 12}});
  } catch (const enough&) {
  }
  if (save) sim.save_checkpoint(*save);
  return {1 + sim.u(x[0]), sim.u(x[1]), sim.statistics().steps, sim.statistics().rejected_steps,
          sim.statistics().newton_iterations};
}

}  // namespace

TEST_SUITE("elements/condensed beam") {
  TEST_CASE("BEAM3C: passport and help are BEAM3's (15 parameters, A and B with their q4), its state the inner nodes") {
    static_assert(check_element<condensed_beam>());
    static_assert(condensed_beam::segments == 4);
    static_assert(condensed_beam::passport.ext == 12 && condensed_beam::passport.ent == 2);
    static_assert(condensed_beam::passport.par == 15);
    static_assert(condensed_beam::passport.str == 3 * 7);  // three inner nodes, x y z q1 q2 q3 q4 each
    static_assert(condensed_beam::passport.adr == 1 && condensed_beam::passport.ign == 23);  // K only
    static_assert(condensed_beam::rotation_nodes == elastic_beam::rotation_nodes);
    static_assert(check_element<condensed_beam_t<2>>() && check_element<condensed_beam_t<8>>());
    CHECK(condensed_beam::passport.name == std::string_view("BEAM3C"));
    CHECK(help_lines(condensed_beam::help.parameters) == 15);
    CHECK(std::string(condensed_beam::help.parameters) == std::string(elastic_beam::help.parameters));
    CHECK(help_lines(condensed_beam::help.work) == condensed_beam::passport.wrk);
    CHECK(std::string(condensed_beam::help.work).find("part 4 'BEAM3' (segment 4): strain energy") !=
          std::string::npos);
    CHECK(std::string(condensed_beam::help.special).find("GALPHA") != std::string::npos);
    // Segment i: the whole beam's section, ends at i/N and (i+1)/N of A -> B.
    const elastic_beam::parameters s = condensed_beam::segment(elastic_beam::example(), 1);
    const elastic_beam::parameters w = elastic_beam::example();
    CHECK(s.xa == doctest::Approx(w.xa + (w.xb - w.xa) / 4));
    CHECK(s.zb == doctest::Approx(w.za + (w.zb - w.za) / 2));
    CHECK(s.iz == w.iz);
  }

  TEST_CASE("BEAM3C has one BEAM3's stiffness at rest and turned rigidly to 150 degrees (cubic elements are exact)") {
    // Two cubic Euler-Bernoulli elements loaded only at their ends deform as one (the exact solution is cubic), so
    // the condensed chain of the oblique example beam has the tangent of one BEAM3, at rest and, being objective,
    // turned rigidly; its flows there are zero.
    const elastic_beam::parameters q = elastic_beam::example();
    condensed_beam c(q);
    elastic_beam b(q);
    cond_context<condensed_beam> cc("chain");
    cond_context<elastic_beam> bc("one");
    c.new_integration(cc.ctx);
    b.new_integration(bc.ctx);
    const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
    const Eigen::Vector3d a0(q.xa, q.ya, q.za), b0(q.xb, q.yb, q.zb);
    for (int k = 0; k <= 5; ++k) {
      const double angle = 30.0 * k * pradis_element_tests::deg;
      const Eigen::Matrix3d rot = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      const Eigen::Vector4d qr(axis.x() * std::sin(angle / 2), axis.y() * std::sin(angle / 2),
                               axis.z() * std::sin(angle / 2), std::cos(angle / 2));
      const Eigen::Vector3d centre = (a0 + b0) / 2;
      local_input<condensed_beam> in;
      in.u.segment<3>(0) = centre + rot * (a0 - centre) - a0;
      in.u.segment<3>(6) = centre + rot * (b0 - centre) - b0;
      in.u.segment<3>(3) = in.u.segment<3>(9) = qr.head<3>();
      in.u(12) = in.u(13) = qr(3);
      local_output<condensed_beam> out;
      c.evaluate(in, out, cc.ctx);
      cc.accept();  // each turn starts from the last (an accepted step)
      local_input<elastic_beam> bi;
      bi.u = in.u;
      local_output<elastic_beam> bo;
      b.evaluate(bi, bo, bc.ctx);
      CAPTURE(angle);
      CHECK((out.K - bo.K).norm() <= 1e-9 * bo.K.norm());
      CHECK(out.f.norm() <= 1e-12 * bo.K.norm());
    }
    CHECK(cc.work[static_cast<std::size_t>(condensed_beam::passport.wrk - 1)] > 0);  // Newton iterations in all
  }

  TEST_CASE("a cantilever of one BEAM3C under a tip load to P L^2 / E I = 1 and 3: the elastica, and the kept model") {
    // Reference values of the elastica: Bisshopp and Drucker (1945), alpha = 1: x = 0.9436 L, y = 0.3017 L.
    const auto e1 = pradis_test::elastica_tip(1.0), e3 = pradis_test::elastica_tip(3.0);
    CHECK(e1[0] == doctest::Approx(0.9436).epsilon(1e-4));
    CHECK(e1[1] == doctest::Approx(0.3017).epsilon(3e-4));
    for (const double alpha : {1.0, 3.0}) {
      const auto ref = alpha == 1.0 ? e1 : e3;
      const tip_result c4 = cantilever<4>(alpha, false), k4 = cantilever<4>(alpha, true);
      const tip_result c8 = cantilever<8>(alpha, false);
      const double err4 = std::hypot(c4.x - ref[0], c4.y - ref[1]), err8 = std::hypot(c8.x - ref[0], c8.y - ref[1]);
      MESSAGE("alpha ", alpha, ": elastica tip (", ref[0], ", ", ref[1], "); BEAM3C N=4 (", c4.x, ", ", c4.y,
              ") error ", err4, ", N=8 error ", err8, "; kept N=4 differs by ", std::hypot(c4.x - k4.x, c4.y - k4.y),
              "; steps/failed/Newton: N=4 ", c4.steps, "/", c4.failed, "/", c4.newton, ", kept ", k4.steps, "/",
              k4.failed, "/", k4.newton, ", N=8 ", c8.steps, "/", c8.failed, "/", c8.newton);
      // Condensation is exact: the kept segments give the same tip to the Newton tolerance.
      CHECK(std::hypot(c4.x - k4.x, c4.y - k4.y) < 1e-8);
      // Second-order convergence to the elastica: halving the segments quarters the error (3.5x at least), and
      // four segments are within 1 % of L even at alpha = 3 (the tip turned by 65 degrees).
      CHECK(err8 < err4 / 3.5);
      CHECK(err4 < 1e-2);
    }
  }

  TEST_CASE("an undamped scheme that cuts many steps of a quasi-static model is warned about, naming a massless DOF") {
    // The same cantilever under NEWMARK (average acceleration): the velocities of its massless DOFs alternate and
    // the predictor extrapolates them; it cuts steps by the thousand (BEAM3C: about 7000 up to t = 0.24, measured)
    // where GALPHA cuts none. The warning is the driver's, so the model here keeps its four segments (the cheaper
    // run: 24 massless DOFs, x y z q1 q2 q3 of the four free nodes). The NEWMARK run stops soon after its 50th cut
    // step.
    std::ostringstream newmark_log, galpha_log;
    const tip_result n = cantilever<4>(3.0, true, newmark(), 1.0, &newmark_log, 51);
    const tip_result g = cantilever<4>(3.0, true, generalized_alpha(0.0), 1.0, &galpha_log);
    INFO("NEWMARK's log: ", newmark_log.str());
    MESSAGE("NEWMARK: ", n.steps, " steps, ", n.failed, " cut; GALPHA to t = 1: ", g.steps, " steps, ",
            g.failed, " cut");
    REQUIRE(n.failed >= 50);
    const std::string w = newmark_log.str();
    CHECK(w.find("warning: 50 steps of this stage were cut and 24 DOFs have neither mass nor viscosity (the first: "
                 "'x1") != std::string::npos);
    CHECK(w.find("NEWMARK has no numerical damping") != std::string::npos);
    CHECK(w.find("GALPHA and RHOINF = 0") != std::string::npos);
    CHECK(g.failed == 0);
    CHECK(galpha_log.str().find("neither mass nor viscosity") == std::string::npos);
    // A run restored from a checkpoint (saved at t = 0.02, before the cuts begin) warns as well: the checkpoint
    // keeps the massless DOFs found at the zero step.
    std::stringstream cp;
    std::ostringstream first_log, restored_log;
    const tip_result early = cantilever<4>(3.0, true, newmark(), 0.02, &first_log, 0, nullptr, &cp);
    const tip_result r = cantilever<4>(3.0, true, newmark(), 1.0, &restored_log, 51, &cp);
    INFO("restored run's log: ", restored_log.str());
    CHECK(early.failed < 5);
    REQUIRE(r.failed - early.failed >= 50);
    CHECK(restored_log.str().find("24 DOFs have neither mass nor viscosity (the first: 'x1") != std::string::npos);
  }

  TEST_CASE("BEAM3C: bad parameters are code 100 with BEAM3C's parameter numbers, naming the instance") {
    const auto with = [](auto change) {
      elastic_beam::parameters q = elastic_beam::example();
      change(q);
      cond_context<condensed_beam> c("arm");
      return error_from([&] { condensed_beam(q).new_integration(c.ctx); });
    };
    check_error(with([](auto& q) { q.e = 0; }), error_code::invalid_parameter, "BEAM3C", "arm", "Young's modulus");
    check_error(with([](auto& q) { q.j = -1; }), error_code::invalid_parameter, "BEAM3C", "arm", "torsion constant");
    check_error(with([](auto& q) { q.xb = q.xa, q.yb = q.ya, q.zb = q.za; }), error_code::invalid_parameter, "BEAM3C",
                "arm", "coincide");
    check_error(with([](auto& q) { q.vx = q.xb - q.xa, q.vy = q.yb - q.ya, q.vz = q.zb - q.za; }),
                error_code::invalid_parameter, "BEAM3C", "arm", "section vector");
    check_error(with([](auto& q) { q.ya = pradis_test::not_a_number; }), error_code::invalid_parameter, "BEAM3C",
                "arm", "finite");
    // The flat path of the model language: too few parameters.
    model<condensed_beam> md;
    const std::vector<dof> dofs = md.add_dofs(12, "d");
    const auto e = pradis_element_tests::flat_add_error<condensed_beam>(md, "arm", dofs, std::vector<double>(14, 1.0));
    REQUIRE(e.has_value());
    CHECK(std::string(e->what()).find("BEAM3C") != std::string::npos);
  }

  TEST_CASE("BEAM3C: a segment's failure at a crushed state is code 75 naming the segment") {
    // B pushed back onto A: the first segment's chord... every chord vanishes only if the inner nodes do too; the
    // condensation then fails (singular or not converging) or a segment reports its chord: code 75 either way.
    condensed_beam c(elastic_beam::example());
    cond_context<condensed_beam> cc("crushed");
    c.new_integration(cc.ctx);
    const elastic_beam::parameters q = elastic_beam::example();
    local_input<condensed_beam> in;
    in.u(12) = in.u(13) = 1;
    in.u(6) = q.xa - q.xb;
    in.u(7) = q.ya - q.yb;
    in.u(8) = q.za - q.zb;
    local_output<condensed_beam> out;
    const auto e = error_from([&] { c.evaluate(in, out, cc.ctx); });
    REQUIRE(e.has_value());
    CHECK(e->number() == static_cast<int>(error_code::singular_situation));
    CHECK(e->element_type() == std::string("BEAM3C"));
    CHECK(e->instance() == std::string("crushed"));
    CHECK_FALSE(c.admissible(in));
  }
}
