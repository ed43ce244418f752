#pragma once
/// \file
/// ELLPL: contact of an ellipse in plane motion with a fixed polyline, with a
/// state per contact point (contact, stick or slip and the stick anchor) for
/// Coulomb friction that holds without creep.

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/planar/ellipse_contact_geometry.hpp"

namespace pradis::elements {

template <class = void>
struct ellipse_contact_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using ellipse_contact = ellipse_contact_t<>;
/// ELLPL: an ellipse carried by a planar body (DOFs dx, dy, dphi of its centre,
/// as MD's) against a fixed polyline (x1, y1), (x2, y2), ... Each segment is a
/// contact point with its own state (STP): the ellipse may touch several
/// segments at once. A segment acts on its left side (the left normal
/// n = (-t_y, t_x) of its direction t points towards the ellipse) and only while
/// the ellipse's deepest point lies within its length.
///
/// Normal force (Hunt-Crossley form, never pulling):
///
///     N = max(0, k delta^e (1 + d delta'))      delta: penetration [m]
///
/// e = 1 is a linear penalty spring with damping k d delta', e = 1.5 Hertz
/// (d = 0) or Hunt-Crossley (d = 3 alpha / 2).
///
/// Friction, per contact point, from the state of the last accepted step:
/// - stick: a tangential spring-damper k_t e + c_t e' holds the material point of the ellipse
///   that touched (its body-axes position and the anchor along the segment are in
///   the state). After every accepted step the anchor moves to the new deepest
///   point keeping the spring's stretch, so a rolling ellipse sticks too. The
///   contact slips when |k_t e + c_t e'| exceeds mu_s N;
/// - slip: the force mu_k N against the direction of sliding s of the last
///   step; the contact sticks again when the slip velocity stops or reverses.
/// A new contact slips if its tangential velocity is not zero. Flows stay
/// smooth within a step (the mode only changes between steps); the switch is
/// at most one step late.
template <class>
struct ellipse_contact_t {
  static constexpr pradis::passport passport{.name = "ELLPL", .ext = 3, .par = 16, .vpr = 21, .str = 4, .stp = 2,
                                             .wrk = 8, .wrp = 2, .adr = 1, .ign = 3};
  static constexpr std::array<pradis::domain, 3> domains{pradis::domain::mechanical, pradis::domain::mechanical,
                                                         pradis::domain::mechanical};
  static constexpr element_help help{
      .title = "contact of an ellipse in plane motion with a fixed polyline, with friction",
      .name = "Ellipse on a planar body against a polyline: Hunt-Crossley normal force, Coulomb friction with a "
              "stick state per contact point",
      .field = "mechanics",
      .dofs = "1 - translation of the ellipse's centre along X [m]\n"
              "2 - translation of the ellipse's centre along Y [m]\n"
              "3 - rotation about Z [rad]",
      .parameters = "1 - initial abscissa X0 of the centre [m]\n2 - initial ordinate Y0 of the centre [m]\n"
                    "3 - initial angle of the ellipse's a axis to X [rad]\n"
                    "4 - semi-axis a [m] (> 0)\n5 - semi-axis b [m] (> 0)\n"
                    "6 - contact stiffness k [N/m^e] (> 0)\n7 - exponent e (>= 1; 1 linear, 1.5 Hertz)\n"
                    "8 - damping factor d [s/m] (>= 0; Hunt-Crossley d = 3 alpha / 2)\n"
                    "9 - static friction coefficient mu_s (>= 0)\n"
                    "10 - kinetic friction coefficient mu_k (0 <= mu_k <= mu_s)\n"
                    "11 - stick stiffness k_t [N/m] (> 0 if mu_s > 0)\n"
                    "12 - stick damping c_t [N s/m] (>= 0; about 2 sqrt(k_t m) holds a load without ringing)\n"
                    "13, 14 - first polyline point x1, y1 [m]\n15, 16 - second point x2, y2 [m]\n"
                    "(more points may follow: an even count, at least 16)",
      .work = "1 - contact force on the body along X [N]\n2 - contact force on the body along Y [N]\n"
              "3 - its moment about the centre [N m]\n4 - number of segments in contact\n"
              "5 - segment 1: penetration [m] (negative: gap)\n6 - segment 1: normal force N [N]\n"
              "7 - segment 1: tangential force along the segment [N]\n"
              "8 - segment 1: mode of the last accepted step (0 free, 1 stick, 2 slip forward, 3 slip backward); "
              "4 more entries for each further segment",
      .special = "code 100 if a value is not finite, a or b <= 0, k <= 0, e < 1, d < 0, mu_s < 0, mu_k < 0, "
                 "mu_k > mu_s, k_t <= 0 with mu_s > 0, or two successive polyline points coincide; code 101 for "
                 "an odd count; code 75 if the ellipse's centre passes behind a segment, within its length, that "
                 "it was in front of at the last step (it went through within one step; the integrator cuts the "
                 "step). STEPMD: while the ellipse approaches a segment at "
                 "closing speed v the step is limited to max(gap / 2, r) / v, r = min(a, b)/1000, so that the contact "
                 "is not stepped over, and while the penetration grows to max(penetration, r) / v. A corner of "
                 "the polyline that is convex towards the ellipse is not a contact "
                 "point of its own: round it with short segments. State: 4 entries per segment"};
  /// The parameters, in PAR order.
  struct parameters {
    double x0 = 0, y0 = 0, angle = 0;  ///< initial centre [m] and angle of the a axis [rad]
    double a = 1, b = 1;               ///< semi-axes [m]
    double k = 0;                      ///< contact stiffness [N/m^e]
    double exponent = 1;               ///< e
    double damping = 0;                ///< d [s/m]
    double mu_s = 0, mu_k = 0;         ///< friction coefficients
    double k_t = 0;                    ///< stick stiffness [N/m]
    double c_t = 0;                    ///< stick damping [N s/m]
    std::vector<double> polyline{};    ///< x1, y1, x2, y2, ... [m]
  };
  /// Stores the parameters and the segments (allocates here, never in evaluate).
  explicit ellipse_contact_t(parameters q) : p(std::move(q)) {
    for (std::size_t i = 0; i + 3 < p.polyline.size(); i += 2)
      seg_.push_back(detail::contact_segment::between(p.polyline[i], p.polyline[i + 1], p.polyline[i + 2],
                                                      p.polyline[i + 3]));
  }
  /// Example parameters: an ellipse pressed about 1 cm into a floor of two segments, with friction.
  static parameters example() {
    return {0.3, 0.16, 0.2, 0.4, 0.2, 1e5, 1.5, 0.2, 0.5, 0.4, 1e4, 50.0, {-1.0, 0.0, 0.5, -0.05, 1.5, 0.1}};
  }
  static ellipse_contact from_parameters(std::span<const double> v) {
    return ellipse_contact({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11],
                            std::vector<double>(v.begin() + 12, v.end())});
  }
  const parameters& params() const noexcept { return p; }
  /// The flat parameter count (12 + the polyline's coordinates): model::add sizes
  /// the per-segment state and work vectors (STP, WRP) from it.
  int parameter_count() const noexcept { return 12 + static_cast<int>(p.polyline.size()); }
  /// Number of segments (contact points).
  int segments() const noexcept { return static_cast<int>(seg_.size()); }

  /// Modes of a contact point, stored in its first state entry.
  enum mode : int { free = 0, stick = 1, slip_forward = 2, slip_backward = 3 };

  /// Finite-difference checks stay away from the kinks: the contact's edges
  /// (zero penetration, segment ends), the clamp of N and the stick/slip switch.
  bool admissible(const local_input<ellipse_contact>& in) const {
    const double cx = p.x0 + in.u(0), cy = p.y0 + in.u(1), phi = p.angle + in.u(2);
    for (const auto& g : seg_) {
      const auto e = detail::ellipse_support::at(cx, cy, phi, p.a, p.b, g);
      if (std::abs(e.delta) < 1e-4 || std::abs(e.along) < 1e-3 || std::abs(e.along - g.length) < 1e-3) return false;
      const double rate = -(g.nx * in.v(0) + g.ny * in.v(1)) + e.dw * in.v(2);
      if (e.delta > 0 && std::abs(1 + p.damping * rate) < 1e-3) return false;
    }
    return true;
  }

  void new_integration(element_context& ctx) const {
    const std::array<double, 12> all{p.x0,      p.y0, p.angle, p.a,   p.b,   p.k, p.exponent,
                                     p.damping, p.mu_s, p.mu_k, p.k_t, p.c_t};
    for (std::size_t i = 0; i < all.size(); ++i)
      if (!std::isfinite(all[i])) ctx.invalid_parameter("parameter " + std::to_string(i + 1) + " is not finite");
    for (std::size_t i = 0; i < p.polyline.size(); ++i)
      if (!std::isfinite(p.polyline[i]))
        ctx.invalid_parameter("polyline coordinate " + std::to_string(i + 1) + " is not finite");
    if (p.polyline.size() % 2 != 0 || p.polyline.size() < 4)
      ctx.invalid_parameter("the polyline needs pairs of coordinates, at least 2 points; got " +
                            std::to_string(p.polyline.size()) + " coordinates");
    if (!(p.a > 0) || !(p.b > 0))
      ctx.invalid_parameter("semi-axes a = " + to_text(p.a) + ", b = " + to_text(p.b) + " must be > 0");
    if (!(p.k > 0)) ctx.invalid_parameter("contact stiffness k = " + to_text(p.k) + " must be > 0");
    if (!(p.exponent >= 1)) ctx.invalid_parameter("exponent e = " + to_text(p.exponent) + " must be >= 1");
    if (!(p.damping >= 0)) ctx.invalid_parameter("damping factor d = " + to_text(p.damping) + " must be >= 0");
    if (!(p.mu_s >= 0))
      ctx.invalid_parameter("static friction coefficient mu_s = " + to_text(p.mu_s) + " must be >= 0");
    if (!(p.mu_k >= 0) || p.mu_k > p.mu_s)
      ctx.invalid_parameter("kinetic friction coefficient mu_k = " + to_text(p.mu_k) + " must be >= 0 and <= mu_s = " +
                            to_text(p.mu_s));
    if (!(p.c_t >= 0)) ctx.invalid_parameter("stick damping c_t = " + to_text(p.c_t) + " must be >= 0");
    if (p.mu_s > 0 && !(p.k_t > 0))
      ctx.invalid_parameter("stick stiffness k_t = " + to_text(p.k_t) + " must be > 0 when mu_s > 0");
    for (std::size_t i = 0; i < seg_.size(); ++i)
      if (!(seg_[i].length > 0))
        ctx.invalid_parameter("polyline points " + std::to_string(i + 1) + " and " + std::to_string(i + 2) +
                              " coincide");
  }

  void evaluate(const local_input<ellipse_contact>& in, local_output<ellipse_contact>& out,
                element_context& ctx) const {
    using vec3 = Eigen::Vector3d;
    const double cx = p.x0 + in.u(0), cy = p.y0 + in.u(1), phi = p.angle + in.u(2);
    const bool have_state = ctx.old_state.size() >= 4 * seg_.size() && ctx.new_state.size() >= 4 * seg_.size();
    const bool have_work = ctx.work.size() >= 4 + 4 * seg_.size();
    const double resolution = 1e-3 * std::min(p.a, p.b);
    double fx = 0, fy = 0, mz = 0;
    int active = 0;
    for (std::size_t i = 0; i < seg_.size(); ++i) {
      const auto& g = seg_[i];
      const auto e = detail::ellipse_support::at(cx, cy, phi, p.a, p.b, g);
      const double* old = have_state ? &ctx.old_state[4 * i] : nullptr;
      const int old_mode = old ? static_cast<int>(old[0]) : free;
      const vec3 ddelta(-g.nx, -g.ny, e.dw);               // d delta / dq
      const double rate = ddelta.dot(in.v);                 // delta'
      const vec3 jt(g.tx, g.ty, e.w);                       // tangential velocity: jt . q'
      const bool within = e.along >= 0 && e.along <= g.length;
      // Tunnelling: the centre was in front of the segment at the last accepted
      // step (in contact, or free with a recorded positive distance) and is now
      // behind it, within its length.
      const double centre = (cx - g.px) * g.nx + (cy - g.py) * g.ny;
      const double centre_along = (cx - g.px) * g.tx + (cy - g.py) * g.ty;
      const bool was_front = old && (old_mode != free || (old[2] == 1 && old[1] > 0));
      if (was_front && centre < 0 && centre_along >= 0 && centre_along <= g.length)
        ctx.singular("the ellipse's centre passed behind polyline segment " + std::to_string(i + 1) +
                     " (penetration " + to_text(e.delta) + " m): it went through within one step");
      const bool touching = within && e.delta > 0 && centre >= 0;
      // STEPMD: approach halves the gap per step down to the resolution; in contact
      // the penetration at most doubles per step while it grows.
      if (within && rate > 0) ctx.recommend_step(std::max(e.delta < 0 ? -0.5 * e.delta : e.delta, resolution) / rate);
      double n_force = 0, t_force = 0;
      int new_mode = free;
      double nsx = centre, nsy = 1, nanchor = 0;  // free: the centre's distance, marked as recorded
      if (touching) {
        ++active;
        // Normal force N = k delta^e (1 + d delta') and its derivatives.
        const double de = std::pow(e.delta, p.exponent), ddedelta = p.exponent * de / e.delta;
        const double hc = 1 + p.damping * rate;
        vec3 dn_du = vec3::Zero(), dn_dv = vec3::Zero();
        if (hc > 0) {
          n_force = p.k * de * hc;
          dn_du = p.k * ddedelta * hc * ddelta;
          dn_du(2) += p.k * de * p.damping * e.ddw * in.v(2);  // d delta'/dphi = w'' phi'
          dn_dv = p.k * de * p.damping * ddelta;
        }
        out.f += n_force * ddelta;
        if (out.want_jacobian) {
          out.K += ddelta * dn_du.transpose();
          out.K(2, 2) += n_force * e.ddw;
          out.C += ddelta * dn_dv.transpose();
        }
        const double vt = jt.dot(in.v);
        const double along_deep = e.along;
        new_mode = (vt > 0) ? slip_forward : (vt < 0 ? slip_backward : stick);
        nsx = e.sx;
        nsy = e.sy;
        nanchor = along_deep;
        if (old_mode == stick && p.mu_s > 0) {
          // Tangential spring at the stuck material point xi: e = (c + R xi - P).t - anchor.
          const double cp = std::cos(phi), sp = std::sin(phi);
          const double rx = cp * old[1] - sp * old[2], ry = sp * old[1] + cp * old[2];
          const double stretch = (cx + rx - g.px) * g.tx + (cy + ry - g.py) * g.ty - old[3];
          const vec3 dstretch(g.tx, g.ty, rx * g.ty - ry * g.tx);
          const double rate_t = dstretch.dot(in.v);  // the material point's tangential velocity
          const double spring = p.k_t * stretch + p.c_t * rate_t;
          t_force = -spring;
          out.f += spring * dstretch;
          if (out.want_jacobian) {
            out.K += dstretch * (p.k_t * dstretch).transpose();
            // d(rate_t)/dphi = (R'' xi).t phi' = -(rho.t) phi'; d^2 stretch/dphi^2 = -(rho.t)
            const double rho_t = rx * g.tx + ry * g.ty;
            out.K(2, 2) -= spring * rho_t;
            out.K.col(2) -= p.c_t * rho_t * in.v(2) * dstretch;
            out.C += p.c_t * dstretch * dstretch.transpose();
          }
          if (std::abs(spring) > p.mu_s * n_force) {
            new_mode = stretch > 0 ? slip_forward : slip_backward;
          } else {
            new_mode = stick;  // re-anchor at the new deepest point, keeping the stretch
            nanchor = along_deep - stretch;
          }
        } else if ((old_mode == slip_forward || old_mode == slip_backward) && p.mu_s > 0) {
          const double s = old_mode == slip_forward ? 1.0 : -1.0;
          t_force = -p.mu_k * n_force * s;
          out.f += p.mu_k * s * n_force * jt;
          if (out.want_jacobian) {
            out.K += p.mu_k * s * jt * dn_du.transpose();
            out.K(2, 2) += p.mu_k * s * n_force * e.dw;
            out.C += p.mu_k * s * jt * dn_dv.transpose();
          }
          new_mode = (vt * s > 0) ? old_mode : stick;
        }
        if (p.mu_s == 0) new_mode = stick;  // no friction: the mode only records contact
      }
      if (have_state) {
        ctx.new_state[4 * i] = new_mode;
        ctx.new_state[4 * i + 1] = nsx;
        ctx.new_state[4 * i + 2] = nsy;
        ctx.new_state[4 * i + 3] = nanchor;
      }
      // Contact force on the body: N n - (flows' tangential part) along t.
      const double bx = n_force * g.nx + t_force * g.tx, by = n_force * g.ny + t_force * g.ty;
      fx += bx;
      fy += by;
      mz += e.rx * by - e.ry * bx;
      if (have_work) {
        ctx.work[4 + 4 * i] = e.delta;
        ctx.work[5 + 4 * i] = n_force;
        ctx.work[6 + 4 * i] = t_force;
        ctx.work[7 + 4 * i] = old_mode;
      }
    }
    if (have_work) {
      ctx.work[0] = fx;
      ctx.work[1] = fy;
      ctx.work[2] = mz;
      ctx.work[3] = active;
    }
  }

 private:
  parameters p;
  std::vector<detail::contact_segment> seg_;
};

}  // namespace pradis::elements
