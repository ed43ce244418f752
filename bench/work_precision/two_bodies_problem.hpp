#pragma once
/// \file
/// The two-body system of the PRADIS element developer's manual (Fig. 3.3,
/// section 3.6.9; examples/two_bodies and examples/models/two_bodies.prd) as a
/// plain second-order system M u'' + g(u) = 0 for the work-precision peers, and
/// the same system as a pradis model. tests/integrators/test_two_bodies_peer.cpp
/// checks that M a + g(u) equals pradis's assembled residual at random states.
///
/// Two bodies in plane motion (MD: body 1 m = 1 kg, J = 0.1 kg m^2 at (1, 1);
/// body 2 m = 2 kg, J = 0.1 kg m^2 at (2, 2)) joined at their centres of gravity
/// by an ideal elastic link (LINKD, k = 5e3 N/m, L0 = sqrt 2), a constant force
/// P = -1e3 N on body 2's Y DOF. DOF order: x1, y1, theta1, x2, y2, theta2
/// (displacements from the initial positions; the system starts at rest).

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/model/model.hpp"

namespace wp::two_bodies {

/// Masses and moments of inertia of bodies 1 and 2 [kg, kg m^2].
inline constexpr double m1 = 1.0, j1 = 0.1, m2 = 2.0, j2 = 0.1;
/// Initial centres of gravity [m].
inline constexpr double xa0 = 1, ya0 = 1, xb0 = 2, yb0 = 2;
/// Link stiffness [N/m] and the force on body 2's Y DOF [N] (negative: downward).
inline constexpr double k = 5e3, force = -1e3;
/// Number of DOFs.
inline constexpr int n = 6;

/// Diagonal mass matrix, in DOF order.
inline std::vector<double> mass() { return {m1, m1, j1, m2, m2, j2}; }

/// g(u): the non-inertial flows per DOF (pradis's sign convention: the residual
/// is M a + g = 0). LINKD: F_A = -k (L - L0) e, F_B = -F_A, e = (B - A) / L
/// (planar_link); F: flow -P on its DOF (constant_force); MD contributes only M a.
inline void forces(const double* u, double* g) {
  const double l0 = std::hypot(xb0 - xa0, yb0 - ya0);
  const double dx = (xb0 + u[3]) - (xa0 + u[0]), dy = (yb0 + u[4]) - (ya0 + u[1]);
  const double l = std::hypot(dx, dy), c = dx / l, s = dy / l, du = l - l0;
  g[0] = -k * du * c;
  g[1] = -k * du * s;
  g[2] = 0;
  g[3] = k * du * c;
  g[4] = k * du * s - force;
  g[5] = 0;
}

/// dg/du (6 x 6), the link stiffness of manual section 3.6.3.
inline void stiffness(const double* u, Eigen::MatrixXd& gu) {
  const double l0 = std::hypot(xb0 - xa0, yb0 - ya0);
  const double dx = (xb0 + u[3]) - (xa0 + u[0]), dy = (yb0 + u[4]) - (ya0 + u[1]);
  const double l = std::hypot(dx, dy), c = dx / l, s = dy / l, r = l0 / l;
  const double kxx = k * (1 - r * s * s), kxy = k * r * s * c, kyy = k * (1 - r * c * c);
  gu.setZero(n, n);
  const int idx[4] = {0, 1, 3, 4};
  const double blk[2][2] = {{kxx, kxy}, {kxy, kyy}};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) gu(idx[a], idx[b]) = (a / 2 == b / 2 ? 1.0 : -1.0) * blk[a % 2][b % 2];
}

/// Centre-of-mass motion, exact for this system (the only external force is P on
/// body 2's Y DOF): Y_c = P t^2 / (2 (m1 + m2)), X_c = 0; used to express the
/// final state about the centre of mass for the error scale.
inline double yc(double t) { return force * t * t / (2 * (m1 + m2)); }
/// d Y_c / dt.
inline double vc(double t) { return force * t / (m1 + m2); }

/// The manual's model in pradis (MD, MD, LINKD, F); `dofs` receives the six DOFs.
using model_type = pradis::model<pradis::elements::planar_inertia, pradis::elements::planar_link,
                                 pradis::elements::constant_force>;
inline void build(model_type& m, std::vector<pradis::dof>& dofs) {
  using namespace pradis::elements;
  dofs = m.add_dofs(6, "DOF ");
  m.add<planar_inertia>("Body 1", {.m = m1, .j = j1}, dofs[0], dofs[1], dofs[2]);
  m.add<planar_inertia>("Body 2", {.m = m2, .j = j2}, dofs[3], dofs[4], dofs[5]);
  m.add<planar_link>("Connection", {xa0, ya0, xb0, yb0, k}, dofs[0], dofs[1], dofs[3], dofs[4]);
  m.add<constant_force>("Force", {.force = force}, dofs[4]);
}

}  // namespace wp::two_bodies
