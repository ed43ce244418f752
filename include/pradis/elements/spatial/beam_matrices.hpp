#pragma once
/// \file
/// The stiffness and mass matrices of a straight beam of linear Euler-Bernoulli
/// elements, as an input of a reduced elastic part (linalg/reduction.hpp,
/// elements/spatial/reduced_body.hpp): the linearisation at rest of a chain of
/// BEAM3 (beam.hpp) and BEAMI3 (beam_inertia.hpp) elements. docs/reduction.md.

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "pradis/core/error.hpp"
#include "pradis/elements/spatial/beam_kinematics.hpp"

namespace pradis::elements {

/// Section and material of a straight beam (the parameters BEAM3 and BEAMI3 share).
struct beam_section {
  double e = 0, g = 0;            ///< Young's and shear modulus [Pa]
  double a = 0;                   ///< cross-section area [m^2]
  double iy = 0, iz = 0, j = 0;   ///< second moments about the section's y and z axes, torsion constant [m^4]
  double rho = 0;                 ///< density [kg/m^3]
  double ip = 0;                  ///< polar moment for the rotary inertia about the axis [m^4]
};

/// K and M of a straight beam.
struct beam_matrices {
  Eigen::MatrixXd k;  ///< stiffness, 6 (n + 1) square
  Eigen::MatrixXd m;  ///< mass, 6 (n + 1) square
};

/// The free-free stiffness and mass matrices of a straight beam from `a` to `b`
/// (section y axis along the part of `v` normal to the axis) divided into `n`
/// equal elements: nodes 0..n from a to b, 6 DOFs per node in global axes (ux,
/// uy, uz, rx, ry, rz: translations [m], small rotations [rad]), node k's DOFs at
/// 6k..6k+5. Each element is the linearisation at rest of BEAM3 (axial EA/L,
/// torsion GJ/L, the Hermite bending stiffness with EIy in the local x-z plane and
/// EIz in the x-y plane) and of BEAMI3 (translational mass (m/6) [2 1; 1 2] per
/// axis, m = rho A L, and the lumped rotary inertia (rho L / 2) T0 diag(Ip, Iy, Iz)
/// T0^T at each end). So a reduction of these matrices describes the same beam as
/// n BEAM3 + BEAMI3 in small deformation. Throws pradis::error (invalid_model) for
/// n < 1, a zero length, a section vector along the axis or a non-positive or
/// non-finite property.
template <class = void>  // compiled only in units that call it
beam_matrices straight_beam_matrices(const beam_section& s, const spatial::vec3& a, const spatial::vec3& b,
                                            const spatial::vec3& v, int n) {
  const std::string f = "straight_beam_matrices: ";
  if (n < 1) throw error(error_code::invalid_model, f + "the number of elements " + std::to_string(n) + " must be >= 1");
  for (double x : {s.e, s.g, s.a, s.iy, s.iz, s.j, s.rho, s.ip})
    if (!std::isfinite(x) || !(x > 0))
      throw error(error_code::invalid_model, f + "E, G, A, Iy, Iz, J, rho and Ip must be finite and > 0");
  if (!a.allFinite() || !b.allFinite() || !v.allFinite())
    throw error(error_code::invalid_model, f + "the end points and the section vector must be finite");
  const detail::beam_geometry geo{a, b, v};
  if (!(geo.length() > 0)) throw error(error_code::invalid_model, f + "the ends coincide: the length of the beam is zero");
  if (!geo.section_ok()) throw error(error_code::invalid_model, f + "the section vector is zero or along the beam axis");
  const double l = geo.length() / n;
  // The element in its local axes (x along the beam, y the section's y axis).
  Eigen::Matrix<double, 12, 12> kl = Eigen::Matrix<double, 12, 12>::Zero();
  const auto put = [&kl](int r, int c, double x) {
    kl(r, c) += x;
    if (r != c) kl(c, r) += x;
  };
  put(0, 0, s.e * s.a / l), put(6, 6, s.e * s.a / l), put(0, 6, -s.e * s.a / l);
  put(3, 3, s.g * s.j / l), put(9, 9, s.g * s.j / l), put(3, 9, -s.g * s.j / l);
  // Bending in the local x-y plane: uy (1, 7) and rz (5, 11), E Iz.
  double c = s.e * s.iz / (l * l * l);
  put(1, 1, 12 * c), put(1, 5, 6 * l * c), put(1, 7, -12 * c), put(1, 11, 6 * l * c);
  put(5, 5, 4 * l * l * c), put(5, 7, -6 * l * c), put(5, 11, 2 * l * l * c);
  put(7, 7, 12 * c), put(7, 11, -6 * l * c), put(11, 11, 4 * l * l * c);
  // Bending in the local x-z plane: uz (2, 8) and ry (4, 10), E Iy (a positive ry lowers z ahead).
  c = s.e * s.iy / (l * l * l);
  put(2, 2, 12 * c), put(2, 4, -6 * l * c), put(2, 8, -12 * c), put(2, 10, -6 * l * c);
  put(4, 4, 4 * l * l * c), put(4, 8, 6 * l * c), put(4, 10, 2 * l * l * c);
  put(8, 8, 12 * c), put(8, 10, 6 * l * c), put(10, 10, 4 * l * l * c);
  const spatial::mat3 t0 = geo.frame();
  Eigen::Matrix<double, 12, 12> t = Eigen::Matrix<double, 12, 12>::Zero();
  for (int i = 0; i < 4; ++i) t.block<3, 3>(3 * i, 3 * i) = t0;
  const Eigen::Matrix<double, 12, 12> ke = t * kl * t.transpose();
  Eigen::Matrix<double, 12, 12> me = Eigen::Matrix<double, 12, 12>::Zero();
  const double m6 = s.rho * s.a * l / 6.0;
  const spatial::mat3 jn = (0.5 * s.rho * l) * t0 * spatial::vec3(s.ip, s.iy, s.iz).asDiagonal() * t0.transpose();
  for (int i : {0, 6}) {
    me.block<3, 3>(i, i) = 2 * m6 * spatial::mat3::Identity();
    me.block<3, 3>(i, 6 - i) = m6 * spatial::mat3::Identity();
    me.block<3, 3>(i + 3, i + 3) = jn;
  }
  beam_matrices r{Eigen::MatrixXd::Zero(6 * (n + 1), 6 * (n + 1)), Eigen::MatrixXd::Zero(6 * (n + 1), 6 * (n + 1))};
  for (int e = 0; e < n; ++e) {
    r.k.block<12, 12>(6 * e, 6 * e) += ke;
    r.m.block<12, 12>(6 * e, 6 * e) += me;
  }
  // Exactly symmetric (the transformation leaves round-off).
  r.k = 0.5 * (r.k + r.k.transpose()).eval();
  r.m = 0.5 * (r.m + r.m.transpose()).eval();
  return r;
}

}  // namespace pradis::elements
