// Bad input ends in one pradis::error with the right code, the element type and
// instance it concerns (empty for kernel errors, which name the DOF instead) and
// a message that says what is wrong; the diagnostics log (SYSPRINT.TXT role)
// receives the same text unless an element_context::mute_guard is alive (the
// SYSPRN = 0 of a super-element). Codes 75, 90 and 100 are the ones of the
// PRADIS element developer's manual (section 3.3 / pradis-methods.md section 3).

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "testing/test_support.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

using pradis_test::contains;
using pradis_test::error_of;

/// The last non-empty line of a log.
std::string last_line(const std::string& s) {
  std::string t = s;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  const auto p = t.rfind('\n');
  return p == std::string::npos ? t : t.substr(p + 1);
}

/// Flow v - 1 with the WRONG sign of its velocity Jacobian (dF/dv = -1 reported,
/// +1 true): Newton moves away from v = 1 at every step size, since with the
/// velocity unknown the Newton matrix is C alone, independent of h.
struct wrong_jacobian {
  static constexpr pradis::passport passport{.name = "WRONGJ", .ext = 1, .par = 0, .adr = 2, .ign = 3};
  static constexpr element_help help{.title = "test: wrong Jacobian sign",
                                     .name = "Test element whose Jacobian has the wrong sign",
                                     .field = "tests",
                                     .dofs = "1 - any DOF",
                                     .parameters = "",
                                     .work = "",
                                     .special = "Newton diverges"};
  struct parameters {};
  explicit wrong_jacobian(parameters) {}
  static wrong_jacobian from_parameters(std::span<const double>) { return wrong_jacobian(parameters{}); }
  void evaluate(const local_input<wrong_jacobian>& in, local_output<wrong_jacobian>& out, element_context&) const {
    out.f(0) = in.v(0) - 1.0;
    if (out.want_jacobian) out.C(0, 0) = -1.0;
  }
};

/// A spring that goes bad from time t_bad on: mode 0 NaN flow, 1 infinite flow,
/// 2 NaN stiffness entry, 3 singular situation (code 75).
struct bad_spring {
  static constexpr pradis::passport passport{.name = "BADSPRING", .ext = 1, .par = 2, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test: a spring that goes bad",
                                     .name = "Test spring producing NaN, Inf or a singular situation",
                                     .field = "tests",
                                     .dofs = "1 - the DOF",
                                     .parameters = "1 - mode\n2 - time from which it is bad",
                                     .work = "",
                                     .special = "by design"};
  struct parameters {
    double mode = 0, t_bad = 0;
  };
  parameters p;
  explicit bad_spring(parameters q) : p(q) {}
  static bad_spring from_parameters(std::span<const double> v) { return bad_spring({v[0], v[1]}); }
  void evaluate(const local_input<bad_spring>& in, local_output<bad_spring>& out, element_context& ctx) const {
    const bool bad = ctx.time >= p.t_bad;
    const int mode = static_cast<int>(p.mode);
    out.f(0) = 10.0 * in.u(0);
    if (bad && mode == 0) out.f(0) = std::numeric_limits<double>::quiet_NaN();
    if (bad && mode == 1) out.f(0) = std::numeric_limits<double>::infinity();
    if (bad && mode == 3) ctx.singular("the test spring reached its singular state");
    if (out.want_jacobian)
      out.K(0, 0) = bad && mode == 2   ? std::numeric_limits<double>::quiet_NaN()
                    : bad && mode == 4 ? std::numeric_limits<double>::infinity()
                                       : 10.0;
  }
};

/// A super-element: a LINKD sub-model evaluated under a mute_guard (SYSPRN = 0).
/// With `probe` set, each evaluation also tries the sub-model at a zero-length
/// state, catches its code 75 silently and carries on (the super-element's
/// business); without `mute`, the same probe writes to the log.
struct super_link {
  static constexpr pradis::passport passport{.name = "SUPERLINK", .ext = 4, .par = 5, .wrk = 3, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test: LINKD wrapped in a super-element",
                                     .name = "Test super-element calling LINKD",
                                     .field = "tests",
                                     .dofs = "1 - A.x\n2 - A.y\n3 - B.x\n4 - B.y",
                                     .parameters = "1 - xa0\n2 - ya0\n3 - xb0\n4 - yb0\n5 - k",
                                     .work = "1 - L0\n2 - L\n3 - axial force",
                                     .special = "none"};
  using parameters = planar_link::parameters;
  planar_link inner;
  bool mute = true;
  bool probe = false;
  int probe_failures = 0;
  explicit super_link(parameters q) : inner(q) {}
  static super_link from_parameters(std::span<const double> v) { return super_link({v[0], v[1], v[2], v[3], v[4]}); }
  void new_integration(element_context& ctx) { inner.new_integration(ctx); }
  void evaluate(const local_input<super_link>& in, local_output<super_link>& out, element_context& ctx) const {
    local_input<planar_link> li;
    li.u = in.u;
    li.v = in.v;
    li.a = in.a;
    li.t = in.t;
    local_output<planar_link> lo;
    lo.want_jacobian = out.want_jacobian;
    if (probe) {
      local_input<planar_link> zero = li;  // B moved onto A: zero length
      zero.u(2) = inner.p.xa0 - inner.p.xb0 + zero.u(0);
      zero.u(3) = inner.p.ya0 - inner.p.yb0 + zero.u(1);
      try {
        if (mute) {
          element_context::mute_guard quiet(ctx);
          inner.evaluate(zero, lo, ctx);
        } else {
          inner.evaluate(zero, lo, ctx);
        }
      } catch (const error& e) {
        if (e.code() != error_code::singular_situation) throw;
        ++const_cast<super_link*>(this)->probe_failures;
      }
      lo.clear();
    }
    {
      element_context::mute_guard quiet(ctx);
      inner.evaluate(li, lo, ctx);
    }
    out.f = lo.f;
    if (out.want_jacobian) out.K = lo.K;
  }
};

using bad_model = model<point_mass, linear_spring, linear_damper, planar_inertia, planar_link, initial_displacement,
                        initial_velocity, displacement_source, velocity_source, constant_force, wrong_jacobian,
                        bad_spring, super_link>;

run_options quick(double end = 0.2) {
  run_options o;
  o.end = end;
  o.smax = 0.01;
  o.smin = 1e-6;
  return o;
}

/// Runs the model; returns the error and the log text.
struct outcome {
  std::optional<error> e;
  std::string log;
};
template <class Scheme = newmark>
outcome run_model(bad_model& m, run_options o = quick(), Scheme s = {}) {
  simulation sim(m, s);
  std::ostringstream log;
  sim.log().to(log);
  auto e = error_of([&] { sim.run(o); });
  return {e, log.str()};
}

/// A healthy oscillator on DOF 'x' so that the model has something to integrate.
dof add_oscillator(bad_model& m) {
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {10.0}, x, m.ground());
  return x;
}

void check_logged(const outcome& r) {
  REQUIRE(r.e);
  // The error text is the last line written to the log.
  CHECK(last_line(r.log) == std::string(r.e->what()));
}

}  // namespace

TEST_CASE("invalid element parameters stop the run with code 100 naming the element and instance") {
  SUBCASE("negative SPRING stiffness") {
    bad_model m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("weak spring", {-5.0}, x, m.ground());
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::invalid_parameter);
    CHECK(r.e->number() == 100);
    CHECK(r.e->element_type() == "SPRING");
    CHECK(r.e->instance() == "weak spring");
    CHECK(contains(r.e->message(), "stiffness k = -5"));
    CHECK(contains(r.e->message(), ">= 0"));
    CHECK(contains(r.e->what(), "pradis error 100 (invalid parameter) in SPRING 'weak spring'"));
    check_logged(r);
  }
  SUBCASE("a small negative stiffness is shown as it is, not rounded to -0.000000") {
    bad_model m;
    const dof x = m.add_dof("x");
    m.add<point_mass>("mass", {1.0}, x);
    m.add<linear_spring>("almost zero", {-2.5e-7}, x, m.ground());
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::invalid_parameter);
    CHECK(r.e->instance() == "almost zero");
    INFO(r.e->message());
    CHECK(contains(r.e->message(), "2.5"));
    CHECK_FALSE(contains(r.e->message(), "-0.000000"));
  }
  SUBCASE("negative LINKD stiffness") {
    bad_model m;
    const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
    m.add<point_mass>("mx", {1.0}, bx);
    m.add<point_mass>("my", {1.0}, by);
    m.add<planar_link>("rod", {0, 0, 1, 0, -1e3}, m.ground(), m.ground(), bx, by);
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::invalid_parameter);
    CHECK(r.e->element_type() == "LINKD");
    CHECK(r.e->instance() == "rod");
    CHECK(contains(r.e->message(), "stiffness k = -1000"));
    check_logged(r);
  }
  SUBCASE("zero-length LINKD") {
    bad_model m;
    const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
    m.add<point_mass>("mx", {1.0}, bx);
    m.add<point_mass>("my", {1.0}, by);
    m.add<planar_link>("stub", {0.5, 0.5, 0.5, 0.5, 1e3}, m.ground(), m.ground(), bx, by);
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::invalid_parameter);
    CHECK(r.e->element_type() == "LINKD");
    CHECK(r.e->instance() == "stub");
    CHECK(contains(r.e->message(), "coincide"));
    CHECK(contains(r.e->message(), "length is zero"));
    check_logged(r);
  }
  SUBCASE("negative mass (MASS) and negative moment of inertia (MD)") {
    {
      bad_model m;
      const dof x = m.add_dof("x");
      m.add<point_mass>("heavy", {-2.0}, x);
      m.add<linear_spring>("spring", {10.0}, x, m.ground());
      const auto r = run_model(m);
      REQUIRE(r.e);
      CHECK(r.e->code() == error_code::invalid_parameter);
      CHECK(r.e->element_type() == "MASS");
      CHECK(r.e->instance() == "heavy");
      CHECK(contains(r.e->message(), "mass m = -2"));
      check_logged(r);
    }
    {
      bad_model m;
      const auto d = m.add_dofs(3, "body.");
      m.add<planar_inertia>("body", {1.0, -0.1}, d[0], d[1], d[2]);
      const auto r = run_model(m);
      REQUIRE(r.e);
      CHECK(r.e->code() == error_code::invalid_parameter);
      CHECK(r.e->element_type() == "MD");
      CHECK(r.e->instance() == "body");
      CHECK(contains(r.e->message(), "moment of inertia J = -0.1"));
    }
  }
}

TEST_CASE("conflicting initial conditions stop the run with code 90 naming the later element") {
  SUBCASE("two X0 with different values on one DOF") {
    bad_model m;
    const dof x = add_oscillator(m);
    m.add<initial_displacement>("x0 first", {0.1}, x);
    m.add<initial_displacement>("x0 second", {0.2}, x);
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::conflicting_initial);
    CHECK(r.e->number() == 90);
    CHECK(r.e->element_type() == "X0");
    CHECK(r.e->instance() == "x0 second");
    CHECK(contains(r.e->message(), "conflicts with 0.1 set by 'x0 first'"));
    CHECK(contains(r.e->message(), "DOF 'x'"));
    check_logged(r);
  }
  SUBCASE("V0 on a DOF driven by a displacement source") {
    bad_model m;
    const dof x = add_oscillator(m);
    const dof drive = m.add_dof("drive");
    m.add<linear_spring>("coupling", {5.0}, drive, x);
    m.add<displacement_source>("shaker", {0.1, 1.0, 0.0, 0.0}, drive);
    m.add<initial_velocity>("kick", {1.0}, drive);
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::conflicting_initial);
    CHECK(r.e->element_type() == "V0");
    CHECK(r.e->instance() == "kick");
    CHECK(contains(r.e->message(), "driven by XSRC 'shaker'"));
  }
}

TEST_CASE("a DOF with neither stiffness, viscosity nor mass: singular matrix naming the DOF and its elements") {
  // SPRING with k = 0 between a free DOF and the ground: the DOF has a (zero)
  // Jacobian entry, so the pattern is fine but every Newton matrix is singular
  // at it; every step is cut down to SMIN, then the kernel reports it.
  bad_model m;
  add_oscillator(m);
  const dof lonely = m.add_dof("lonely");
  m.add<linear_spring>("slack spring", {0.0}, lonely, m.ground());
  const auto r = run_model(m);
  REQUIRE(r.e);
  CHECK(r.e->code() == error_code::singular_matrix);
  CHECK(r.e->number() == 131);
  CHECK(r.e->instance().empty());
  CHECK(r.e->dof() == lonely.index);
  CHECK(contains(r.e->message(), "singular at DOF 'lonely'"));
  CHECK(contains(r.e->message(), "SPRING 'slack spring'"));
  check_logged(r);
}

TEST_CASE("a DOF that no element touches: structurally singular, naming the DOF") {
  bad_model m;
  add_oscillator(m);
  const dof orphan = m.add_dof("orphan");
  const auto r = run_model(m);
  REQUIRE(r.e);
  CHECK(r.e->code() == error_code::structurally_singular);
  CHECK(r.e->number() == 130);
  CHECK(r.e->instance().empty());
  CHECK(r.e->dof() == orphan.index);
  CHECK(contains(r.e->message(), "DOF 'orphan'"));
  CHECK(contains(r.e->message(), "no element acts on it"));
  check_logged(r);
}

TEST_CASE("Newton divergence down to SMIN: code 140 with 'SMIN' and the worst DOF") {
  bad_model m;
  add_oscillator(m);
  const dof wobbly = m.add_dof("wobbly");
  m.add<wrong_jacobian>("wrong", {}, wobbly);
  run_options o = quick();
  o.smin = 1e-5;  // 10 halvings from SMAX = 1e-2
  o.newton.itr = 3;
  simulation sim(m, newmark{});
  std::ostringstream log;
  sim.log().to(log);
  const auto e = error_of([&] { sim.run(o); });
  REQUIRE(e);
  CHECK(e->code() == error_code::newton_failure);
  CHECK(e->number() == 140);
  CHECK(e->instance().empty());
  CHECK(e->dof() == wobbly.index);
  CHECK(contains(e->message(), "SMIN"));
  CHECK(contains(e->message(), "DOF 'wobbly'"));
  CHECK(sim.statistics().steps == 0);
  CHECK(sim.statistics().rejected_steps >= 10);
  CHECK(last_line(log.str()) == std::string(e->what()));
}

TEST_CASE("a NaN or infinite flow or Jacobian entry: code 150 naming the instance") {
  struct case_t {
    double mode, t_bad;
    const char* fragment;
  };
  // t_bad = 0: at the zero step; 0.05: during a step (not treated as a failed step).
  for (const case_t c : {case_t{0, 0.0, "a flow is NaN or infinite"}, case_t{0, 0.05, "a flow is NaN or infinite"},
                         case_t{1, 0.05, "a flow is NaN or infinite"},
                         case_t{2, 0.05, "a Jacobian entry dF/du is NaN or infinite"},
                         case_t{4, 0.05, "a Jacobian entry dF/du is NaN or infinite"}}) {
    CAPTURE(c.mode);
    CAPTURE(c.t_bad);
    bad_model m;
    const dof x = add_oscillator(m);
    m.add<bad_spring>("bad one", {c.mode, c.t_bad}, x);
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::non_finite);
    CHECK(r.e->number() == 150);
    CHECK(r.e->element_type() == "BADSPRING");
    CHECK(r.e->instance() == "bad one");
    CHECK(contains(r.e->message(), c.fragment));
    check_logged(r);
  }
}

TEST_CASE("a singular situation persisting at SMIN: code 75 naming the element") {
  SUBCASE("custom element from t = 0.05 on") {
    bad_model m;
    const dof x = add_oscillator(m);
    m.add<bad_spring>("fragile", {3, 0.05}, x);
    const auto r = run_model(m);
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::singular_situation);
    CHECK(r.e->number() == 75);
    CHECK(r.e->element_type() == "BADSPRING");
    CHECK(r.e->instance() == "fragile");
    CHECK(contains(r.e->message(), "singular state"));
    CHECK(contains(r.e->message(), "persists at SMIN"));
    check_logged(r);
  }
  SUBCASE("LINKD whose end B is driven onto A") {
    // A grounded at (0, 0), B at (1, 0); VSRC drives B.x with v = -1, so the
    // length 1 - t vanishes at END = 1, where every last step lands.
    bad_model m;
    const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
    m.add<velocity_source>("pull", {0.0, 0.0, 0.0, -1.0}, bx);
    m.add<point_mass>("my", {1.0}, by);
    m.add<planar_link>("link", {0, 0, 1, 0, 10.0}, m.ground(), m.ground(), bx, by);
    const auto r = run_model(m, quick(1.0));
    REQUIRE(r.e);
    CHECK(r.e->code() == error_code::singular_situation);
    CHECK(r.e->element_type() == "LINKD");
    CHECK(r.e->instance() == "link");
    CHECK(contains(r.e->message(), "length of the link has become close to zero"));
    CHECK(contains(r.e->message(), "persists at SMIN"));
    check_logged(r);
  }
}

TEST_CASE("invalid integration options: code 120 with the option named; the run does not start") {
  auto option_error = [](run_options o, const std::string& fragment) {
    CAPTURE(fragment);
    bad_model m;
    add_oscillator(m);
    simulation sim(m, newmark{});
    std::ostringstream log;
    sim.log().to(log);
    const auto e = error_of([&] { sim.run(o); });
    REQUIRE(e);
    CHECK(e->code() == error_code::invalid_option);
    CHECK(e->number() == 120);
    CHECK(e->instance().empty());
    CHECK(contains(e->message(), fragment));
    CHECK(last_line(log.str()) == std::string(e->what()));
    // Nothing ran: a valid stage afterwards starts from the zero step at t = 0.
    CHECK(sim.statistics().steps == 0);
    CHECK(sim.time() == 0.0);
    run_options ok;
    ok.end = 0.05;
    CHECK_NOTHROW(sim.run(ok));
    CHECK(sim.statistics().steps == 5);
  };
  run_options o;
  SUBCASE("SMIN > SMAX") {
    o.smin = 0.1;
    o.smax = 0.01;
    option_error(o, "SMIN = 0.1 is above SMAX = 0.01");
  }
  SUBCASE("negative OUT") {
    o.out = -0.1;
    option_error(o, "OUT = -0.1 must be >= 0");
  }
  SUBCASE("ITR = 0") {
    o.newton.itr = 0;
    option_error(o, "ITR = 0 must be >= 1");
  }
  SUBCASE("NaN END") {
    o.end = std::numeric_limits<double>::quiet_NaN();
    option_error(o, "END must be a finite number");
  }
  SUBCASE("END before the start time") {
    o.end = -1.0;
    option_error(o, "END = -1 must be after the current time 0");
  }
  SUBCASE("SMAX = 0") {
    o.smax = 0.0;
    option_error(o, "SMAX = 0 must be > 0");
  }
  SUBCASE("negative DABSU") {
    o.newton.dabsu = -1.0;
    option_error(o, "DABSU = -1 must be >= 0");
  }
}

TEST_CASE("END before the current time on the second stage is refused; the simulation stays usable") {
  bad_model m;
  const dof x = add_oscillator(m);
  simulation sim(m, newmark{});
  std::ostringstream log;
  sim.log().to(log);
  run_options o;
  o.end = 1.0;
  sim.run(o);
  const double u1 = sim.u(x);
  o.end = 0.5;
  auto e = error_of([&] { sim.run(o); });
  REQUIRE(e);
  CHECK(e->code() == error_code::invalid_option);
  CHECK(contains(e->message(), "END = 0.5 must be after the current time 1"));
  CHECK(last_line(log.str()) == std::string(e->what()));
  o.end = 1.0;  // END equal to the current time: nothing to do, also refused
  e = error_of([&] { sim.run(o); });
  REQUIRE(e);
  CHECK(e->code() == error_code::invalid_option);
  CHECK(sim.time() == 1.0);
  CHECK(sim.u(x) == u1);
  o.end = 1.1;
  CHECK_NOTHROW(sim.run(o));
  CHECK(sim.time() == 1.1);
}

TEST_CASE("NEWMARK parameters out of range: code 120 naming gamma or beta") {
  struct case_t {
    double beta, gamma;
    const char* fragment;
  };
  for (const case_t c : {case_t{0.25, 0.4, "gamma = 0.4"}, case_t{0.25, 1.5, "gamma = 1.5"},
                         case_t{0.25, std::numeric_limits<double>::quiet_NaN(), "gamma"}, case_t{0.0, 0.5, "beta = 0"},
                         case_t{0.6, 0.6, "beta = 0.6"}}) {
    CAPTURE(c.fragment);
    const auto e = error_of([&] { newmark s(newmark_parameters{c.beta, c.gamma}); });
    REQUIRE(e);
    CHECK(e->code() == error_code::invalid_option);
    CHECK(contains(e->message(), "NEWMARK"));
    CHECK(contains(e->message(), c.fragment));
    CHECK(contains(e->message(), "valid range"));
  }
  CHECK_NOTHROW(newmark(newmark_parameters{0.5, 1.0}));
  CHECK_NOTHROW(newmark(newmark_parameters{0.3025, 0.6}));
}

TEST_CASE("diagnostics: errors go to the log; a mute_guard suppresses a sub-model's messages") {
  SUBCASE("element_context::fail writes to the log, muted or not it throws") {
    diagnostics log;
    std::ostringstream os;
    log.to(os);
    super_link sup({0, 0, 1, 0, 100.0});
    element_context ctx("SUPERLINK", "super", &log);
    std::vector<double> work(3, 0.0);
    ctx.work = work;
    sup.new_integration(ctx);
    CHECK(work[0] == 1.0);
    local_input<super_link> in;
    in.u << 0.0, 0.0, -1.0, 0.0;  // B moved onto A
    local_output<super_link> out;
    // The sub-model's code 75 propagates with the super-element's identity, unlogged.
    auto e = error_of([&] { sup.evaluate(in, out, ctx); });
    REQUIRE(e);
    CHECK(e->code() == error_code::singular_situation);
    CHECK(e->element_type() == "SUPERLINK");
    CHECK(e->instance() == "super");
    CHECK(contains(e->message(), "close to zero"));
    CHECK(os.str().empty());
    CHECK_FALSE(ctx.muted());  // the guard is gone after the throw
    // Unmuted, the same failure is logged.
    local_input<planar_link> li;
    li.u = in.u;
    local_output<planar_link> lo;
    e = error_of([&] { sup.inner.evaluate(li, lo, ctx); });
    REQUIRE(e);
    CHECK(last_line(os.str()) == std::string(e->what()));
    // Warnings too are muted under the guard only.
    os.str("");
    {
      element_context::mute_guard quiet(ctx);
      element_context::mute_guard nested(ctx);
      ctx.warn("hidden");
    }
    CHECK(os.str().empty());
    ctx.warn("visible");
    CHECK(os.str() == "SUPERLINK 'super': visible\n");
  }
  SUBCASE("in a run: a super-element's muted probe leaves the log empty") {
    for (const bool mute : {true, false}) {
      CAPTURE(mute);
      bad_model m;
      const dof bx = m.add_dof("B.x"), by = m.add_dof("B.y");
      m.add<point_mass>("mx", {1.0}, bx);
      m.add<point_mass>("my", {1.0}, by);
      m.add<constant_force>("gravity", {-9.81}, by);
      const auto sref = m.add<super_link>("super", {0, 0, 1, 0, 1e3}, m.ground(), m.ground(), bx, by);
      m.element(sref).probe = true;
      m.element(sref).mute = mute;
      simulation sim(m, newmark{});
      std::ostringstream log;
      sim.log().to(log);
      run_options o;
      o.end = 0.05;
      CHECK_NOTHROW(sim.run(o));
      CHECK(m.element(sref).probe_failures > 0);
      if (mute) {
        CHECK(log.str().empty());
      } else {
        CHECK(contains(log.str(), "pradis error 75 (singular situation) in SUPERLINK 'super'"));
      }
    }
  }
}
