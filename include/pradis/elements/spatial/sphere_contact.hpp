#pragma once
/// \file
/// Contact of spheres carried by bodies in spatial motion: CSPHPL (a sphere against a
/// fixed plane, with Coulomb stick-slip friction) and CSPHSP (two spheres, normal force
/// only). The normal laws, the friction return mapping and STEPMD are in
/// contact_law.hpp; docs/contact.md describes both elements.

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/attachment.hpp"
#include "pradis/elements/spatial/contact_law.hpp"
#include "pradis/elements/spatial/sphere_friction.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

template <class = void>
struct sphere_plane_contact_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using sphere_plane_contact = sphere_plane_contact_t<>;
/// CSPHPL: a sphere of radius R whose centre is attached to a body (offset a in the body
/// frame from the reference point, initially at X0) against a fixed plane through P with
/// unit normal n (the sphere's side). With the centre c = X0 + x + R(q) a:
///
///     delta = R - (c - P) . n  (penetration),  delta' = -c' . n
///     N = law(delta, delta') >= 0 (contact_law.hpp), zero for delta <= 0
///
/// Friction: the state vector keeps, from the last accepted step, the material point
/// of the sphere that was at the contact (offset b in the body frame, global position
/// m) and the elastic slip z. The trial slip is z_tr = P_t (z + p_b - m), P_t = I - n n^T,
/// with p_b the current position of that material point (a rolling sphere moves it by
/// O(h^3) per step: rolling is not resisted); detail::friction_state maps it to the
/// stick force -kt z_tr or the sliding force -mu N z_tr / |z_tr|. The force
/// F = N n + F_t acts at the contact point c - R n; flows: -F on x, y, z and
/// -(rho_c x F) on q1..q3 (rho_c = R(q) a - R n), none on q4. K and C (IGN=3).
template <class>
struct sphere_plane_contact_t {
  static constexpr pradis::passport passport{.name = "CSPHPL", .ext = 6, .ent = 1, .par = 19, .str = 10, .wrk = 4, .adr = 1, .ign = 3};
  /// q1..q3 are local DOFs 4..6 (0-based 3..5) with the hidden q4 at 6.
  static constexpr std::array<rotation_slot, 1> rotation_nodes{{{3, 6}}};
  static constexpr element_help help{
      .title = "contact of a body-fixed sphere with a fixed plane, Coulomb stick-slip friction",
      .name = "Sphere-plane contact: penalty, Hertz or Hunt-Crossley normal force and Coulomb friction [N]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of the body's reference point along X [m]\n"
              "2 - along Y [m]\n"
              "3 - along Z [m]\n"
              "4 - rotation potential q1 of the body's rotational node (flow: moment about X) [-]\n"
              "5 - q2 [-]\n"
              "6 - q3 [-]",
      .parameters = "1 - initial X of the body's reference point [m]\n"
                    "2 - initial Y [m]\n"
                    "3 - initial Z [m]\n"
                    "4 - x of the sphere centre from the reference point, body frame [m]\n"
                    "5 - y of the centre, body frame [m]\n"
                    "6 - z of the centre, body frame [m]\n"
                    "7 - sphere radius R [m] (> 0)\n"
                    "8 - X of a point P of the plane [m]\n"
                    "9 - Y of P [m]\n"
                    "10 - Z of P [m]\n"
                    "11 - X of the plane normal n, towards the sphere's side [-]\n"
                    "12 - Y of n [-]\n"
                    "13 - Z of n [-] (n must not be zero; it is normalised)\n"
                    "14 - normal law: 0 linear k delta + c delta', 1 Hertz k delta^1.5, 2 Hunt-Crossley "
                    "k delta^1.5 (1 + 1.5 c delta')\n"
                    "15 - contact stiffness k [N/m or N/m^1.5] (> 0)\n"
                    "16 - damping c [N s/m] (linear) or alpha [s/m] (Hunt-Crossley), unused by Hertz (>= 0)\n"
                    "17 - friction coefficient mu [-] (>= 0; 0: frictionless)\n"
                    "18 - tangential stick stiffness kt [N/m] (> 0 when mu > 0)\n"
                    "19 - mass for the step recommendation [kg] (>= 0; 0: no STEPMD)",
      .work = "1 - penetration delta [m] (negative: gap)\n"
              "2 - normal force N [N]\n"
              "3 - tangential (friction) force |F_t| [N]\n"
              "4 - stick flag: 1 sticking, 0 sliding or no contact",
      .special = "code 100 if R <= 0, the normal is zero, the law is not 0, 1 or 2, k <= 0, c < 0, mu < 0, kt < 0 "
                 "(or 0 with mu > 0), the mass < 0 or a parameter is not finite; code 75 if the penetration reaches "
                 "R (the centre at or behind the plane: tunnelling; the step is cut) or a quaternion norm comes "
                 "near zero. The state vector (STR = 10) holds the stick anchor and elastic slip of the last "
                 "accepted step. STEPMD with the mass: t_c / 20 in contact, entering within delta* / 10 "
                 "(docs/contact.md)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double x0 = 0, y0 = 0, z0 = 0;  ///< initial global position of the body's reference point [m]
    double ax = 0, ay = 0, az = 0;  ///< sphere centre in the body frame [m]
    double r = 0;                   ///< sphere radius [m]
    double px = 0, py = 0, pz = 0;  ///< a point of the plane [m]
    double nx = 0, ny = 0, nz = 1;  ///< plane normal towards the sphere [-]
    double law = 0;                 ///< 0 linear, 1 Hertz, 2 Hunt-Crossley
    double k = 0;                   ///< contact stiffness
    double c = 0;                   ///< damping (linear) or alpha (Hunt-Crossley)
    double mu = 0;                  ///< friction coefficient
    double kt = 0;                  ///< tangential stick stiffness [N/m]
    double mass = 0;                ///< mass for STEPMD [kg] (0: none)
  };
  parameters p;

  explicit sphere_plane_contact_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test): a ball of
  /// radius 2 whose centre sits 0.3 off the reference point, a tilted plane through the
  /// origin; the states of the check penetrate by up to ~1.
  static parameters example() {
    return {0.1, -0.2, 1.9, 0.2, 0.1, 0.3, 2.0, 0.0, 0.0, 0.0, 0.1, -0.2, 1.0, 2, 4e3, 0.05, 0.4, 1e4, 2.0};
  }
  static sphere_plane_contact from_parameters(std::span<const double> v) {
    return sphere_plane_contact({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12],
                                 v[13], v[14], v[15], v[16], v[17], v[18]});
  }
  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): a vertex at the sphere's centre
  /// and the body's arm to it.
  template <class Drawer>
  void draw(Drawer& d) const {
    const spatial::vec3 x0{p.x0, p.y0, p.z0};
    const int c = d.body_point(x0, 0, 0, {p.ax, p.ay, p.az});
    d.vertex(c);
    d.line(d.body_point(x0, 0, 0, spatial::vec3::Zero()), c);
  }
  void new_integration(element_context& ctx) const {
    for (double x : {p.x0, p.y0, p.z0, p.ax, p.ay, p.az, p.px, p.py, p.pz, p.nx, p.ny, p.nz})
      if (!std::isfinite(x)) ctx.invalid_parameter("positions, offsets and the plane normal must be finite");
    if (!(p.r > 0) || !std::isfinite(p.r)) ctx.invalid_parameter("sphere radius R = " + to_text(p.r) + " must be finite and > 0");
    if (!(normal().norm() > 0)) ctx.invalid_parameter("the plane normal n is zero");
    detail::check_contact_parameters(ctx, p.law, p.k, p.c, p.mu, p.kt, p.mass);
  }
  void evaluate(const local_input<sphere_plane_contact>& in, local_output<sphere_plane_contact>& out,
                element_context& ctx) const {
    using namespace spatial;
    const quaternion q = detail::slot_quaternion(in.u, 3, 6), qd = detail::slot_quaternion(in.v, 3, 6);
    if (!(q.norm() > lq_near_zero)) ctx.singular("Lq near zero: the quaternion norm |q| of the rotational node has vanished");
    const vec3 n = normal().normalized(), x0(p.x0, p.y0, p.z0), a(p.ax, p.ay, p.az), pl(p.px, p.py, p.pz);
    const vec3 x = in.u.head<3>(), xd = in.v.head<3>();
    const detail::attached_point c(x0, a, x, xd, q, qd);
    const double delta = p.r - (c.p - pl).dot(n), rate = -c.v.dot(n);
    if (!(delta < p.r))
      ctx.singular("tunnelling: the penetration delta = " + to_text(delta) + " has reached the radius R = " +
                   to_text(p.r) + " (the sphere centre is at or behind the plane)");
    const auto law = static_cast<detail::contact_law>(static_cast<int>(p.law));
    ctx.recommend_step(detail::contact_step(law, p.k, p.mass, delta, rate));
    const detail::normal_force nf = detail::contact_normal(law, p.k, p.c, delta, rate);
    // Friction: trial elastic slip from the anchor of the last accepted step (if any).
    const bool anchored = ctx.old_state.size() == 10 && ctx.old_state[0] > 0;
    const bool friction = p.mu > 0 && delta > 0 && anchored;
    const auto& os = ctx.old_state;
    const vec3 b_old = anchored ? vec3(os[4], os[5], os[6]) : vec3::Zero();
    const detail::attached_point pb(x0, b_old, x, xd, q, qd);
    const mat3 pt = mat3::Identity() - n * n.transpose();
    vec3 ztr = vec3::Zero();
    if (friction) {
      const vec3 z_old = os[0] > 1.5 ? vec3(os[1], os[2], os[3]) : vec3::Zero();
      ztr = pt * (z_old + pb.p - vec3(os[7], os[8], os[9]));
    }
    const detail::friction_state fr(ztr, friction ? p.mu : 0.0, friction ? p.kt : 1.0, nf.n);
    const vec3 f = nf.n * n + fr.force;
    const vec3 rc = c.rho - p.r * n;
    out.f.setZero();
    out.f.head<3>() = -f;
    out.f.segment<3>(3) = -rc.cross(f);
    // Outputs and the state for the next step: anchor at the current contact point.
    ctx.work[0] = delta;
    ctx.work[1] = nf.n;
    ctx.work[2] = fr.force.norm();
    ctx.work[3] = (delta > 0 && fr.stick) ? 1.0 : 0.0;
    if (ctx.new_state.size() == 10) {
      const vec3 b = a - p.r * rotation_matrix(q).transpose() * n, m = c.p - p.r * n;
      const double st[10] = {delta > 0 ? 2.0 : 1.0, fr.z_new(0), fr.z_new(1), fr.z_new(2), b(0), b(1), b(2),
                             m(0), m(1), m(2)};
      for (std::size_t i = 0; i < 10; ++i) ctx.new_state[i] = delta > 0 || i == 0 || i > 3 ? st[i] : 0.0;
    }
    if (!out.want_jacobian) return;
    // dF/du and dF/dv over the columns x (0..2), q1..q4 (3..6).
    using row7 = Eigen::Matrix<double, 1, 7>;
    using mat37 = Eigen::Matrix<double, 3, 7>;
    row7 dn_du = row7::Zero(), dn_dv = row7::Zero();
    dn_du.head<3>() = -nf.dn_dd * n.transpose();
    dn_du.tail<4>() = -nf.dn_dd * n.transpose() * c.dp_dq - nf.dn_dr * n.transpose() * c.dv_dq;
    dn_dv.head<3>() = -nf.dn_dr * n.transpose();
    dn_dv.tail<4>() = -nf.dn_dr * n.transpose() * c.dp_dq;
    mat37 ku = n * dn_du, cv = n * dn_dv;
    if (friction) {
      mat37 dz = mat37::Zero();
      dz.leftCols<3>() = pt;
      dz.rightCols<4>() = pt * pb.dp_dq;
      ku += fr.dforce_dz * dz + fr.dforce_dn * dn_du;
      cv += fr.dforce_dn * dn_dv;
    }
    out.K.setZero();
    out.C.setZero();
    const mat3 rx = skew(rc);
    out.K.topLeftCorner<3, 7>() = -ku;
    out.K.block<3, 7>(3, 0) = -rx * ku;
    out.K.block<3, 4>(3, 3) += skew(f) * c.dp_dq;
    out.C.topLeftCorner<3, 7>() = -cv;
    out.C.block<3, 7>(3, 0) = -rx * cv;
  }
  /// States the checks may use: the quaternion far from zero, the penetration away
  /// from 0 and R, the normal force away from its clipping at zero.
  bool admissible(const local_input<sphere_plane_contact>& in) const {
    using namespace spatial;
    const quaternion q = detail::slot_quaternion(in.u, 3, 6), qd = detail::slot_quaternion(in.v, 3, 6);
    if (!(q.norm() > 0.2)) return false;
    const detail::attached_point c(vec3(p.x0, p.y0, p.z0), vec3(p.ax, p.ay, p.az), in.u.head<3>(), in.v.head<3>(), q, qd);
    const vec3 n = normal().normalized();
    const double delta = p.r - (c.p - vec3(p.px, p.py, p.pz)).dot(n), rate = -c.v.dot(n);
    if (!(delta < 0.9 * p.r) || std::abs(delta) < 1e-3 * p.r) return false;
    if (delta < 0 || p.law == 1) return true;
    const double damp = p.law == 0 ? p.k * delta + p.c * rate : 1.0 + 1.5 * p.c * rate;
    return std::abs(damp) > (p.law == 0 ? 0.05 * p.k * delta : 0.05);
  }

 private:
  spatial::vec3 normal() const { return {p.nx, p.ny, p.nz}; }
};

template <class = void>
struct sphere_sphere_contact_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using sphere_sphere_contact = sphere_sphere_contact_t<>;
/// CSPHSP: two spheres of radii R1 and R2 whose centres are attached to two bodies
/// (offsets a1, a2 in the body frames from reference points initially at X1, X2;
/// either body may be the ground). With the centres c1, c2, L = |c2 - c1|, e = (c2 - c1) / L:
///
///     delta = R1 + R2 - L,  delta' = -L' = -e . (c2' - c1')
///     N = law(delta, delta') >= 0 (contact_law.hpp), zero for delta <= 0
///
/// N pushes the centres apart along e: the flows are those of SD3 with the tension
/// T = -N (detail::two_point_flows), none on the q4. Friction (mu > 0) as CSPHPL's,
/// in the tangent plane of e, which turns with the line of centres: the state keeps
/// the material points of both spheres at the last accepted contact point
/// m = c1 + (R1 - delta/2) e and the elastic slip z; the trial slip is
/// z_tr = P (z + p_b2 - p_b1), P = I - e e^T, and the tangential force acts at m
/// (detail::sphere_pair_friction). K and C (IGN=3).
template <class>
struct sphere_sphere_contact_t {
  static constexpr pradis::passport passport{.name = "CSPHSP", .ext = 12, .ent = 2, .par = 20, .str = 10, .wrk = 4, .adr = 1, .ign = 3};
  /// Body 1's q1..q3 are local DOFs 4..6 (0-based 3..5) with hidden q4 at 12; body 2's 10..12 (9..11) with q4 at 13.
  static constexpr std::array<rotation_slot, 2> rotation_nodes{{{3, 12}, {9, 13}}};
  static constexpr element_help help{
      .title = "contact of two body-fixed spheres in spatial motion, Coulomb stick-slip friction",
      .name = "Sphere-sphere contact: penalty, Hertz or Hunt-Crossley normal force and Coulomb friction [N]",
      .field = "mechanics, spatial motion",
      .dofs = "1 - translation of body 1's reference point along X [m]\n"
              "2 - along Y [m]\n"
              "3 - along Z [m]\n"
              "4 - rotation potential q1 of body 1's rotational node (flow: moment about X) [-]\n"
              "5 - q2 of body 1 [-]\n"
              "6 - q3 of body 1 [-]\n"
              "7 - translation of body 2's reference point along X [m]\n"
              "8 - along Y [m]\n"
              "9 - along Z [m]\n"
              "10 - rotation potential q1 of body 2's rotational node [-]\n"
              "11 - q2 of body 2 [-]\n"
              "12 - q3 of body 2 [-] (connect DOFs 1-6 or 7-12 to the ground for a fixed sphere)",
      .parameters = "1 - initial X of body 1's reference point [m]\n"
                    "2 - initial Y [m]\n"
                    "3 - initial Z [m]\n"
                    "4 - x of sphere 1's centre from the reference point, body 1 frame [m]\n"
                    "5 - y, body 1 frame [m]\n"
                    "6 - z, body 1 frame [m]\n"
                    "7 - radius R1 [m] (> 0)\n"
                    "8 - initial X of body 2's reference point [m]\n"
                    "9 - initial Y [m]\n"
                    "10 - initial Z [m]\n"
                    "11 - x of sphere 2's centre from the reference point, body 2 frame [m]\n"
                    "12 - y, body 2 frame [m]\n"
                    "13 - z, body 2 frame [m]\n"
                    "14 - radius R2 [m] (> 0)\n"
                    "15 - normal law: 0 linear k delta + c delta', 1 Hertz k delta^1.5, 2 Hunt-Crossley "
                    "k delta^1.5 (1 + 1.5 c delta')\n"
                    "16 - contact stiffness k [N/m or N/m^1.5] (> 0)\n"
                    "17 - damping c [N s/m] (linear) or alpha [s/m] (Hunt-Crossley), unused by Hertz (>= 0)\n"
                    "18 - effective mass m1 m2 / (m1 + m2) for the step recommendation [kg] (>= 0; 0: no STEPMD)\n"
                    "19 - friction coefficient mu [-] (>= 0; 0: frictionless)\n"
                    "20 - tangential stick stiffness kt [N/m] (> 0 when mu > 0)",
      .work = "1 - penetration delta = R1 + R2 - L [m] (negative: gap)\n2 - normal force N [N]\n"
              "3 - tangential (friction) force |F_t| [N]\n4 - stick flag: 1 sticking, 0 sliding or no contact",
      .special = "code 100 if R1 <= 0, R2 <= 0, the law is not 0, 1 or 2, k <= 0, c < 0, the mass < 0, mu < 0, "
                 "kt <= 0 with mu > 0 or a parameter is not finite; code 75 if the penetration reaches the smaller radius (tunnelling; the "
                 "step is cut) or a quaternion norm comes near zero. STEPMD as CSPHPL (docs/contact.md)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double x1 = 0, y1 = 0, z1 = 0;  ///< initial global position of body 1's reference point [m]
    double a1x = 0, a1y = 0, a1z = 0;  ///< sphere 1's centre in body 1's frame [m]
    double r1 = 0;                  ///< radius of sphere 1 [m]
    double x2 = 0, y2 = 0, z2 = 0;  ///< initial global position of body 2's reference point [m]
    double a2x = 0, a2y = 0, a2z = 0;  ///< sphere 2's centre in body 2's frame [m]
    double r2 = 0;                  ///< radius of sphere 2 [m]
    double law = 0;                 ///< 0 linear, 1 Hertz, 2 Hunt-Crossley
    double k = 0;                   ///< contact stiffness
    double c = 0;                   ///< damping (linear) or alpha (Hunt-Crossley)
    double mass = 0;                ///< effective mass for STEPMD [kg] (0: none)
    double mu = 0;                  ///< friction coefficient
    double kt = 0;                  ///< tangential stick stiffness [N/m]
  };
  parameters p;

  explicit sphere_sphere_contact_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {0.1, -0.2, 0.3, 0.2, 0.1, -0.15, 1.5, 1.2, 0.4, 2.3, -0.1, 0.25, 0.2, 1.5, 2, 4e3, 0.05, 1.0, 0.4, 1e4};
  }
  static sphere_sphere_contact from_parameters(std::span<const double> v) {
    return sphere_sphere_contact({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12],
                                  v[13], v[14], v[15], v[16], v[17], v[18], v[19]});
  }
  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): vertices at the two centres and
  /// the bodies' arms to them.
  template <class Drawer>
  void draw(Drawer& d) const {
    const spatial::vec3 x1{p.x1, p.y1, p.z1}, x2{p.x2, p.y2, p.z2};
    const int c1 = d.body_point(x1, 0, 0, {p.a1x, p.a1y, p.a1z}), c2 = d.body_point(x2, 6, 1, {p.a2x, p.a2y, p.a2z});
    d.vertex(c1);
    d.vertex(c2);
    d.line(d.body_point(x1, 0, 0, spatial::vec3::Zero()), c1);
    d.line(d.body_point(x2, 6, 1, spatial::vec3::Zero()), c2);
  }
  void new_integration(element_context& ctx) const {
    for (double x : {p.x1, p.y1, p.z1, p.a1x, p.a1y, p.a1z, p.x2, p.y2, p.z2, p.a2x, p.a2y, p.a2z})
      if (!std::isfinite(x)) ctx.invalid_parameter("positions and offsets must be finite");
    if (!(p.r1 > 0) || !std::isfinite(p.r1)) ctx.invalid_parameter("radius R1 = " + to_text(p.r1) + " must be finite and > 0");
    if (!(p.r2 > 0) || !std::isfinite(p.r2)) ctx.invalid_parameter("radius R2 = " + to_text(p.r2) + " must be finite and > 0");
    detail::check_contact_parameters(ctx, p.law, p.k, p.c, p.mu, p.kt, p.mass);
  }
  void evaluate(const local_input<sphere_sphere_contact>& in, local_output<sphere_sphere_contact>& out,
                element_context& ctx) const {
    using namespace spatial;
    if (!detail::two_quaternions_admissible_strict(in))
      ctx.singular("Lq near zero: the quaternion norm |q| of a rotational node has vanished");
    const auto [a, b] = centres(in);
    const vec3 d = b.p - a.p, dd = b.v - a.v;
    const double l = d.norm(), delta = p.r1 + p.r2 - l;
    if (!(delta < std::min(p.r1, p.r2)))
      ctx.singular("tunnelling: the penetration delta = " + to_text(delta) + " has reached the smaller radius " +
                   to_text(std::min(p.r1, p.r2)));
    const vec3 e = d / l;
    const double ld = e.dot(dd);
    const auto law = static_cast<detail::contact_law>(static_cast<int>(p.law));
    ctx.recommend_step(detail::contact_step(law, p.k, p.mass, delta, -ld));
    const detail::normal_force nf = detail::contact_normal(law, p.k, p.c, delta, -ld);
    ctx.work[0] = delta;
    ctx.work[1] = nf.n;
    // As SD3 with T = -N(delta, delta'): dT/dL = N_delta, dT/dL' = N_delta'.
    const double t = -nf.n;
    const mat3 pe = mat3::Identity() - e * e.transpose();
    const vec3 dld_dd = (dd - e * ld) / l;
    const mat3 fd = e * (nf.dn_dd * e + nf.dn_dr * dld_dd).transpose() + (t / l) * pe;
    const mat3 fdd = nf.dn_dr * e * e.transpose();
    detail::two_point_flows(a, b, vec3(t * e), fd, fdd, out);
    friction(in, out, ctx, a, b, delta, nf, e, dd);
  }
  /// States the checks may use: quaternions far from zero, the penetration away from 0
  /// and the radii, the normal force away from its clipping at zero (and, with an
  /// anchor in the state, the friction away from its stick/slip boundary).
  bool admissible(const local_input<sphere_sphere_contact>& in) const {
    if (!detail::two_quaternions_admissible(in)) return false;
    const auto [a, b] = centres(in);
    const double l = (b.p - a.p).norm(), delta = p.r1 + p.r2 - l, rate = -(b.p - a.p).dot(b.v - a.v) / l;
    if (!(delta < 0.9 * std::min(p.r1, p.r2)) || std::abs(delta) < 1e-3) return false;
    if (delta < 0 || p.law == 1) return true;
    const double damp = p.law == 0 ? p.k * delta + p.c * rate : 1.0 + 1.5 * p.c * rate;
    return std::abs(damp) > (p.law == 0 ? 0.05 * p.k * delta : 0.05);
  }

 private:
  /// Friction (mu > 0, in contact, with an anchor from the last accepted step), and
  /// the state for the next step: the contact point's material points and the slip.
  template <class In, class Out>
  void friction(const In& in, Out& out, element_context& ctx, const detail::attached_point& a,
                const detail::attached_point& b, double delta, const detail::normal_force& nf, const spatial::vec3& e,
                const spatial::vec3& dd) const {
    using namespace spatial;
    const auto& os = ctx.old_state;
    const bool anchored = os.size() == 10 && os[0] > 0;
    const bool on = p.mu > 0 && delta > 0 && anchored;
    const quaternion q1 = detail::slot_quaternion(in.u, 3, 12), q2 = detail::slot_quaternion(in.u, 9, 13);
    const quaternion q1d = detail::slot_quaternion(in.v, 3, 12), q2d = detail::slot_quaternion(in.v, 9, 13);
    const vec3 x10(p.x1, p.y1, p.z1), x20(p.x2, p.y2, p.z2);
    const vec3 b1 = anchored ? vec3(os[4], os[5], os[6]) : vec3::Zero(), b2 = anchored ? vec3(os[7], os[8], os[9]) : vec3::Zero();
    const detail::attached_point pb1(x10, b1, in.u.template segment<3>(0), in.v.template segment<3>(0), q1, q1d);
    const detail::attached_point pb2(x20, b2, in.u.template segment<3>(6), in.v.template segment<3>(6), q2, q2d);
    const vec3 z_old = on && os[0] > 1.5 ? vec3(os[1], os[2], os[3]) : vec3::Zero();
    // dN/du and dN/dv over the 14 local columns.
    const detail::mat3x14 dc = detail::point_columns(1, b.dp_dq) - detail::point_columns(0, a.dp_dq);
    const detail::mat3x14 dcv = detail::rotation_columns(1, b.dv_dq) - detail::rotation_columns(0, a.dv_dq);
    const double l = (b.p - a.p).norm();
    const detail::mat3x14 de = (Eigen::Matrix3d::Identity() - e * e.transpose()) * dc / l;
    const detail::row14 ddelta = -e.transpose() * dc;
    const detail::row14 drate_du = -(dd.transpose() * de + e.transpose() * dcv);
    const detail::row14 dn_du = nf.dn_dd * ddelta + nf.dn_dr * drate_du, dn_dv = nf.dn_dr * ddelta;
    const detail::sphere_pair_friction fr(a, b, p.r1, delta, nf.n, dn_du, dn_dv, pb1, pb2, z_old, on ? p.mu : 0.0,
                                          on ? p.kt : 1.0, out);
    ctx.work[2] = fr.force.norm();
    ctx.work[3] = (delta > 0 && fr.stick) ? 1.0 : 0.0;
    if (ctx.new_state.size() == 10) {
      const vec3 n1 = rotation_matrix(q1).transpose() * (fr.point - (a.p - a.rho));
      const vec3 n2 = rotation_matrix(q2).transpose() * (fr.point - (b.p - b.rho));
      const bool c = delta > 0;
      const double st[10] = {c ? 2.0 : 1.0, c ? fr.z_new(0) : 0.0, c ? fr.z_new(1) : 0.0, c ? fr.z_new(2) : 0.0,
                             n1(0), n1(1), n1(2), n2(0), n2(1), n2(2)};
      for (std::size_t i = 0; i < 10; ++i) ctx.new_state[i] = st[i];
    }
  }
  template <class In>
  std::pair<detail::attached_point, detail::attached_point> centres(const In& in) const {
    using spatial::vec3;
    return detail::two_points(in, vec3(p.x1, p.y1, p.z1), vec3(p.a1x, p.a1y, p.a1z), vec3(p.x2, p.y2, p.z2),
                              vec3(p.a2x, p.a2y, p.a2z));
  }
};

}  // namespace pradis::elements
