// Element lifecycle and model building (PRADIS element developer's manual,
// section 3.3; pradis-methods.md section 3):
//  - placing elements: flat parameter vectors and DOF lists checked at run time
//    (codes 110, 101), unique instance names, placing by catalog name;
//  - phases: NEWINT first (checks and precomputation), then the zero step
//    (NSTEP = 0: initial conditions, flows at t0, Jacobian may be skipped), then
//    the steps (NSTEP = 1, 2, ...; every Newton iteration calls every element);
//    each new stage (integration-program call) re-triggers NEWINT;
//  - NEW/OLD state: NEW written on every call, copied to OLD on acceptance;
//  - parameters replaced between stages ($REPLACE) are checked again at NEWINT
//    and take effect; DOFs added between stages start at rest.

#include <doctest/doctest.h>

#include <algorithm>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "testing/test_support.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

using pradis_test::contains;
using pradis_test::error_of;

/// What the probe saw at one call.
struct event {
  enum kind_t { newint, zero_step, evaluate, commit } kind;
  double time = 0, step = 0;
  long nstep = 0;
  int niter = 0;
  bool newint_flag = false, want_jacobian = false;
  double old_state = 0;
};

/// Records every call the kernel makes into it; STR = 1 with NEW = OLD + 1, so
/// OLD counts the accepted evaluations (zero step included) if and only if the
/// kernel commits exactly once per accepted step.
struct lifecycle_probe {
  static constexpr pradis::passport passport{.name = "PROBE", .ext = 1, .par = 0, .str = 1, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test: records the kernel's calls",
                                     .name = "Lifecycle probe",
                                     .field = "tests",
                                     .dofs = "1 - any DOF",
                                     .parameters = "",
                                     .work = "1 - number of NEWINT calls",
                                     .special = "none"};
  struct parameters {};
  std::vector<event>* events = nullptr;
  explicit lifecycle_probe(parameters) {}
  static lifecycle_probe from_parameters(std::span<const double>) { return lifecycle_probe(parameters{}); }
  void record(event::kind_t k, const element_context& ctx, bool jac = false) const {
    if (!events) return;
    event e{k, ctx.time, ctx.step, ctx.nstep, ctx.niter, ctx.newint, jac, 0.0};
    e.old_state = ctx.old_state.empty() ? -1 : ctx.old_state[0];
    events->push_back(e);
  }
  void new_integration(element_context& ctx) {
    ctx.work[0] += 1;  // the work vector persists between calls and stages
    record(event::newint, ctx);
  }
  void zero_step(initial_values<1>&, element_context& ctx) { record(event::zero_step, ctx); }
  void commit(element_context& ctx) { record(event::commit, ctx); }
  void evaluate(const local_input<lifecycle_probe>&, local_output<lifecycle_probe>& out,
                element_context& ctx) const {
    ctx.new_state[0] = ctx.old_state[0] + 1.0;
    record(event::evaluate, ctx, out.want_jacobian);
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

/// Captures the initial displacement of its DOF at the zero step, as the manual
/// describes the zero step ("installation of initial values", section 3.5;
/// NSTEP = 0 is the zero step, integration starts with NSTEP = 1), keeping it
/// in its state vector: NEW(1) = X(1) if NSTEP = 0, else NEW(1) = OLD(1).
/// A reference position of this kind is what a friction or plasticity element keeps.
struct initial_reference {
  static constexpr pradis::passport passport{.name = "REF0", .ext = 1, .par = 0, .str = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test: keeps the initial displacement",
                                     .name = "Reference position captured at the zero step",
                                     .field = "tests",
                                     .dofs = "1 - any DOF",
                                     .parameters = "",
                                     .work = "",
                                     .special = "none"};
  struct parameters {};
  explicit initial_reference(parameters) {}
  static initial_reference from_parameters(std::span<const double>) { return initial_reference(parameters{}); }
  void evaluate(const local_input<initial_reference>& in, local_output<initial_reference>& out,
                element_context& ctx) const {
    ctx.new_state[0] = ctx.nstep == 0 ? in.u(0) : ctx.old_state[0];
    if (out.want_jacobian) out.K(0, 0) = 0.0;
  }
};

using life_model = model<point_mass, linear_spring, linear_damper, constant_force, planar_inertia, planar_link,
                         initial_displacement, lifecycle_probe, initial_reference>;

}  // namespace

TEST_CASE("add_flat checks the DOF and parameter counts at run time") {
  life_model m;
  const dof a = m.add_dof("a"), b = m.add_dof("b"), c = m.add_dof("c");
  const std::array<double, 5> par{0, 0, 1, 0, 100};
  SUBCASE("DOF count mismatch: code 110") {
    const std::array<dof, 3> three{a, b, c};
    const auto e = error_of([&] { m.add_flat<planar_link>("link", three, par); });
    REQUIRE(e);
    CHECK(e->code() == error_code::invalid_model);
    CHECK(e->number() == 110);
    CHECK(e->element_type() == "LINKD");
    CHECK(e->instance() == "link");
    CHECK(contains(e->message(), "needs 4 DOFs (EXT), got 3"));
    CHECK(m.element_count() == 0);
  }
  SUBCASE("parameter count mismatch: code 101") {
    const std::array<dof, 4> four{m.ground(), m.ground(), a, b};
    const std::array<double, 4> short_par{0, 0, 1, 0};
    const auto e = error_of([&] { m.add_flat<planar_link>("link", four, short_par); });
    REQUIRE(e);
    CHECK(e->code() == error_code::parameter_count);
    CHECK(e->instance() == "link");
    CHECK(contains(e->message(), "got 4 parameters"));
  }
  SUBCASE("non-finite parameter: code 100") {
    const std::array<dof, 2> two{a, m.ground()};
    const std::array<double, 1> nan_par{std::numeric_limits<double>::quiet_NaN()};
    const auto e = error_of([&] { m.add_flat<linear_spring>("spring", two, nan_par); });
    REQUIRE(e);
    CHECK(e->code() == error_code::invalid_parameter);
    CHECK(e->element_type() == "SPRING");
    CHECK(e->instance() == "spring");
  }
  SUBCASE("a DOF that does not exist: code 110 naming the connection") {
    const std::array<dof, 2> two{a, dof{42}};
    const std::array<double, 1> k{10.0};
    const auto e = error_of([&] { m.add_flat<linear_spring>("spring", two, k); });
    REQUIRE(e);
    CHECK(e->code() == error_code::invalid_model);
    CHECK(contains(e->message(), "DOF 42 does not exist"));
    CHECK(contains(e->message(), "connection 2"));
  }
  SUBCASE("a correct flat placement") {
    const std::array<dof, 4> four{m.ground(), m.ground(), a, b};
    const auto r = m.add_flat<planar_link>("link", four, par);
    CHECK(m.instance(r).name == "link");
    CHECK(m.dof_of(r, 2) == a);
    CHECK(m.element(r).p.k == 100.0);
    CHECK(m.work(r).size() == 3);
  }
}

TEST_CASE("instance names are unique across element types") {
  life_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("body", {1.0}, x);
  auto e = error_of([&] { m.add<point_mass>("body", {2.0}, x); });
  REQUIRE(e);
  CHECK(e->code() == error_code::invalid_model);
  CHECK(e->instance() == "body");
  CHECK(contains(e->message(), "an element named 'body' already exists"));
  e = error_of([&] { m.add<linear_spring>("body", {1.0}, x, m.ground()); });
  REQUIRE(e);
  CHECK(e->code() == error_code::invalid_model);
  CHECK(e->element_type() == "SPRING");
  CHECK(m.element_count() == 1);
  // Unnamed instances get distinct generated names.
  m.add<linear_spring>("", {1.0}, x, m.ground());
  m.add<linear_spring>("", {2.0}, x, m.ground());
  CHECK(m.element_count() == 3);
  CHECK(m.instances<linear_spring>()[0].name != m.instances<linear_spring>()[1].name);
}

TEST_CASE("add_by_name places by catalog name; an unknown name is refused") {
  life_model m;
  const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
  const std::array<dof, 4> four{m.ground(), m.ground(), bx, by};
  const std::array<double, 5> par{0, 0, 1, 0, 100};
  const auto loc = m.add_by_name("LINKD", "link", four, par);
  CHECK(m.type_name(loc) == "LINKD");
  CHECK(m.instances<planar_link>().size() == 1);
  CHECK(m.instances<planar_link>()[static_cast<std::size_t>(loc.index)].name == "link");
  const auto found = m.find("link");
  REQUIRE(found);
  CHECK(found->type == loc.type);
  CHECK(found->index == loc.index);

  const auto e = error_of([&] { m.add_by_name("LINKQQ", "typo", four, par); });
  REQUIRE(e);
  CHECK(e->code() == error_code::invalid_model);
  CHECK(e->instance() == "typo");
  CHECK(contains(e->message(), "unknown element type 'LINKQQ'"));
  CHECK_FALSE(m.find("typo"));

  // A catalog-placed LINKD works in a run: it is the pendulum rod of a mass.
  const std::array<dof, 1> one_x{bx}, one_y{by};
  const std::array<double, 1> mass{1.0}, weight{-9.81};
  m.add_by_name("MASS", "mx", one_x, mass);
  m.add_by_name("MASS", "my", one_y, mass);
  m.add_by_name("F", "gravity", one_y, weight);
  simulation sim(m, newmark{});
  run_options o;
  o.end = 0.1;
  CHECK_NOTHROW(sim.run(o));
  CHECK(m.work("link")[0] == 1.0);  // W(1) = L0, computed at NEWINT
  CHECK(sim.u(by) < 0);             // released horizontally, it falls
}

TEST_CASE("lifecycle: NEWINT, zero step, steps with NSTEP and NITER, commit, NEWINT per stage") {
  life_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<initial_displacement>("x0", {0.1}, x);
  const auto pr = m.add<lifecycle_probe>("probe", {}, x);
  std::vector<event> ev;
  m.element(pr).events = &ev;
  simulation sim(m, newmark{});
  run_options o;
  o.end = 0.03;  // three steps of 0.01
  o.newton.method = newton_method::full;  // the default: a fresh Jacobian at every evaluation (modified: below)
  const auto st = sim.run(o);
  REQUIRE(st.steps == 3);
  REQUIRE(ev.size() >= 6);

  // NEWINT comes first, at t = 0, flagged, NSTEP = 0; then the zero-step hook.
  CHECK(ev[0].kind == event::newint);
  CHECK(ev[0].time == 0.0);
  CHECK(ev[0].nstep == 0);
  CHECK(ev[0].newint_flag);
  CHECK(ev[1].kind == event::zero_step);
  CHECK(ev[1].nstep == 0);
  // Zero step: evaluations at t = 0 with NSTEP = 0, the last one without the
  // Jacobian (flows for the results at t0), then the commit.
  std::size_t i = 2;
  bool saw_flows_only = false;
  for (; i < ev.size() && ev[i].kind == event::evaluate; ++i) {
    CHECK(ev[i].time == 0.0);
    CHECK(ev[i].nstep == 0);
    CHECK(ev[i].step == 0.0);
    saw_flows_only = !ev[i].want_jacobian;
  }
  CHECK(saw_flows_only);
  REQUIRE(i < ev.size());
  CHECK(ev[i].kind == event::commit);
  ++i;

  // Steps k = 1, 2, 3: evaluations at the END of the step (t = k h) with STEP = h,
  // NSTEP = k (the manual's test driver sets NSTEP = 1 for the first step),
  // NITER = 0, 1, ... within the step, OLD unchanged during the step; then one commit.
  for (long k = 1; k <= 3; ++k) {
    CAPTURE(k);
    int expected_iter = 0;
    REQUIRE(i < ev.size());
    REQUIRE(ev[i].kind == event::evaluate);
    CHECK(ev[i].nstep == k);
    const long nstep_of_step = ev[i].nstep;
    for (; i < ev.size() && ev[i].kind == event::evaluate; ++i) {
      CHECK(ev[i].time == doctest::Approx(0.01 * static_cast<double>(k)).epsilon(1e-12));
      CHECK(ev[i].step == doctest::Approx(0.01).epsilon(1e-12));
      CHECK(ev[i].nstep == nstep_of_step);
      CHECK(ev[i].niter == expected_iter++);
      CHECK(ev[i].want_jacobian);
      CHECK(ev[i].old_state == static_cast<double>(k));  // OLD = 1 (zero step) + k - 1
      CHECK_FALSE(ev[i].newint_flag);
    }
    CHECK(expected_iter >= 2);  // at least a correction and its check
    REQUIRE(i < ev.size());
    CHECK(ev[i].kind == event::commit);
    ++i;
  }
  CHECK(i == ev.size());
  // OLD counts the accepted evaluations: zero step + 3 steps, despite several
  // evaluations per step (NEW = OLD + 1 is repeatable).
  CHECK(m.old_state_pool()[m.instance(pr).state_offset] == 4.0);
  CHECK(m.work(pr)[0] == 1.0);

  // Second stage: NEWINT again, at the stage's start time, with NSTEP = steps so far.
  ev.clear();
  o.end = 0.05;
  sim.run(o);
  REQUIRE(!ev.empty());
  CHECK(ev[0].kind == event::newint);
  CHECK(ev[0].newint_flag);
  CHECK(ev[0].time == doctest::Approx(0.03).epsilon(1e-15));
  CHECK(ev[0].nstep == 3);
  int newints = 0, zero_steps = 0;
  for (const auto& e : ev) {
    newints += e.kind == event::newint;
    zero_steps += e.kind == event::zero_step;
  }
  CHECK(newints == 1);
  CHECK(zero_steps == 0);  // the zero step belongs to the first stage only
  CHECK(m.work(pr)[0] == 2.0);
  CHECK(m.old_state_pool()[m.instance(pr).state_offset] == 6.0);
}

TEST_CASE("an element that initialises at NSTEP = 0 captures the state at t0, not after the first step") {
  // Oscillator released from u0 = 0.1: the captured reference must be 0.1
  // exactly. If NSTEP were still 0 during step 1, the element would capture
  // u(h) = 0.1 cos(10 h) + O(h^2) = 0.099500... instead.
  life_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<initial_displacement>("x0", {0.1}, x);
  const auto ref = m.add<initial_reference>("reference", {}, x);
  simulation sim(m, newmark{});
  run_options o;
  o.end = 0.1;
  sim.run(o);
  CHECK(m.old_state_pool()[m.instance(ref).state_offset] == 0.1);
}

TEST_CASE("$REPLACE between stages: a changed parameter is checked at NEWINT and takes effect") {
  // Damped mass on a spring under a constant force settles at P/k (Hooke).
  life_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  const auto spring = m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<linear_damper>("damper", {20.0}, x, m.ground());  // critical: 2 sqrt(k m)
  m.add<constant_force>("load", {5.0}, x);
  simulation sim(m, stoermer{});
  run_options o;
  o.end = 3.0;
  o.newton.dabsi = 1e-10;
  o.newton.dabsu = 1e-12;
  sim.run(o);
  CHECK(sim.u(x) == doctest::Approx(5.0 / 100.0).epsilon(1e-9));

  SUBCASE("a valid new stiffness") {
    m.element(spring).p.k = 400.0;  // critical damping is now 40: c = 20 is under-critical, still decays
    o.end = 8.0;
    sim.run(o);
    CHECK(sim.u(x) == doctest::Approx(5.0 / 400.0).epsilon(1e-9));
    CHECK(m.work(spring)[0] == doctest::Approx(-5.0).epsilon(1e-9));  // spring force k (u2 - u1), compressive
  }
  SUBCASE("an invalid new stiffness stops the next stage with code 100") {
    m.element(spring).p.k = -1.0;
    o.end = 4.0;
    const auto e = error_of([&] { sim.run(o); });
    REQUIRE(e);
    CHECK(e->code() == error_code::invalid_parameter);
    CHECK(e->element_type() == "SPRING");
    CHECK(e->instance() == "spring");
    CHECK(sim.time() == 3.0);
  }
}

TEST_CASE("DOFs and elements added between stages start at rest; the rest of the state carries on") {
  life_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<initial_displacement>("x0", {0.1}, x);
  simulation sim(m, newmark{});
  run_options o;
  o.end = 0.5;
  sim.run(o);
  const double u_half = sim.u(x);
  CHECK(u_half == doctest::Approx(0.1 * std::cos(10.0 * 0.5)).epsilon(1e-2));

  const dof y = m.add_dof("y");
  m.add<point_mass>("mass 2", {2.0}, y);
  m.add<linear_spring>("spring 2", {50.0}, y, m.ground());
  o.end = 0.6;
  sim.run(o);
  CHECK(sim.u(y) == 0.0);  // at rest in its equilibrium: stays there
  CHECK(sim.v(y) == 0.0);
  // x carried on from its state at 0.5 (exact solution within the trapezoidal phase error).
  CHECK(sim.u(x) == doctest::Approx(0.1 * std::cos(10.0 * 0.6)).epsilon(1e-2));
  CHECK(sim.statistics().steps == 60);
}

TEST_CASE("lifecycle under modified Newton: only the evaluations that refresh the Jacobian ask for it") {
  // Same model; modified Newton. The first evaluation of the stage
  // assembles the Jacobian (a fresh one per stage); the linear model at a constant
  // step needs no other, so every later evaluation asks for the flows only.
  life_model m;
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {100.0}, x, m.ground());
  m.add<initial_displacement>("x0", {0.1}, x);
  const auto pr = m.add<lifecycle_probe>("probe", {}, x);
  std::vector<event> ev;
  m.element(pr).events = &ev;
  simulation sim(m, newmark{});
  run_options o;
  o.end = 0.03;
  o.newton.method = newton_method::modified;
  sim.run(o);
  std::vector<bool> in_steps;  // want_jacobian of the evaluations of steps 1..3, in order
  for (const auto& e : ev)
    if (e.kind == event::evaluate && e.nstep >= 1 && e.step > 0) in_steps.push_back(e.want_jacobian);
  REQUIRE(in_steps.size() >= 6);  // at least a correction and its check per step
  CHECK(in_steps[0]);
  CHECK(std::count(in_steps.begin(), in_steps.end(), true) == 1);
  CHECK(sim.statistics().steps == 3);
}
