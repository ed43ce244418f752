#pragma once
/// \file
/// TRIPL: the 12-DOF triangle plate of the PRADIS paper (three translations per vertex,
/// one rotation about each side at its middle), a membrane CST plus the Morley bending
/// triangle, geometrically linear. The matrices are in plate_kernel.hpp, the mesh helper
/// in plate_mesh.hpp; docs/plates.md.

#include <array>
#include <cmath>
#include <span>
#include <string>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/plate_kernel.hpp"

namespace pradis::elements {

template <class = void>
struct triangle_plate_t;
/// The element type (a class template so that units that do not use it skip its members: docs/adding-an-element.md).
using triangle_plate = triangle_plate_t<>;
/// TRIPL: elastic triangle plate in space with mass. DOFs: the displacements
/// (x, y, z) of the vertices 1, 2, 3, then r12, r23, r31: the rotation at the middle of
/// each side about that side, times the side's sign s (+1 or -1): r = s * (rotation
/// about the side's tangent from its first to its second vertex, right-hand rule).
/// Neighbouring triangles traverse a shared side in opposite directions; the signs make
/// the shared DOF the same physical rotation (plate_mesh.hpp sets them: the axis points
/// from the lower to the higher mesh vertex number). Flows:
///
///     F = K d + M a - p l
///
/// K = T^T (A B^T Dm B + A Bk^T Db Bk) T: constant-strain membrane (CST) and Morley
/// constant-curvature bending (quadratic deflection) in the frame of the initial
/// triangle; M = (rho h A / 3) I on the vertex translations (lumped, no rotary inertia);
/// l the consistent load of a unit pressure along the initial normal n = (P2 - P1) x
/// (P3 - P1) / |...|. Geometrically linear: K and M are constant (ADR 1, IGN 2).
template <class>
struct triangle_plate_t {
  static constexpr pradis::passport passport{.name = "TRIPL", .ext = 12, .par = 17, .wrk = 6, .adr = 1, .ign = 2};
  static constexpr element_help help{
      .title = "elastic triangle plate in space (membrane CST + Morley bending), 12 DOFs",
      .name = "Triangle plate with three translations per vertex and one rotation about each side at its middle",
      .field = "mechanics, spatial motion, plates and shells",
      .dofs = "1 - translation of vertex 1 along X [m]\n"
              "2 - translation of vertex 1 along Y [m]\n"
              "3 - translation of vertex 1 along Z [m]\n"
              "4 - translation of vertex 2 along X [m]\n"
              "5 - translation of vertex 2 along Y [m]\n"
              "6 - translation of vertex 2 along Z [m]\n"
              "7 - translation of vertex 3 along X [m]\n"
              "8 - translation of vertex 3 along Y [m]\n"
              "9 - translation of vertex 3 along Z [m]\n"
              "10 - rotation at the middle of side 1-2 about the side, times sign s12 (flow: moment) [rad]\n"
              "11 - rotation at the middle of side 2-3 about the side, times sign s23 [rad]\n"
              "12 - rotation at the middle of side 3-1 about the side, times sign s31 [rad]",
      .parameters = "1 - Young's modulus E [Pa] (> 0)\n"
                    "2 - Poisson's ratio nu [-] (-1 < nu < 0.5)\n"
                    "3 - thickness h [m] (> 0)\n"
                    "4 - density rho [kg/m^3] (>= 0)\n"
                    "5 - initial X of vertex 1 [m]\n"
                    "6 - initial Y of vertex 1 [m]\n"
                    "7 - initial Z of vertex 1 [m]\n"
                    "8 - initial X of vertex 2 [m]\n"
                    "9 - initial Y of vertex 2 [m]\n"
                    "10 - initial Z of vertex 2 [m]\n"
                    "11 - initial X of vertex 3 [m]\n"
                    "12 - initial Y of vertex 3 [m]\n"
                    "13 - initial Z of vertex 3 [m] (the vertices must span a triangle)\n"
                    "14 - sign s12 of side 1-2 (+1: DOF 10 is the rotation about the axis 1 -> 2, -1: about 2 -> 1)\n"
                    "15 - sign s23 of side 2-3 (+1 or -1)\n"
                    "16 - sign s31 of side 3-1 (+1 or -1)\n"
                    "17 - uniform pressure p along the initial normal (P2 - P1) x (P3 - P1) [Pa] (0: none)",
      .work = "1 - membrane force Nx in the local frame (x along side 1-2, z the normal) [N/m]\n"
              "2 - membrane force Ny [N/m]\n"
              "3 - membrane shear force Nxy [N/m]\n"
              "4 - bending moment Mx = -D (w_xx + nu w_yy) [N m/m]\n"
              "5 - bending moment My = -D (w_yy + nu w_xx) [N m/m]\n"
              "6 - twisting moment Mxy = -D (1 - nu) w_xy [N m/m]",
      .special = "code 100 if E <= 0, nu outside (-1, 0.5), h <= 0, rho < 0, a sign other than +1 or -1, a "
                 "parameter is not finite, or the vertices do not span a triangle. Geometrically linear (small "
                 "displacements and rotations about the initial configuration): a rigid rotation by an angle phi "
                 "gives spurious forces of order phi^2 (docs/plates.md)"};

  /// Typed parameters, in PAR order.
  struct parameters {
    double e = 0;                          ///< Young's modulus [Pa]
    double nu = 0;                         ///< Poisson's ratio
    double h = 0;                          ///< thickness [m]
    double rho = 0;                        ///< density [kg/m^3]
    double x1 = 0, y1 = 0, z1 = 0;         ///< initial vertex 1 [m]
    double x2 = 1, y2 = 0, z2 = 0;         ///< initial vertex 2 [m]
    double x3 = 0, y3 = 1, z3 = 0;         ///< initial vertex 3 [m]
    double s12 = 1, s23 = 1, s31 = 1;      ///< side signs (+1 or -1)
    double pressure = 0;                   ///< uniform pressure along the initial normal [Pa]
  };
  parameters p;

  explicit triangle_plate_t(parameters q) : p(q) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() {
    return {1e3, 0.3, 0.2, 500, 0.1, -0.2, 0.05, 1.1, 0.1, -0.1, 0.3, 0.9, 0.2, 1, -1, 1, 3.0};
  }
  static triangle_plate from_parameters(std::span<const double> v) {
    return triangle_plate({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12], v[13],
                           v[14], v[15], v[16]});
  }
  /// The geometry of the initial triangle.
  detail::plate_geometry geometry() const {
    return {spatial::vec3(p.x1, p.y1, p.z1), spatial::vec3(p.x2, p.y2, p.z2), spatial::vec3(p.x3, p.y3, p.z3)};
  }
  /// The constant matrices (stiffness, unit-pressure load, strain and Hessian maps).
  void matrices(detail::plate_matrices& out) const {
    detail::plate_build(geometry(), p.e, p.nu, p.h, {p.s12, p.s23, p.s31}, out);
  }
  /// Flexural rigidity D = E h^3 / (12 (1 - nu^2)).
  double rigidity() const { return p.e * p.h * p.h * p.h / (12 * (1 - p.nu * p.nu)); }

  /// NEWINT: parameter checks (code 100).
  /// Animation geometry (io/model_scene.hpp): the triangle on its three vertices.
  template <class Drawer>
  void draw(Drawer& d) const {
    d.triangle(d.point({p.x1, p.y1, p.z1}, 0), d.point({p.x2, p.y2, p.z2}, 3), d.point({p.x3, p.y3, p.z3}, 6));
  }
  void new_integration(element_context& ctx) const {
    for (double x : {p.e, p.nu, p.h, p.rho, p.x1, p.y1, p.z1, p.x2, p.y2, p.z2, p.x3, p.y3, p.z3, p.s12, p.s23, p.s31,
                     p.pressure})
      if (!std::isfinite(x)) ctx.invalid_parameter("the parameters must be finite");
    if (!(p.e > 0)) ctx.invalid_parameter("Young's modulus E = " + to_text(p.e) + " must be > 0");
    if (!(p.nu > -1 && p.nu < 0.5))
      ctx.invalid_parameter("Poisson's ratio nu = " + to_text(p.nu) + " must be in (-1, 0.5)");
    if (!(p.h > 0)) ctx.invalid_parameter("thickness h = " + to_text(p.h) + " must be > 0");
    if (!(p.rho >= 0)) ctx.invalid_parameter("density rho = " + to_text(p.rho) + " must be >= 0");
    for (double s : {p.s12, p.s23, p.s31})
      if (s != 1.0 && s != -1.0) ctx.invalid_parameter("side sign " + to_text(s) + " must be +1 or -1");
    if (!(geometry().area > 0))
      ctx.invalid_parameter("the vertices do not span a triangle (degenerate triangle: they coincide or are collinear)");
  }

  void evaluate(const local_input<triangle_plate>& in, local_output<triangle_plate>& out, element_context& ctx) const {
    const detail::plate_geometry g = geometry();
    detail::plate_matrices mt;
    detail::plate_build(g, p.e, p.nu, p.h, {p.s12, p.s23, p.s31}, mt);
    const double mass3 = p.rho * p.h * g.area / 3.0;
    out.f.noalias() = mt.k * in.u;
    out.f.head<9>() += mass3 * in.a.head<9>();
    out.f -= p.pressure * mt.load;
    // Outputs: N = (E h / (1 - nu^2)) D0 eps, M = D D0 kappa with kappa = -(w_xx, w_yy, 2 w_xy).
    const Eigen::Vector3d eps = mt.strain * in.u, hs = mt.hessian * in.u;
    const double cm = p.e * p.h / (1 - p.nu * p.nu), d = rigidity();
    ctx.work[0] = cm * (eps(0) + p.nu * eps(1));
    ctx.work[1] = cm * (eps(1) + p.nu * eps(0));
    ctx.work[2] = cm * 0.5 * (1 - p.nu) * eps(2);
    ctx.work[3] = -d * (hs(0) + p.nu * hs(2));
    ctx.work[4] = -d * (hs(2) + p.nu * hs(0));
    ctx.work[5] = -d * (1 - p.nu) * hs(1);
    if (!out.want_jacobian) return;
    out.K = mt.k;
    out.M.setZero();
    for (int i = 0; i < 9; ++i) out.M(i, i) = mass3;
  }
};

}  // namespace pradis::elements
