// The work-precision benchmark's peers (SUNDIALS IDA/CVODE, Boost.Odeint) integrate
// the 3D problems (the torque-free HLW body and the heavy top of
// examples/spinning_top) as first-order ODEs in (x, x', q, omega_b) written out by
// hand in bench/work_precision/rigid_body_problems.hpp. For the comparison to be
// honest they must be pradis's equations: at random states, the motion the peer's
// right-hand side gives (x'' and omega_b', turned into q' = (1/2) q (x) (omega_b, 0)
// and q'' = (1/2) (q' (x) (omega_b, 0) + q (x) (omega_b', 0))) must make the residual
// that pradis assembles from its elements (BODY3, SPH3, F3) vanish, to round-off, in
// the force rows and the moment rows q1..q3. For the top on the exact joint (topx),
// whose peer equations are Euler's equations about the tip without the joint's
// multipliers, the check is the heavy top's invariants instead, and the start; the
// same top with its node at the tip and no joint (top_parameters::pivot: BODY3 with
// the centre of mass offset, F3A for the weight; series BDF-pivot of topx) is exactly
// that formulation, and the peer's motion zeroes its residual.

#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/spatial/node_state.hpp"
#include "rigid_body_problems.hpp"

using namespace pradis;
using pradis::spatial::quaternion;
using pradis::spatial::vec3;

namespace {

/// Sets u, v, a of a rotational node from q, omega_b and omega_b' (the peer's state).
void set_rotation(global_state& s, const rotation_node& n, const quaternion& q, const vec3& w, const vec3& wd) {
  const quaternion qd = wp::rigid::quaternion_rate(q.data(), w);
  const quaternion qdd = 0.5 * spatial::multiply(qd, quaternion(w.x(), w.y(), w.z(), 0)) +
                         0.5 * spatial::multiply(q, quaternion(wd.x(), wd.y(), wd.z(), 0));
  const dof d[4] = {n.q1, n.q2, n.q3, n.q4};
  for (int i = 0; i < 4; ++i) {
    s.u(d[i].index) = q(i);
    s.v(d[i].index) = qd(i);
    s.a(d[i].index) = qdd(i);
  }
}

/// The assembled residual of the rows `rows`, each relative to its sum of absolute
/// contributions or to `scale`, whichever is larger (the round-off scale): the largest.
template <class M>
double largest_relative_residual(assembler<M>& as, const std::vector<dof>& rows, double scale = 0) {
  double worst = 0;
  for (const dof& d : rows) {
    worst = std::max(worst, std::abs(as.residual()(d.index)) / std::max({as.abs_sum()(d.index), scale, 1e-300}));
  }
  return worst;
}

/// A model's state after one tiny Newmark step (NEWINT of every element; the ground and
/// every DOF a test does not set stay as the run left them) and its assembler, built with
/// the ground (DOF 0) prescribed: the residual of any motion a test writes into `state`.
template <class Model>
struct residual_probe {
  global_state state;
  assembler<Model> as;
  residual_probe(Model& m, double step) {
    simulation sim(m, newmark{});
    sim.run({.end = step, .smax = step});
    state = sim.state();
    std::vector<char> prescribed(static_cast<std::size_t>(m.dof_count()), 0);
    prescribed[0] = 1;
    as.build(m, prescribed);
  }
  void evaluate(Model& m) { as.evaluate(m, state, {1.0, 0.0, 0.0}, call_info{1.0, 1e-3, 1, 0, true, nullptr}); }
};

/// A random quaternion of norm 0.95..1.05: pradis's equations hold for any |q| near 1, the peer keeps |q|.
quaternion random_quaternion(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), scale(0.95, 1.05);
  quaternion q(unit(rng), unit(rng), unit(rng), unit(rng));
  q *= scale(rng) / q.norm();
  return q;
}

}  // namespace

TEST_CASE("bench 3D peer equations: the free body's right-hand side zeroes pradis's assembled residual") {
  wp::rigid::freebody_model b;
  residual_probe p(b.m, 1e-4);
  global_state& s = p.state;
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const quaternion q = random_quaternion(rng);
    double y[7] = {q(0), q(1), q(2), q(3), 3 * unit(rng), 3 * unit(rng), 3 * unit(rng)}, dy[7];
    wp::rigid::freebody_rhs(y, dy);
    // dq/dt of the peer is the kinematic relation itself (checked here once more).
    const vec3 w(y[4], y[5], y[6]), wd(dy[4], dy[5], dy[6]);
    const quaternion qd = wp::rigid::quaternion_rate(y, w);
    for (int i = 0; i < 4; ++i) CHECK(dy[i] == doctest::Approx(qd(i)).epsilon(1e-15));
    // omega_b = (2/s) G(q) q' (pradis/spatial/quaternion.hpp) for the peer's q'.
    const vec3 wb = spatial::body_angular_velocity(q, qd);
    for (int i = 0; i < 3; ++i) CHECK(wb(i) == doctest::Approx(w(i)).epsilon(1e-13));
    for (const dof& d : b.x) s.u(d.index) = s.v(d.index) = s.a(d.index) = 0;
    set_rotation(s, b.r, q, w, wd);
    p.evaluate(b.m);
    // One element per row: the scale is that of its inertial moment, I (|omega'| + |omega|^2).
    const double scale = wp::rigid::hlw_inertia.maxCoeff() * (wd.cwiseAbs().maxCoeff() + w.squaredNorm());
    worst = std::max(worst, largest_relative_residual(p.as, {b.x[0], b.x[1], b.x[2], b.r.q1, b.r.q2, b.r.q3}, scale));
  }
  MESSAGE("free body: largest assembled residual / its scale on the peer's motion: ", worst);
  CHECK(worst < 1e-13);
}

TEST_CASE("bench 3D peer equations: the heavy top's right-hand side zeroes pradis's assembled residual") {
  pradis_examples::spinning_top t;
  const wp::rigid::top_data d = wp::rigid::top_data::from_example();
  residual_probe p(t.m, 1e-5);
  global_state& s = p.state;
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const quaternion q = random_quaternion(rng);
    double y[13], dy[13];
    for (int i = 0; i < 3; ++i) y[i] = 1e-3 * unit(rng), y[3 + i] = 0.1 * unit(rng), y[10 + i] = 30 * unit(rng);
    for (int i = 0; i < 4; ++i) y[6 + i] = q(i);
    wp::rigid::top_rhs(d, y, dy);
    for (int i = 0; i < 3; ++i) {
      const dof x = t.x[static_cast<std::size_t>(i)];
      s.u(x.index) = y[i];
      s.v(x.index) = y[3 + i];
      s.a(x.index) = dy[3 + i];
      CHECK(dy[i] == y[3 + i]);
    }
    set_rotation(s, t.r, q, vec3(y[10], y[11], y[12]), vec3(dy[10], dy[11], dy[12]));
    p.evaluate(t.m);
    worst = std::max(worst, largest_relative_residual(p.as, {t.x[0], t.x[1], t.x[2], t.r.q1, t.r.q2, t.r.q3}));
  }
  MESSAGE("top: largest assembled residual / its scale on the peer's motion: ", worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("bench 3D peer equations: the exact-joint top's right-hand side keeps the heavy top's invariants") {
  // Euler's equations about the fixed tip (top_exact_rhs, problem topx) of a
  // symmetric top conserve the energy (1/2) omega_b . I_O omega_b + m g z_c, the
  // angular momentum about the vertical (R I_O omega_b)_Z and the spin omega_3
  // (Goldstein, Classical Mechanics, 3rd ed., section 5.7). RK4 at h = 1e-4 over
  // 0.2 s (6 rad of spin) keeps them to round-off (measured: 4e-16 relative).
  const wp::rigid::top_data d = wp::rigid::top_data::from_example();
  const vec3 io(d.j1 + d.m * d.l * d.l, d.j1 + d.m * d.l * d.l, d.j3);
  auto invariants = [&](const Eigen::VectorXd& y) {
    const Eigen::Matrix3d r = spatial::rotation_matrix(quaternion(y.head<4>()));
    const vec3 w = y.tail<3>();
    const double e = 0.5 * w.dot(io.cwiseProduct(w)) + d.m * d.g * (r * vec3(0, 0, d.l)).z();
    return Eigen::Vector3d(e, (r * io.cwiseProduct(w)).z(), w.z());
  };
  Eigen::VectorXd y = wp::rigid::top_start(d).tail<7>(), k1(7), k2(7), k3(7), k4(7), tmp(7);
  const Eigen::Vector3d c0 = invariants(y);
  const double h = 1e-4;
  for (int i = 0; i < 2000; ++i) {
    wp::rigid::top_exact_rhs(d, y.data(), k1.data());
    tmp = y + 0.5 * h * k1;
    wp::rigid::top_exact_rhs(d, tmp.data(), k2.data());
    tmp = y + 0.5 * h * k2;
    wp::rigid::top_exact_rhs(d, tmp.data(), k3.data());
    tmp = y + h * k3;
    wp::rigid::top_exact_rhs(d, tmp.data(), k4.data());
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  const Eigen::Vector3d c1 = invariants(y);
  // The motion is not trivial: the symmetry axis has moved (precession, nutation).
  const vec3 axis = spatial::rotation_matrix(quaternion(y.head<4>())) * vec3(0, 0, 1);
  CHECK((axis - d.axis0).norm() > 0.05);
  for (int i = 0; i < 3; ++i) CHECK(std::abs(c1(i) - c0(i)) <= 1e-13 * std::abs(c0(i)));
}

TEST_CASE("bench 3D peer equations: the exact-joint top's right-hand side zeroes the pivot model's residual") {
  // top_parameters::pivot: BODY3 with its reference point at the tip (translations on the
  // ground, centre of mass at l along body Z) and the weight F3A at the centre of mass.
  // Its moment rows about the tip are Euler's equations about the fixed tip, which the
  // peers of topx integrate (top_exact_rhs): the residual vanishes to round-off.
  pradis_examples::top_parameters p;
  p.pivot = true;
  pradis_examples::spinning_top t(p);
  REQUIRE(t.m.dof_count() == 1 + 4);  // the ground and the rotational node: no translation, no multiplier
  const wp::rigid::top_data d = wp::rigid::top_data::from_example();
  residual_probe probe(t.m, 1e-5);
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const quaternion q = random_quaternion(rng);
    double y[7] = {q(0), q(1), q(2), q(3), 30 * unit(rng), 30 * unit(rng), 30 * unit(rng)}, dy[7];
    wp::rigid::top_exact_rhs(d, y, dy);
    set_rotation(probe.state, t.r, q, vec3(y[4], y[5], y[6]), vec3(dy[4], dy[5], dy[6]));
    probe.evaluate(t.m);
    // The moment about the vertical is zero in both (dL_Z/dt = 0, the weight is horizontal): each row
    // is measured against the scale of the inertial moment, I_O (|omega'| + |omega|^2).
    const vec3 wd(dy[4], dy[5], dy[6]), w(y[4], y[5], y[6]);
    const double scale = std::max(d.j1 + d.m * d.l * d.l, d.j3) * (wd.cwiseAbs().maxCoeff() + w.squaredNorm());
    worst = std::max(worst, largest_relative_residual(probe.as, {t.r.q1, t.r.q2, t.r.q3}, scale));
  }
  MESSAGE("top with its node at the tip: largest assembled residual / its scale on the peer's motion: ", worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("bench 3D problems: the start of the peers is the start of the pradis models") {
  // The free body starts at the identity with omega_b = m0 / I, the top tilted by
  // theta0 about X and spinning at w3 about its axis (ROT0 in both models); the
  // state at t = 0 is read in the output call of the first run.
  auto start_of = [](auto& sim, const rotation_node& r, std::vector<dof> x) {
    Eigen::VectorXd z, v(3);
    sim.on_output([&](const auto& s) {
      if (s.time() != 0) return;
      z = wp::rigid::compare_state(spatial::node_quaternion(s, r), spatial::node_body_angular_velocity(s, r));
      for (int i = 0; i < 3; ++i) v(i) = s.v(x[static_cast<std::size_t>(i)]);
    });
    sim.run({.end = 1e-5, .out = 1e-5, .smax = 1e-5});
    REQUIRE(z.size() == 7);
    return std::pair{z, v};
  };
  SUBCASE("free body") {
    wp::rigid::freebody_model b;
    simulation sim(b.m, newmark{});
    const auto [z, v] = start_of(sim, b.r, b.x);
    const Eigen::VectorXd ref = wp::rigid::compare_state(quaternion(0, 0, 0, 1), wp::rigid::hlw_omega0());
    CHECK(wp::rigid::rotation_error(z, ref) < 1e-14);
    CHECK(v.norm() == 0.0);
  }
  SUBCASE("top") {
    pradis_examples::spinning_top t;
    simulation sim(t.m, newmark{});
    const auto [z, v] = start_of(sim, t.r, t.x);
    const Eigen::VectorXd y0 = wp::rigid::top_start(wp::rigid::top_data::from_example());
    const Eigen::VectorXd ref = wp::rigid::compare_state(y0.segment<4>(6), y0.segment<3>(10));
    CHECK(wp::rigid::rotation_error(z, ref) < 1e-14);
    CHECK(v.norm() == 0.0);  // y0's x' = 0
  }
  SUBCASE("topx: the top on the exact joint, and with its node at the tip (series BDF-pivot)") {
    for (const bool pivot : {false, true}) {
      CAPTURE(pivot);
      pradis_examples::top_parameters p;
      (pivot ? p.pivot : p.exact_joint) = true;
      pradis_examples::spinning_top t(p);
      simulation sim(t.m, newmark{});
      const auto [z, v] = start_of(sim, t.r, t.x);
      const Eigen::VectorXd y0 = wp::rigid::top_start(wp::rigid::top_data::from_example()).tail<7>();
      CHECK(wp::rigid::rotation_error(z, wp::rigid::compare_state(y0.head<4>(), y0.tail<3>())) < 1e-14);
      if (pivot) {
        CHECK(v.norm() == 0.0);  // x, y, z are the ground
      } else {
        CHECK(v.norm() < 1e-12);  // the centre of mass starts at rest (the spin axis passes through the tip)
      }
    }
  }
}

TEST_CASE("bench 3D error measure: rotation angle and relative angular-velocity error") {
  // A rotation by 1e-9 rad about any axis reads as 1e-9 (no loss near zero), the sign
  // of q does not matter, and omega_b errors are relative to |omega_ref|_inf.
  const quaternion q0 = spatial::from_axis_angle(vec3(1, 2, 3), 0.7);
  const vec3 w(0.5, -2.0, 1.0);
  const Eigen::VectorXd ref = wp::rigid::compare_state(q0, w);
  const quaternion dq = spatial::from_axis_angle(vec3(-3, 1, 2), 1e-9);
  CHECK(wp::rigid::rotation_error(wp::rigid::compare_state(spatial::multiply(q0, dq), w), ref) ==
        doctest::Approx(1e-9).epsilon(1e-6));
  CHECK(wp::rigid::rotation_error(wp::rigid::compare_state(-2.0 * q0, w), ref) < 1e-15);
  CHECK(wp::rigid::rotation_error(wp::rigid::compare_state(q0, w + vec3(0, 0, 1e-6)), ref) ==
        doctest::Approx(0.5e-6).epsilon(1e-9));
}
