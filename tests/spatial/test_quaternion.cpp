// Quaternion utilities of spatial rotations (include/pradis/spatial/quaternion.hpp),
// checked numerically against their defining properties: R(q) is a rotation
// (orthogonal, det = +1) and Rodrigues' formula for q = (e sin(phi/2), cos(phi/2));
// E(q) and G(q) satisfy E q = G q = 0 and E E^T = G G^T = s I (Nikravesh,
// Computer-Aided Analysis of Mechanical Systems, 1988, section 6.3; Haug, Computer
// Aided Kinematics and Dynamics of Mechanical Systems, 1989, section 9.3); the
// angular velocities (2/s) E q' and (2/s) G q' agree with the finite-difference
// derivative of R ([omega x] = R' R^T, [omega' x] = R^T R'); the generalized force
// does the same virtual work as the torque; the Hamilton product composes rotations;
// conversions round-trip at every angle including 180 degrees.

#include <doctest/doctest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <random>

#include "pradis/spatial/quaternion.hpp"
#include "spatial_test_support.hpp"

using namespace pradis::spatial;

namespace {

using pradis_spatial_tests::pi;

/// A random non-unit quaternion with |q| in [0.5, 2].
quaternion random_quaternion(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> len(0.5, 2.0);
  quaternion q(n(rng), n(rng), n(rng), n(rng));
  return len(rng) * q / q.norm();
}

/// The vector of a skew matrix (the inverse of skew()).
vec3 unskew(const mat3& m) { return vec3(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)) / 2; }

}  // namespace

TEST_SUITE("spatial/quaternion") {
  TEST_CASE("R(q) of a non-unit quaternion is orthogonal with det = +1, and equals Rodrigues' formula") {
    std::mt19937 rng(7);
    double worst_orth = 0, worst_det = 0, worst_rodrigues = 0;
    for (int i = 0; i < 500; ++i) {
      const quaternion q = random_quaternion(rng);
      const mat3 r = rotation_matrix(q);
      worst_orth = std::max(worst_orth, (r.transpose() * r - mat3::Identity()).cwiseAbs().maxCoeff());
      worst_det = std::max(worst_det, std::abs(r.determinant() - 1.0));
      // Rodrigues: R = cos(phi) I + (1 - cos(phi)) e e^T + sin(phi) [e x] for q = |q| (e sin(phi/2), cos(phi/2)).
      const axis_angle aa = to_axis_angle(q);
      const vec3 e = aa.axis;
      const mat3 rod = std::cos(aa.angle) * mat3::Identity() + (1 - std::cos(aa.angle)) * e * e.transpose() +
                       std::sin(aa.angle) * skew(e);
      worst_rodrigues = std::max(worst_rodrigues, (r - rod).cwiseAbs().maxCoeff());
    }
    CHECK(worst_orth < 1e-14);
    CHECK(worst_det < 1e-14);
    CHECK(worst_rodrigues < 1e-14);
    // A quarter turn about Z maps X to Y (active rotation, body -> global).
    const mat3 rz = rotation_matrix(from_axis_angle(vec3::UnitZ(), pi / 2));
    CHECK((rz * vec3::UnitX() - vec3::UnitY()).norm() < 1e-15);
    CHECK((skew(vec3(1, 2, 3)) * vec3(-1, 0.5, 2) - vec3(1, 2, 3).cross(vec3(-1, 0.5, 2))).norm() < 1e-15);
  }

  TEST_CASE("E(q) and G(q): E q = G q = 0, E E^T = G G^T = s I, E^T E = s I4 - q q^T, G = E R-transformed") {
    std::mt19937 rng(11);
    double worst = 0;
    for (int i = 0; i < 500; ++i) {
      const quaternion q = random_quaternion(rng);
      const double s = q.squaredNorm();
      const mat34 e = e_matrix(q), g = g_matrix(q);
      worst = std::max(worst, (e * q).norm() / s);
      worst = std::max(worst, (g * q).norm() / s);
      worst = std::max(worst, (e * e.transpose() - s * mat3::Identity()).cwiseAbs().maxCoeff() / s);
      worst = std::max(worst, (g * g.transpose() - s * mat3::Identity()).cwiseAbs().maxCoeff() / s);
      worst = std::max(worst, (e.transpose() * e - (s * Eigen::Matrix4d::Identity() - q * q.transpose()))
                                      .cwiseAbs()
                                      .maxCoeff() /
                                  s);
      // R = E G^T / s (Nikravesh 6.3): both factorisations of the rotation.
      worst = std::max(worst, (e * g.transpose() / s - rotation_matrix(q)).cwiseAbs().maxCoeff());
      // E(q) p = -E(p) q: E is linear and antisymmetric in its two arguments.
      const quaternion p = random_quaternion(rng);
      worst = std::max(worst, (e * p + e_matrix(p) * q).norm());
    }
    CHECK(worst < 1e-14);
  }

  TEST_CASE("omega = (2/s) E q' and omega' = (2/s) G q' match R' R^T and R^T R' by finite differences") {
    std::mt19937 rng(13);
    double worst_global = 0, worst_body = 0, worst_alpha = 0;
    for (int i = 0; i < 200; ++i) {
      const quaternion q = random_quaternion(rng), qd = random_quaternion(rng), qdd = random_quaternion(rng);
      // q' is arbitrary: it may change |q| too, which the formulas must ignore.
      const double h = 1e-5;
      auto qt = [&](double t) -> quaternion { return q + t * qd + 0.5 * t * t * qdd; };
      const mat3 r = rotation_matrix(q);
      const mat3 rdot = (rotation_matrix(qt(h)) - rotation_matrix(qt(-h))) / (2 * h);
      const vec3 w_fd = unskew(rdot * r.transpose()), wb_fd = unskew(r.transpose() * rdot);
      const vec3 w = global_angular_velocity(q, qd), wb = body_angular_velocity(q, qd);
      worst_global = std::max(worst_global, (w - w_fd).norm() / (1 + w.norm()));
      worst_body = std::max(worst_body, (wb - wb_fd).norm() / (1 + w.norm()));
      CHECK((wb - r.transpose() * w).norm() < 1e-12 * (1 + w.norm()));
      // alpha: derivative of omega along the same path.
      const vec3 alpha_fd = (global_angular_velocity(qt(h), qd + h * qdd) - global_angular_velocity(qt(-h), qd - h * qdd)) /
                            (2 * h);
      worst_alpha = std::max(worst_alpha, (global_angular_acceleration(q, qd, qdd) - alpha_fd).norm() /
                                              (1 + alpha_fd.norm()));
    }
    CHECK(worst_global < 1e-8);
    CHECK(worst_body < 1e-8);
    CHECK(worst_alpha < 1e-8);
  }

  TEST_CASE("the rate of an angular velocity is orthogonal to q and gives the angular velocity back") {
    std::mt19937 rng(17);
    for (int i = 0; i < 100; ++i) {
      const quaternion q = random_quaternion(rng);
      const vec3 w(std::sin(i), std::cos(2.0 * i), 0.3 * i - 10);
      const quaternion qd = rate_from_global_angular_velocity(q, w);
      CHECK(std::abs(q.dot(qd)) < 1e-13 * (1 + w.norm()));
      CHECK((global_angular_velocity(q, qd) - w).norm() < 1e-13 * (1 + w.norm()));
    }
  }

  TEST_CASE("the generalized force (2/s) E^T n of a torque does the virtual work n . dtheta") {
    // Virtual work of a torque n on a small rotation: n . dtheta with [dtheta x] = dR R^T.
    std::mt19937 rng(19);
    double worst = 0;
    for (int i = 0; i < 200; ++i) {
      const quaternion q = random_quaternion(rng), dq = random_quaternion(rng);
      const vec3 n(1.5 * std::sin(i), -0.5, std::cos(3.0 * i));
      const double h = 1e-6;
      const mat3 dr = (rotation_matrix(q + h * dq) - rotation_matrix(q - h * dq)) / (2 * h);
      const vec3 dtheta = unskew(dr * rotation_matrix(q).transpose());
      worst = std::max(worst, std::abs(generalized_force(q, n).dot(dq) - n.dot(dtheta)) / (1 + n.norm() * dq.norm()));
      CHECK(std::abs(generalized_force(q, n).dot(q)) < 1e-13 * (1 + n.norm()));  // no work on a change of |q|
    }
    CHECK(worst < 1e-8);
  }

  TEST_CASE("the Hamilton product composes rotations and relative_rotation gives R(a)^T R(b)") {
    std::mt19937 rng(23);
    double worst = 0;
    for (int i = 0; i < 300; ++i) {
      const quaternion a = random_quaternion(rng), b = random_quaternion(rng);
      worst = std::max(worst, (rotation_matrix(multiply(a, b)) - rotation_matrix(a) * rotation_matrix(b)).cwiseAbs().maxCoeff());
      worst = std::max(worst, std::abs(multiply(a, b).norm() - a.norm() * b.norm()) / (a.norm() * b.norm()));
      const quaternion r = relative_rotation(a, b);
      worst = std::max(worst, (rotation_matrix(r) - rotation_matrix(a).transpose() * rotation_matrix(b)).cwiseAbs().maxCoeff());
      // a r is parallel to b (the same rotation).
      const quaternion ar = multiply(a, r);
      worst = std::max(worst, (ar / ar.norm() - b / b.norm()).norm());
    }
    CHECK(worst < 1e-14);
    // Two quarter turns about X make a half turn: (1, 0, 0, 0) up to sign and scale.
    const quaternion qx = from_axis_angle(vec3::UnitX(), pi / 2);
    CHECK((multiply(qx, qx) - quaternion(1, 0, 0, 0)).norm() < 1e-15);
    CHECK((multiply(qx, conjugate(qx)) - identity()).norm() < 1e-15);
  }

  TEST_CASE("axis-angle and matrix conversions round-trip at every angle, including 0 and 180 degrees") {
    std::mt19937 rng(29);
    std::normal_distribution<double> n(0.0, 1.0);
    double worst_aa = 0, worst_matrix = 0;
    auto check_angle = [&](const vec3& axis, double angle) {
      const quaternion q = from_axis_angle(axis, angle);
      CHECK(std::abs(q.norm() - 1.0) < 1e-15);
      const axis_angle back = to_axis_angle(q);
      // The same rotation: compare the matrices (at pi, axis and -axis are the same rotation).
      const mat3 r = rotation_matrix(q);
      worst_aa = std::max(worst_aa, (matrix_from_axis_angle(back.axis, back.angle) - r).cwiseAbs().maxCoeff());
      if (angle > 1e-3 && angle < pi - 1e-3) {
        worst_aa = std::max(worst_aa, std::abs(back.angle - angle));
        worst_aa = std::max(worst_aa, (back.axis - axis.normalized()).norm());
      }
      const quaternion qm = from_matrix(r);
      worst_matrix = std::max(worst_matrix, std::min((qm - q).norm(), (qm + q).norm()));
      worst_matrix = std::max(worst_matrix, (rotation_matrix(qm) - r).cwiseAbs().maxCoeff());
    };
    for (int i = 0; i < 400; ++i) {
      const vec3 axis(n(rng), n(rng), n(rng));
      check_angle(axis, pi * (i % 100) / 99.0);  // 0 .. pi, both ends included
    }
    // Exactly 180 degrees about the coordinate axes and diagonals; tiny angles.
    for (const vec3& axis : {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), vec3(1, 1, 0), vec3(1, -1, 1), vec3(0, -1, 1)}) {
      check_angle(axis, pi);
      check_angle(axis, pi - 1e-9);
      check_angle(axis, 1e-12);
      check_angle(axis, 0.0);
    }
    CHECK(worst_aa < 1e-13);
    CHECK(worst_matrix < 1e-14);
    // Angles beyond pi come back as the equivalent rotation in [0, pi].
    const axis_angle big = to_axis_angle(from_axis_angle(vec3::UnitZ(), 1.5 * pi));
    CHECK(big.angle == doctest::Approx(0.5 * pi).epsilon(1e-14));
    CHECK((big.axis + vec3::UnitZ()).norm() < 1e-14);
    CHECK(to_axis_angle(identity()).angle == 0.0);
  }
}
