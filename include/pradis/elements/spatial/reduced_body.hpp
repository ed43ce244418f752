#pragma once
/// \file
/// FLEX3: a reduced elastic part (Guyan or Craig-Bampton, linalg/reduction.hpp) on
/// spatial nodes in large overall motion, corotational in the floating frame of
/// its first boundary node. The flows are in reduced_body_kernel.hpp.
/// docs/reduction.md.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "pradis/core/element.hpp"
#include "pradis/elements/spatial/beam_matrices.hpp"
#include "pradis/elements/spatial/reduced_body_kernel.hpp"
#include "pradis/linalg/reduction.hpp"
#include "pradis/spatial/quaternion.hpp"

namespace pradis::elements {

namespace detail {
/// A text built at compile time (the help lists of a family of element types).
template <std::size_t N>
struct fixed_text {
  std::array<char, N> data{};
  std::size_t size = 0;
  constexpr void add(std::string_view s) {
    for (char c : s) data[size++] = c;
  }
  constexpr void add(int x) {
    char buf[12]{};
    int n = 0;
    do {
      buf[n++] = static_cast<char>('0' + x % 10);
      x /= 10;
    } while (x > 0);
    while (n > 0) data[size++] = buf[--n];
  }
  constexpr std::string_view view() const { return {data.data(), size}; }
};

/// The DOF lines of FLEX3 with nb boundary nodes.
template <int NB>
constexpr auto reduced_body_dof_text() {
  fixed_text<NB * 6 * 80> t;
  constexpr std::array<std::string_view, 6> what{
      "translation along X [m]", "translation along Y [m]", "translation along Z [m]",
      "rotation potential q1 of its rotational node (flow: moment about X) [-]", "q2 (flow: moment about Y) [-]",
      "q3 (flow: moment about Z) [-]"};
  for (int i = 0; i < NB; ++i)
    for (int j = 0; j < 6; ++j) {
      if (i + j > 0) t.add("\n");
      t.add(6 * i + j + 1), t.add(" - boundary node "), t.add(i + 1), t.add(": "), t.add(what[static_cast<std::size_t>(j)]);
    }
  return t;
}

/// The parameter lines of FLEX3 with nb boundary nodes and n = 6 nb + nm reduced coordinates.
template <int NB, int NM>
constexpr auto reduced_body_parameter_text() {
  constexpr int n = 6 * NB + NM;
  fixed_text<(3 * NB + n * (n + 1)) * 90> t;
  int line = 0;
  constexpr std::array<std::string_view, 3> axis{"X", "Y", "Z"};
  for (int i = 0; i < NB; ++i)
    for (int j = 0; j < 3; ++j) {
      if (line > 0) t.add("\n");
      t.add(++line), t.add(" - "), t.add(axis[static_cast<std::size_t>(j)]), t.add(" of boundary node "), t.add(i + 1),
          t.add(" in the reference configuration of the reduction [m]");
    }
  for (int w = 0; w < 2; ++w)
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) {
        t.add("\n"), t.add(++line), t.add(w == 0 ? " - reduced stiffness K(" : " - reduced mass M("), t.add(r + 1),
            t.add(","), t.add(c + 1), t.add(") (lower triangle, row by row) [SI]");
      }
  return t;
}

/// NEWINT of FLEX3 for any size (compiled once, not per element type: the checks
/// run on dynamic copies of K and M, so no fixed-size decomposition is instantiated
/// for every NB and NM). x0 holds X, Y, Z of each boundary node; K and M have
/// 6 per node, then the modes. Code 100 through ctx if a parameter is not finite,
/// M is not positive definite, K is not positive semidefinite or K resists a rigid
/// motion of the reference positions.
inline void check_reduced_part(std::span<const double> x0, const Eigen::Ref<const Eigen::MatrixXd>& k_in,
                               const Eigen::Ref<const Eigen::MatrixXd>& m_in, element_context& ctx) {
  for (double x : x0)
    if (!std::isfinite(x)) ctx.invalid_parameter("the node positions must be finite");
  if (!k_in.allFinite() || !m_in.allFinite()) ctx.invalid_parameter("K and M must be finite");
  const Eigen::MatrixXd k = k_in, m = m_in;
  if (Eigen::LLT<Eigen::MatrixXd>(m).info() != Eigen::Success)
    ctx.invalid_parameter("the reduced mass M is not positive definite");
  const double sk = std::max(k.cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(k, Eigen::EigenvaluesOnly);
  if (es.eigenvalues()(0) < -1e-9 * sk)
    ctx.invalid_parameter("the reduced stiffness K is not positive semidefinite (smallest eigenvalue " +
                          to_text(es.eigenvalues()(0)) + ")");
  // The six rigid motions of the reference positions: translations and small rotations about node 1.
  const auto nb = static_cast<Eigen::Index>(x0.size() / 3);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(k.rows(), 6);
  const spatial::vec3 x1(x0[0], x0[1], x0[2]);
  double size = 0;
  for (Eigen::Index i = 0; i < nb; ++i) {
    const auto at = static_cast<std::size_t>(3 * i);
    const spatial::vec3 r = spatial::vec3(x0[at], x0[at + 1], x0[at + 2]) - x1;
    size = std::max(size, r.norm());
    g.block<3, 3>(6 * i, 0) = spatial::mat3::Identity();
    g.block<3, 3>(6 * i, 3) = -spatial::skew(r);
    g.block<3, 3>(6 * i + 3, 3) = spatial::mat3::Identity();
  }
  if (!(size > 0)) ctx.invalid_parameter("all boundary nodes are at one point");
  const Eigen::MatrixXd kg = k * g;
  for (Eigen::Index c = 0; c < 6; ++c)
    if (kg.col(c).norm() > 1e-8 * sk * g.col(c).norm())
      ctx.invalid_parameter(std::string("K resists a rigid ") + (c < 3 ? "translation along " : "rotation about ") +
                            "XYZ"[c % 3] + " of the reference node positions: the part must be free (no grounded "
                            "DOF) and the positions and coordinate order those of the reduction");
}
}  // namespace detail

/// FLEX3: a linear elastic part reduced to NB >= 2 boundary nodes (6 coordinates
/// each: ux uy uz rx ry rz in the part's reference axes) and NM modal coordinates,
/// e.g. by linalg::craig_bampton, on NB spatial nodes in large motion.
/// Corotational: node 1's position and orientation carry the part as a rigid body
/// (the floating frame R = R(q_1)); the other nodes' translations and rotations
/// relative to that frame and the modal coordinates are the (small) deformation d,
/// with strain energy d^T K d / 2. The kinetic energy is nubar^T M nubar / 2 with
/// nubar the nodes' velocities and angular velocities in the frame and the modal
/// rates; the flows are its exact Lagrange equations (gyroscopic and frame terms
/// included), so a rigid motion is exact for a Guyan part, energy is conserved and
/// the Jacobian is exact (reduced_body_kernel.hpp: the strain part per node pair with
/// dual numbers and a material product, the inertia part in closed form). Not included:
/// geometric stiffening (K is constant in the frame), damping.
/// The reference configuration has identity nodal quaternions.
template <int NB, int NM>
struct reduced_body {
  static_assert(NB >= 2, "pradis: a reduced body needs at least two boundary nodes");
  static_assert(NM >= 0, "pradis: the number of modes must be >= 0");
  /// Reduced coordinates: 6 per boundary node, then the modes.
  static constexpr int nr = 6 * NB + NM;
  static constexpr pradis::passport passport{
      .name = "FLEX3", .ext = 6 * NB, .ent = NB + NM, .par = 3 * NB + nr * (nr + 1), .wrk = 2, .adr = 1, .ign = 0};
  /// Node i: q1..q3 at 6i+3..6i+5, its hidden q4 at 6 NB + i; the modes follow at 7 NB.
  static constexpr auto rotation_nodes = [] {
    std::array<rotation_slot, NB> r{};
    for (int i = 0; i < NB; ++i) r[static_cast<std::size_t>(i)] = {6 * i + 3, 6 * NB + i};
    return r;
  }();
  static constexpr auto dof_text = detail::reduced_body_dof_text<NB>();
  static constexpr auto parameter_text = detail::reduced_body_parameter_text<NB, NM>();
  static constexpr element_help help{
      .title = "reduced elastic body (Guyan / Craig-Bampton) in large spatial motion",
      .name = "Linear elastic part given by its reduced stiffness and mass, corotational in the floating frame of "
              "its first boundary node, with internal modal coordinates; in a model file, K and M of a finite "
              "element model are read from Matrix Market files and reduced by CRAIGBAMPTON(\"k.mtx\", \"m.mtx\", "
              "modes, dof, ...) in $DATA, which gives the parameters after the positions (docs/reduction.md)",
      .field = "mechanics, spatial motion, flexible bodies",
      .dofs = dof_text.view(),
      .parameters = parameter_text.view(),
      .work = "1 - strain energy [J]\n2 - kinetic energy [J]",
      .special = "code 100 if a parameter is not finite, M is not positive definite, K is not positive semidefinite "
                 "or K resists a rigid-body motion of the reference node positions (the part must be free and the "
                 "positions those of the reduction); code 75 if a quaternion norm comes near zero or a node turns "
                 "by 180 degrees relative to node 1 (far beyond small deformation)"};

  using matrix = Eigen::Matrix<double, nr, nr>;
  /// Typed parameters: the boundary nodes' reference positions and the reduced matrices.
  struct parameters {
    std::array<double, 3 * NB> x0{};     ///< X, Y, Z of each boundary node [m]
    matrix k = matrix::Zero();           ///< reduced stiffness (symmetric)
    matrix m = matrix::Identity();       ///< reduced mass (symmetric positive definite)
  };
  parameters p;

  explicit reduced_body(parameters q) : p(std::move(q)) {
    p.k = 0.5 * (p.k + p.k.transpose()).eval();
    p.m = 0.5 * (p.m + p.m.transpose()).eval();
  }
  /// From the flat PAR vector: positions, then the lower triangles of K and M row by row.
  static reduced_body from_parameters(std::span<const double> v) {
    parameters q;
    std::size_t at = 0;
    for (auto& x : q.x0) x = v[at++];
    for (matrix* a : {&q.k, &q.m})
      for (int r = 0; r < nr; ++r)
        for (int c = 0; c <= r; ++c) (*a)(r, c) = (*a)(c, r) = v[at++];
    return reduced_body(q);
  }
  /// The typed parameters of a reduced part (linalg::craig_bampton) whose boundary
  /// is NB nodes of 6 coordinates each (node by node: ux uy uz rx ry rz), at the
  /// given reference positions. Throws pradis::error (invalid_model) if the sizes differ.
  static parameters from_part(const linalg::reduced_part& r, const std::array<spatial::vec3, NB>& nodes) {
    if (r.k.rows() != nr || r.m.rows() != nr || static_cast<int>(r.boundary.size()) != 6 * NB)
      throw error(error_code::invalid_model,
                  "FLEX3: the reduced part has " + std::to_string(r.boundary.size()) + " boundary coordinates and " +
                      std::to_string(r.k.rows() - static_cast<Eigen::Index>(r.boundary.size())) +
                      " modes; this element type takes " + std::to_string(6 * NB) + " and " + std::to_string(NM));
    parameters q;
    for (int i = 0; i < NB; ++i)
      for (int j = 0; j < 3; ++j) q.x0[static_cast<std::size_t>(3 * i + j)] = nodes[static_cast<std::size_t>(i)](j);
    q.k = r.k;
    q.m = r.m;
    return q;
  }
  /// Example parameters (used by `pradis check` and the all-elements test): an
  /// oblique beam of two elements reduced to its ends and NM modes.
  static parameters example() {
    const spatial::vec3 a(0.1, -0.2, 0.3), b(1.1, 0.3, -0.2);
    const int n = NB + (NM + 5) / 6;  // enough interior DOFs for NM modes
    const beam_matrices bm = straight_beam_matrices({2e2, 80, 0.5, 0.2, 0.1, 0.15, 7.0, 0.3}, a, b, {0.2, 0.3, 1.0}, n);
    std::vector<int> boundary;
    std::array<spatial::vec3, NB> nodes;
    for (int i = 0; i < NB; ++i) {
      const int node = i == 0 ? 0 : (i == 1 ? n : i - 1);  // the two ends, then interior nodes
      nodes[static_cast<std::size_t>(i)] = a + (b - a) * (static_cast<double>(node) / n);
      for (int j = 0; j < 6; ++j) boundary.push_back(6 * node + j);
    }
    return from_part(linalg::craig_bampton(bm.k, bm.m, boundary, NM), nodes);
  }

  /// Animation geometry (io/model_scene.hpp): lines from node 1 to the other nodes.
  template <class Drawer>
  void draw(Drawer& d) const {
    const auto pt = [&](int i) {
      const auto k = static_cast<std::size_t>(3 * i);
      return d.body_point({p.x0[k], p.x0[k + 1], p.x0[k + 2]}, 6 * i, i, spatial::vec3::Zero());
    };
    for (int i = 1; i < NB; ++i) d.line(pt(0), pt(i));
  }

  /// NEWINT: finite parameters, M positive definite, K positive semidefinite and
  /// free of the rigid-body motions of the reference node positions (code 100).
  void new_integration(element_context& ctx) const {
    detail::check_reduced_part(p.x0, p.k, p.m, ctx);
  }

  void evaluate(const local_input<reduced_body>& in, local_output<reduced_body>& out, element_context& ctx) const {
    for (int i = 0; i < NB; ++i)
      if (!(kernel::quat(in.u, i).squaredNorm() > spatial::lq_near_zero * spatial::lq_near_zero))
        ctx.singular("Lq near zero: the quaternion norm |q| has vanished");
    out.f.setZero();
    if (!out.want_jacobian) {
      const auto [strain, w] = kernel::elastic(in.u, p.k, p.x0, out.f, nullptr);
      check(w, ctx);
      ctx.work[0] = strain;
      ctx.work[1] = kernel::inertia(in.u, in.v, in.a, p.m, out.f, nullptr, nullptr, nullptr);
      return;
    }
    out.K.setZero();
    out.C.setZero();
    out.M.setZero();
    const auto [strain, w] = kernel::elastic(in.u, p.k, p.x0, out.f, &out.K);
    check(w, ctx);
    ctx.work[0] = strain;
    ctx.work[1] = kernel::inertia(in.u, in.v, in.a, p.m, out.f, &out.K, &out.C, &out.M);
  }

  /// States the checks may use: quaternion norms not near zero, every node within
  /// about 170 degrees of node 1.
  bool admissible(const local_input<reduced_body>& in) const {
    for (int i = 0; i < NB; ++i)
      if (!(quaternion_of(in.u, i).norm() > 0.2)) return false;
    const spatial::quaternion q1 = quaternion_of(in.u, 0).normalized();
    for (int i = 1; i < NB; ++i)
      if (!(std::abs(spatial::relative_rotation(q1, quaternion_of(in.u, i).normalized())(3)) > 0.1)) return false;
    return true;
  }

 private:
  using kernel = detail::reduced_body_kernel<NB, NM>;
  template <class V>
  static spatial::quaternion quaternion_of(const V& u, int i) {
    return kernel::quat(u, i);
  }
  /// Code 75 at a relative rotation near 180 degrees.
  static void check(double min_w, element_context& ctx) {
    if (!(min_w > 1e-3)) ctx.singular("a boundary node has turned by 180 degrees relative to node 1 (far beyond small deformation)");
  }
};

/// FLEX3 of the built-in library: two boundary nodes and two modes.
using reduced_body_2x2 = reduced_body<2, 2>;

}  // namespace pradis::elements
