// Node kinds (include/pradis/core/node_kind.hpp) as a plug-in point: a kind written
// outside the library, that an element type declares (E::node_kinds), becomes part of
// the model, and the assembler, the zero step and both drivers run it.
//
// The kind: the "integral node" (x, h) of examples/pi_control/integral_node.hpp, whose
// hidden DOF h carries the equation h' - x = 0, so h(t) = integral of x from 0 to t. On
// the oscillator m x'' + k x = 0 with x(0) = 0, x'(0) = V, w = sqrt(k / m):
//   x(t) = (V / w) sin(w t),   h(t) = (V / w^2) (1 - cos(w t))   (exact).
// The zero step's row of h is d/dt of its equation, h'' = x' (so h''(0) = V).

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "pradis/elements/composite.hpp"
#include "pradis/elements/condensed.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pi_control/integral_node.hpp"
#include "testing/test_support.hpp"

using namespace pradis;
using namespace pradis::elements;

// The composites' specs (outside the anonymous namespace: the help title is read only when
// a help text is made).
namespace node_kind_specs {
struct marked_mass_spec {
  static constexpr std::string_view name = "MMASS";
  static constexpr std::string_view title = "point mass with the integral node marker";
  static constexpr int ext = 1, ent = 0;
};
struct marked_series_spec {
  static constexpr std::string_view name = "MSERIES";
  static constexpr std::string_view title = "two springs in series with the integral node marker";
  static constexpr int ext = 2, ent = 1;
};
}  // namespace node_kind_specs

namespace {

// The kind: examples/pi_control/integral_node.hpp (h' - x = 0 in the row of the hidden h).
using pradis_examples::integral_node;
using pradis_examples::integral_registry;

/// The integral node with a fault once x passes 0.5: a flow (Fault 0) or a Jacobian entry dF/du
/// (Fault 1) is NaN. Its own registry type (each kind of a model keeps its own registry).
template <int Fault>
struct faulty_node : integral_node {
  struct registry : integral_registry {};
  static constexpr std::string_view label = "FAULTY";
  static void evaluate(const record& r, const node_values<2>& x, const node_call& call, node_flows<2>& out,
                       element_context& ctx) {
    integral_node::evaluate(r, x, call, out, ctx);
    if (x.u(0) <= 0.5) return;
    if (Fault == 0) out.f(1) = std::nan("");
    if (Fault == 1 && call.want_jacobian) out.K(1, 0) = std::nan("");
  }
};
static_assert(NodeKind<faulty_node<0>> && NodeKind<faulty_node<1>>);
/// An element type that brings the integral node (or another kind) into a model: inert
/// (no flow), it only declares the kind. I numbers such types.
template <int I, class Kind = integral_node>
struct integral_marker_t {
  static constexpr pradis::passport passport{
      .name = I == 0 ? std::string_view("INTMARK") : std::string_view("INTMARK2"), .ext = 1, .par = 0, .adr = 1,
      .ign = 23};
  static constexpr element_help help{.title = "integral node marker", .name = "declares the integral node kind",
                                     .field = "test", .dofs = "1", .parameters = "", .work = "", .special = "none"};
  using node_kinds = type_list<Kind>;
  struct parameters {};
  parameters p;
  explicit integral_marker_t(parameters) {}
  static integral_marker_t from_parameters(std::span<const double>) { return integral_marker_t({}); }
  static constexpr bool inert = true;
  void evaluate(const local_input<integral_marker_t>&, local_output<integral_marker_t>&, element_context&) const {}
};
using integral_marker = integral_marker_t<0>;
/// The marker of a faulty node kind.
template <int Fault>
using faulty_marker = integral_marker_t<2 + Fault, faulty_node<Fault>>;


using integral_model = model<point_mass, linear_spring, initial_velocity, integral_marker>;
static_assert(std::is_same_v<integral_model::node_kinds, type_list<spatial::rotation_node_kind, integral_node>>);
static_assert(std::is_same_v<model<point_mass>::node_kinds, type_list<spatial::rotation_node_kind>>);
// Two element types declaring the same kind bring it once.
static_assert(std::is_same_v<model<integral_marker, integral_marker_t<1>>::node_kinds,
                             type_list<spatial::rotation_node_kind, integral_node>>);

// A composite brings its parts' node kinds: a model that lists only the composite (a point
// mass with the marker as a second part) has the integral node.
using marked_mass = composite<node_kind_specs::marked_mass_spec, part<point_mass, 0>, part<integral_marker, 0>>;
static_assert(std::is_same_v<marked_mass::node_kinds, type_list<integral_node>>);
using composite_model = model<marked_mass, linear_spring, initial_velocity>;
static_assert(std::is_same_v<composite_model::node_kinds, type_list<spatial::rotation_node_kind, integral_node>>);
// A condensed composite brings them too (two springs in series, the marker on an end).
using marked_series = condensed<node_kind_specs::marked_series_spec, part<linear_spring, 0, 2>,
                                part<linear_spring, 2, 1>, part<integral_marker, 0>>;
static_assert(std::is_same_v<model<marked_series>::node_kinds, type_list<spatial::rotation_node_kind, integral_node>>);

constexpr double osc_mass = 2.0, osc_k = 8.0, osc_v0 = 1.5;  // w = 2 rad/s

/// The oscillator's mass: a point mass, or the composite with the marker.
template <class M>
void add_mass(M& m, dof x) {
  if constexpr (std::is_same_v<M, composite_model>)
    m.template add<marked_mass>("m", {{{osc_mass}, {}}}, x);
  else
    m.template add<point_mass>("m", {osc_mass}, x);
}

/// The oscillator with its integral node; x and h returned through the arguments.
template <class M = integral_model>
M oscillator(dof& x, dof& h) {
  M m;
  x = m.add_dof("x");
  h = m.add_dof("h");
  add_mass(m, x);
  m.template add<linear_spring>("k", {osc_k}, x, m.ground());
  m.template add<initial_velocity>("v0", {osc_v0}, x);
  m.template add_node<integral_node>({{x.index, h.index}});
  return m;
}

double exact_x(double t) {
  const double w = std::sqrt(osc_k / osc_mass);
  return osc_v0 / w * std::sin(w * t);
}
double exact_h(double t) {
  const double w = std::sqrt(osc_k / osc_mass);
  return osc_v0 / (w * w) * (1 - std::cos(w * t));
}
/// The integral of h: (V / w^2) (t - sin(w t) / w).
double exact_h2(double t) {
  const double w = std::sqrt(osc_k / osc_mass);
  return osc_v0 / (w * w) * (t - std::sin(w * t) / w);
}

}  // namespace

TEST_SUITE("core/node kinds") {
  TEST_CASE("a node kind declared by an element type: h = integral of x under Newmark, its zero step h'' = x'") {
    dof x, h;
    integral_model m = oscillator(x, h);
    REQUIRE(m.nodes<integral_node>().size() == 1);
    CHECK(m.hidden_dofs()[static_cast<std::size_t>(h.index)] == 1);
    simulation sim(m);
    double worst = 0;
    bool first = true;
    sim.on_output([&](const auto& s) {
      if (first) {  // the zero step: h' = x = 0 and h'' = x' = V from the node's row
        CHECK(s.v(h) == doctest::Approx(0.0));
        CHECK(s.a(h) == doctest::Approx(osc_v0).epsilon(1e-12));
        first = false;
      }
      worst = std::max({worst, std::abs(s.u(x) - exact_x(s.time())), std::abs(s.u(h) - exact_h(s.time()))});
    });
    const run_statistics st = sim.run({.end = 3.0, .out = 0.05, .smax = 1e-3});
    MESSAGE("integral node, Newmark h = 1e-3: worst |error| of x and h ", worst, " over ", st.steps, " steps");
    // Trapezoidal rule: phase error w^3 t h^2 / 12 = 8 * 3 * 1e-6 / 12 = 2e-6 rad on amplitudes of at
    // most 0.75, an error of about 1.5e-6 (measured 1.44e-6).
    CHECK(worst < 5e-6);
    CHECK(m.rotation_nodes().empty());
  }

  TEST_CASE("the same node under the BDF driver with error control follows the exact integral") {
    dof x, h;
    integral_model m = oscillator(x, h);
    bdf_simulation sim(m);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max({worst, std::abs(s.u(x) - exact_x(s.time())), std::abs(s.u(h) - exact_h(s.time()))});
    });
    const run_statistics st =
        sim.run({.end = 3.0, .out = 0.05, .smax = 0.1, .error_control = true, .dabsx = 1e-8, .drltx = 1e-8});
    MESSAGE("integral node, BDF DRLTX 1e-8: worst |error| of x and h ", worst, " over ", st.steps, " steps");
    CHECK(worst < 1e-6);
  }

  TEST_CASE("the hidden DOF starts with the velocity of its node's equation: h'(0) = x(0)") {
    // x(0) = X0, x'(0) = 0: x = X0 cos(w t), h = X0 sin(w t) / w, and h' must start at X0, not at 0
    // (integrators/initialisation.hpp, hidden_dof_velocities). Started at 0, Newmark keeps an offset of
    // h X0 / 2 = 5e-4 in h for ever and the BDF driver stops at t = 0 (code 141): measured before the start
    // velocities were solved for.
    constexpr double x0 = 1.0;
    const double w = std::sqrt(osc_k / osc_mass);
    for (int driver = 0; driver < 2; ++driver) {
      model<point_mass, linear_spring, initial_displacement, integral_marker> m;
      const dof x = m.add_dof("x"), h = m.add_dof("h");
      m.add<point_mass>("m", {osc_mass}, x);
      m.add<linear_spring>("k", {osc_k}, x, m.ground());
      m.add<initial_displacement>("x0", {x0}, x);
      m.add_node<integral_node>({{x.index, h.index}});
      double worst = 0, hv0 = 0;
      bool first = true;
      auto track = [&](const auto& s) {
        if (first) hv0 = s.v(h), first = false;
        worst = std::max(worst, std::abs(s.u(h) - x0 * std::sin(w * s.time()) / w));
      };
      if (driver == 0) {
        simulation sim(m);
        sim.on_output(track);
        sim.run({.end = 3.0, .out = 0.05, .smax = 1e-3});
        MESSAGE("x(0) = 1, Newmark h = 1e-3: h'(0) = ", hv0, ", worst |error| of h ", worst);
        // As above: the trapezoidal phase error w^3 t h^2 / 12 = 2e-6 rad on the amplitude X0 / w = 0.5, an error
        // of about 1e-6 (measured 9.6e-7).
        CHECK(worst < 2e-6);
      } else {
        bdf_simulation sim(m);
        sim.on_output(track);
        sim.run({.end = 3.0, .out = 0.05, .smax = 0.1, .error_control = true, .dabsx = 1e-8, .drltx = 1e-8});
        MESSAGE("x(0) = 1, BDF DRLTX 1e-8: h'(0) = ", hv0, ", worst |error| of h ", worst);
        CHECK(worst < 1e-6);
      }
      CHECK(hv0 == doctest::Approx(x0).epsilon(1e-14));
    }
  }

  TEST_CASE("an initial velocity set on a hidden DOF that the node's equation replaces is a warning") {
    model<point_mass, linear_spring, initial_displacement, initial_velocity, integral_marker> m;
    const dof x = m.add_dof("x"), h = m.add_dof("h");
    m.add<point_mass>("m", {osc_mass}, x);
    m.add<linear_spring>("k", {osc_k}, x, m.ground());
    m.add<initial_displacement>("x0", {1.0}, x);
    m.add<initial_velocity>("hv", {5.0}, h);  // h' = x(0) = 1, not 5
    m.add_node<integral_node>({{x.index, h.index}});
    simulation sim(m);
    std::ostringstream log;
    sim.log().to(log);
    double hv0 = 0;
    bool first = true;
    sim.on_output([&](const auto& s) {
      if (first) hv0 = s.v(h), first = false;
    });
    sim.run({.end = 0.01, .smax = 1e-3});
    CHECK(hv0 == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(log.str().find("warning: the initial velocity 5 set by 'hv' on DOF 'h' is not kept: it is the hidden DOF "
                         "of a INTEGRAL node, whose equation gives 1") != std::string::npos);
  }

  TEST_CASE("a checkpoint carries the nodes: refused by the model without the node, continued by the same model") {
    dof x, h;
    integral_model a = oscillator(x, h);
    simulation sa(a);
    sa.run({.end = 1.0, .smax = 1e-3});
    std::stringstream ck;
    sa.save_checkpoint(ck);
    sa.run({.end = 2.0, .smax = 1e-3});
    // The same elements and DOFs without the integral node: another model.
    integral_model b;
    const dof bx = b.add_dof("x");
    b.add_dof("h");
    b.add<point_mass>("m", {osc_mass}, bx);
    b.add<linear_spring>("k", {osc_k}, bx, b.ground());
    b.add<initial_velocity>("v0", {osc_v0}, bx);
    simulation sb(b);
    CHECK(sb.model_fingerprint() != sa.model_fingerprint());
    std::stringstream in_b(ck.str());
    const auto e = pradis_test::error_of([&] { sb.load_checkpoint(in_b); });
    REQUIRE(e.has_value());
    CHECK(e->number() == 160);
    CHECK(std::string(e->message()).find("different model") != std::string::npos);
    // The same model continues bit for bit.
    dof cx, ch;
    integral_model c = oscillator(cx, ch);
    simulation sc(c);
    std::stringstream in_c(ck.str());
    sc.load_checkpoint(in_c);
    sc.run({.end = 2.0, .smax = 1e-3});
    CHECK(sc.u(ch) == sa.u(h));
    CHECK(sc.u(cx) == sa.u(x));
  }

  TEST_CASE("a node's flow or Jacobian entry that is NaN is code 150 in the name of the node") {
    // x = 0.75 sin(2 t) passes 0.5 at t = 0.37: the fault appears during the run, not at the zero step.
    auto run = [&]<int Fault>(std::integral_constant<int, Fault>) {
      model<point_mass, linear_spring, initial_velocity, faulty_marker<Fault>> m;
      const dof x = m.add_dof("x"), h = m.add_dof("h");
      m.template add<point_mass>("m", {osc_mass}, x);
      m.template add<linear_spring>("k", {osc_k}, x, m.ground());
      m.template add<initial_velocity>("v0", {osc_v0}, x);
      m.template add_node<faulty_node<Fault>>({{x.index, h.index}});
      simulation sim(m);
      return pradis_test::error_of([&] { sim.run({.end = 3.0, .smax = 1e-3}); });
    };
    const auto e0 = run(std::integral_constant<int, 0>{});
    REQUIRE(e0.has_value());
    CHECK(e0->number() == 150);
    CHECK(std::string(e0->instance()) == "h");
    CHECK(std::string(e0->message()).find("FAULTY node of DOF 'h': a flow of its equation is NaN") !=
          std::string::npos);
    const auto e1 = run(std::integral_constant<int, 1>{});
    REQUIRE(e1.has_value());
    CHECK(e1->number() == 150);
    CHECK(std::string(e1->message()).find("FAULTY node of DOF 'h': a Jacobian entry of its equation is NaN") !=
          std::string::npos);
  }

  TEST_CASE("a node whose DOF does not exist or appears twice, or whose hidden DOF is the ground, is code 110") {
    integral_model m;
    const dof x = m.add_dof("x");
    const auto e1 = pradis_test::error_of([&] { m.add_node<integral_node>({{x.index, 7}}); });
    REQUIRE(e1.has_value());
    CHECK(e1->number() == 110);
    CHECK(std::string(e1->message()).find("DOF 7 of a INTEGRAL node does not exist") != std::string::npos);
    const auto e2 = pradis_test::error_of([&] { m.add_node<integral_node>({{x.index, 0}}); });
    REQUIRE(e2.has_value());
    CHECK(e2->number() == 110);
    CHECK(std::string(e2->message()).find("hidden DOF 2 of a INTEGRAL node cannot be the ground") != std::string::npos);
    const auto e3 = pradis_test::error_of([&] { m.add_node<integral_node>({{x.index, x.index}}); });
    REQUIRE(e3.has_value());
    CHECK(e3->number() == 110);
    CHECK(std::string(e3->message()).find("DOF 'x' is connection 1 and 2 of a INTEGRAL node") != std::string::npos);
    CHECK(m.nodes<integral_node>().empty());
  }

  TEST_CASE("a hidden DOF that is already a node's hidden DOF is code 110; a chain of nodes is not") {
    dof x, h;
    integral_model m = oscillator(x, h);
    const dof y = m.add_dof("y");
    // Two nodes would write two equations into the row of h.
    const auto e1 = pradis_test::error_of([&] { m.add_node<integral_node>({{y.index, h.index}}); });
    REQUIRE(e1.has_value());
    CHECK(e1->number() == 110);
    CHECK(std::string(e1->message()).find("hidden DOF 2 of a INTEGRAL node, 'h', is already the hidden or slaved "
                                          "DOF of a node") != std::string::npos);
    // The same for the hidden q4 of a rotational node (another kind).
    const rotation_node r = m.add_rotation_node("r");
    const auto e2 = pradis_test::error_of([&] { m.add_node<integral_node>({{y.index, r.q4.index}}); });
    REQUIRE(e2.has_value());
    CHECK(e2->number() == 110);
    CHECK(std::string(e2->message()).find("'r.q4', is already the hidden or slaved DOF") != std::string::npos);
    CHECK(m.nodes<integral_node>().size() == 1);
  }

  TEST_CASE("a chain of integral nodes: h2 = integral of h, where h is the first node's hidden DOF") {
    dof x, h;
    integral_model m = oscillator(x, h);
    const dof h2 = m.add_dof("h2");
    m.add_node<integral_node>({{h.index, h2.index}});  // h is hidden in the first node, an input here
    REQUIRE(m.nodes<integral_node>().size() == 2);
    simulation sim(m);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max({worst, std::abs(s.u(h) - exact_h(s.time())), std::abs(s.u(h2) - exact_h2(s.time()))});
    });
    const run_statistics st = sim.run({.end = 3.0, .out = 0.05, .smax = 1e-3});
    MESSAGE("chain of integral nodes, Newmark h = 1e-3: worst |error| of h and h2 ", worst, " over ", st.steps,
            " steps");
    // h2 integrates h's phase error (at most 1.5e-6, see above) over 3 s: at most 4.5e-6.
    CHECK(worst < 5e-6);
  }

  TEST_CASE("a model that lists only a composite with the marker as a part has the integral node") {
    dof x, h;
    composite_model m = oscillator<composite_model>(x, h);
    REQUIRE(m.nodes<integral_node>().size() == 1);
    simulation sim(m);
    double worst = 0;
    sim.on_output([&](const auto& s) { worst = std::max(worst, std::abs(s.u(h) - exact_h(s.time()))); });
    sim.run({.end = 3.0, .out = 0.05, .smax = 1e-3});
    MESSAGE("integral node brought by a composite, Newmark h = 1e-3: worst |error| of h ", worst);
    CHECK(worst < 5e-6);
  }
}
