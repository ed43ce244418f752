// The all-elements test: every element type of the built-in library (the type
// list pradis::elements::library_elements, so a new element is covered
// automatically) passes the finite-difference Jacobian check at many random
// states, has help text whose line counts match its passport, and rejects bad
// flat parameter counts (code 101 from the model's flat path, model::add_flat and
// add_by_name, which the model language uses: too few, and too many or of the wrong
// parity where PAR/VPR bounds them); the claims of inert and guard-state elements
// hold at every state. Reference: PRADIS element developer's manual, 3.6.8.

#include <doctest/doctest.h>

#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/testing/jacobian_check.hpp"
#include "testing/test_support.hpp"

using namespace pradis;

namespace {

/// Bad flat parameter counts: placing E from a flat PAR vector, as the model language does (model::add_flat<E>,
/// and add_by_name with its catalog name, which the language builder calls), with too few parameters (PAR - 1),
/// and with too many (PAR + 1: for VPR = 0 too many, for VPR = 11 or 21 the wrong parity; VPR = 1 has no upper
/// bound) must throw code 101 naming the element type and the instance, before the element is built from the
/// vector. The rule's own count, PAR, must not be refused with code 101 (the values, all 1, may be refused
/// otherwise: add_flat builds the element but runs no NEWINT).
template <class E>
void check_flat_parameter_counts() {
  constexpr passport p = E::passport;
  static_assert(p.parameter_count_ok(p.par), "PAR itself must satisfy the passport's PAR/VPR rule");
  library_model m;
  const std::vector<dof> ds(static_cast<std::size_t>(p.ext), m.ground());
  std::vector<int> bad;
  if (p.par > 0) bad.push_back(p.par - 1);
  if (p.vpr == 0 || p.vpr == 11 || p.vpr == 21) bad.push_back(p.par + 1);
  CHECK(!bad.empty());
  for (const int n : bad) {
    CAPTURE(n);
    REQUIRE(!p.parameter_count_ok(n));
    const std::vector<double> par(static_cast<std::size_t>(n), 1.0);
    const std::string mention = "got " + std::to_string(n) + " parameters";
    for (const bool by_name : {false, true}) {
      CAPTURE(by_name);
      const std::optional<error> e = pradis_test::error_of([&] {
        if (by_name)
          m.add_by_name(p.name, "count", ds, par);
        else
          m.add_flat<E>("count", ds, par);
      });
      REQUIRE_MESSAGE(e.has_value(), "a flat parameter count of ", n, " was accepted");
      INFO("what(): ", std::string(e->what()));
      CHECK(e->code() == error_code::parameter_count);
      CHECK(e->number() == 101);
      CHECK(e->element_type() == std::string(p.name));
      CHECK(e->instance() == "count");
      CHECK(e->message().find(mention) != std::string::npos);
    }
  }
  CHECK(m.element_count() == 0);  // nothing was placed
  const std::vector<double> par(static_cast<std::size_t>(p.par), 1.0);
  const std::optional<error> ok = pradis_test::error_of([&] { m.add_flat<E>("count", ds, par); });
  if (ok) {
    INFO("what(): ", std::string(ok->what()));
    CHECK(ok->code() != error_code::parameter_count);
  }
}

template <class E>
void check_one_element() {
  constexpr passport p = E::passport;
  CAPTURE(p.name);
  // Help text: one line per external DOF, per parameter (fixed count), per work entry.
  CHECK(!E::help.title.empty());
  CHECK(!E::help.name.empty());
  CHECK(!E::help.field.empty());
  CHECK(help_lines(E::help.dofs) == p.ext);
  if (p.vpr == 0) CHECK(help_lines(E::help.parameters) == p.par);
  if (!E::help.work.empty()) CHECK(help_lines(E::help.work) == p.wrk);
  CHECK(!E::help.special.empty());
  check_flat_parameter_counts<E>();

  testing::jacobian_checker<E> chk{E(E::example())};
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int checked = 0;
  // 200 random states; an element that admits fewer than 150 of them (a super-element with
  // five rotational nodes, each of which must keep |q| > 0.2) draws on, in the same two
  // ranges, until 150 admissible states are checked. Under the sanitizers (-O0, some 200x
  // slower: BEAM3C alone, whose every call runs a condensation, took over 20 minutes at 150
  // states) the same checks run at 10 states drawn alternately from both ranges: that run
  // looks for memory errors and undefined behaviour on every element's code paths; the
  // numerical coverage is the dev preset's 150 states.
  constexpr int trials = pradis_test::sanitized ? 10 : 200, required = pradis_test::sanitized ? 10 : 150;
  for (int trial = 0; trial < trials || (checked < required && trial < 2000); ++trial) {
    local_input<E> in;
    // Large displacements and rotations: up to +-3 (m or rad); velocities and accelerations up to +-10.
    const bool large = pradis_test::sanitized ? trial % 2 == 1 : trial % 200 >= 100;
    const double big = large ? 3.0 : 0.3;
    for (int k = 0; k < element_traits<E>::n; ++k) {
      in.u(k) = big * uni(rng);
      in.v(k) = 10 * uni(rng);
      in.a(k) = 10 * uni(rng);
    }
    in.t = 1.0 + uni(rng);
    if constexpr (requires(const E& e) { e.admissible(in); })
      if (!chk.element().admissible(in)) continue;
    if constexpr (InertElement<E>) {  // the assembler skips it: it must write nothing
      local_output<E> out;
      element_context ctx(p.name, "inert");
      std::vector<double> work(static_cast<std::size_t>(p.wrk));
      ctx.work = work;
      chk.element().evaluate(in, out, ctx);
      CHECK(out.f.isZero(0.0));
      if constexpr (element_traits<E>::has_k) CHECK(out.K.isZero(0.0));
      if constexpr (element_traits<E>::has_c) CHECK(out.C.isZero(0.0));
      if constexpr (element_traits<E>::has_m) CHECK(out.M.isZero(0.0));
      CHECK(ctx.recommended_step == std::numeric_limits<double>::infinity());
    }
    if constexpr (GuardStateElement<E>) {  // OLD must not enter the flows; NEW depends on the state alone
      std::fill(chk.old_state().begin(), chk.old_state().end(), 0.0);
      const auto f0 = chk.flows(in);
      const std::vector<double> new0(chk.new_state().begin(), chk.new_state().end());
      std::copy(new0.begin(), new0.end(), chk.old_state().begin());  // OLD as the step would leave it
      CHECK(chk.flows(in) == f0);
      CHECK(std::equal(new0.begin(), new0.end(), chk.new_state().begin(), chk.new_state().end()));
      std::fill(chk.old_state().begin(), chk.old_state().end(), 0.0);
    }
    auto r = chk.check(in);
    ++checked;
    if (!r.ok) {
      std::ostringstream os;
      r.print(os);
      FAIL_CHECK(os.str());
      break;
    }
  }
  CHECK(checked >= required);
}

template <class... Es>
void check_all(type_list<Es...>) {
  (check_one_element<Es>(), ...);
}

// The flows and dF/du of the LINKD `link` at in.u, for the test elements derived from it.
template <class E>
void linkd_flows(const elements::planar_link& link, const local_input<E>& in, local_output<E>& out,
                 element_context& ctx) {
  local_input<elements::planar_link> i2;
  i2.u = in.u;
  local_output<elements::planar_link> o2;
  link.evaluate(i2, o2, ctx);
  out.f = o2.f;
  out.K = o2.K;
}

// A deliberately wrong LINKD: the manual's dF1/dX2 with the wrong sign.
struct wrong_link : elements::planar_link {
  static constexpr pradis::passport passport{.name = "WRONG", .ext = 4, .par = 5, .wrk = 3, .adr = 1, .ign = 23};
  using elements::planar_link::planar_link;
  static wrong_link from_parameters(std::span<const double> v) { return wrong_link({v[0], v[1], v[2], v[3], v[4]}); }
  void evaluate(const local_input<wrong_link>& in, local_output<wrong_link>& out, element_context& ctx) const {
    linkd_flows(*this, in, out, ctx);
    out.K(0, 1) = -out.K(0, 1);
  }
};

// An element that declares IGN=2 (no velocity block) but whose flow depends on velocity.
struct hidden_damper {
  static constexpr pradis::passport passport{.name = "HIDDEN", .ext = 1, .par = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test", .name = "test", .field = "test", .dofs = "1", .parameters = "1",
                                     .work = "", .special = "none"};
  struct parameters {
    double c = 2;
  } p;
  explicit hidden_damper(parameters q) : p(q) {}
  static hidden_damper from_parameters(std::span<const double> v) { return hidden_damper({v[0]}); }
  void evaluate(const local_input<hidden_damper>& in, local_output<hidden_damper>& out, element_context&) const {
    out.f(0) = p.c * in.v(0) + in.u(0);
    out.K(0, 0) = 1.0;
  }
};

// LINKD claiming that its first flow does not depend on the second DOF (dF1/dX2 = 0),
// which is false: the checker must reject the claim.
struct wrong_structure_link : elements::planar_link {
  static constexpr pradis::passport passport{.name = "WRONGS", .ext = 4, .par = 5, .wrk = 3, .adr = 1, .ign = 23};
  using elements::planar_link::planar_link;
  static wrong_structure_link from_parameters(std::span<const double> v) {
    return wrong_structure_link({v[0], v[1], v[2], v[3], v[4]});
  }
  void evaluate(const local_input<wrong_structure_link>& in, local_output<wrong_structure_link>& out,
                element_context& ctx) const {
    linkd_flows(*this, in, out, ctx);
  }
  bool jacobian_entry(int r, int c) const { return !(r == 0 && c == 1); }
};

}  // namespace

TEST_SUITE("testing/jacobian_check") {
  TEST_CASE("the checker rejects a declared Jacobian structure that leaves out a nonzero entry") {
    static_assert(HasJacobianStructure<wrong_structure_link>);
    testing::jacobian_checker<wrong_structure_link> chk(wrong_structure_link({0, 0, 1, 0.5, 5e3}));
    local_input<wrong_structure_link> in;
    in.u << 0.1, -0.2, 0.05, 0.3;  // the link is stretched and turned: dF1/dX2 != 0
    auto r = chk.check(in);
    CHECK_FALSE(r.ok);
    REQUIRE(!r.problems.empty());
    CHECK(r.problems.front().find("dF1/du2 lies outside the structure") != std::string::npos);
    // The diagonal is always part of the structure, whatever the element says.
    CHECK(jacobian_entry_of(chk.element(), 1, 1));
    CHECK_FALSE(jacobian_entry_of(chk.element(), 0, 1));
  }

  TEST_CASE("every library element passes the finite-difference Jacobian check at random states (200; 10 under "
            "the sanitizers)") {
    check_all(elements::library_elements{});
  }

  TEST_CASE("the checker catches a deliberately wrong Jacobian entry and names it") {
    testing::jacobian_checker<wrong_link> chk(wrong_link({0, 0, 1, 0.5, 5e3}));
    local_input<wrong_link> in;
    in.u << 0.1, -0.2, 0.05, 0.3;
    auto r = chk.check(in);
    CHECK_FALSE(r.ok);
    REQUIRE(!r.problems.empty());
    CHECK(r.problems.front().find("F1/du2") != std::string::npos);
    CHECK(r.problems.front().find("does not shrink") != std::string::npos);
  }

  TEST_CASE("the checker catches a flow that depends on a variable whose block IGN declares absent") {
    testing::jacobian_checker<hidden_damper> chk(hidden_damper({2.0}));
    local_input<hidden_damper> in;
    in.v(0) = 1.0;
    auto r = chk.check(in);
    CHECK_FALSE(r.ok);
    REQUIRE(!r.problems.empty());
    CHECK(r.problems.front().find("declared absent") != std::string::npos);
  }

  TEST_CASE("the checker's difference shrinks with the step for a correct element (LINKD)") {
    // Steps large enough that truncation, not round-off, dominates: the error must fall as h^2.
    testing::jacobian_checker<elements::planar_link> chk(elements::planar_link({0, 0, 1, 0.5, 5e3}), 5,
                                                         {.rel_step = 0, .abs_step = 1e-3, .tolerance = 1e-2});
    local_input<elements::planar_link> in;
    in.u << 0.3, -0.2, -0.4, 0.6;
    auto r = chk.check(in);
    CHECK(r.ok);
    double fine = 0, coarse = 0;
    for (const auto& e : r.entries) {
      fine = std::max(fine, std::abs(e.numeric - e.analytic));
      coarse = std::max(coarse, std::abs(e.numeric_coarse - e.analytic));
    }
    CHECK(fine < coarse);
    CHECK(fine < 0.05 * coarse);  // 10x smaller step, ~100x smaller error
  }
}
