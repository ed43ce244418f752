// Condensed super-elements (elements/condensed.hpp): a composite whose internal DOFs are eliminated inside the element
// by nonlinear static condensation. References: springs in series have the stiffness k1 k2 / (k1 + k2) (Hooke's law,
// equal force in both springs); static (Guyan) condensation of a linear element is exact for its massless internal DOFs
// (R. J. Guyan, "Reduction of stiffness and mass matrices", AIAA J. 3 (1965) 380); the invariant that the condensed
// element is the composite with its internal equations solved, so a model with it moves as the model with the composite
// kept (docs/super-elements.md).

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "condensed_parts.hpp"
#include "element_test_support.hpp"
#include "pradis/elements/condensed.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/spatial/node_state.hpp"
#include "pradis/spatial/quaternion.hpp"
#include "pradis/testing/jacobian_check.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;
using pradis_element_tests::fixed_step;
using pradis_element_tests::jacobian_passes;
using namespace pradis_condensed_tests;

namespace {

// ---- condensed elements of the tests ----------------------------------------------

/// A spring whose force saturates: f = atan(u1 - u2). Newton on it diverges from far away.
struct atan_spring {
  static constexpr pradis::passport passport{.name = "ATANS", .ext = 2, .par = 0, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test spring with force atan(u1 - u2)",
                                     .name = "test",
                                     .field = "test",
                                     .dofs = "1 - a\n2 - b",
                                     .parameters = "",
                                     .work = "",
                                     .special = "none"};
  struct parameters {};
  explicit atan_spring(parameters) {}
  static atan_spring from_parameters(std::span<const double>) { return atan_spring({}); }
  void evaluate(const local_input<atan_spring>& in, local_output<atan_spring>& out, element_context&) const {
    const double d = in.u(0) - in.u(1), f = std::atan(d), k = 1 / (1 + d * d);
    out.f << f, -f;
    if (out.want_jacobian) out.K << k, -k, -k, k;
  }
};
struct soft_spec {
  static constexpr std::string_view name = "SOFT2C";
  static constexpr std::string_view title = "a weak linear spring in series with a saturating one";
  static constexpr int ext = 2, ent = 1;
};
using soft_series = condensed<soft_spec, part<linear_spring, 0, 2>, part<atan_spring, 2, 1>>;
/// A saturating spring from the external DOF to the condensed one, pulled there by a constant force: with |P| above
/// pi / 2 the condensed DOF has no equilibrium.
struct pulled_spec {
  static constexpr std::string_view name = "PULL1C";
  static constexpr std::string_view title = "a saturating spring pulled by a constant force at its condensed end";
  static constexpr int ext = 1, ent = 1;
};
using pulled_spring = condensed<pulled_spec, part<atan_spring, 0, 1>, part<constant_force, 1>>;
/// A spring whose force is d |d|, d = u1 - u2: its stiffness vanishes at rest, so Newton converges only linearly there.
struct square_spring {
  static constexpr pradis::passport passport{.name = "SQS", .ext = 2, .par = 0, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test spring with force d |d|",
                                     .name = "test",
                                     .field = "test",
                                     .dofs = "1 - a\n2 - b",
                                     .parameters = "",
                                     .work = "",
                                     .special = "none"};
  struct parameters {};
  explicit square_spring(parameters) {}
  static square_spring from_parameters(std::span<const double>) { return square_spring({}); }
  void evaluate(const local_input<square_spring>& in, local_output<square_spring>& out, element_context&) const {
    const double d = in.u(0) - in.u(1), f = d * std::abs(d), k = 2 * std::abs(d);
    out.f << f, -f;
    if (out.want_jacobian) out.K << k, -k, -k, k;
  }
};
struct square_spec {
  static constexpr std::string_view name = "SQUARE1C";
  static constexpr std::string_view title = "a spring of force d |d| with its far end condensed";
  static constexpr int ext = 1, ent = 1;
};
using square_end = condensed<square_spec, part<square_spring, 0, 1>>;

/// Parts that put mass, damping, or an initial value on the condensed DOF (all refused).
struct bad_spec {
  static constexpr std::string_view name = "BAD2C";
  static constexpr std::string_view title = "springs in series with something on the middle point";
  static constexpr int ext = 2, ent = 1;
};
using mass_in_middle = condensed<bad_spec, part<linear_spring, 0, 2>, part<point_mass, 2>, part<linear_spring, 2, 1>>;
using damper_to_middle =
    condensed<bad_spec, part<linear_spring, 0, 2>, part<linear_damper, 0, 2>, part<linear_spring, 2, 1>>;
using x0_in_middle =
    condensed<bad_spec, part<linear_spring, 0, 2>, part<initial_displacement, 2>, part<linear_spring, 2, 1>>;
/// Two links in a straight line A - C - B: the centre has no stiffness across the line when unstretched.
struct line_spec {
  static constexpr std::string_view name = "LINE2C";
  static constexpr std::string_view title = "two links in a line, the middle point condensed";
  static constexpr int ext = 4, ent = 2;
};
using straight_pair = condensed<line_spec, part<planar_link, 0, 1, 4, 5>, part<planar_link, 4, 5, 2, 3>>;

/// A random state around the reference (displacements of +-0.1, hidden q4 slots near 1).
template <class E>
local_input<E> random_state(std::mt19937& gen, std::initializer_list<int> q4 = {}) {
  std::uniform_real_distribution<double> d(-0.1, 0.1);
  local_input<E> in;
  for (int k = 0; k < element_traits<E>::n; ++k) {
    in.u(k) = d(gen);
    in.v(k) = 10 * d(gen);
    in.a(k) = 100 * d(gen);
  }
  for (int k : q4) in.u(k) += 1.0;
  return in;
}

/// The error that NEWINT and one call of e at the state `in` raise, with the instance name `name`, or nothing.
template <class E>
std::optional<pradis::error> evaluation_error(E e, std::string_view name, const local_input<E>& in = {}) {
  cond_context<E> c(name);
  return error_from([&] {
    e.new_integration(c.ctx);
    local_output<E> out;
    e.evaluate(in, out, c.ctx);
  });
}

/// A cantilever of one BEAM2C (or its kept composite BEAM2K): A clamped (its q1..q3 on the ground), B free.
template <class E>
struct beam2_cantilever {
  model<E, spatial_force, point_mass, initial_velocity> m;
  std::vector<dof> x;  ///< B's translations
  rotation_node rb;    ///< B's rotational node
  beam2_cantilever() {
    const rotation_node root = m.add_rotation_node("r0", m.ground(), m.ground(), m.ground());
    x = m.add_dofs(3, "xb");
    rb = m.add_rotation_node("rb");
    const dof g = m.ground();
    m.template add<E>("beam", E::example(), g, g, g, root, x[0], x[1], x[2], rb);
  }
};

}  // namespace

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using condensed_model = pradis::model<point_mass, linear_spring, series, initial_displacement, star, star_kept,
    initial_velocity>;
TEST_SUITE("elements/condensed") {
  TEST_CASE("the passport of a condensed composite: the external DOFs, the parts' PAR, one state per condensed DOF") {
    static_assert(check_element<series>());
    static_assert(series::passport.ext == 2 && series::passport.ent == 0);
    static_assert(series::passport.par == 2);
    static_assert(series::passport.str == 1);  // the middle point's displacement
    static_assert(series::passport.wrk == series_kept::passport.wrk + 2);
    static_assert(series::passport.adr == 1 && series::passport.ign == 23);  // K only, as the springs
    static_assert(series::condensed_dofs == std::array<int, 1>{2});
    static_assert(check_element<star>());
    static_assert(star::passport.ext == 6 && star::passport.ent == 0 && star::passport.str == 3 * 2 + 2);
    // The hidden q4 of the external rotational nodes stay, renumbered after the external DOFs.
    static_assert(check_element<beam_parts>());
    static_assert(beam_parts::passport.ext == 12 && beam_parts::passport.ent == 2);
    static_assert(beam_parts::rotation_nodes ==
                  std::array<rotation_slot, 2>{rotation_slot{3, 12}, rotation_slot{9, 13}});
    static_assert(beam_parts::condensed_dofs == std::array<int, 1>{14});
    CHECK(std::string(series::help.name) ==
          "Condensed super-element of 2 parts: SPRING, SPRING. Internal DOFs eliminated by static condensation: 1.");
    CHECK(std::string(series::help.work).find("6 - Newton iterations on the condensed DOFs in the last call") !=
          std::string::npos);
    CHECK(help_lines(series::help.parameters) == 2);
    CHECK(std::string(series::help.parameters).find("part 2 'SPRING' (right spring)") != std::string::npos);
    // Each condensed element's help title is its spec's.
    CHECK(std::string_view(soft_series::help.title) == soft_spec::title);
    CHECK(std::string_view(pulled_spring::help.title) == pulled_spec::title);
    CHECK(std::string_view(square_end::help.title) == square_spec::title);
    CHECK(std::string_view(mass_in_middle::help.title) == bad_spec::title);
    CHECK(std::string_view(straight_pair::help.title) == line_spec::title);
  }

  TEST_CASE("two springs in series condense to one spring of stiffness k1 k2 / (k1 + k2)") {
    const double k1 = 2.0e3, k2 = 3.0e3, keff = k1 * k2 / (k1 + k2);
    series s({{linear_spring::parameters{k1}, linear_spring::parameters{k2}}});
    cond_context<series> c("pair");
    s.new_integration(c.ctx);
    std::mt19937 gen(7);
    for (int trial = 0; trial < 5; ++trial) {
      const local_input<series> in = random_state<series>(gen);
      local_output<series> out;
      s.evaluate(in, out, c.ctx);
      const double d = in.u(0) - in.u(1);
      CHECK(out.f(0) == doctest::Approx(keff * d).epsilon(1e-13));
      CHECK(out.f(1) == doctest::Approx(-keff * d).epsilon(1e-13));
      CHECK(out.K(0, 0) == doctest::Approx(keff).epsilon(1e-13));
      CHECK(out.K(0, 1) == doctest::Approx(-keff).epsilon(1e-13));
      CHECK(out.K(1, 1) == doctest::Approx(keff).epsilon(1e-13));
      // The middle point where both springs carry the same force: (k1 u1 + k2 u2) / (k1 + k2).
      CHECK(c.new_s[0] == doctest::Approx((k1 * in.u(0) + k2 * in.u(1)) / (k1 + k2)).epsilon(1e-13));
      // Linear parts: one Newton step is exact, the second confirms it.
      CHECK(c.work[static_cast<std::size_t>(series::work_at)] <= 2.0);
    }
    CHECK(c.work[static_cast<std::size_t>(series::work_at + 1)] <= 10.0);
  }

  TEST_CASE("the damped Newton iterations converge where plain Newton cycles: a weak spring in series with a saturating one") {
    // r(x) = k x + atan(x - 5), k = 1e-3, from x = 0 (A at 0, B at 5): plain Newton overshoots ever further and ends
    // cycling between about -+ pi / (2 k); the line search (natural monotonicity) keeps the iterates near the root,
    // x* = 5 - tan(k x*) = 4.99500...
    soft_series s({{linear_spring::parameters{1e-3}, atan_spring::parameters{}}});
    cond_context<soft_series> c("soft");
    local_input<soft_series> in;
    in.u << 0.0, 5.0;
    local_output<soft_series> out;
    s.evaluate(in, out, c.ctx);
    const double x = c.new_s[0];
    CHECK(std::abs(1e-3 * x + std::atan(x - 5)) < 1e-12);
    CHECK(x == doctest::Approx(4.995).epsilon(1e-4));
    // Both ends carry the spring force k x* (the flows the system applies to the element).
    CHECK(out.f(0) == doctest::Approx(-1e-3 * x).epsilon(1e-10));
    CHECK(out.f(1) == doctest::Approx(1e-3 * x).epsilon(1e-10));
    MESSAGE("Newton iterations: ", c.work[static_cast<std::size_t>(soft_series::work_at)]);
    CHECK(c.work[static_cast<std::size_t>(soft_series::work_at)] <= 30.0);
  }

  TEST_CASE("a mass on the condensed springs moves as a mass on one spring of the series stiffness, to round-off") {
    // The same equation m u'' + keff u = 0 in both runs, same steps: only round-off in keff differs.
    const double k1 = 2.0e3, k2 = 3.0e3, keff = k1 * k2 / (k1 + k2), m = 0.5;
    const auto run = [&](bool condense) {
      condensed_model md;
      const dof x = md.add_dof("x");
      md.add<point_mass>("body", {m}, x);
      if (condense)
        md.add<series>("pair", {{linear_spring::parameters{k1}, linear_spring::parameters{k2}}}, x, md.ground());
      else
        md.add<linear_spring>("spring", {keff}, x, md.ground());
      md.add<initial_displacement>("x0", {0.01}, x);
      simulation sim(md);
      std::vector<double> u;
      sim.on_output([&](const auto& st) { u.push_back(st.u(x)); });
      sim.run(fixed_step(0.2, 1e-3));
      return u;
    };
    const std::vector<double> a = run(true), b = run(false);
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() == 201);
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    CHECK(worst <= 1e-14);  // measured 0 to a few 1e-18 (of a 1e-2 m motion)
    // The trapezoidal rule conserves the energy of the linear oscillator: the amplitude stays 0.01.
    double amp = 0;
    for (double u : a) amp = std::max(amp, std::abs(u));
    CHECK(amp <= 0.01 * (1 + 1e-9));
    CHECK(amp >= 0.0099);
  }

  TEST_CASE(
      "a condensed star of links: the centre in equilibrium, the flows those of the composite there, the Jacobian "
      "checked by finite differences") {
    star s(star::example());
    star_kept full(star_kept::example());
    cond_context<star> c("star");
    cond_context<star_kept> ck("kept");
    s.new_integration(c.ctx);
    full.new_integration(ck.ctx);
    std::mt19937 gen(11);
    for (int trial = 0; trial < 5; ++trial) {
      const local_input<star> in = random_state<star>(gen);
      local_output<star> out;
      s.evaluate(in, out, c.ctx);
      local_input<star_kept> fin;
      fin.u.head<6>() = in.u;
      fin.u.tail<2>() << c.new_s[6], c.new_s[7];
      local_output<star_kept> fout;
      full.evaluate(fin, fout, ck.ctx);
      const double scale = fout.f.cwiseAbs().maxCoeff();
      CHECK(fout.f.tail<2>().cwiseAbs().maxCoeff() <= 1e-12 * scale);  // the centre is in equilibrium
      CHECK((fout.f.head<6>() - out.f).cwiseAbs().maxCoeff() <= 1e-12 * scale);
      CHECK(c.work[static_cast<std::size_t>(star::work_at)] <= 6.0);  // Newton converges in a few steps
    }
    testing::jacobian_checker<star> chk{star(star::example())};
    for (int trial = 0; trial < 5; ++trial)
      if (!jacobian_passes(chk.check(random_state<star>(gen)))) break;
  }

  TEST_CASE("a model with the condensed star moves as the model with the star kept (its centre massless)") {
    // The same DAE, the same 300 steps: the kept model solves the centre's equations in its global Newton iterations,
    // the condensed element in its own. The bound is what the Newton tolerance allows (a velocity correction below
    // dabsu = 1e-9 m/s moves a displacement by less than h / 2 x 1e-9 m a step, 1.5e-10 m in 300 steps); measured:
    // 3.3e-16 m, round-off, as both Newton iterations converge quadratically far below it. The condensed model needs
    // 600 global Newton iterations, the kept one 1513.
    const auto run = [&](bool condense) {
      condensed_model md;
      std::vector<dof> x;
      for (int k = 0; k < 6; ++k) {
        x.push_back(md.add_dof("x" + std::to_string(k + 1)));
        md.add<point_mass>("m" + std::to_string(k + 1), {0.2}, x.back());
      }
      if (condense) {
        md.add<star>("star", star::example(), x[0], x[1], x[2], x[3], x[4], x[5]);
      } else {
        md.add<star_kept>("star", star_kept::example(), x[0], x[1], x[2], x[3], x[4], x[5]);  // C: internal
      }
      md.add<initial_velocity>("v3y", {1.0}, x[5]);
      md.add<initial_velocity>("v1x", {-0.5}, x[0]);
      simulation sim(md);
      std::vector<double> u;
      sim.on_output([&](const auto& st) {
        for (int k = 0; k < 6; ++k) u.push_back(st.u(x[static_cast<std::size_t>(k)]));
      });
      // Tolerances both models reach: the trapezoidal velocity of the kept massless centre changes by 2 / h times its
      // displacement correction, so tight_newton's 1e-12 m/s would ask for round-off in u.
      sim.run({.end = 0.3, .smax = 1e-3, .newton = {.dabsu = 1e-9, .drltu = 0, .dabsi = 1e-6, .drlti = 0, .itr = 10}});
      const auto& st = sim.statistics();
      INFO("condense ", condense, " steps ", st.steps, " rejected ", st.rejected_steps, " iterations ",
           st.newton_iterations);
      CHECK(st.rejected_steps == 0);
      return u;
    };
    const std::vector<double> a = run(true), b = run(false);
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() == 6 * 301);
    double worst = 0, size = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      worst = std::max(worst, std::abs(a[i] - b[i]));
      size = std::max(size, std::abs(b[i]));
    }
    CHECK(size > 0.1);
    CHECK(worst <= 1e-9 * size);
  }

  TEST_CASE(
      "the hidden q4 of external rotational nodes stay: a beam with condensed springs beside it is the beam with one "
      "spring of the series stiffness") {
    const double k1 = 4e2, k2 = 6e2, keff = k1 * k2 / (k1 + k2);
    const auto bp = elastic_beam::example();
    beam_parts s({{bp, linear_spring::parameters{k1}, linear_spring::parameters{k2}}});
    beam_one_spring one({{bp, linear_spring::parameters{keff}}});
    cond_context<beam_parts> c("beam");
    cond_context<beam_one_spring> c1("one");
    s.new_integration(c.ctx);
    one.new_integration(c1.ctx);
    std::mt19937 gen(5);
    for (int trial = 0; trial < 3; ++trial) {
      const local_input<beam_parts> in = random_state<beam_parts>(gen, {12, 13});
      local_input<beam_one_spring> i1;
      i1.u = in.u;
      i1.v = in.v;
      i1.a = in.a;
      local_output<beam_parts> out;
      local_output<beam_one_spring> o1;
      s.evaluate(in, out, c.ctx);
      one.evaluate(i1, o1, c1.ctx);
      const double fs = o1.f.cwiseAbs().maxCoeff(), ks = o1.K.cwiseAbs().maxCoeff();
      CHECK((out.f - o1.f).cwiseAbs().maxCoeff() <= 1e-12 * fs);
      CHECK((out.K - o1.K).cwiseAbs().maxCoeff() <= 1e-12 * ks);
    }
    testing::jacobian_checker<beam_parts> chk(
        beam_parts({{bp, linear_spring::parameters{k1}, linear_spring::parameters{k2}}}));
    for (int trial = 0; trial < 3; ++trial)
      if (!jacobian_passes(chk.check(random_state<beam_parts>(gen, {12, 13})))) break;
  }

  TEST_CASE("an inner rotational node is condensed with its q4: the passport of two BEAM3 with their middle node condensed") {
    static_assert(check_element<beam2>());
    static_assert(beam2::passport.ext == 12 && beam2::passport.ent == 2);  // the hidden q4 of A and B stay
    static_assert(beam2::rotation_nodes == std::array<rotation_slot, 2>{{{3, 12}, {9, 13}}});
    static_assert(beam2::inner_rotation_nodes == 1 && beam2::condensed_count == 7);  // N: x y z q1 q2 q3 q4
    static_assert(beam2::condensed_dofs == std::array<int, 7>{12, 13, 14, 15, 16, 17, 20});
    static_assert(beam2::passport.str == beam2_kept::passport.str + 7);
    static_assert(beam2_kept::rotation_nodes.size() == 3);  // the kept composite has N as a rotational node
    CHECK(std::string_view(beam2::help.name).find("Internal DOFs eliminated by static condensation: 7.") !=
          std::string_view::npos);
  }

  TEST_CASE(
      "two BEAM3 with their middle node condensed have the stiffness of one BEAM3 of the whole length, at rest and "
      "turned rigidly by a large rotation") {
    // Reference: the static Euler-Bernoulli beam under end loads has a cubic deflection, which the cubic element
    // represents exactly, so the static condensation of two elements equals one element of the total length (Guyan,
    // AIAA J. 3 (1965) 380; any FE text on beam elements). BEAM3 is corotational: a rigid rotation of the whole beam
    // leaves its flows zero and turns its stiffness with it (objectivity), and the condensed middle node must then
    // sit at the turned midpoint with the turned orientation.
    beam2 s(beam2::example());
    const elastic_beam one(beam2_spec::half(0, 1.0));
    cond_context<beam2> c("two halves");
    cond_context<elastic_beam> c1("one");
    s.new_integration(c.ctx);
    const auto compare = [&](const spatial::quaternion& q, const char* what) {
      CAPTURE(what);
      const spatial::mat3 r = spatial::rotation_matrix(q);
      local_input<beam2> in;
      const spatial::vec3 b0(1, 0, 0), ub = r * b0 - b0;  // A at the origin stays
      in.u.segment<3>(3) = q.head<3>();
      in.u.segment<3>(6) = ub;
      in.u.segment<3>(9) = q.head<3>();
      in.u(12) = in.u(13) = q(3);
      local_input<elastic_beam> i1;
      i1.u = in.u;
      local_output<beam2> out;
      local_output<elastic_beam> o1;
      s.evaluate(in, out, c.ctx);
      one.evaluate(i1, o1, c1.ctx);
      const double ks = o1.K.cwiseAbs().maxCoeff();
      CHECK(out.f.cwiseAbs().maxCoeff() <= 1e-12 * ks);  // a rigid motion stresses nothing
      CHECK((out.K - o1.K).cwiseAbs().maxCoeff() <= 1e-9 * ks);
      // The middle node N (condensed DOFs 0..5 and 6: x y z q1 q2 q3 q4) at the turned midpoint, turned by q.
      const spatial::vec3 n0(0.5, 0, 0), un = r * n0 - n0;
      for (int k = 0; k < 3; ++k) CHECK(std::abs(c.new_s[static_cast<std::size_t>(k)] - un(k)) <= 1e-12);
      const spatial::quaternion qn(c.new_s[3], c.new_s[4], c.new_s[5], c.new_s[6]);
      CHECK(std::min((qn - q).norm(), (qn + q).norm()) <= 1e-12);
      c.old_s = c.new_s;  // accept: the next call starts from here
      c.ctx.old_state = c.old_s;
    };
    compare(spatial::identity(), "at rest");
    // Turned in ten steps up to 170 degrees about an oblique axis, each call starting from the last accepted N.
    const spatial::vec3 axis = spatial::vec3(1, 2, 2) / 3;
    for (int k = 1; k <= 10; ++k) compare(spatial::from_axis_angle(axis, k * 0.1 * 170 * 3.14159265358979 / 180), "turned");
  }

  TEST_CASE(
      "two condensed BEAM3: the middle node in equilibrium, the flows those of the kept composite there, the "
      "Jacobian checked by finite differences") {
    beam2 s(beam2::example());
    beam2_kept full(beam2_kept::example());
    cond_context<beam2> c("beam2");
    cond_context<beam2_kept> ck("kept");
    s.new_integration(c.ctx);
    std::mt19937 gen(17);
    for (int trial = 0; trial < 5; ++trial) {
      const local_input<beam2> in = random_state<beam2>(gen, {12, 13});
      local_output<beam2> out;
      s.evaluate(in, out, c.ctx);
      local_input<beam2_kept> fin;
      fin.u.head<12>() = in.u.head<12>();
      fin.u(18) = in.u(12);
      fin.u(19) = in.u(13);
      for (int j = 0; j < 6; ++j) fin.u(12 + j) = c.new_s[static_cast<std::size_t>(j)];
      fin.u(20) = c.new_s[6];
      local_output<beam2_kept> fout;
      full.evaluate(fin, fout, ck.ctx);
      const double scale = fout.f.cwiseAbs().maxCoeff();
      CHECK(fout.f.segment<6>(12).cwiseAbs().maxCoeff() <= 1e-12 * scale);  // N is in equilibrium
      CHECK(std::abs(fin.u.segment<3>(15).squaredNorm() + fin.u(20) * fin.u(20) - 1) <= 1e-12);  // |q_N| = 1
      CHECK((fout.f.head<12>() - out.f.head<12>()).cwiseAbs().maxCoeff() <= 1e-12 * scale);
      CHECK(c.work[static_cast<std::size_t>(beam2::work_at)] <= 6.0);  // Newton converges in a few steps
    }
    testing::jacobian_checker<beam2> chk{beam2(beam2::example())};
    for (int trial = 0; trial < 5; ++trial)
      if (!jacobian_passes(chk.check(random_state<beam2>(gen, {12, 13})))) break;
  }

  TEST_CASE(
      "a cantilever of two condensed BEAM3: static tip deflection P L^3 / (3 E I) in both planes, as the kept "
      "composite") {
    // Reference: Euler-Bernoulli cantilever under a tip load, deflection P L^3 / (3 E I) and slope P L^2 / (2 E I)
    // (Timoshenko and Gere, Mechanics of Materials); the cubic elements are exact for it. P = 1e-4 N gives a tip
    // deflection of 3e-5 L, so the geometric nonlinearity of the corotational beam is ~1e-9 relative.
    const double p = 1e-4, e = 1e4, iy = 1e-4, iz = 2e-4;
    const auto run = [&](auto tag) {
      beam2_cantilever<typename decltype(tag)::type> c;
      c.m.template add<spatial_force>("load", {0, p, p, 0, 0, 0, 0, 0}, c.x[0], c.x[1], c.x[2]);
      simulation sim(c.m);
      sim.run({.end = 1.0, .smax = 0.5,
               .newton = {.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-11, .drlti = 0, .itr = 8}});
      const spatial::quaternion q = spatial::node_quaternion(sim, c.rb);
      MESSAGE("rotational nodes ", c.m.rotation_nodes().size(), ", Newton iterations ",
              sim.statistics().newton_iterations);
      return std::array<double, 4>{sim.u(c.x[1]), sim.u(c.x[2]), -2 * q(1) / q(3), 2 * q(2) / q(3)};
    };
    const auto a = run(std::type_identity<beam2>{}), b = run(std::type_identity<beam2_kept>{});
    const double uy = p / (3 * e * iz), uz = p / (3 * e * iy), slope_y = p / (2 * e * iy), slope_z = p / (2 * e * iz);
    MESSAGE("condensed: tip deflection errors y ", a[0] / uy - 1, ", z ", a[1] / uz - 1);
    CHECK(std::abs(a[0] / uy - 1) < 1e-6);
    CHECK(std::abs(a[1] / uz - 1) < 1e-6);
    CHECK(std::abs(a[2] / slope_y - 1) < 1e-6);  // the slope about -Y from the bending in the X-Z plane
    CHECK(std::abs(a[3] / slope_z - 1) < 1e-6);
    for (int k = 0; k < 4; ++k) CHECK(std::abs(a[static_cast<std::size_t>(k)] - b[static_cast<std::size_t>(k)]) <=
                                      1e-9 * std::abs(b[static_cast<std::size_t>(k)]));
  }

  TEST_CASE(
      "a mass on a cantilever of two condensed BEAM3 swings with the period 2 pi sqrt(m L^3 / (3 E I)), as on the kept "
      "composite") {
    // Reference: a massless cantilever with a tip mass m (translations only) is a spring of k = 3 E I / L^3 in each
    // bending plane (Timoshenko and Gere); small amplitude (1e-3 of L), so the period is 2 pi sqrt(m / k). The kept
    // composite solves the same equations with N among the global DOFs: the two runs agree to round-off.
    const double e = 1e4, iz = 2e-4, mass = 0.06, k = 3 * e * iz, period = 2 * 3.14159265358979 * std::sqrt(mass / k);
    const auto run = [&](auto tag) {
      beam2_cantilever<typename decltype(tag)::type> c;
      for (int i = 0; i < 3; ++i)
        c.m.template add<point_mass>("m" + std::to_string(i + 1), {mass}, c.x[static_cast<std::size_t>(i)]);
      c.m.template add<initial_velocity>("v0", {0.01}, c.x[1]);
      simulation sim(c.m);
      std::vector<double> y, t;
      sim.on_output([&](const auto& st) {
        y.push_back(st.u(c.x[1]));
        t.push_back(st.time());
      });
      sim.run({.end = 0.7, .smax = 1e-3, .newton = {.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-10, .drlti = 0, .itr = 8}});
      MESSAGE("Newton iterations ", sim.statistics().newton_iterations, ", steps ", sim.statistics().steps);
      CHECK(sim.statistics().rejected_steps == 0);
      // The period from the two downward zero crossings (linear interpolation between outputs).
      std::vector<double> down;
      for (std::size_t i = 1; i < y.size(); ++i)
        if (y[i - 1] > 0 && y[i] <= 0) down.push_back(t[i - 1] + (t[i] - t[i - 1]) * y[i - 1] / (y[i - 1] - y[i]));
      REQUIRE(down.size() >= 1);
      return std::pair<std::vector<double>, double>{y, down[0]};
    };
    const auto ra = run(std::type_identity<beam2>{}), rk = run(std::type_identity<beam2_kept>{});
    const std::vector<double>&ya = ra.first, &yb = rk.first;
    const double ta = ra.second;
    // The first downward crossing is at half a period.
    MESSAGE("half period ", ta, " exact ", period / 2);
    CHECK(std::abs(2 * ta / period - 1) < 1e-3);
    REQUIRE(ya.size() == yb.size());
    double worst = 0, size = 0;
    for (std::size_t i = 0; i < ya.size(); ++i) {
      worst = std::max(worst, std::abs(ya[i] - yb[i]));
      size = std::max(size, std::abs(yb[i]));
    }
    MESSAGE("largest difference condensed - kept: ", worst / size, " of the amplitude");
    CHECK(size > 5e-4);
    CHECK(worst <= 1e-9 * size);
  }

  TEST_CASE("the parts' admissibility tests apply at the condensed state") {
    // Invariant: a condensed element admits exactly the states at which the kept composite, with the condensed DOFs
    // solved, admits its parts' states; without a part's test there is none.
    static_assert(!composite_detail::has_admissible<series>);
    static_assert(composite_detail::has_admissible<beam2> && composite_detail::has_admissible<star>);
    const beam2 s(beam2::example());
    const beam2_kept full(beam2_kept::example());
    std::mt19937 gen(23);
    for (int trial = 0; trial < 5; ++trial) {
      const local_input<beam2> in = random_state<beam2>(gen, {12, 13});
      CHECK(s.admissible(in));
    }
    local_input<beam2> in;
    in.u(12) = in.u(13) = 1.0;
    REQUIRE(s.admissible(in));
    SUBCASE("node B's quaternion near zero: BEAM3's test refuses it") {
      in.u(13) = 0.1;
      local_input<beam2_kept> fin;
      fin.u.head<12>() = in.u.head<12>();
      fin.u(18) = in.u(12);
      fin.u(19) = in.u(13);
      fin.u(20) = 1.0;
      CHECK(!full.admissible(fin));
      CHECK(!s.admissible(in));
    }
    SUBCASE("B pushed back onto A: the chords collapse") {
      in.u(6) = -0.97;
      CHECK(!s.admissible(in));
    }
    SUBCASE("a star whose point P1 is pulled onto its centre") {
      const star st(star::example());
      local_input<star> sin;
      CHECK(st.admissible(sin));
      sin.u(0) = 1.0;  // P1 from (0, 0) to (1, 0); the centre at rest is at (1, 0.7)
      sin.u(1) = 0.7;
      CHECK(!st.admissible(sin));
    }
  }

  TEST_CASE("errors of a condensed composite") {
    SUBCASE("a part's bad parameter: code 100 at NEWINT, naming the part") {
      check_error(evaluation_error(series({{linear_spring::parameters{1.0}, linear_spring::parameters{-2.0}}}), "pair"),
                  error_code::invalid_parameter, "SPRING2C", "pair",
                  "part 2 'SPRING' (right spring), parameters 2..2 of SPRING2C: stiffness k = -2 must be finite");
    }
    SUBCASE("mass on the condensed DOF: code 100") {
      const mass_in_middle s(
          {{linear_spring::parameters{1.0}, point_mass::parameters{2.0}, linear_spring::parameters{1.0}}});
      check_error(evaluation_error(s, "mid"), error_code::invalid_parameter, "BAD2C", "mid",
                  "internal DOF 3 (on part 1 'SPRING') carries mass (dF/da): a condensed DOF must be quasi-static");
    }
    SUBCASE("damping on the condensed DOF: code 100") {
      const damper_to_middle s(
          {{linear_spring::parameters{1.0}, linear_damper::parameters{2.0}, linear_spring::parameters{1.0}}});
      check_error(evaluation_error(s, "mid"), error_code::invalid_parameter, "BAD2C", "mid",
                  "internal DOF 3 (on part 1 'SPRING') carries damping (dF/dv)");
    }
    SUBCASE("an initial value requested on the condensed DOF: code 90") {
      x0_in_middle s(
          {{linear_spring::parameters{1.0}, initial_displacement::parameters{0.1}, linear_spring::parameters{1.0}}});
      cond_context<x0_in_middle> c("mid");
      initial_values<2> iv;
      check_error(error_from([&] { s.zero_step(iv, c.ctx); }), error_code::conflicting_initial, "BAD2C", "mid",
                  "a part requests an initial value of internal DOF 3, which is condensed");
    }
    SUBCASE("no stiffness on the condensed DOF: code 75, the step is cut") {
      // A - C - B on a line, unstretched: the centre can move across the line freely (K_II singular).
      const straight_pair s({{planar_link::parameters{0, 0, 1, 0, 1e3}, planar_link::parameters{1, 0, 2, 0, 1e3}}});
      check_error(evaluation_error(s, "line"), error_code::singular_situation, "LINE2C", "line",
                  "the stiffness of the condensed DOFs is singular");
    }
    SUBCASE("Newton on the condensed DOF converges too slowly: code 75 after 30 iterations") {
      // r(x) = (x - 1) |x - 1| from x = 0: at the double root Newton halves the distance per iteration, so the
      // correction is still 2^-30 ~ 1e-9 (above the tolerance 1e-10) after 30 iterations.
      local_input<square_end> in;
      in.u << 1.0;
      check_error(evaluation_error(square_end(square_end::parameters{std::tuple{square_spring::parameters{}}}), "square", in),
                  error_code::singular_situation, "SQUARE1C", "square",
                  "the condensed DOFs did not converge in 30 Newton iterations");
    }
    SUBCASE("no equilibrium of the condensed DOF: code 75 when its stiffness vanishes") {
      // r(x) = atan(x - u1) - P with P = 2 > pi / 2 has no root: the iterations walk off to where the saturated
      // spring's stiffness is zero.
      local_input<pulled_spring> in;
      in.u << 0.5;
      check_error(
          evaluation_error(pulled_spring({{atan_spring::parameters{}, constant_force::parameters{2.0}}}), "pulled", in),
          error_code::singular_situation, "PULL1C", "pulled", "the stiffness of the condensed DOFs is singular");
    }
    SUBCASE("a non-finite input: code 150, no NaN leaves the element") {
      local_input<series> in;
      in.u(0) = std::nan("");
      check_error(
          evaluation_error(series({{linear_spring::parameters{1.0}, linear_spring::parameters{1.0}}}), "pair", in),
          error_code::non_finite, "SPRING2C", "pair", "non-finite flow or stiffness on a condensed DOF");
    }
  }
}
