// Composite super-elements (elements/composite.hpp) and the crank throws THROW and THROWP. References: the
// PRADIS element developer's manual (an element may call other elements as a sub-model, with SYSPRN = 0 muting
// their messages); the invariant that a super-element kept without condensation is the same set of nodal equations
// as the expanded model of its parts (docs/super-elements.md).

#include <doctest/doctest.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "element_test_support.hpp"
#include "pradis/elements/electric/passive.hpp"
#include "pradis/elements/spatial/crank_throw.hpp"
#include "pradis/io/model_scene.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

namespace {

using throw_t = crank_throw;
constexpr int n_throw = element_traits<throw_t>::n;

// ---- test-only parts ---------------------------------------------------------

/// A spring that writes a warning to the diagnostics log at every evaluation.
struct warning_spring {
  static constexpr pradis::passport passport{.name = "WARNS", .ext = 2, .par = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{.title = "test spring that warns",
                                     .name = "test",
                                     .field = "test",
                                     .dofs = "1 - a\n2 - b",
                                     .parameters = "1 - k",
                                     .work = "",
                                     .special = "code 100 never"};
  struct parameters {
    double k = 1;
  } p;
  explicit warning_spring(parameters q) : p(q) {}
  static warning_spring from_parameters(std::span<const double> v) { return warning_spring({v[0]}); }
  void evaluate(const local_input<warning_spring>& in, local_output<warning_spring>& out, element_context& ctx) const {
    ctx.warn("stretched");
    out.f(0) = p.k * (in.u(0) - in.u(1));
    out.f(1) = -out.f(0);
    if (out.want_jacobian) out.K << p.k, -p.k, -p.k, p.k;
  }
};
/// A spring that adds its stiffness to the blocks it is handed and counts the
/// evaluations that received blocks that were not zero (local_output's contract:
/// with want_jacobian they arrive zeroed, so elements may add to them).
struct adding_spring {
  static constexpr pradis::passport passport{.name = "ADDS", .ext = 2, .par = 1, .adr = 1, .ign = 23};
  static constexpr element_help help = [] {
    element_help h = warning_spring::help;
    h.title = "test spring that adds to its block";
    return h;
  }();
  using parameters = warning_spring::parameters;
  parameters p;
  static inline int dirty_blocks = 0;
  explicit adding_spring(parameters q) : p(q) {}
  static adding_spring from_parameters(std::span<const double> v) { return adding_spring({v[0]}); }
  void evaluate(const local_input<adding_spring>& in, local_output<adding_spring>& out, element_context&) const {
    out.f(0) = p.k * (in.u(0) - in.u(1));
    out.f(1) = -out.f(0);
    if (!out.want_jacobian) return;
    if (!out.K.isZero(0.0)) ++dirty_blocks;
    out.K(0, 0) += p.k;
    out.K(0, 1) -= p.k;
    out.K(1, 0) -= p.k;
    out.K(1, 1) += p.k;
  }
};
struct add_spec {
  static constexpr std::string_view name = "APAIR";
  static constexpr std::string_view title = "two adding springs in series";
  static constexpr int ext = 2, ent = 1;
};
using add_pair = composite<add_spec, part<adding_spring, 0, 2>, part<adding_spring, 2, 1>>;

/// Fills 32 kB of the stack below the caller with non-zero values.
[[gnu::noinline]] double dirty_stack() {
  volatile double junk[4096];
  for (int i = 0; i < 4096; ++i) junk[i] = 1.0 + i;
  return junk[4095];
}

struct warn_spec {
  static constexpr std::string_view name = "WPAIR";
  static constexpr std::string_view title = "two warning springs in series";
  static constexpr int ext = 2, ent = 1;
};
using warn_pair = composite<warn_spec, part<warning_spring, 0, 2>, part<warning_spring, 2, 1>>;

/// Two initial-displacement requests on the same DOF (code 90 if they differ).
struct x0_spec {
  static constexpr std::string_view name = "X0X0";
  static constexpr std::string_view title = "two initial displacements on one DOF";
  static constexpr int ext = 1, ent = 0;
};
using x0_pair = composite<x0_spec, part<initial_displacement, 0>, part<initial_displacement, 0>>;

/// An RC series branch: resistor from end 1 to the inner node, capacitor to end 2.
struct rc_spec {
  static constexpr std::string_view name = "RCS";
  static constexpr std::string_view title = "resistor and capacitor in series";
  static constexpr int ext = 2, ent = 1;
};
using rc_series = composite<rc_spec, part<resistor, 0, 2>, part<capacitor, 2, 1>>;

/// A context with its own work and state vectors for an element of type E.
template <class E>
struct own_context {
  std::vector<double> work = std::vector<double>(static_cast<std::size_t>(E::passport.wrk), 0.0);
  std::vector<double> old_s = std::vector<double>(static_cast<std::size_t>(E::passport.str), 0.0);
  std::vector<double> new_s = std::vector<double>(static_cast<std::size_t>(E::passport.str), 0.0);
  element_context ctx;
  own_context(std::string_view name, diagnostics* log = nullptr) : ctx(E::passport.name, name, log) {
    ctx.work = work;
    ctx.old_state = old_s;
    ctx.new_state = new_s;
    ctx.npar = E::passport.par;
  }
};

/// Local DOFs of a throw's nodes, written out by hand (crank_throw.hpp): x, y, z, q1, q2, q3 and the hidden q4
/// of A, N1, N2 (THROWP's external P), N3, B; whether N2 is external.
struct node_dofs {
  int x, q1, q4;
};
template <class T>
struct throw_layout;
template <>
struct throw_layout<crank_throw> {
  static constexpr std::array<node_dofs, 5> nodes{{{0, 3, 12}, {14, 17, 20}, {21, 24, 27}, {28, 31, 34}, {6, 9, 13}}};
  static constexpr bool pin_external = false;
};
template <>
struct throw_layout<crank_throw_pin> {
  static constexpr std::array<node_dofs, 5> nodes{{{0, 3, 18}, {21, 24, 27}, {12, 15, 20}, {28, 31, 34}, {6, 9, 19}}};
  static constexpr bool pin_external = true;
};
constexpr const auto& throw_nodes = throw_layout<crank_throw>::nodes;
/// The local DOF list of a beam of throw T from node a to node b (BEAM3's order).
template <class T>
std::array<int, 14> beam_dofs(int a, int b) {
  const auto& na = throw_layout<T>::nodes[static_cast<std::size_t>(a)];
  const auto& nb = throw_layout<T>::nodes[static_cast<std::size_t>(b)];
  return {na.x,     na.x + 1, na.x + 2, na.q1,     na.q1 + 1, na.q1 + 2, nb.x,
          nb.x + 1, nb.x + 2, nb.q1,    nb.q1 + 1, nb.q1 + 2, na.q4,     nb.q4};
}

/// The expanded model's parts in the order front web, rear web, pin (a reordering for the round-off floor).
constexpr std::array<std::size_t, 8> throw_webs_first{0, 1, 6, 7, 2, 3, 4, 5};

using scene_model = model<elastic_beam, beam_inertia, crank_throw, crank_throw_pin, spatial_force, spatial_torque>;

/// A throw's external nodes in a model: A on the ground (clamped), B, and for THROWP the middle of the pin P.
struct throw_ends {
  std::vector<dof> xb, xp;
  rotation_node rb, rp;
  /// A's, B's (and P's) DOFs in the order of the throw's external DOFs.
  std::vector<dof> dofs(dof ground) const {
    std::vector<dof> d{ground, ground, ground, ground, ground, ground, xb[0], xb[1], xb[2], rb.q1, rb.q2, rb.q3};
    if (!xp.empty()) d.insert(d.end(), {xp[0], xp[1], xp[2], rp.q1, rp.q2, rp.q3});
    return d;
  }
};

/// Creates B, and P if throw T has it external (the expanded model creates them first as well, so that both
/// number the DOFs alike).
template <class T>
throw_ends make_ends(scene_model& m) {
  throw_ends e;
  e.xb = m.add_dofs(3, "xb");
  e.rb = m.add_rotation_node("rb");
  if (throw_layout<T>::pin_external) {
    e.xp = m.add_dofs(3, "xp");
    e.rp = m.add_rotation_node("rp");
  }
  return e;
}

/// A force at B across the throw and a torque about the shaft axis, and for THROWP a force at P, all suddenly
/// applied.
void add_loads(scene_model& m, const throw_ends& e) {
  m.add<spatial_force>("force", {0, -3000, 2000, 0, 0, 0, 0, 0}, e.xb[0], e.xb[1], e.xb[2]);
  m.add<spatial_torque>("torque", {40, 0, 0, 0, 0, 0, 0, 0}, e.rb);
  if (!e.xp.empty()) m.add<spatial_force>("pin force", {1000, 4000, -1500, 0, 0, 0, 0, 0}, e.xp[0], e.xp[1], e.xp[2]);
}

}  // namespace

TEST_SUITE("elements/composite") {
  TEST_CASE("the passport of THROW is derived from its parts") {
    constexpr passport p = throw_t::passport;
    static_assert(p.ext == 12 && p.ent == 23);
    static_assert(p.par == 4 * 15 + 4 * 14);        // BEAM3 15, BEAMI3 14 parameters
    static_assert(p.wrk == 4 * 3 + 4 * 1 + 1 + 8);  // the parts' work + evaluations + errors per part
    static_assert(p.str == 0);
    static_assert(p.adr == 1 && p.ign == 0);             // BEAMI3 brings C and M, BEAM3 K
    static_assert(throw_t::rotation_nodes.size() == 5);  // A, N1, N2, N3, B: deduplicated
    static_assert(throw_t::rotation_nodes[0] == rotation_slot{3, 12});
    static_assert(throw_t::rotation_nodes[4] == rotation_slot{9, 13});
    static_assert(throw_t::rotation_nodes[1] == rotation_slot{17, 20});  // an inner node: q1..q3 internal
    // Inner nodes (core/element.hpp): q1..q3 internal and before their q4; no q4 among another node's q1..q3.
    static_assert(rotation_slots_problem(std::array<rotation_slot, 1>{{{7, 10}}}, 6, 5) == nullptr);
    static_assert(rotation_slots_problem(std::array<rotation_slot, 1>{{{8, 7}}}, 6, 5) != nullptr);
    static_assert(rotation_slots_problem(std::array<rotation_slot, 2>{{{6, 10}, {3, 7}}}, 6, 5) != nullptr);
    static_assert(warn_pair::passport.adr == 1 && warn_pair::passport.ign == 23);  // K only
    CHECK(help_lines(throw_t::help.parameters) == p.par);
    CHECK(help_lines(throw_t::help.dofs) == p.ext);
    CHECK(help_lines(throw_t::help.work) == p.wrk);
    const std::string pars(throw_t::help.parameters);
    CHECK(pars.find("30 - part 3 'BEAM3' (pin front), its parameter 1: Young's modulus") != std::string::npos);
    CHECK(pars.find("116 - part 8 'BEAMI3' (rear web mass), its parameter 14:") != std::string::npos);
  }

  TEST_CASE("the passport of THROWP is derived from its parts: THROW's with the middle of the pin external") {
    using tp = crank_throw_pin;
    constexpr passport p = tp::passport;
    static_assert(p.ext == 18 && p.ent == 17);  // A, B, P; the q4 of A, B, P, and N1, N3 with 7 DOFs each
    static_assert(p.par == 4 * 15 + 4 * 14 && p.par == throw_t::passport.par);
    static_assert(p.wrk == throw_t::passport.wrk && p.str == 0 && p.adr == 1 && p.ign == 0);
    // A, N1, P, N3, B: P's q1..q3 external (15..17) with its q4 at 20, N1 and N3 inner nodes.
    static_assert(tp::rotation_nodes.size() == 5);
    static_assert(tp::rotation_nodes[0] == rotation_slot{3, 18});
    static_assert(tp::rotation_nodes[1] == rotation_slot{24, 27});
    static_assert(tp::rotation_nodes[2] == rotation_slot{15, 20});
    static_assert(tp::rotation_nodes[3] == rotation_slot{31, 34});
    static_assert(tp::rotation_nodes[4] == rotation_slot{9, 19});
    static_assert(std::tuple_size_v<decltype(tp::parameters::parts)> == 8);
    CHECK(help_lines(tp::help.parameters) == p.par);
    CHECK(help_lines(tp::help.dofs) == p.ext);
    CHECK(help_lines(tp::help.work) == p.wrk);
    CHECK(std::string(tp::help.parameters) == std::string(throw_t::help.parameters));  // the same parts
    // P's DOFs are described by the first part on them, the pin's front piece (its end B).
    const std::string dofs(tp::help.dofs);
    CHECK(dofs.find("13 - translation of end B along X [m] (part 3 'BEAM3' (pin front), its DOF 7)") !=
          std::string::npos);
    CHECK(dofs.find("18 - q3 of end B (flow: moment about Z) [-] (part 3 'BEAM3' (pin front), its DOF 12)") !=
          std::string::npos);
  }

  TEST_CASE_TEMPLATE("a throw's flows and Jacobian are the sum of its parts' (assembled by hand) at random states", T,
                     crank_throw, crank_throw_pin) {
    // The composite adds the parts' flows and blocks into zeroed arrays in part order; adding them here in
    // the same order gives the same numbers bit for bit.
    constexpr int n = element_traits<T>::n;
    const auto pp = crank_throw_parts();
    T t(typename T::parameters{pp});
    own_context<T> c("t");
    t.new_integration(c.ctx);
    const elastic_beam b1(std::get<0>(pp)), b2(std::get<2>(pp)), b3(std::get<4>(pp)), b4(std::get<6>(pp));
    const beam_inertia i1(std::get<1>(pp)), i2(std::get<3>(pp)), i3(std::get<5>(pp)), i4(std::get<7>(pp));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 50; ++trial) {
      local_input<T> in;
      for (int k = 0; k < n; ++k) {
        in.u(k) = 1e-3 * uni(rng);
        in.v(k) = uni(rng);
        in.a(k) = 100 * uni(rng);
      }
      for (const auto& nd : throw_layout<T>::nodes) in.u(nd.q4) = 1.0 + 0.1 * uni(rng);  // quaternions near identity
      if (!t.admissible(in)) continue;
      ++checked;
      local_output<T> out;
      t.evaluate(in, out, c.ctx);
      Eigen::Matrix<double, n, 1> f = Eigen::Matrix<double, n, 1>::Zero();
      Eigen::Matrix<double, n, n> K = decltype(K)::Zero(), C = decltype(C)::Zero(), M = decltype(M)::Zero();
      const auto add = [&]<class E>(const E& e, int a, int b) {
        const auto d = beam_dofs<T>(a, b);
        local_input<E> li;
        for (int k = 0; k < 14; ++k) {
          li.u(k) = in.u(d[static_cast<std::size_t>(k)]);
          li.v(k) = in.v(d[static_cast<std::size_t>(k)]);
          li.a(k) = in.a(d[static_cast<std::size_t>(k)]);
        }
        local_output<E> lo;
        std::vector<double> w(static_cast<std::size_t>(E::passport.wrk));
        element_context ec(E::passport.name, "part");
        ec.work = w;
        e.new_integration(ec);
        e.evaluate(li, lo, ec);
        for (int r = 0; r < 14; ++r) {
          f(d[static_cast<std::size_t>(r)]) += lo.f(r);
          for (int q = 0; q < 14; ++q) {
            if constexpr (element_traits<E>::has_k)
              K(d[static_cast<std::size_t>(r)], d[static_cast<std::size_t>(q)]) += lo.K(r, q);
            if constexpr (element_traits<E>::has_c)
              C(d[static_cast<std::size_t>(r)], d[static_cast<std::size_t>(q)]) += lo.C(r, q);
            if constexpr (element_traits<E>::has_m)
              M(d[static_cast<std::size_t>(r)], d[static_cast<std::size_t>(q)]) += lo.M(r, q);
          }
        }
      };
      add(b1, 0, 1), add(i1, 0, 1), add(b2, 1, 2), add(i2, 1, 2), add(b3, 2, 3), add(i3, 2, 3), add(b4, 3, 4),
          add(i4, 3, 4);
      CHECK((out.f - f).cwiseAbs().maxCoeff() == 0.0);
      CHECK((out.K - K).cwiseAbs().maxCoeff() == 0.0);
      CHECK((out.C - C).cwiseAbs().maxCoeff() == 0.0);
      CHECK((out.M - M).cwiseAbs().maxCoeff() == 0.0);
    }
    CHECK(checked >= 40);
    CHECK(c.work[static_cast<std::size_t>(T::stats)] == checked);  // the evaluation count
  }

  TEST_CASE_TEMPLATE("a THROW (THROWP) moves as the expanded model of its BEAM3 and BEAMI3 parts, to round-off, and "
                     "draws the same animation scene",
                     T, crank_throw, crank_throw_pin) {
    // Same equations, same DOF numbering (the expanded model creates its DOFs in the order THROW's placement
    // creates its internal ones), same integrator (Newmark, the default) and the same 200 steps of 1e-5 s (no
    // step cut in either run: the Newton tolerances are tight but reachable, three iterations a step). Only
    // the order in which the element contributions are summed differs (inside THROW the parts first, then
    // into the model): a relative round-off of ~1e-16 per flow and matrix entry, which the Newton solves
    // amplify by the condition of the Newton matrix (stiffness ~1e10 N/m against masses of ~0.1 kg at h =
    // 1e-5 s: ~1e4) and 200 steps accumulate. The tolerance is that round-off floor measured on the problem
    // itself: the largest difference between three orderings of the expanded model's elements (forward,
    // reversed, webs first: a different summation order, nothing else), 9.4e-12 of the largest motion for
    // THROW (reversed alone: 4.9e-12); THROW must differ by no more than twice that (measured: 4.2e-12), and
    // the hidden q4 (near 1) by round-off relative to 1. THROWP carries in addition a force at its external P,
    // which the expanded model applies to the same DOFs, its middle node of the pin (measured: 1.06e-11 against
    // a floor of 9.8e-12; reversed alone gave 4.4e-12, too small a sample of the floor for the factor 2).
    const auto pp = crank_throw_parts();
    constexpr bool pin_external = throw_layout<T>::pin_external;
    enum { expanded, reversed, webs_first, as_throw };
    const auto run = [&](int mode) {
      scene_model m;
      const dof G = m.ground();
      const throw_ends ends = make_ends<T>(m);
      const std::vector<dof>& xb = ends.xb;
      const rotation_node rb = ends.rb;
      const rotation_node ga = m.add_rotation_node("ra", G, G, G);
      (void)ga;
      if (mode == as_throw) {
        if constexpr (pin_external)
          m.add<T>("throw", {pp}, G, G, G, G, G, G, xb[0], xb[1], xb[2], rb, ends.xp[0], ends.xp[1], ends.xp[2],
                   ends.rp);
        else
          m.add<T>("throw", {pp}, G, G, G, G, G, G, xb[0], xb[1], xb[2], rb);
      } else {
        // The inner nodes, created in the order the throw's placement creates them; THROWP's P is external.
        std::array<std::vector<dof>, 3> xi;
        std::array<rotation_node, 3> ri;
        for (std::size_t i = 0; i < 3; ++i) {
          if (pin_external && i == 1) {
            xi[i] = ends.xp;
            ri[i] = ends.rp;
            continue;
          }
          xi[i] = m.add_dofs(3, "n" + std::to_string(i + 1));
          ri[i] = m.add_rotation_node("rn" + std::to_string(i + 1));
        }
        // The beams A -> N1 -> N2 -> N3 -> B; `reversed` places them from B's end.
        const std::array<std::array<dof, 6>, 5> nd{{{G, G, G, G, G, G},
                                                    {xi[0][0], xi[0][1], xi[0][2], ri[0].q1, ri[0].q2, ri[0].q3},
                                                    {xi[1][0], xi[1][1], xi[1][2], ri[1].q1, ri[1].q2, ri[1].q3},
                                                    {xi[2][0], xi[2][1], xi[2][2], ri[2].q1, ri[2].q2, ri[2].q3},
                                                    {xb[0], xb[1], xb[2], rb.q1, rb.q2, rb.q3}}};
        const auto beams = [&]<std::size_t I>(std::integral_constant<std::size_t, I>) {
          constexpr std::size_t k = I / 2;
          const auto& a = nd[k];
          const auto& b = nd[k + 1];
          using E = std::conditional_t<I % 2 == 0, elastic_beam, beam_inertia>;
          m.add<E>("part" + std::to_string(I + 1), std::get<I>(pp), a[0], a[1], a[2], a[3], a[4], a[5], b[0], b[1],
                   b[2], b[3], b[4], b[5]);
        };
        // `reversed` places the parts from B's end, `webs_first` the two webs, then the pin. (Placing each BEAMI3
        // before its BEAM3 instead gave results bit for bit equal to the forward order's: no floor sample.)
        const auto place = [&]<std::size_t... I>(std::index_sequence<I...>) {
          if (mode == expanded)
            (beams(std::integral_constant<std::size_t, I>{}), ...);
          else if (mode == reversed)
            (beams(std::integral_constant<std::size_t, 7 - I>{}), ...);
          else
            (beams(std::integral_constant<std::size_t, throw_webs_first[I]>{}), ...);
        };
        place(std::make_index_sequence<8>{});
      }
      add_loads(m, ends);
      simulation sim(m);
      const auto st = sim.run(
          {.end = 2e-3, .smax = 1e-5, .newton = {.dabsu = 1e-9, .drltu = 0, .dabsi = 1e-5, .drlti = 0, .itr = 10}});
      CHECK(st.steps == 200);
      CHECK(st.rejected_steps == 0);
      std::vector<double> u;
      std::vector<char> q4;  // the hidden q4 (near 1: not a motion)
      for (int d = 0; d < m.dof_count(); ++d) {
        u.push_back(sim.state().u(d));
        q4.push_back(m.dof_name(d).ends_with(".q4") || m.dof_name(d).starts_with("rotation node"));
      }
      // The animation scene (io/model_scene.hpp): THROW draws its parts through their maps.
      const io::vtk_scene scene = io::model_scene(m);
      std::vector<spatial::vec3> points;
      for (std::size_t i = 0; i < scene.points(); ++i) points.push_back(scene.motion(sim, i).position);
      return std::make_tuple(u, q4, m.dof_count(), points, scene.connectivity(), scene.types());
    };
    const auto [ue, qe, ne, pe, ce, te] = run(expanded);
    const auto [ur, qr, nr, pr, cr, tr] = run(reversed);
    const auto [us, qs, ns, ps, cs, ts] = run(webs_first);
    const auto [uc, qc, nc, pc, cc, tc] = run(as_throw);
    REQUIRE(ne == nc);
    REQUIRE(nr == nc);
    REQUIRE(ns == nc);
    CHECK(qe == qc);  // the same DOFs in the same order
    double umax = 0, dthrow = 0, dreversed = 0, dq4 = 0;
    for (std::size_t d = 0; d < ue.size(); ++d) {
      if (qe[d]) {
        dq4 = std::max(dq4, std::abs(ue[d] - uc[d]));
        continue;
      }
      umax = std::max(umax, std::abs(ue[d]));
      dthrow = std::max(dthrow, std::abs(ue[d] - uc[d]));
      // The floor: the largest difference between two orderings of the expanded model.
      dreversed = std::max({dreversed, std::abs(ue[d] - ur[d]), std::abs(ue[d] - us[d]), std::abs(ur[d] - us[d])});
    }
    INFO(T::passport.name, ": max |u| = ", umax, ", difference to the expanded model ", dthrow,
         ", between reorderings of the expanded model ", dreversed, ", on the hidden q4 ", dq4);
    MESSAGE(T::passport.name, ": max |u| = ", umax, ", difference to the expanded model ", dthrow,
            ", between reorderings of the expanded model ", dreversed, ", on the hidden q4 ", dq4);
    CHECK(umax > 1e-5);  // the throw did move
    // Round-off, and no more than a mere reordering of the expanded model's sums gives.
    CHECK(dreversed > 0);
    CHECK(dthrow <= 2 * dreversed);
    CHECK(dthrow <= 1e-10 * umax);
    CHECK(dq4 <= 1e-12);  // q4 stays near 1: round-off relative to 1
    // The scenes: the 5 nodes of the throw and its 4 beam lines (BEAM3 and BEAMI3 draw the same line, kept
    // once), in the same order, and the points where the DOFs put them (beam ends carry no offset, so a point
    // moves exactly as its translational DOFs).
    CHECK(pe.size() == 5);
    CHECK(te.size() == 4);
    CHECK(pc.size() == pe.size());
    CHECK(cc == ce);
    CHECK(tc == te);
    double dpoint = 0;
    for (std::size_t i = 0; i < std::min(pc.size(), pe.size()); ++i) dpoint = std::max(dpoint, (pc[i] - pe[i]).norm());
    CHECK(dpoint <= std::sqrt(3.0) * dthrow);
    (void)pr;
    (void)cr;
    (void)tr;
    (void)qs;
    (void)ps;
    (void)cs;
    (void)ts;
  }

  TEST_CASE("THROWP clamped at A and B under a force at the middle of the pin deflects as linear beam theory says") {
    // Reference: the throw is a portal frame in its plane, two clamped columns (the webs, height h = r) and a
    // beam (the pin, span L), here loaded by F along Y at mid-span P. BEAM3 is Euler-Bernoulli with axial strain,
    // and THROWP's tangent at the undeformed state is that linear frame's stiffness (rotations as q = theta / 2
    // with q4 = 1: a scaling of the rotational unknowns, which leaves the translations alone). Beam theory by
    // Castigliano's theorem: cut at P, by symmetry each half (the clamped L A -> N1 -> P) carries V = F / 2 at P,
    // and P neither moves along the pin nor rotates; with the unknown axial force H and moment M at P, the
    // half's energy U = int M^2 / (2 EI) ds + int N^2 / (2 EA) ds, in the pin M(x) = M + V (a - x), N = H
    // (a = L / 2), in the web M(s) = M + a V - s H, N = V (s from the corner), gives from dU/dM = 0 and
    // dU/dH = 0 the equations below, and the deflection of P is dU/dV.
    using tp = crank_throw_pin;
    constexpr auto& nodes = throw_layout<tp>::nodes;
    struct shape {
      double r, length;
    };
    for (const shape sh : {shape{0.04, 0.04}, shape{0.1, 0.3}}) {
      CAPTURE(sh.r);
      CAPTURE(sh.length);
      const auto pp = crank_throw_parts(0.08, sh.r, sh.length);
      tp t(tp::parameters{pp});
      own_context<tp> c("throw");
      t.new_integration(c.ctx);
      local_input<tp> in;
      for (const auto& nd : nodes) in.u(nd.q4) = 1.0;
      local_output<tp> out;
      out.want_jacobian = true;
      t.evaluate(in, out, c.ctx);
      // The undeformed state is free of stress, to the round-off of the corotational frame (EA ~ 3e8 N times
      // 1e-16: measured 4e-8 N).
      CHECK(out.f.cwiseAbs().maxCoeff() <= 1e-6);
      // The free DOFs: x, y, z, q1, q2, q3 of P, N1, N3 (A and B clamped, the q4 held at 1).
      std::array<int, 18> fr{};
      std::size_t k = 0;
      for (const std::size_t i : {2u, 1u, 3u})
        for (int j = 0; j < 3; ++j) {
          fr[k++] = nodes[i].x + j;
          fr[k++] = nodes[i].q1 + j;
        }
      Eigen::Matrix<double, 18, 18> kf;
      for (int i = 0; i < 18; ++i)
        for (int j = 0; j < 18; ++j) kf(i, j) = out.K(fr[static_cast<std::size_t>(i)], fr[static_cast<std::size_t>(j)]);
      const double F = 1000;
      Eigen::Matrix<double, 18, 1> rhs = Eigen::Matrix<double, 18, 1>::Zero();
      rhs(2) = F;  // P's y (fr: P x, P q1, P y, ...)
      const Eigen::Matrix<double, 18, 1> u = kf.fullPivLu().solve(rhs);
      // Beam theory. Bending in the throw's plane: about Z, the pin's Iz and the web's (b t^3 / 12).
      const auto& web = std::get<0>(pp);
      const auto& pin = std::get<2>(pp);
      const double a = sh.length / 2, h = sh.r, V = F / 2;
      const double eip = pin.e * pin.iz, eap = pin.e * pin.a, eiw = web.e * web.iz, eaw = web.e * web.a;
      // dU/dM = 0: M (a / EIp + h / EIw) - H h^2 / (2 EIw) = -V (a^2 / (2 EIp) + a h / EIw);
      // dU/dH = 0: -M h^2 / (2 EIw) + H (h^3 / (3 EIw) + a / EAp) = V a h^2 / (2 EIw).
      const double m11 = a / eip + h / eiw, m12 = -h * h / (2 * eiw), m22 = h * h * h / (3 * eiw) + a / eap;
      const double r1 = -V * (a * a / (2 * eip) + a * h / eiw), r2 = V * a * h * h / (2 * eiw);
      const double det = m11 * m22 - m12 * m12;
      const double M = (r1 * m22 - m12 * r2) / det, H = (m11 * r2 - m12 * r1) / det;
      const double deflection =
          (M * a * a / 2 + V * a * a * a / 3) / eip + a * ((M + a * V) * h - H * h * h / 2) / eiw + V * h / eaw;
      INFO("deflection of P ", u(2), ", beam theory ", deflection);
      CHECK(u(2) == doctest::Approx(deflection).epsilon(1e-10));
      // Symmetry: P moves along Y only, and does not rotate.
      for (const int i : {0, 1, 3, 4, 5}) CHECK(std::abs(u(i)) <= 1e-12 * std::abs(u(2)));
    }
  }

  TEST_CASE("a part's error names the super-element, its instance and the part, with the part's code") {
    std::ostringstream log_text;
    diagnostics log;
    log.to(log_text);
    SUBCASE("code 100 at NEWINT: the part and its parameter range") {
      auto pp = crank_throw_parts();
      std::get<2>(pp).e = -1.0;  // part 3, BEAM3 (pin front): Young's modulus
      throw_t t(throw_t::parameters{pp});
      own_context<throw_t> c("Throw 1", &log);
      const auto e = error_from([&] { t.new_integration(c.ctx); });
      check_error(e, error_code::invalid_parameter, "THROW", "Throw 1",
                  "part 3 'BEAM3' (pin front), parameters 30..44 of THROW: Young's modulus E = -1 must be > 0");
      // One line in the log, in THROW's name: the part's own report was muted.
      CHECK(log_text.str() == std::string(e->what()) + "\n");
    }
    SUBCASE("code 75 during the run: the part, the count in the work vector") {
      throw_t t(throw_t::example());
      own_context<throw_t> c("Throw 1", &log);
      t.new_integration(c.ctx);
      local_input<throw_t> in;
      for (const auto& nd : throw_nodes) in.u(nd.q4) = 1.0;
      in.u(27) = 0.0;  // N2's quaternion vanishes: the pin's first piece (part
                       // 3) fails first
      const auto e = error_from([&] {
        local_output<throw_t> out;
        t.evaluate(in, out, c.ctx);
      });
      check_error(e, error_code::singular_situation, "THROW", "Throw 1", "part 3 'BEAM3' (pin front): Lq near zero");
      CHECK(e->message().find("parameters") == std::string::npos);
      CHECK(c.work[static_cast<std::size_t>(throw_t::stats + 1 + 2)] == 1.0);  // part 3's error count
      CHECK(c.work[static_cast<std::size_t>(throw_t::stats + 1 + 0)] == 0.0);
      CHECK(log_text.str() == std::string(e->what()) + "\n");
    }
  }

  TEST_CASE("a part's warnings do not reach the log inside the composite (SYSPRN = 0)") {
    std::ostringstream log_text;
    diagnostics log;
    log.to(log_text);
    local_input<warn_pair> in;
    in.u << 0.1, -0.2, 0.3;
    warn_pair w({{warning_spring::parameters{2.0}, warning_spring::parameters{3.0}}});
    own_context<warn_pair> c("pair", &log);
    local_output<warn_pair> out;
    w.evaluate(in, out, c.ctx);
    CHECK(log_text.str().empty());
    CHECK_FALSE(c.ctx.muted());  // the guard is released
    // Flows of two springs in series through the internal DOF 3 (k1 (u1 - u3), k2 (u3 - u2)).
    CHECK(out.f(0) == doctest::Approx(2.0 * (0.1 - 0.3)));
    CHECK(out.f(1) == doctest::Approx(-3.0 * (0.3 + 0.2)));
    CHECK(out.f(2) == doctest::Approx(-2.0 * (0.1 - 0.3) + 3.0 * (0.3 + 0.2)));
    // The same part evaluated on its own does write its warning.
    own_context<warning_spring> c1("alone", &log);
    local_output<warning_spring> o1;
    local_input<warning_spring> i1;
    warning_spring({2.0}).evaluate(i1, o1, c1.ctx);
    CHECK(log_text.str() == "WARNS 'alone': stretched\n");
  }

  TEST_CASE("a part is handed zeroed blocks, as by the assembler, and may add to them") {
    // The stack the composite's part outputs will occupy is dirtied first (by a call
    // that fills a large local array), so that blocks left uninitialised would show.
    add_pair a({{adding_spring::parameters{2.0}, adding_spring::parameters{3.0}}});
    own_context<add_pair> c("pair");
    local_input<add_pair> in;
    in.u << 0.1, -0.2, 0.3;
    adding_spring::dirty_blocks = 0;
    for (int trial = 0; trial < 3; ++trial) {
      CHECK(dirty_stack() == 4096.0);
      local_output<add_pair> out;
      out.clear();
      a.evaluate(in, out, c.ctx);
      // Springs k1 = 2 between DOFs 1 and 3, k2 = 3 between 3 and 2.
      Eigen::Matrix3d k;
      k << 2, 0, -2, 0, 3, -3, -2, -3, 5;
      CHECK(out.K == k);
    }
    CHECK(adding_spring::dirty_blocks == 0);
  }

  TEST_CASE("initial values of the parts are merged; different requests for one DOF are code 90") {
    own_context<x0_pair> c("x0s");
    SUBCASE("the same value twice") {
      x0_pair x({{initial_displacement::parameters{0.5}, initial_displacement::parameters{0.5}}});
      initial_values<1> iv;
      x.zero_step(iv, c.ctx);
      CHECK(iv.has_displacement(0));
      CHECK(iv.displacement(0) == 0.5);
    }
    SUBCASE("two values") {
      x0_pair x({{initial_displacement::parameters{0.5}, initial_displacement::parameters{0.7}}});
      initial_values<1> iv;
      check_error(error_from([&] { x.zero_step(iv, c.ctx); }), error_code::conflicting_initial, "X0X0", "x0s",
                  "part 2 'X0' requests an initial displacement of local DOF 1 "
                  "different from the one part 1 requested");
    }
  }

  TEST_CASE_TEMPLATE("THROW (THROWP) from the flat parameter vector: a wrong count is code 101, a bad value code 100 "
                     "naming the part",
                     T, crank_throw, crank_throw_pin) {
    const std::string name(T::passport.name);
    scene_model m;
    const std::vector<dof> d = make_ends<T>(m).dofs(m.ground());
    std::vector<double> flat;
    const auto put = [&](const auto& p) {
      if constexpr (std::is_same_v<std::remove_cvref_t<decltype(p)>, elastic_beam::parameters>)
        flat.insert(flat.end(), {p.e, p.g, p.a, p.iy, p.iz, p.j});
      else
        flat.insert(flat.end(), {p.rho, p.a, p.iy, p.iz, p.ip});
      flat.insert(flat.end(), {p.xa, p.ya, p.za, p.xb, p.yb, p.zb, p.vx, p.vy, p.vz});
    };
    std::apply([&](const auto&... p) { (put(p), ...); }, crank_throw_parts());
    REQUIRE(flat.size() == 116);
    const std::vector<double> short_list(flat.begin(), flat.end() - 1);
    check_error(pradis_element_tests::flat_add_error<T>(m, "short", d, short_list), error_code::parameter_count,
                name, "short", "got 115 parameters");
    flat[58 + 2] = 0.0;  // part 5 (pin rear, BEAM3), its parameter 3: the area
    m.add_flat<T>("bad", d, flat);
    simulation sim(m);
    check_error(error_from([&] { sim.run({.end = 1e-4, .smax = 1e-5}); }), error_code::invalid_parameter, name, "bad",
                "part 5 'BEAM3' (pin rear), parameters 59..73 of " + name + ": area A = 0 must be > 0");
  }
}
