// The rotational node as a node kind (include/pradis/spatial/rotation_node_kind.hpp,
// include/pradis/core/node_kind.hpp), checked on its own:
// - the norm equation's Jacobian row against central differences of its flow
//   f = Mu (q . q') / |q| (the definition of the derivative);
// - the zero step's row against the second time derivative of |q(t)| along
//   q(t) = q + t q' + t^2 q'' / 2, by central differences with Richardson extrapolation (d2(Lq)/dt2 = row . q'' - rhs
//   with rhs independent of the unknown's increment: docs/rotations.md, "The zero step");
// - Lq near zero, far from 1 or not finite is code 75 in the name of the node's owner;
// - the model's node-kind interface: nodes<K>(), the hidden DOFs and their start values,
//   and the registry's refusal of a second fully fixed node (code 110).

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pradis/pradis.hpp"
#include "../elements/element_test_support.hpp"
#include "pradis/spatial/rotation_node_kind.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

namespace {

using kind = rotation_node_kind;

/// A node record on DOFs 1..4 owned by a BODY3 named "body".
rotation_node_record test_node() { return rotation_node_record{"r", {1, 2, 3, 4}, "BODY3", "body"}; }

/// The node's flow on q4 at (u, v).
double norm_flow(const node_values<4>& x, double dabsi) {
  node_flows<4> out;
  element_context ctx;
  kind::evaluate(test_node(), x, node_call{dabsi, false}, out, ctx);
  return out.f(3);
}

/// A node state with |q| in [0.95, 1.05] and a random q'.
node_values<4> random_state(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> len(0.95, 1.05);
  node_values<4> x;
  for (int k = 0; k < 4; ++k) {
    x.u(k) = n(rng);
    x.v(k) = n(rng);
    x.a(k) = n(rng);
  }
  x.u *= len(rng) / x.u.norm();
  return x;
}

}  // namespace

// A type without evaluate() or zero_step_row() is not a node kind.
struct not_a_node_kind {
  using record = rotation_node_record;
  static constexpr int size = 4;
  static constexpr std::string_view label = "X";
  static constexpr std::array<bool, 4> hidden{}, rows{};
  static constexpr std::array<double, 4> start{};
  static constexpr bool inertial_block = false;
};
static_assert(NodeKind<rotation_node_kind>);
static_assert(!NodeKind<not_a_node_kind>);
/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using rotation_node_kind_model = pradis::model<rigid_body, initial_displacement, initial_velocity>;
static_assert(std::is_same_v<model<rigid_body>::node_kinds, type_list<rotation_node_kind>>);

TEST_SUITE("spatial/rotation node kind") {
  TEST_CASE("the norm equation's Jacobian row equals central differences of its flow") {
    std::mt19937 rng(11);
    const double dabsi = 0.1, mu = norm_viscosity(dabsi);
    double worst = 0;
    for (int trial = 0; trial < 50; ++trial) {
      const node_values<4> x = random_state(rng);
      node_flows<4> out;
      element_context ctx;
      kind::evaluate(test_node(), x, node_call{dabsi, true}, out, ctx);
      CHECK(out.f(3) == doctest::Approx(mu * x.u.dot(x.v) / x.u.norm()).epsilon(1e-14));
      const double h = 1e-6;
      for (int k = 0; k < 4; ++k) {
        node_values<4> p = x, m = x;
        p.u(k) += h;
        m.u(k) -= h;
        const double dk = (norm_flow(p, dabsi) - norm_flow(m, dabsi)) / (2 * h);
        p = x;
        m = x;
        p.v(k) += h;
        m.v(k) -= h;
        const double dc = (norm_flow(p, dabsi) - norm_flow(m, dabsi)) / (2 * h);
        worst = std::max({worst, std::abs(out.K(3, k) - dk) / mu, std::abs(out.C(3, k) - dc) / mu});
      }
    }
    MESSAGE("norm equation: worst |J - J_fd| / Mu = ", worst);
    CHECK(worst < 1e-8);  // central differences at h = 1e-6: O(h^2) truncation, O(eps / h) rounding
  }

  TEST_CASE("the zero step's row is the second time derivative of Lq over q''") {
    std::mt19937 rng(5);
    double worst = 0;
    for (int trial = 0; trial < 50; ++trial) {
      const node_values<4> x = random_state(rng);
      Eigen::Vector4d row;
      double rhs = 0;
      kind::zero_step_row(x, 3, row, rhs);
      CHECK((row - x.u / x.u.norm()).norm() < 1e-15);  // the gradient of Lq = |q|
      const auto lq = [&](double t) { return (x.u + t * x.v + 0.5 * t * t * x.a).norm(); };
      const auto central = [&](double h) { return (lq(h) - 2 * lq(0) + lq(-h)) / (h * h); };
      const double h = 1e-3, d2 = (4 * central(h / 2) - central(h)) / 3;  // Richardson: O(h^4)
      worst = std::max(worst, std::abs(d2 + rhs));  // rhs = -d2(Lq)/dt2 at the state's own q''
    }
    MESSAGE("zero-step row: worst |d2Lq/dt2 + rhs| = ", worst);
    CHECK(worst < 1e-7);  // O(h^4) truncation, O(eps / h^2) = 1e-9 rounding
  }

  TEST_CASE("Lq near zero, far from 1 or not finite is code 75 in the name of the node's owner") {
    const auto fails = [](double scale, const char* what) {
      node_values<4> x;
      x.u << 0.1, 0.2, 0.3, 0.9;
      x.u *= scale / x.u.norm();
      x.v.setZero();
      x.a.setZero();
      node_flows<4> out;
      element_context ctx;
      const auto e = error_from([&] { kind::evaluate(test_node(), x, {}, out, ctx); });
      check_error(e, error_code::singular_situation, "BODY3", "body", what);
    };
    fails(1e-4, "Lq near zero");
    fails(0.0, "Lq near zero");
    fails(1.2, "Lq far from 1");
    fails(0.85, "Lq far from 1");
    fails(std::numeric_limits<double>::quiet_NaN(), "Lq near zero");
    fails(std::numeric_limits<double>::infinity(), "Lq near zero");
    // A node without an owner element is named by its own name.
    node_values<4> x;
    x.u << 0, 0, 0, 2;
    x.v.setZero();
    x.a.setZero();
    node_flows<4> out;
    element_context ctx;
    const rotation_node_record lone{"lone", {1, 2, 3, 4}, {}, {}};
    check_error(error_from([&] { kind::evaluate(lone, x, {}, out, ctx); }),
                                      error_code::singular_situation, "ROTATION NODE", "lone", "Lq far from 1");
  }

  TEST_CASE("the model's nodes of the kind, their hidden q4 and its start value; one fully fixed node") {
    rotation_node_kind_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node a = m.add_rotation_node("a");
    const rotation_node fixed = m.add_rotation_node("fixed", m.ground(), m.ground(), m.ground());
    m.add<rigid_body>("body", pradis_spatial_tests::body(1, 1, 1, 1), x[0], x[1], x[2], a);
    CHECK(&m.nodes<rotation_node_kind>() == &m.rotation_nodes());
    REQUIRE(m.rotation_nodes().size() == 2);
    const std::vector<char> hidden = m.hidden_dofs();
    int count = 0;
    for (std::size_t d = 0; d < hidden.size(); ++d) count += hidden[d];
    CHECK(count == 2);
    CHECK(hidden[static_cast<std::size_t>(a.q4.index)] == 1);
    CHECK(hidden[static_cast<std::size_t>(fixed.q4.index)] == 1);
    CHECK(hidden[static_cast<std::size_t>(a.q1.index)] == 0);
    Eigen::VectorXd u = Eigen::VectorXd::Constant(m.dof_count(), 7.0);
    m.start_hidden_dofs(u, fixed.q4.index);  // only the DOFs from fixed.q4 on
    CHECK(u(a.q4.index) == 7.0);
    CHECK(u(fixed.q4.index) == 1.0);
    m.start_hidden_dofs(u);
    CHECK(u(a.q4.index) == 1.0);
    CHECK(u(a.q1.index) == 7.0);  // external DOFs keep their potentials
    // A second fully fixed node is code 110; an element on three ground DOFs uses the first.
    check_error(
        error_from([&] { m.add_rotation_node("again", m.ground(), m.ground(), m.ground()); }),
        error_code::invalid_model, "", "again", "already exists");
    CHECK(m.rotation_nodes().size() == 2);
  }

  TEST_CASE("the hidden q4 starts with the velocity of the norm equation: q4' = -(q1 q1' + q2 q2' + q3 q3') / q4") {
    // A free body whose node starts at q = (0.1, 0, 0, 1) with q1' = 0.3, q2' = 0.2 set on the external DOFs
    // (INITIAL_DISPLACEMENT, INITIAL_VELOCITY): the norm equation d|q|/dt = 0 fixes q4' = -0.03 at the zero step
    // (integrators/initialisation.hpp, hidden_dof_velocities), and |q| = sqrt(1.01) is then kept.
    rotation_node_kind_model m;
    const auto x = m.add_dofs(3, "x");
    const rotation_node a = m.add_rotation_node("a");
    m.add<rigid_body>("body", pradis_spatial_tests::body(1, 2, 1.5, 1), x[0], x[1], x[2], a);
    m.add<initial_displacement>("q1", {0.1}, a.q1);
    m.add<initial_velocity>("w1", {0.3}, a.q1);
    m.add<initial_velocity>("w2", {0.2}, a.q2);
    simulation sim(m);
    bool first = true;
    double worst = 0;
    const double lq0 = std::sqrt(1.01);
    sim.on_output([&](const auto& st) {
      if (first) {
        CHECK(st.v(a.q4) == doctest::Approx(-0.03).epsilon(1e-14));
        first = false;
      }
      const Eigen::Vector4d q(st.u(a.q1), st.u(a.q2), st.u(a.q3), st.u(a.q4));
      worst = std::max(worst, std::abs(q.norm() - lq0));
    });
    sim.run({.end = 1.0, .out = 0.01, .smax = 1e-3});
    MESSAGE("free body from q1' = 0.3, q2' = 0.2: worst ||q| - sqrt(1.01)| over 1 s, Newmark h = 1e-3: ", worst);
    CHECK(!first);
    CHECK(worst < 1e-9);
  }
}
