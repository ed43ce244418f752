// Models: internal DOFs (ENT) allocated automatically, variable parameter counts
// (VPR) with state (STR/STP) and work (WRK/WRP) lengths, by-name lookup of work
// vectors, and the analytic relaxation of a Maxwell element that lives on an
// internal DOF.

#include <doctest/doctest.h>

#include <cmath>
#include <span>
#include <sstream>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

// Maxwell element (spring k and damper c in series) between DOF 1 and the ground,
// with the series point as an internal DOF (ENT = 1): flows on the external DOF
// k (u1 - ui); on the internal DOF k (ui - u1) + c vi. ADR=1, IGN=3 (no inertia).
struct maxwell {
  static constexpr pradis::passport passport{.name = "MAXW", .ext = 1, .ent = 1, .par = 2, .wrk = 1, .adr = 1, .ign = 3};
  static constexpr element_help help{.title = "Maxwell element to ground",
                                     .name = "spring and damper in series, series point internal",
                                     .field = "mechanics",
                                     .dofs = "1 - the connected DOF",
                                     .parameters = "1 - k\n2 - c",
                                     .work = "1 - force",
                                     .special = "none"};
  struct parameters {
    double k = 1, c = 1;
  } p;
  explicit maxwell(parameters q) : p(q) {}
  static parameters example() { return {}; }
  static maxwell from_parameters(std::span<const double> v) { return maxwell({v[0], v[1]}); }
  void evaluate(const local_input<maxwell>& in, local_output<maxwell>& out, element_context& ctx) const {
    const double f = p.k * (in.u(0) - in.u(1));
    out.f << f, -f + p.c * in.v(1);
    ctx.work[0] = f;
    if (!out.want_jacobian) return;
    out.K << p.k, -p.k, -p.k, p.k;
    out.C << 0, 0, 0, p.c;
  }
};

// Variable parameter count: odd number of parameters (VPR=11), STP=1, WRP=2.
struct table_element {
  static constexpr pradis::passport passport{
      .name = "TAB", .ext = 1, .par = 1, .vpr = 11, .str = 1, .stp = 1, .wrk = 1, .wrp = 2, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "t", .name = "t", .field = "t", .dofs = "1", .parameters = "1",
                                     .work = "1", .special = "none"};
  struct parameters {
    std::vector<double> values;
  } p;
  explicit table_element(parameters q) : p(std::move(q)) {}
  static parameters example() { return {{1.0}}; }
  static table_element from_parameters(std::span<const double> v) { return table_element({{v.begin(), v.end()}}); }
  int parameter_count() const { return static_cast<int>(p.values.size()); }
  void evaluate(const local_input<table_element>&, local_output<table_element>& out, element_context&) const {
    if (out.want_jacobian) out.K(0, 0) = 1.0;
  }
};

// An element that declares itself inert (core/element.hpp, InertElement) but, to show
// that the assembler never calls it, would write a flow and a Jacobian entry.
struct claims_inert {
  static constexpr pradis::passport passport{.name = "INERT", .ext = 1, .par = 0, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "t", .name = "t", .field = "t", .dofs = "1", .parameters = "",
                                     .work = "", .special = "none"};
  struct parameters {};
  parameters p;
  explicit claims_inert(parameters) {}
  static claims_inert from_parameters(std::span<const double>) { return claims_inert({}); }
  static constexpr bool inert = true;
  void evaluate(const local_input<claims_inert>&, local_output<claims_inert>& out, element_context&) const {
    out.f(0) = 1.0;
    if (out.want_jacobian) out.K(0, 0) = 1.0;
  }
};

}  // namespace

TEST_CASE("the assembler skips inert elements (initial conditions): no flow, no Jacobian entry") {
  // X0, V0 and ROT0 declare themselves inert; claims_inert would write 1 if it were called.
  static_assert(InertElement<elements::initial_displacement> && InertElement<elements::initial_velocity> &&
                InertElement<elements::initial_rotation> && InertElement<claims_inert>);
  static_assert(!InertElement<point_mass> && !InertElement<linear_spring>);
  using M = model<point_mass, linear_spring, claims_inert>;
  M m;
  const dof a = m.add_dof("a");
  m.add<point_mass>("m", {2.0}, a);
  m.add<linear_spring>("k", {5.0}, a, m.ground());
  m.add<claims_inert>("i", {}, a);
  std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
  assembler<M> as;
  as.build(m, prescribed);
  global_state s;
  s.resize(m.dof_count());
  s.u(a.index) = 0.1;
  s.a(a.index) = 0.3;
  as.evaluate(m, s, jacobian_coefficients{0.5, 1.0, 4.0}, call_info{0.0, 1e-3, 1, 0, true, nullptr});
  CHECK(as.residual()(a.index) == doctest::Approx(5.0 * 0.1 + 2.0 * 0.3));  // the spring and the mass alone
  const int e = as.equation_of(a.index);
  CHECK(as.values()[static_cast<std::size_t>(as.pattern().find(e, e))] == doctest::Approx(0.5 * 5.0 + 4.0 * 2.0));
}

TEST_SUITE("core/model") {
  TEST_CASE("an element with ENT = 1 gets a hidden internal DOF allocated by the model") {
    model<maxwell, point_mass> m;
    const auto x = m.add_dof("x");
    const int before = m.dof_count();
    const auto r = m.add<maxwell>("mx", {2.0, 3.0}, x);
    CHECK(m.dof_count() == before + 1);
    CHECK(m.dof_of(r, 0) == x);
    CHECK(m.dof_of(r, 1).index == before);
    CHECK(m.dof_name(before) == "mx.internal1");
  }

  TEST_CASE("a Maxwell element held at a constant stretch relaxes as k u0 exp(-k t / c)") {
    // Exact: the internal point obeys c vi = k (u0 - ui), ui(0) = 0, so the force
    // k (u0 - ui) = k u0 exp(-k t / c). Newmark average acceleration on this
    // first-order equation is the trapezoidal rule: relative error ~ (k h / c)^2 t k / (12 c).
    model<maxwell, displacement_source> m;
    const auto x = m.add_dof("x");
    const double k = 10, c = 2, u0 = 0.1;
    m.add<maxwell>("mx", {k, c}, x);
    m.add<displacement_source>("hold", {.amplitude = 0, .frequency = 0, .phase_deg = 0, .offset = u0}, x);
    simulation sim(m, newmark{});
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double exact = k * u0 * std::exp(-k * s.time() / c);
      worst = std::max(worst, std::abs(s.get_model().work("mx")[0] - exact));
    });
    sim.run({.end = 1.0, .out = 0.01, .smax = 1e-3, .newton = {.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-12, .drlti = 0}});
    // bound: k u0 * (k h / c)^2 / 12 * (k t / c) e^{-k t / c} <= 1 * 2.5e-5 / 12 * 0.37 ~ 8e-7
    CHECK(worst < 1e-6);
    // The reaction of the source equals the Maxwell force (W(1) of XSRC).
    CHECK(m.work("hold")[0] == doctest::Approx(m.work("mx")[0]).epsilon(1e-9));
  }

  TEST_CASE("variable parameter counts follow VPR=11 and size state and work by STP and WRP") {
    model<table_element> m;
    const auto x = m.add_dof();
    const std::array<dof, 1> d{x};
    const std::vector<double> five{1, 2, 3, 4, 5};
    const auto r = m.add_flat<table_element>("t5", d, five);
    CHECK(m.instance(r).npar == 5);
    CHECK(m.instance(r).state_size == 1 + 4 * 1);
    CHECK(m.instance(r).work_size == 1 + 4 * 2);
    CHECK(m.work("t5").size() == 9);
    const std::vector<double> four{1, 2, 3, 4};
    try {
      m.add_flat<table_element>("t4", d, four);
      FAIL("an even count must be refused");
    } catch (const error& e) {
      CHECK(e.code() == error_code::parameter_count);
      CHECK(e.instance() == "t4");
      CHECK(e.element_type() == "TAB");
      CHECK(std::string(e.what()).find("odd") != std::string::npos);
    }
  }

  TEST_CASE("elements are found by instance name and by catalog name") {
    library_model m;
    const auto d = m.add_dofs(4);
    const std::vector<double> par{0, 0, 1, 0, 100};
    const auto loc = m.add_by_name("LINKD", "link", d, par);
    CHECK(m.type_name(loc) == "LINKD");
    CHECK(m.find("link").has_value());
    CHECK_FALSE(m.find("nothing").has_value());
    CHECK(m.work("link").size() == 3);
    CHECK_THROWS_AS(m.work("nothing"), error);
    try {
      m.add_by_name("LINKQQ", "bad", d, par);
      FAIL("unknown catalog name must be refused");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_model);
      CHECK(std::string(e.what()).find("LINKQQ") != std::string::npos);
    }
  }

  TEST_CASE("a DOF index outside the model is refused with the connection number") {
    model<point_mass> m;
    try {
      m.add<point_mass>("m", {1.0}, dof{7});
      FAIL("must throw");
    } catch (const error& e) {
      CHECK(e.code() == error_code::invalid_model);
      CHECK(e.instance() == "m");
      CHECK(std::string(e.what()).find("DOF 7 does not exist") != std::string::npos);
    }
  }
}

TEST_CASE("a partial Jacobian (call_info::jacobian_types) assembles the listed element types only") {
  // Two masses joined by a spring, the second on a damper to the ground: with
  // J = cu K + cv C + ca M the full values are the sum of each type's part; asking
  // for the spring's type alone gives cu k [1 -1; -1 1] and nothing of the masses
  // or the damper. The flows are those of all types either way.
  using M = model<point_mass, linear_spring, linear_damper>;
  M m;
  const dof a = m.add_dof("a"), b = m.add_dof("b");
  m.add<point_mass>("ma", {2.0}, a);
  m.add<point_mass>("mb", {3.0}, b);
  m.add<linear_spring>("k", {5.0}, a, b);
  m.add<linear_damper>("c", {7.0}, b, m.ground());
  std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
  prescribed[0] = 1;
  assembler<M> as;
  as.build(m, prescribed);
  global_state s;
  s.resize(m.dof_count());
  s.u(a.index) = 0.1;
  s.v(b.index) = 0.2;
  const jacobian_coefficients c{0.5, 1.0, 4.0};
  as.evaluate(m, s, c, call_info{0.0, 1e-3, 1, 0, true, nullptr});
  const std::vector<double> full(as.values().begin(), as.values().end());
  const Eigen::VectorXd flows = as.residual();
  const std::vector<char> spring_only{0, 1, 0};  // model<point_mass, linear_spring, linear_damper>
  call_info partial{0.0, 1e-3, 1, 0, false, nullptr};
  partial.jacobian_types = &spring_only;
  as.evaluate(m, s, c, partial);
  const auto& pat = as.pattern();
  auto value = [&](std::span<const double> v, dof r, dof col) {
    const int ra = as.equation_of(r.index), ca = as.equation_of(col.index);
    return v[static_cast<std::size_t>(pat.find(ra, ca))];
  };
  CHECK(value(as.values(), a, a) == doctest::Approx(0.5 * 5.0));
  CHECK(value(as.values(), a, b) == doctest::Approx(-0.5 * 5.0));
  CHECK(value(as.values(), b, b) == doctest::Approx(0.5 * 5.0));
  CHECK(value(full, a, a) == doctest::Approx(0.5 * 5.0 + 4.0 * 2.0));
  CHECK(value(full, b, b) == doctest::Approx(0.5 * 5.0 + 7.0 + 4.0 * 3.0));
  CHECK(as.residual()(a.index) == flows(a.index));
  CHECK(as.residual()(b.index) == flows(b.index));
  // Restricted to the rows of b (as the BDF driver restricts G to its constraint rows):
  // row b as before, bit for bit, row a not assembled; a full Jacobian is unaffected.
  const std::vector<double> spring_part(as.values().begin(), as.values().end());
  as.restrict_partial_rows({as.equation_of(b.index)});
  as.evaluate(m, s, c, partial);
  CHECK(value(as.values(), b, a) == value(spring_part, b, a));
  CHECK(value(as.values(), b, b) == value(spring_part, b, b));
  CHECK(value(as.values(), a, a) == 0.0);
  CHECK(value(as.values(), a, b) == 0.0);
  as.evaluate(m, s, c, call_info{0.0, 1e-3, 1, 0, true, nullptr});
  CHECK(std::vector<double>(as.values().begin(), as.values().end()) == full);
  // build() lifts the restriction.
  as.build(m, prescribed);
  as.evaluate(m, s, c, partial);
  CHECK(std::vector<double>(as.values().begin(), as.values().end()) == spring_part);
}

TEST_CASE("kept element blocks (keep_blocks): J for other coefficients from them equals a fresh assembly") {
  // A rigid body with an offset centre of mass and a weight at an offset on a
  // rotational node (its norm equation has K and C parts) at a turned, moving
  // state: K, C and M are kept apart, so reform(c2) after an evaluation at c1 is
  // cu2 K + cv2 C + ca2 M, the matrix a full evaluation at c2 assembles (to
  // rounding: the sums are taken in another order).
  using namespace pradis::elements;
  using M = model<rigid_body, offset_force, initial_rotation>;
  M m;
  const auto x = m.add_dofs(3, "x");
  const rotation_node r = m.add_rotation_node("r");
  m.add<rigid_body>("body", rigid_body::example(), x[0], x[1], x[2], r);
  m.add<offset_force>("weight", offset_force::example(), x[0], x[1], x[2], r);
  std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
  prescribed[0] = 1;
  assembler<M> as;
  as.build(m, prescribed);
  CHECK_FALSE(as.keeps_blocks());
  as.keep_blocks(true);
  CHECK(as.keeps_blocks());
  global_state s;
  s.resize(m.dof_count());
  for (int d = 1; d < m.dof_count(); ++d) {
    s.u(d) = 0.3 * std::sin(1.7 * d);
    s.v(d) = 2.0 * std::cos(0.9 * d);
    s.a(d) = 5.0 * std::sin(0.4 * d);
  }
  s.u(r.q4.index) = 0.9;
  const jacobian_coefficients c1{1 / 0.37, 1.0, 0.37}, c2{1 / 2.9, 1.0, 2.9};
  const call_info full{0.0, 1e-3, 1, 0, true, nullptr}, flows{0.0, 1e-3, 1, 0, false, nullptr};
  as.evaluate(m, s, c2, full);
  const std::vector<double> fresh(as.values().begin(), as.values().end());
  as.evaluate(m, s, c1, full);
  const std::size_t version = as.blocks_version();
  as.evaluate(m, s, c1, flows);  // flows only: the kept blocks stay
  CHECK(as.blocks_version() == version);
  as.reform(c2);
  double scale = 0, diff = 0;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    scale = std::max(scale, std::abs(fresh[i]));
    diff = std::max(diff, std::abs(as.values()[i] - fresh[i]));
  }
  CHECK(scale > 1.0);
  CHECK(diff <= 1e-14 * scale);
  as.evaluate(m, s, c1, full);  // another Jacobian evaluation: the version moves on
  CHECK(as.blocks_version() != version);
}
