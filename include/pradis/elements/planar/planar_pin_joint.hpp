#pragma once
/// \file
/// PIN2X: exact pin (revolute) joint between two bodies in plane motion, the
/// constraint p_B - p_A = 0 with the pin force as Lagrange multipliers.

#include <cmath>
#include <span>

#include "pradis/core/element.hpp"

namespace pradis::elements {

template <class = void>
struct planar_pin_joint_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using planar_pin_joint = planar_pin_joint_t<>;
/// PIN2X: holds point A of body a (node x_a, y_a, theta_a) on point B of body b
/// exactly. A point's position is p = X0 + x + R(theta) r, r its offset from the
/// node at theta = 0. The pin force lambda = (lambda_x, lambda_y) is a pair of
/// internal DOFs (velocity-level unknowns, local 6, 7). Flows:
///
///     F_a = -lambda,  M_a = -(rho_A x lambda),  F_b = lambda,  M_b = rho_B x lambda,
///     F_lambda = p_B - p_A = 0,                  rho = R(theta) r,
///
/// with the geometric stiffness dM_a/dtheta_a = rho_A . lambda,
/// dM_b/dtheta_b = -rho_B . lambda (d rho / d theta = (-rho_y, rho_x)), the
/// constraint rows [-I, -d rho_A/d theta, I, d rho_B/d theta] and the multiplier
/// columns in C. The rows have a zero diagonal (see LINKX).
template <class>
struct planar_pin_joint_t {
  static constexpr pradis::passport passport{
      .name = "PIN2X", .ext = 6, .ent = 2, .par = 8, .wrk = 3, .adr = 1, .ign = 3};
  static constexpr element_help help{
      .title = "exact pin joint between two bodies in plane motion (constraint with multipliers)",
      .name = "Pin (revolute) joint for plane motion: two body-fixed points held together exactly; the pin force "
              "is an internal unknown [N]",
      .field = "mechanics",
      .dofs = "1 - translation of body a's node along X [m]\n"
              "2 - translation of body a's node along Y [m]\n"
              "3 - rotation of body a about Z [rad]\n"
              "4 - translation of body b's node along X [m]\n"
              "5 - translation of body b's node along Y [m]\n"
              "6 - rotation of body b about Z [rad] (connect DOFs 1-3 or 4-6 to the ground for a pin to the ground)",
      .parameters = "1 - initial abscissa of body a's node [m]\n"
                    "2 - initial ordinate of body a's node [m]\n"
                    "3 - x of pin point A from a's node at rotation 0 [m]\n"
                    "4 - y of A from a's node [m]\n"
                    "5 - initial abscissa of body b's node [m]\n"
                    "6 - initial ordinate of body b's node [m]\n"
                    "7 - x of pin point B from b's node at rotation 0 [m]\n"
                    "8 - y of B from b's node [m] (A and B should coincide initially)",
      .work = "1 - gap |p_B - p_A| [m] (the constraint's residual)\n"
              "2 - pin force on body b, X [N]\n"
              "3 - pin force on body b, Y [N]",
      .special = "Internal DOFs 1..2: the pin force lambda, X and Y [N] (velocity-level unknowns); code 100 if a "
                 "parameter is not finite. The constraint rows have a zero diagonal; the joined bodies must carry "
                 "mass. Use HHT or generalized-alpha when the pin force matters: under NEWMARK it may alternate from "
                 "step to step"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double xa0 = 0, ya0 = 0, rax = 0, ray = 0;  ///< a's node and the offset of A [m]
    double xb0 = 0, yb0 = 0, rbx = 0, rby = 0;  ///< b's node and the offset of B [m]
  };
  parameters p;

  explicit planar_pin_joint_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return {0.1, -0.2, 0.3, 0.25, 0.5, 0.4, -0.2, 0.3}; }
  static planar_pin_joint from_parameters(std::span<const double> v) {
    return planar_pin_joint({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
  }
  /// NEWINT: parameter checks (code 100).
  void new_integration(element_context& ctx) const {
    for (double x : {p.xa0, p.ya0, p.rax, p.ray, p.xb0, p.yb0, p.rbx, p.rby})
      if (!std::isfinite(x)) ctx.invalid_parameter("positions and offsets must be finite (a parameter is not finite)");
  }

  void evaluate(const local_input<planar_pin_joint>& in, local_output<planar_pin_joint>& out,
                element_context& ctx) const {
    const double ca = std::cos(in.u(2)), sa = std::sin(in.u(2)), cb = std::cos(in.u(5)), sb = std::sin(in.u(5));
    const double rax = ca * p.rax - sa * p.ray, ray = sa * p.rax + ca * p.ray;
    const double rbx = cb * p.rbx - sb * p.rby, rby = sb * p.rbx + cb * p.rby;
    const double dx = (p.xb0 + in.u(3) + rbx) - (p.xa0 + in.u(0) + rax);
    const double dy = (p.yb0 + in.u(4) + rby) - (p.ya0 + in.u(1) + ray);
    const double lx = in.v(6), ly = in.v(7);
    out.f << -lx, -ly, -(rax * ly - ray * lx), lx, ly, rbx * ly - rby * lx, dx, dy;
    ctx.work[0] = std::hypot(dx, dy);
    ctx.work[1] = -lx;
    ctx.work[2] = -ly;
    if (!out.want_jacobian) return;
    out.K.setZero();
    out.C.setZero();
    out.K(2, 2) = rax * lx + ray * ly;
    out.K(5, 5) = -(rbx * lx + rby * ly);
    out.K.row(6) << -1, 0, ray, 1, 0, -rby, 0, 0;
    out.K.row(7) << 0, -1, -rax, 0, 1, rbx, 0, 0;
    out.C.col(6) << -1, 0, ray, 1, 0, -rby, 0, 0;
    out.C.col(7) << 0, -1, -rax, 0, 1, rbx, 0, 0;
  }
};

}  // namespace pradis::elements
