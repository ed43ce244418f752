// FLEX3 (elements/spatial/reduced_body.hpp): a Guyan / Craig-Bampton reduced
// beam in large motion.
// - Rigid motions: a rigid displacement of the reference configuration gives no
//   elastic flows, and in a steady spin about node 1 the inertia flows are those of
//   the rigid body whose mass, first moment and inertia are the reduced mass's
//   rigid-body projection G^T M G (G the six rigid motions of the boundary; rigid
//   body dynamics: F = m a_c, dH/dt = omega x (J omega) for a constant omega).
// - Static: the Guyan reduction of a cantilever carries the exact tip deflection
//   P L^3 / (3 E I) and slope P L^2 / (2 E I) (Timoshenko and Gere, Mechanics of
//   Materials); turned and moved as a whole, the flows turn with it (objectivity).
// - A rotating beam: a free steel bar spun up by a torque at one end, as one FLEX3
//   (10 beam elements reduced to its ends and 4 fixed-interface modes) and as 10
//   BEAM3 + BEAMI3 (the same discretisation). The tip deflection in the root's
//   frame agrees to 1e-3 of its maximum at a low spin; the rest of the difference
//   is BEAM3's centrifugal stiffening, which FLEX3 (constant K in its frame) leaves
//   out: it grows with the square of the spin rate (relative effect of order
//   (Omega / omega_1)^2, Southwell's rotating-beam stiffening).
// - The finite-difference Jacobian check for three boundary nodes and a mode (FLEX3
//   of the library, two nodes and two modes, is in the all-elements test), and bad
//   input: codes 100, 101, 75 and invalid_model with element, instance and message.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "../elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/elements/spatial/reduced_body.hpp"
#include "pradis/testing/jacobian_check.hpp"
#include "spatial_test_support.hpp"
#include "../../bench/spun_bar.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

namespace {
/// Evaluates E at `in` (flows and, with `jac`, the blocks) after its NEWINT check.
template <class E>
local_output<E> flex_eval(const E& e, const local_input<E>& in, std::array<double, 2>& work) {
  element_context ctx("FLEX3", "bar");
  ctx.work = work;
  e.new_integration(ctx);
  local_output<E> out;
  e.evaluate(in, out, ctx);
  return out;
}

/// Sets node i (0-based) of a FLEX3 input: displacement from its reference x0, quaternion q.
template <class E>
void flex_set_node(local_input<E>& in, int nb, int i, const vec3& displacement, const quaternion& q) {
  in.u.template segment<3>(6 * i) = displacement;
  in.u.template segment<3>(6 * i + 3) = q.head<3>();
  in.u(6 * nb + i) = q(3);
}

}  // namespace

TEST_SUITE("spatial/reduced_body") {
  TEST_CASE("FLEX3: the beam matrices are BEAM3's and BEAMI3's linearisation at rest") {
    // Stiffness and mass of one oblique element from the elements' Jacobians at identity quaternions, by
    // rotation angle (dtheta/dq = 2 E(q) = 2 [I 0] there), against straight_beam_matrices with n = 1.
    const vec3 a(0.1, -0.2, 0.3), b(1.1, 0.5, -0.4), v(0.2, 0.3, 1.0);
    const beam_section s{2e2, 80, 0.5, 0.2, 0.1, 0.15, 7.0, 0.3};
    const beam_matrices bm = straight_beam_matrices(s, a, b, v, 1);
    const elastic_beam eb({s.e, s.g, s.a, s.iy, s.iz, s.j, a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), v.x(), v.y(), v.z()});
    const beam_inertia ei({s.rho, s.a, s.iy, s.iz, s.ip, a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), v.x(), v.y(), v.z()});
    local_input<elastic_beam> in;
    in.u(12) = in.u(13) = 1.0;
    local_input<beam_inertia> ini;
    ini.u = in.u;
    local_output<elastic_beam> ob;
    local_output<beam_inertia> oi;
    std::array<double, 3> wb{};
    std::array<double, 1> wi{};
    element_context cb("BEAM3", "b"), ci("BEAMI3", "m");
    cb.work = wb;
    ci.work = wi;
    eb.evaluate(in, ob, cb);
    ei.evaluate(ini, oi, ci);
    Eigen::MatrixXd k(12, 12), mm(12, 12);
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c) {
        const double scale = (c % 6) >= 3 ? 0.5 : 1.0;
        k(r, c) = scale * ob.K(r, c);
        mm(r, c) = scale * oi.M(r, c);
      }
    CHECK((k - bm.k).norm() < 1e-9 * bm.k.norm());
    CHECK((mm - bm.m).norm() < 1e-12 * bm.m.norm());
    // Bad input of the matrices: invalid_model with a plain message.
    const auto e1 = error_from([&] { (void)straight_beam_matrices(s, a, a, v, 2); });
    REQUIRE(e1);
    CHECK(e1->code() == error_code::invalid_model);
    CHECK(std::string(e1->what()).find("length of the beam is zero") != std::string::npos);
    const auto e2 = error_from([&] { (void)straight_beam_matrices(s, a, b, b - a, 2); });
    REQUIRE(e2);
    CHECK(std::string(e2->what()).find("section vector") != std::string::npos);
    beam_section bad = s;
    bad.rho = -1;
    const auto e3 = error_from([&] { (void)straight_beam_matrices(bad, a, b, v, 2); });
    REQUIRE(e3);
    CHECK(std::string(e3->what()).find("must be finite and > 0") != std::string::npos);
    const auto e4 = error_from([&] { (void)straight_beam_matrices(s, a, b, v, 0); });
    REQUIRE(e4);
    CHECK(std::string(e4->what()).find("number of elements 0") != std::string::npos);
  }

  TEST_CASE("FLEX3: a rigid displacement gives no elastic flows; a steady spin gives the rigid body's inertia flows") {
    using E = reduced_body<3, 2>;
    const E e(E::example());
    const auto& p = e.p;
    // The rigid body of the reduced mass: G^T M G = [m I, -m [c x]; m [c x], J1] about node 1 (body axes).
    Eigen::Matrix<double, E::nr, 6> g = Eigen::Matrix<double, E::nr, 6>::Zero();
    const vec3 x1(p.x0[0], p.x0[1], p.x0[2]);
    std::array<vec3, 3> rel;
    for (int i = 0; i < 3; ++i) {
      rel[static_cast<std::size_t>(i)] =
          vec3(p.x0[static_cast<std::size_t>(3 * i)], p.x0[static_cast<std::size_t>(3 * i + 1)],
               p.x0[static_cast<std::size_t>(3 * i + 2)]) - x1;
      g.block<3, 3>(6 * i, 0) = mat3::Identity();
      g.block<3, 3>(6 * i, 3) = -skew(rel[static_cast<std::size_t>(i)]);
      g.block<3, 3>(6 * i + 3, 3) = mat3::Identity();
    }
    const Eigen::Matrix<double, 6, 6> rb = g.transpose() * p.m * g;
    const double mass = rb(0, 0);
    const vec3 mc(rb(5, 1), rb(3, 2), rb(4, 0));  // m [c x] below the diagonal
    const mat3 j1 = rb.block<3, 3>(3, 3);
    CHECK(mass > 0);
    // The whole body turned by a large rotation q0 about node 1 (which moves to p0), spinning at w about node 1.
    const quaternion q0 = from_axis_angle(vec3(0.3, -0.5, 0.8).normalized(), 2.1);
    const mat3 r = rotation_matrix(q0);
    const vec3 p0(0.4, -1.0, 2.5), w(3.0, -1.5, 2.0);
    local_input<E> in;
    for (int i = 0; i < 3; ++i) {
      const vec3 ri = r * rel[static_cast<std::size_t>(i)];
      flex_set_node(in, 3, i, p0 + ri - (x1 + rel[static_cast<std::size_t>(i)]), q0);
      in.v.segment<3>(6 * i) = w.cross(ri);
      in.a.segment<3>(6 * i) = w.cross(w.cross(ri));
      const quaternion qd = rate_from_global_angular_velocity(q0, w);
      in.v.segment<3>(6 * i + 3) = qd.head<3>();
      in.v(18 + i) = qd(3);
      // q'' of a constant global angular velocity: q' = (1/2) (w, 0) q, so q'' = (1/2) (w, 0) q'.
      const quaternion qdd = 0.5 * multiply(quaternion(w.x(), w.y(), w.z(), 0), qd);
      in.a.segment<3>(6 * i + 3) = qdd.head<3>();
      in.a(18 + i) = qdd(3);
    }
    for (int i = 0; i < 3; ++i) {
      const auto b = static_cast<Eigen::Index>(6 * i + 3);
      const quaternion qd(in.v(b), in.v(b + 1), in.v(b + 2), in.v(18 + i)), qdd(in.a(b), in.a(b + 1), in.a(b + 2), in.a(18 + i));
      CHECK((global_angular_velocity(q0, qd) - w).norm() < 1e-14 * w.norm());
      CHECK(global_angular_acceleration(q0, qd, qdd).norm() < 1e-14 * w.squaredNorm());
    }
    std::array<double, 2> work{};
    const auto out = flex_eval(e, in, work);
    // The rigid body: F = m w x (w x R c), moment about node 1 dH/dt = w x (R J1 R^T w).
    const vec3 c = r * (mc / mass);
    const vec3 force = mass * w.cross(w.cross(c));
    const vec3 moment = w.cross(r * j1 * r.transpose() * w);
    vec3 f_sum = vec3::Zero(), m_sum = vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      const vec3 fi = out.f.segment<3>(6 * i);
      f_sum += fi;
      m_sum += (r * rel[static_cast<std::size_t>(i)]).cross(fi) + out.f.segment<3>(6 * i + 3);
    }
    const double fs = mass * w.squaredNorm() * c.norm();
    CHECK((f_sum - force).norm() < 1e-10 * fs);
    CHECK((m_sum - moment).norm() < 1e-10 * (j1.norm() * w.squaredNorm()));
    // No modal flows: in a steady spin the frame velocities are constant and the kinetic energy has no term in the
    // modal coordinates themselves, so the interior's centrifugal load reaches the part through its boundary nodes.
    CHECK(out.f.tail<2>().norm() < 1e-10 * fs);
    // No strain, and the kinetic energy of the rigid body: (1/2) (m |v_1|^2 + w . J w) with v_1 = 0 at node 1.
    CHECK(std::abs(work[0]) < 1e-20);
    CHECK(work[1] == doctest::Approx(0.5 * w.dot(r * j1 * r.transpose() * w)).epsilon(1e-12));
    // At rest in the displaced configuration: all flows vanish.
    in.v.setZero();
    in.a.setZero();
    const auto rest = flex_eval(e, in, work);
    CHECK(rest.f.norm() < 1e-12 * p.k.norm());
  }

  TEST_CASE("FLEX3: a Guyan cantilever carries the exact tip deflection P L^3 / (3 E I), turned and moved as a whole") {
    using E = reduced_body<2, 0>;
    const E e(spun_bar::reduced_bar<0>(10));
    const double p = 50.0, l = 1.0, ei = spun_bar::steel.e * spun_bar::steel.iz;
    const double delta = p * l * l * l / (3 * ei), slope = p * l * l / (2 * ei);
    const quaternion q0 = from_axis_angle(vec3(-0.2, 0.9, 0.4).normalized(), 2.7);
    const mat3 r = rotation_matrix(q0);
    const vec3 p0(1.0, 2.0, -3.0);
    local_input<E> in;
    flex_set_node(in, 2, 0, p0, q0);
    flex_set_node(in, 2, 1, p0 + r * vec3(l, delta, 0) - vec3(l, 0, 0), multiply(q0, from_axis_angle(vec3::UnitZ(), slope)));
    std::array<double, 2> work{};
    const auto out = flex_eval(e, in, work);
    // The tip's flow is the force that holds it there: R (0, P, 0), no moment; the root's the reaction. To
    // round-off: the axial stiffness E A / L = 8.4e7 N/m times the round-off of the turned chord (~1e-16 L).
    const double roundoff = 1e-15 * e.p.k.norm() * l;
    MESSAGE("round-off scale ", roundoff, " N against P = ", p, " N");
    CHECK((out.f.segment<3>(6) - r * vec3(0, p, 0)).norm() < roundoff);
    CHECK(out.f.segment<3>(9).norm() < roundoff * l);
    CHECK((out.f.head<3>() + r * vec3(0, p, 0)).norm() < roundoff);
    CHECK((out.f.segment<3>(3) - r * vec3(0, 0, -p * l)).norm() < roundoff * l);
    CHECK(work[0] == doctest::Approx(0.5 * p * delta).epsilon(1e-9));
  }

  TEST_CASE("FLEX3: a spun-up free bar, Craig-Bampton with 4 modes, moves as 10 BEAM3 + BEAMI3 but for the centrifugal stiffening") {
    const double h = 2.5e-4, end = 0.3;
    double rel_low = 0, rel_high = 0;
    // Under the sanitizers (-O0, some 200x slower) the lower torque alone: the same code paths;
    // the growth with the spin is checked in the dev preset.
    const std::vector<double> torques = pradis_test::sanitized ? std::vector{5.0} : std::vector{5.0, 20.0};
    for (double m0 : torques) {
      const auto beams = spun_bar::spin_beams(m0, end, h, 10);
      const auto flex = spun_bar::spin_reduced<4>(m0, end, h, 10);
      REQUIRE(beams.size() == flex.size());
      double angle_diff = 0;
      for (std::size_t i = 0; i < beams.size(); ++i)
        angle_diff = std::max(angle_diff, std::abs(beams[i].angle - flex[i].angle));
      const double rel = spun_bar::deflection_difference(beams, flex);
      const double spin = (beams.back().angle - beams[beams.size() - 2].angle) / 0.01;
      MESSAGE("M0 = ", m0, " N m: root turned by ", beams.back().angle, " rad, spin ~", spin,
              " rad/s; largest tip deflection difference ", rel, " of the peak; root angle difference ", angle_diff,
              " rad");
      CHECK(beams.back().angle > 0.8);     // large overall motion
      CHECK(angle_diff < 1e-4 * beams.back().angle);
      (m0 < 10 ? rel_low : rel_high) = rel;
    }
    CHECK(rel_low < 1e-3);
    // Four times the torque, four times the spin: the relative difference grows about 16-fold, as the
    // stiffening (Omega / omega_1)^2 that FLEX3 leaves out; a reduction error would not grow with the spin.
    if (!pradis_test::sanitized) {
      CHECK(rel_high > 10 * rel_low);
      CHECK(rel_high < 0.03);
    }
  }

  TEST_CASE("FLEX3 with three boundary nodes and a mode passes the finite-difference Jacobian check") {
    using E = reduced_body<3, 1>;
    const E e(E::example());
    std::array<double, 2> work{};
    element_context ctx("FLEX3", "x");
    ctx.work = work;
    e.new_integration(ctx);
    testing::jacobian_checker<E> chk(e);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    int checked = 0;
    for (int trial = 0; trial < 400 && checked < 100; ++trial) {
      local_input<E> in;
      for (int k = 0; k < element_traits<E>::n; ++k) {
        in.u(k) = 0.3 * uni(rng);
        in.v(k) = 10 * uni(rng);
        in.a(k) = 10 * uni(rng);
      }
      for (int i = 0; i < 3; ++i) in.u(18 + i) += 1.0;  // quaternions near unit, any orientation below
      if (!e.admissible(in)) continue;
      ++checked;
      if (!pradis_element_tests::jacobian_passes(chk.check(in))) break;
    }
    CHECK(checked == 100);
  }

  TEST_CASE("FLEX3 refuses bad matrices and positions (100), a wrong count (101), a degenerate state (75)") {
    using E = reduced_body<2, 0>;
    const auto run = [](const E::parameters& p) {
      model<E> m;
      const auto d = m.add_dofs(6);
      m.add<E>("bar", p, d[0], d[1], d[2], m.add_rotation_node("ra"), d[3], d[4], d[5], m.add_rotation_node("rb"));
      simulation sim(m);
      return error_from([&] { sim.run({.end = 0.01, .smax = 0.001}); });
    };
    const E::parameters ok = spun_bar::reduced_bar<0>(10);
    CHECK_FALSE(run(ok).has_value());
    E::parameters bad = ok;
    bad.x0[4] = pradis_element_tests::not_a_number;
    check_error(run(bad), error_code::invalid_parameter, "FLEX3", "bar", "node positions must be finite");
    bad = ok;
    bad.x0[3] = 0.5;  // the tip moved: K no longer free of the rigid rotations of these positions
    check_error(run(bad), error_code::invalid_parameter, "FLEX3", "bar", "K resists a rigid rotation about");
    bad = ok;
    bad.k(0, 0) += 1e6;  // a grounded root
    check_error(run(bad), error_code::invalid_parameter, "FLEX3", "bar", "K resists a rigid translation along X");
    bad = ok;
    bad.m(2, 2) = -1;
    check_error(run(bad), error_code::invalid_parameter, "FLEX3", "bar", "mass M is not positive definite");
    bad = ok;
    bad.k *= -1;
    check_error(run(bad), error_code::invalid_parameter, "FLEX3", "bar", "not positive semidefinite");
    bad = ok;
    bad.x0[3] = 0;  // both nodes at the origin
    bad.k.setZero();
    check_error(run(bad), error_code::invalid_parameter, "FLEX3", "bar", "all boundary nodes are at one point");
    // A part of another size.
    const beam_matrices bm = straight_beam_matrices(spun_bar::steel, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2);
    const auto wrong = error_from([&] {
      (void)E::from_part(linalg::craig_bampton(bm.k, bm.m, {0, 1, 2, 3, 4, 5, 12, 13, 14, 15, 16, 17}, 1),
                         {vec3::Zero(), vec3::UnitX()});
    });
    REQUIRE(wrong);
    CHECK(wrong->code() == error_code::invalid_model);
    CHECK(std::string(wrong->what()).find("takes 12 and 0") != std::string::npos);
    // The flat path counts the parameters: 6 positions and two lower triangles of 12 x 12.
    model<E> m;
    const auto d = m.add_dofs(6);
    const auto ra = m.add_rotation_node("ra"), rb = m.add_rotation_node("rb");
    const std::array<dof, 12> ds{d[0], d[1], d[2], ra.q1, ra.q2, ra.q3, d[3], d[4], d[5], rb.q1, rb.q2, rb.q3};
    const std::vector<double> few(100, 1.0);
    check_error(pradis_element_tests::flat_add_error<E>(m, "bar", ds, few), error_code::parameter_count, "FLEX3", "bar",
                "got 100 parameters");
    // Degenerate states (code 75): a vanished quaternion, a node turned by 180 degrees relative to node 1.
    const E e(ok);
    local_input<E> in;
    flex_set_node(in, 2, 0, vec3::Zero(), identity());
    flex_set_node(in, 2, 1, vec3::Zero(), quaternion(0, 0, 0, 1e-5));
    std::array<double, 2> work{};
    check_error(error_from([&] { (void)flex_eval(e, in, work); }), error_code::singular_situation, "FLEX3", "bar",
                "Lq near zero");
    flex_set_node(in, 2, 1, vec3::Zero(), from_axis_angle(vec3::UnitY(), std::numbers::pi));
    check_error(error_from([&] { (void)flex_eval(e, in, work); }), error_code::singular_situation, "FLEX3", "bar",
                "180 degrees");
  }
}
