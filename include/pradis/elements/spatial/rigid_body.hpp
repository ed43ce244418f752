#pragma once
/// \file
/// BODY3: rigid body in spatial motion on a translational point (x, y, z) and a
/// spatial rotational node (q1, q2, q3 and the hidden q4).

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

template <class = void>
struct rigid_body_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using rigid_body = rigid_body_t<>;
/// BODY3: a rigid body of mass m and inertia tensor J (about the centre of mass, in
/// the body frame) whose reference point P has the displacements x, y, z and whose
/// orientation is the rotational node q = (q1, q2, q3, q4); the centre of mass lies
/// at c (body frame) from P. With R = R(q), rho = R c, A = R J R^T,
/// omega = (2/s) E(q) q', alpha = d omega/dt (spatial/quaternion.hpp), the flows are
/// the inertial force and the inertial moment about P in global axes:
///
///     F = m a_c,   a_c = x'' + alpha x rho + omega x (omega x rho)
///     N = A alpha + omega x (A omega) + rho x F          (flows on q1, q2, q3)
///
/// and zero on q4 (the node's norm equation is assembled by the model). N is the
/// rate of the angular momentum about P: on q1..q3 the moment equations, with the
/// node's norm equation, make a regular Newton matrix (E(q) q = 0 and the norm row
/// is q^T). Full Jacobian (ADR=1, IGN=0), derived in docs/rotations.md.
template <class>
struct rigid_body_t {
  static constexpr pradis::passport passport{.name = "BODY3", .ext = 6, .ent = 1, .par = 10, .wrk = 7, .adr = 1, .ign = 0};
  /// q1..q3 are local DOFs 4..6 (0-based 3..5), the hidden q4 the internal DOF 7 (0-based 6).
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{3, 6}}};
  static constexpr element_help help{
      .title = "rigid body in spatial motion",
      .name = "Rigid body with mass and inertia tensor on a translational point and a spatial rotational node",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of the reference point P along X [m]\n"
              "2 - translation of P along Y [m]\n"
              "3 - translation of P along Z [m]\n"
              "4 - rotation potential q1 of the spatial rotational node (flow: moment about X) [-]\n"
              "5 - rotation potential q2 (flow: moment about Y) [-]\n"
              "6 - rotation potential q3 (flow: moment about Z) [-]",
      .parameters = "1 - mass m [kg] (>= 0)\n"
                    "2 - moment of inertia Jxx about the centre of mass, body frame [kg m^2]\n"
                    "3 - Jyy [kg m^2]\n"
                    "4 - Jzz [kg m^2]\n"
                    "5 - tensor entry Jxy [kg m^2] (J = [Jxx Jxy Jxz; Jxy Jyy Jyz; Jxz Jyz Jzz], positive definite)\n"
                    "6 - Jxz [kg m^2]\n"
                    "7 - Jyz [kg m^2]\n"
                    "8 - x of the centre of mass from P, body frame [m]\n"
                    "9 - y of the centre of mass from P, body frame [m]\n"
                    "10 - z of the centre of mass from P, body frame [m]",
      .work = "1 - kinetic energy T [J]\n"
              "2 - angular momentum about the centre of mass, X component (global) [N m s]\n"
              "3 - angular momentum, Y component [N m s]\n"
              "4 - angular momentum, Z component [N m s]\n"
              "5 - angular velocity about X (global) [rad/s]\n"
              "6 - angular velocity about Y [rad/s]\n"
              "7 - angular velocity about Z [rad/s]",
      .special = "code 100 if m < 0, the inertia tensor is not positive definite (or not finite), or the offset of "
                 "the centre of mass is not finite; code 75 if the quaternion norm Lq comes near zero. The hidden "
                 "fourth rotation potential q4 is shared with every element on the same rotational node; q', q'' "
                 "are not angular velocity and acceleration (docs/rotations.md)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double m = 0;                             ///< mass [kg]
    double jxx = 0, jyy = 0, jzz = 0;         ///< moments of inertia about the centre of mass (body frame) [kg m^2]
    double jxy = 0, jxz = 0, jyz = 0;         ///< off-diagonal tensor entries [kg m^2]
    double cx = 0, cy = 0, cz = 0;            ///< centre of mass from the reference point (body frame) [m]
  };
  parameters p;

  explicit rigid_body_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test): an
  /// asymmetric body with products of inertia and an offset centre of mass.
  static parameters example() { return {2.0, 0.5, 0.4, 0.3, 0.05, -0.03, 0.02, 0.1, -0.2, 0.15}; }
  static rigid_body from_parameters(std::span<const double> v) {
    return rigid_body({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9]});
  }

  /// The inertia tensor about the centre of mass in the body frame.
  spatial::mat3 inertia() const {
    spatial::mat3 j;
    j(0, 0) = p.jxx, j(0, 1) = p.jxy, j(0, 2) = p.jxz;
    j(1, 0) = p.jxy, j(1, 1) = p.jyy, j(1, 2) = p.jyz;
    j(2, 0) = p.jxz, j(2, 1) = p.jyz, j(2, 2) = p.jzz;
    return j;
  }
  /// The centre of mass from the reference point in the body frame.
  spatial::vec3 offset() const { return {p.cx, p.cy, p.cz}; }

  /// Its moments turn with its rotational node when the centre of mass is the
  /// reference point: N = R(q) (J alpha_b + omega_b x J omega_b) and F = m x''
  /// (core/element.hpp, HasBodyFixedFlows).
  bool body_fixed_flows() const noexcept { return p.cx == 0 && p.cy == 0 && p.cz == 0; }

  /// The local Jacobian entries that can be nonzero (core/element.hpp,
  /// HasJacobianStructure): none in the row of q4 (the node's norm equation is the
  /// model's); with the centre of mass on P the translation decouples, F = m x''
  /// (rows 1-3: the diagonal of M) and N does not depend on x, y, z (rows 4-6:
  /// the columns of q1..q4); with an offset every other entry.
  bool jacobian_entry(int r, int c) const noexcept {
    if (r == 6) return false;
    if (!body_fixed_flows()) return true;
    return r < 3 ? c == r : c >= 3;
  }

  /// NEWINT: m >= 0, J symmetric positive definite, finite offset (code 100).
  void new_integration(element_context& ctx) const {
    if (!(p.m >= 0) || !std::isfinite(p.m)) ctx.invalid_parameter("mass m = " + to_text(p.m) + " must be finite and >= 0");
    const spatial::mat3 j = inertia();
    if (!j.allFinite()) ctx.invalid_parameter("the inertia tensor must be finite");
    const Eigen::SelfAdjointEigenSolver<spatial::mat3> es(j, Eigen::EigenvaluesOnly);
    const double lmin = es.eigenvalues()(0), lmax = es.eigenvalues()(2);
    if (!(lmin > 1e-12 * lmax) || !(lmax > 0))
      ctx.invalid_parameter("the inertia tensor is not positive definite (smallest principal moment " + to_text(lmin) +
                            " kg m^2)");
    if (!offset().allFinite()) ctx.invalid_parameter("the offset of the centre of mass must be finite");
  }

  void evaluate(const local_input<rigid_body>& in, local_output<rigid_body>& out, element_context& ctx) const {
    using namespace spatial;
    const quaternion q = in.u.segment<4>(3), qd = in.v.segment<4>(3), qdd = in.a.segment<4>(3);
    const double s = q.squaredNorm();
    if (!(s > lq_near_zero * lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    const mat3 r = rotation_matrix(q);
    const mat34 e = e_matrix(q);
    const double g = q.dot(qd);
    const vec3 w = (2.0 / s) * (e * qd);                // omega
    const vec3 alpha1 = (2.0 / s) * (e * qdd);
    const vec3 alpha = alpha1 - (2.0 * g / s) * w;      // d omega / dt
    const vec3 rho = r * offset();
    // A x = R (J (R^T x)): matrix-vector products only (A itself only for the Jacobian).
    const mat3 j = inertia();
    const vec3 wb = r.transpose().lazyProduct(w), ab = r.transpose().lazyProduct(alpha);
    const vec3 jwb = j.lazyProduct(wb), jab = j.lazyProduct(ab);
    const vec3 h = r.lazyProduct(jwb), a_alpha = r.lazyProduct(jab);
    const vec3 xdd = in.a.head<3>();
    const vec3 ac = xdd + alpha.cross(rho) + w.cross(w.cross(rho));
    const vec3 f = p.m * ac;
    const vec3 n = a_alpha + w.cross(h) + rho.cross(f);
    out.f.head<3>() = f;
    out.f.segment<3>(3) = n;
    out.f(6) = 0.0;
    const vec3 vc = in.v.head<3>() + w.cross(rho);
    ctx.work[0] = 0.5 * p.m * vc.squaredNorm() + 0.5 * w.dot(h);
    ctx.work[1] = h.x();
    ctx.work[2] = h.y();
    ctx.work[3] = h.z();
    ctx.work[4] = w.x();
    ctx.work[5] = w.y();
    ctx.work[6] = w.z();
    if (!out.want_jacobian) return;

    // Partial derivatives of (F, N) by x'', alpha, omega and a small global rotation
    // theta, stacked as 6 x 3 blocks D_th, D_w, D_al (rows F then N).
    using mat63 = Eigen::Matrix<double, 6, 3>;
    using mat64 = Eigen::Matrix<double, 6, 4>;
    using vec6 = Eigen::Matrix<double, 6, 1>;
    const mat3 a = r.lazyProduct(j).eval().lazyProduct(r.transpose());
    const mat3 sr = skew(rho), sw = skew(w), sa = skew(alpha), sh = skew(h);
    mat63 d_al, d_w, d_th;
    const mat3 f_al = -p.m * sr;
    const mat3 f_w = p.m * (w * rho.transpose() + w.dot(rho) * mat3::Identity() - 2.0 * rho * w.transpose());
    const mat3 f_th = -p.m * (sa + sw.lazyProduct(sw)).eval().lazyProduct(sr);
    d_al.topRows<3>() = f_al;
    d_al.bottomRows<3>() = a + sr.lazyProduct(f_al);
    d_w.topRows<3>() = f_w;
    d_w.bottomRows<3>() = sw.lazyProduct(a) - sh + sr.lazyProduct(f_w);
    d_th.topRows<3>() = f_th;
    d_th.bottomRows<3>() = a.lazyProduct(sa) - skew(a_alpha) + sw.lazyProduct((a.lazyProduct(sw) - sh).eval()) +
                           skew(f).lazyProduct(sr) + sr.lazyProduct(f_th);
    // The chain rule through theta, omega, alpha as functions of q, q', q'' with
    // E2 = (2/s) E(q) = d theta/dq = d omega/dq' = d alpha/dq'':
    //   d omega/dq   = -(2/s) (E(q') + omega q^T)
    //   d alpha/dq   = -(2/s) (E(q'') + alpha1 q^T + omega q'^T) - (2g/s) d omega/dq + (4g/s^2) omega q^T
    //   d alpha/dq'  = -(2/s) omega q^T - (2g/s) E2
    // (alpha1 = (2/s) E(q) q'', g = q.q'), so with X = D_w - (2g/s) D_al:
    //   M = D_al E2
    //   C = D_w E2 - (2g/s) M - (2/s) (D_al omega) q^T
    //   K = D_th E2 - (2/s) (X E(q') + D_al E(q'')) + [(4g/s^2) D_al omega - (2/s) (X omega + D_al alpha1)] q^T
    //       - (2/s) (D_al omega) q'^T
    const double c2 = 2.0 / s, cg = 2.0 * g / s;
    const mat34 e2 = c2 * e;
    const mat63 x = d_w - cg * d_al;
    const vec6 dal_w = d_al.lazyProduct(w);
    const vec6 kq = (cg * c2) * dal_w - c2 * (x.lazyProduct(w) + d_al.lazyProduct(alpha1));
    const mat64 mb = d_al.lazyProduct(e2);
    const mat64 cb = d_w.lazyProduct(e2) - cg * mb - c2 * dal_w * q.transpose();
    const mat64 kb = d_th.lazyProduct(e2) - c2 * (x.lazyProduct(e_matrix(qd)) + d_al.lazyProduct(e_matrix(qdd))) +
                     kq * q.transpose() - c2 * dal_w * qd.transpose();
    out.K.setZero();
    out.C.setZero();
    out.M.setZero();
    out.M.block<3, 3>(0, 0) = p.m * mat3::Identity();
    out.M.block<3, 3>(3, 0) = p.m * sr;
    out.M.block<6, 4>(0, 3) = mb;
    out.C.block<6, 4>(0, 3) = cb;
    out.K.block<6, 4>(0, 3) = kb;
  }

  /// States the checks may use: the quaternion norm is not near zero.
  bool admissible(const local_input<rigid_body>& in) const { return in.u.segment<4>(3).norm() > 0.2; }
};

}  // namespace pradis::elements
