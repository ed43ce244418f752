// Positive control of the compile-fail harness, and the compile check of the
// documentation: the C++ snippets of docs/adding-an-element.md that are not
// verbatim quotes of a header are copied here verbatim (between the "doc:"
// markers), together with the inline code of docs/architecture.md and
// docs/notation.md. This file MUST compile (tests/build_tests.cmake, MODE=pass).
// When you change a snippet in the docs, change it here too.

#include <cstdio>
#include <iostream>
#include <span>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/integrators/statistics_io.hpp"
#include "pradis/integrators/tolerance_ladder.hpp"
#include "pradis/spatial/node_state.hpp"
#include "pradis/testing/jacobian_check.hpp"

// An element around the NEW/OLD snippet: a constant force that also accumulates
// the work it receives (state vector of one entry, STR=1).
struct force_with_work {
  static constexpr pradis::passport passport{.name = "FWORK", .ext = 1, .par = 1, .str = 1, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help{.title = "constant force that accumulates its work",
                                             .name = "Constant force with work accumulator",
                                             .field = "mechanics",
                                             .dofs = "1 - the DOF the force acts on [m]",
                                             .parameters = "1 - force P [N]",
                                             .work = "",
                                             .special = "none"};
  struct parameters {
    double force = 0;
  };
  parameters p;
  explicit force_with_work(parameters q) : p(q) {}
  static force_with_work from_parameters(std::span<const double> v) { return force_with_work({v[0]}); }
  void evaluate(const pradis::local_input<force_with_work>& in, pradis::local_output<force_with_work>& out,
                pradis::element_context& ctx) const {
    const double f = -p.force;
    out.f(0) = f;
    // doc: adding-an-element.md, "The state vector: NEW and OLD"
    // Work done by the flow f on DOF 1 since the start: NEW from OLD, never NEW += ...
    ctx.new_state[0] = ctx.old_state[0] + ctx.step * f * in.v(0);
    // end doc
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};
static_assert(pradis::check_element<force_with_work>());

// doc: adding-an-element.md, "Super-elements: muting diagnostics"
/// QLINK: a LINKD that reports its failures as its own (example of a super-element).
struct quiet_link {
  static constexpr pradis::passport passport{.name = "QLINK", .ext = 4, .par = 5, .wrk = 3, .adr = 1, .ign = 23};
  static constexpr pradis::element_help help = pradis::elements::planar_link::help;
  using parameters = pradis::elements::planar_link::parameters;
  pradis::elements::planar_link link;

  explicit quiet_link(parameters q) : link(q) {}
  static quiet_link from_parameters(std::span<const double> v) { return quiet_link({v[0], v[1], v[2], v[3], v[4]}); }

  void new_integration(pradis::element_context& ctx) const { link.new_integration(ctx); }

  void evaluate(const pradis::local_input<quiet_link>& in, pradis::local_output<quiet_link>& out,
                pradis::element_context& ctx) const {
    pradis::local_input<pradis::elements::planar_link> sub_in;
    sub_in.u = in.u;
    pradis::local_output<pradis::elements::planar_link> sub_out;
    sub_out.want_jacobian = out.want_jacobian;
    try {
      pradis::element_context::mute_guard quiet(ctx);  // SYSPRN = 0 until the end of this block
      link.evaluate(sub_in, sub_out, ctx);
    } catch (const pradis::error& e) {
      ctx.fail(e.code(), "the inner link failed: " + e.message());  // logged: the guard is gone
    }
    out.f = sub_out.f;
    if (out.want_jacobian) out.K = sub_out.K;
  }
};
// end doc
static_assert(pradis::check_element<quiet_link>());

void listing_in_a_model() {
  // doc: adding-an-element.md, "Listing the element in a model"
  using namespace pradis;
  using namespace pradis::elements;
  model<planar_inertia, planar_link, constant_force> m;
  const std::vector<dof> d = m.add_dofs(6, "DOF ");
  m.add<planar_inertia>("Body 1", {.m = 1.0, .j = 0.1}, d[0], d[1], d[2]);
  m.add<planar_inertia>("Body 2", {.m = 2.0, .j = 0.1}, d[3], d[4], d[5]);
  m.add<planar_link>("Connection", {.xa0 = 1, .ya0 = 1, .xb0 = 2, .yb0 = 2, .k = 5e3}, d[0], d[1], d[3], d[4]);
  m.add<constant_force>("Force", {.force = -1e3}, d[4]);  // 1e3 N downward

  simulation sim(m, stoermer{});  // SHTERM
  sim.on_output([&](const auto& s) {
    const auto w = s.get_model().work("Connection");  // W:Connection(2) = w[1], W:Connection(3) = w[2]
    std::printf("%g %g %g %g %g\n", s.time(), s.u(d[3]), s.u(d[4]), w[1], w[2]);
  });
  sim.run({.end = 1.0, .out = 0.01, .smax = 1e-4});
  // end doc
}

void checking_the_jacobian() {
  // doc: adding-an-element.md, "Checking the Jacobian"
  using pradis::elements::planar_link;
  pradis::testing::jacobian_checker<planar_link> chk(planar_link({0, 0, 1, 0.5, 5e3}));
  pradis::local_input<planar_link> at;
  at.u << 0.1, -0.2, 0.05, 0.3;
  const pradis::testing::jacobian_check_result r = chk.check(at);
  if (!r.ok) r.print(std::cerr);
  // end doc
}

void inline_code_of_other_docs() {
  using namespace pradis;
  using namespace pradis::elements;
  model<point_mass, linear_spring> m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {.m = 1.0}, x);
  m.add<linear_spring>("spring", {.k = 100.0}, x, m.ground());
  // architecture.md, "Where later capabilities plug in"
  simulation<decltype(m), newmark, linalg::sparse_lu<linalg::natural_ordering>> sim(m);
  sim.run({.end = 0.1});
  // notation.md, "Time integration"
  const double b = 0.3, g = 0.6;
  simulation sim2(m, newmark{{.beta = b, .gamma = g}});
  // architecture.md, "Diagnostics"
  sim2.log().to(std::cerr);
  (void)sim2.statistic("NSTEP");
  // architecture.md, "simulation<Model, Scheme, Solver>"
  std::cout << sim2.statistics() << "\n";
  tolerance_ladder(m, {.end = 0.1}, newmark{}).print(std::cout);
  static_assert(linalg::OrderingPolicy<linalg::min_degree_ordering>);
  static_assert(Integrator<stoermer>);
}

void rotations_api() {
  // doc: rotations.md, "API" (verbatim)
  using namespace pradis;
  using namespace pradis::elements;

  model<rigid_body, spatial_torque, initial_rotation> m;
  const auto x = m.add_dofs(3, "x");                 // translations of the reference point
  const rotation_node r = m.add_rotation_node("r");  // q1, q2, q3 = r.q1, r.q2, r.q3; hidden r.q4
  m.add<rigid_body>("body", {.m = 1, .jxx = 2, .jyy = 1, .jzz = 0.5}, x[0], x[1], x[2], r);
  m.add<spatial_torque>("motor", {.p0z = 1.0}, r);   // a rotation_node stands for its q1, q2, q3
  m.add<initial_rotation>("start", {.ex = 0, .ey = 0, .ez = 1, .angle_deg = 30, .wz = 2.0}, r);
  // or from a matrix: initial_rotation::from_matrix(R0, omega0)

  simulation sim(m);
  sim.run({.end = 1.0, .smax = 1e-3});
  spatial::mat3 R = spatial::node_rotation(sim, r);             // also node_quaternion, node_rate,
  spatial::vec3 w = spatial::node_angular_velocity(sim, r);     // node_norm, node_body_angular_velocity
  // end doc
  // rotations.md, "Fixing angular DOFs" and "For element authors"
  model<rigid_body> m2;
  const dof qz = m2.add_dof("qz");
  const rotation_node r2 = m2.add_rotation_node("r", m2.ground(), m2.ground(), qz);
  static_assert(element_traits<rigid_body>::rotation_nodes[0] == rotation_slot{.q1 = 3, .q4 = 6});
  std::printf("%g %g %d\n", R(0, 0), w(2), r2.q4.index);
}

int main() {
  rotations_api();
  listing_in_a_model();
  checking_the_jacobian();
  inline_code_of_other_docs();
}
