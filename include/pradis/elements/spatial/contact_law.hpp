#pragma once
/// \file
/// Normal force laws, the stick-slip friction return mapping and the step
/// recommendation (STEPMD) shared by the sphere contact elements CSPHPL and CSPHSP
/// (sphere_contact.hpp). No allocation.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements::detail {

/// The normal laws of the contact elements (parameter "law").
enum class contact_law { linear = 0, hertz = 1, hunt_crossley = 2 };

/// A normal force and its derivatives by the penetration delta and its rate delta'.
struct normal_force {
  double n = 0;      ///< normal force N >= 0 [N]
  double dn_dd = 0;  ///< dN/d delta [N/m]
  double dn_dr = 0;  ///< dN/d delta' [N s/m]
};

/// The normal force of a law at penetration delta > 0 and penetration rate
/// delta' (> 0 closing):
///
///     linear:        N = k delta + c delta'
///     Hertz:         N = k delta^1.5                        (c not used)
///     Hunt-Crossley: N = k delta^1.5 (1 + 1.5 c delta')     (c = alpha [s/m])
///
/// and N = 0 (with zero derivatives) where the formula is negative: the contact
/// never pulls (no adhesion while the bodies separate).
inline normal_force contact_normal(contact_law law, double k, double c, double delta, double rate) {
  normal_force r;
  if (!(delta > 0)) return r;
  switch (law) {
    case contact_law::linear:
      r = {k * delta + c * rate, k, c};
      break;
    case contact_law::hertz: {
      const double s = std::sqrt(delta);
      r = {k * delta * s, 1.5 * k * s, 0.0};
      break;
    }
    case contact_law::hunt_crossley: {
      const double s = std::sqrt(delta), damp = 1.0 + 1.5 * c * rate;
      r = {k * delta * s * damp, 1.5 * k * s * damp, 1.5 * c * k * delta * s};
      break;
    }
  }
  if (!(r.n > 0)) r = {};
  return r;
}

/// The elastic energy stored at penetration delta (linear k delta^2 / 2, otherwise
/// 0.4 k delta^2.5).
inline double contact_energy(contact_law law, double k, double delta) {
  if (!(delta > 0)) return 0.0;
  return law == contact_law::linear ? 0.5 * k * delta * delta : 0.4 * k * delta * delta * std::sqrt(delta);
}

/// STEPMD of a contact with effective mass m (0: no recommendation) at penetration
/// delta (negative: a gap of -delta) closing at delta'. With the equivalent impact
/// speed v = sqrt(delta'^2 + 2 U(delta) / m) (U the elastic energy: v is conserved by
/// an elastic impact) the penetration scale and contact time are
///
///     linear: delta* = v sqrt(m / k),                 t_c = pi sqrt(m / k)
///     Hertz:  delta* = (5 m v^2 / (4 k))^(2/5),        t_c = 2.94 delta* / v
///
/// (Johnson, Contact Mechanics, 1985, section 11.4). In contact the step is t_c / 20;
/// out of contact it is (gap + delta* / 10) / |delta'|: approaching, a step enters the
/// contact at most delta* / 10 deep; separating, the step grows by about a factor 2
/// per step after the contact instead of jumping back to SMAX at once. At rest
/// (delta' = 0, no contact): no recommendation.
inline double contact_step(contact_law law, double k, double m, double delta, double rate) {
  constexpr double none = std::numeric_limits<double>::infinity();
  if (!(m > 0) || !(k > 0)) return none;
  const double v = std::sqrt(rate * rate + 2.0 * contact_energy(law, k, delta) / m);
  if (!(v > 0)) return none;
  double scale = 0, tc = 0;
  if (law == contact_law::linear) {
    scale = v * std::sqrt(m / k);
    tc = std::numbers::pi * std::sqrt(m / k);
  } else {
    scale = std::pow(1.25 * m * v * v / k, 0.4);
    tc = 2.94 * scale / v;
  }
  if (delta > 0) return tc / 20.0;
  if (rate != 0) return (-delta + 0.1 * scale) / std::abs(rate);
  return none;
}

/// Checks the parameters common to the contact elements (code 100 naming the parameter).
inline void check_contact_parameters(element_context& ctx, double law, double k, double c, double mu, double kt,
                                     double mass) {
  if (!(law == 0 || law == 1 || law == 2))
    ctx.invalid_parameter("normal law = " + to_text(law) + " must be 0 (linear), 1 (Hertz) or 2 (Hunt-Crossley)");
  if (!(k > 0) || !std::isfinite(k)) ctx.invalid_parameter("contact stiffness k = " + to_text(k) + " must be finite and > 0");
  if (!(c >= 0) || !std::isfinite(c))
    ctx.invalid_parameter("damping c (alpha for Hunt-Crossley) = " + to_text(c) + " must be finite and >= 0");
  if (!(mu >= 0) || !std::isfinite(mu))
    ctx.invalid_parameter("friction coefficient mu = " + to_text(mu) + " must be finite and >= 0");
  if (!(kt >= 0) || !std::isfinite(kt) || (mu > 0 && !(kt > 0)))
    ctx.invalid_parameter("tangential stick stiffness kt = " + to_text(kt) + " must be finite, >= 0, and > 0 when mu > 0");
  if (!(mass >= 0) || !std::isfinite(mass))
    ctx.invalid_parameter("step-recommendation mass = " + to_text(mass) + " must be finite and >= 0 (0: no STEPMD)");
}

/// The Coulomb return mapping of the tangential stick spring (Wriggers, Computational
/// Contact Mechanics, 2nd ed., 2006, section 5.2; Simo and Laursen, Comput. Struct. 42,
/// 1992): with the trial elastic slip z (tangential, in the contact plane), the trial
/// force -kt z sticks while kt |z| <= mu N; beyond, the contact slides with the force
/// -mu N z / |z| and the elastic slip is returned to the cone, z_new = (mu N / kt) z / |z|.
/// The elastic slip stays bounded by mu N / kt: under static friction nothing creeps.
struct friction_state {
  spatial::vec3 force = spatial::vec3::Zero();  ///< tangential force on the body [N]
  spatial::vec3 z_new = spatial::vec3::Zero();  ///< elastic slip after the mapping [m]
  spatial::mat3 dforce_dz = spatial::mat3::Zero();  ///< d force / d z
  spatial::vec3 dforce_dn = spatial::vec3::Zero();  ///< d force / d N
  bool stick = true;

  friction_state(const spatial::vec3& z, double mu, double kt, double n) {
    using namespace spatial;
    const double zn = z.norm();
    if (kt * zn <= mu * n) {
      force = -kt * z;
      z_new = z;
      dforce_dz = -kt * mat3::Identity();
      return;
    }
    stick = false;
    const vec3 t = z / zn;
    force = -mu * n * t;
    z_new = (mu * n / kt) * t;
    dforce_dz = -(mu * n / zn) * (mat3::Identity() - t * t.transpose());
    dforce_dn = -mu * t;
  }
};

}  // namespace pradis::elements::detail
