// TRIPL, the 12-DOF triangle plate (membrane CST + Morley bending), and its mesh helper.
// References: L. S. D. Morley, "The constant-moment plate-bending element", J. Strain
// Analysis 6 (1971) 20-24 (the element passes the constant-moment patch test);
// S. Timoshenko and S. Woinowsky-Krieger, Theory of Plates and Shells, 2nd ed. (1959):
// table 8 (simply supported square plate under uniform load q, centre deflection
// 0.00406 q a^4 / D, nu = 0.3) and table 35 (clamped square plate, 0.00126 q a^4 / D);
// the Navier solution for the first frequency of the simply supported square plate,
// omega = 2 pi^2 / a^2 sqrt(D / (rho h)); A. W. Leissa, Vibration of Plates, NASA SP-160
// (1969), chapter 4: clamped square plate omega a^2 sqrt(rho h / D) = 35.985.

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/elements/spatial/plate_mesh.hpp"
#include "pradis/testing/jacobian_check.hpp"
#include "spatial_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

namespace {
using pradis_spatial_tests::pi;
/// One model type, with every element type of this file's tests, for them all: each model
/// type compiles the drivers anew.
using plate_model = pradis::model<triangle_plate, shaft_coupling, rotational_spring_damper, spatial_torque>;

/// The global matrices of a plate model from the elements' evaluate at u = v = a = 0:
/// K, the lumped mass diagonal and the load F = -f(0) (equation i is model DOF i + 1).
struct assembled {
  Eigen::SparseMatrix<double> k;
  Eigen::VectorXd m, f;
};

assembled assemble(plate_model& m) {
  const int n = m.dof_count() - 1;
  std::vector<Eigen::Triplet<double>> trip;
  assembled out;
  out.m = Eigen::VectorXd::Zero(n);
  out.f = Eigen::VectorXd::Zero(n);
  for (const auto& inst : m.instances<triangle_plate>()) {
    local_input<triangle_plate> in;
    local_output<triangle_plate> lo;
    std::array<double, 6> w{};
    element_context ctx("TRIPL", inst.name);
    ctx.work = w;
    inst.element.new_integration(ctx);
    inst.element.evaluate(in, lo, ctx);
    for (int r = 0; r < 12; ++r) {
      const int gr = inst.dofs[static_cast<std::size_t>(r)] - 1;
      if (gr < 0) continue;
      out.f(gr) -= lo.f(r);
      out.m(gr) += lo.M(r, r);
      for (int c = 0; c < 12; ++c) {
        const int gc = inst.dofs[static_cast<std::size_t>(c)] - 1;
        if (gc >= 0 && lo.K(r, c) != 0.0) trip.emplace_back(gr, gc, lo.K(r, c));
      }
    }
  }
  out.k.resize(n, n);
  out.k.setFromTriplets(trip.begin(), trip.end());
  return out;
}

/// A square plate a x a of an n x n structured mesh, simply supported or clamped on all
/// four edges, under the uniform pressure q (TRIPL's own pressure load).
struct square_plate {
  plate_model m;
  plate_mesh mesh;
  plate_sides sides;
  plate_dofs d;
  double a = 1, e = 1e6, nu = 0.3, h = 0.01, rho = 100, q = 1;
  square_plate(int n, bool clamped) {
    mesh = rectangular_plate_mesh(a, a, n, n);
    sides = find_plate_sides(mesh);
    d = add_plate_mesh(m, mesh, sides, {e, nu, h, rho, q}, boundary_fixity(mesh, sides, clamped));
  }
  double rigidity() const { return e * h * h * h / (12 * (1 - nu * nu)); }
  /// The centre vertex's deflection DOF (n even).
  dof centre(int n) const { return d.vertex[static_cast<std::size_t>((n / 2) * (n + 1) + n / 2)][2]; }
};

/// Static centre deflection of the square plate, in units of q a^4 / D.
double centre_deflection(int n, bool clamped) {
  square_plate s(n, clamped);
  const assembled g = assemble(s.m);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(g.k);
  REQUIRE(solver.info() == Eigen::Success);
  const Eigen::VectorXd u = solver.solve(g.f);
  return u(s.centre(n).index - 1) / (s.q * std::pow(s.a, 4) / s.rigidity());
}

/// First natural frequency of the square plate in units of sqrt(D / (rho h)) / a^2, by
/// inverse iteration x <- K^-1 M x on the assembled matrices (the massless side rotations
/// follow the vertex deflections through K, which is their exact static condensation) and
/// the Rayleigh quotient x^T K x / x^T M x. The start vector, the uniform deflection, is
/// symmetric like the first mode; the next symmetric mode has the frequency ratio 5
/// (Navier (1, 3) and (3, 1)), so 30 iterations converge far below the errors compared.
double first_frequency(int n, bool clamped) {
  square_plate s(n, clamped);
  s.q = 0;
  const assembled g = assemble(s.m);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(g.k);
  REQUIRE(solver.info() == Eigen::Success);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(g.m.size());
  for (const auto& v : s.d.vertex)
    if (v[2].index > 0) x(v[2].index - 1) = 1;
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd y = solver.solve(g.m.asDiagonal() * x);  // a temporary: no aliasing of x
    x = y / y.norm();
  }
  const double lambda = x.dot(g.k * x) / x.dot(g.m.asDiagonal() * x);
  return std::sqrt(lambda) * s.a * s.a / std::sqrt(s.rigidity() / (s.rho * s.h));
}

/// A 3 x 3 mesh of the unit square with its four interior vertices moved off the grid,
/// then rotated into a tilted plane and shifted: an irregular patch in space.
struct tilted_patch {
  plate_mesh mesh;
  plate_sides sides;
  Eigen::Matrix3d rot;
  Eigen::Vector3d shift{0.3, -0.7, 1.1};
  tilted_patch() {
    mesh = rectangular_plate_mesh(1, 1, 3, 3);
    const std::array<std::array<double, 3>, 4> moves{{{5, 0.07, -0.05}, {6, -0.04, 0.06}, {9, 0.05, 0.08}, {10, -0.06, -0.03}}};
    for (const auto& mv : moves) mesh.vertices[static_cast<std::size_t>(mv[0])] += spatial::vec3(mv[1], mv[2], 0);
    rot = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
    for (auto& v : mesh.vertices) v = rot * v + shift;
    sides = find_plate_sides(mesh);
  }
  /// Plane coordinates (x, y) of a point of the patch.
  Eigen::Vector2d plane(const spatial::vec3& p) const { return (rot.transpose() * (p - shift)).head<2>(); }
};
}  // namespace

TEST_SUITE("spatial/plate") {
  TEST_CASE("TRIPL: the Jacobian of a tilted triangle with mixed side signs matches finite differences") {
    testing::jacobian_checker<triangle_plate> chk{triangle_plate(triangle_plate::example())};
    local_input<triangle_plate> at;
    for (int i = 0; i < 12; ++i) {
      at.u(i) = 0.01 * std::sin(1.0 + i);
      at.a(i) = std::cos(2.0 * i);
    }
    CHECK(pradis_element_tests::jacobian_passes(chk.check(at)));
  }

  TEST_CASE("patch test (Morley 1971): constant curvature and constant membrane strain on an irregular tilted patch") {
    const tilted_patch pt;
    plate_model m;
    const double e = 2e5, nu = 0.3, h = 0.02, d = e * h * h * h / (12 * (1 - nu * nu)), cm = e * h / (1 - nu * nu);
    const plate_dofs pd = add_plate_mesh(m, pt.mesh, pt.sides, {e, nu, h, 0, 0});
    // w = (a x^2 + b x y + c y^2) / 2 along the plane normal, in-plane u = (ex x + g y / 2, g x / 2 + ey y).
    const double a = 0.3, b = -0.2, c = 0.5, ex = 1e-3, ey = -2e-3, gm = 1.5e-3;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(m.dof_count() - 1);
    for (std::size_t i = 0; i < pt.mesh.vertices.size(); ++i) {
      const Eigen::Vector2d x = pt.plane(pt.mesh.vertices[i]);
      const Eigen::Vector3d local(ex * x(0) + gm / 2 * x(1), gm / 2 * x(0) + ey * x(1),
                                  (a * x(0) * x(0) + b * x(0) * x(1) + c * x(1) * x(1)) / 2);
      const Eigen::Vector3d dg = pt.rot * local;
      for (int k = 0; k < 3; ++k) u(pd.vertex[i][static_cast<std::size_t>(k)].index - 1) = dg(k);
    }
    // Side DOF: rotation about the axis from the lower to the higher vertex number, i.e. the
    // slope dw/dm at the side's middle along m = n x t.
    for (std::size_t k = 0; k < pt.sides.sides.size(); ++k) {
      const Eigen::Vector2d p0 = pt.plane(pt.mesh.vertices[static_cast<std::size_t>(pt.sides.sides[k][0])]);
      const Eigen::Vector2d p1 = pt.plane(pt.mesh.vertices[static_cast<std::size_t>(pt.sides.sides[k][1])]);
      const Eigen::Vector2d t = (p1 - p0).normalized(), mid = 0.5 * (p0 + p1), mvec(-t(1), t(0));
      const Eigen::Vector2d grad(a * mid(0) + b / 2 * mid(1), b / 2 * mid(0) + c * mid(1));
      u(pd.side[k].index - 1) = grad.dot(mvec);
    }
    // Exact resultants in the plane frame: M = -D [w_xx + nu w_yy, w_yy + nu w_xx, (1 - nu) w_xy].
    Eigen::Matrix3d m_exact = Eigen::Matrix3d::Zero(), n_exact = Eigen::Matrix3d::Zero();
    m_exact.topLeftCorner<2, 2>() << -d * (a + nu * c), -d * (1 - nu) * b / 2, -d * (1 - nu) * b / 2, -d * (c + nu * a);
    n_exact.topLeftCorner<2, 2>() << cm * (ex + nu * ey), cm * (1 - nu) / 2 * gm, cm * (1 - nu) / 2 * gm, cm * (ey + nu * ex);
    m_exact = pt.rot * m_exact * pt.rot.transpose();
    n_exact = pt.rot * n_exact * pt.rot.transpose();
    Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
    double mworst = 0, nworst = 0;
    for (const auto& inst : m.instances<triangle_plate>()) {
      local_input<triangle_plate> in;
      for (int r = 0; r < 12; ++r) {
        const int g = inst.dofs[static_cast<std::size_t>(r)];
        in.u(r) = g > 0 ? u(g - 1) : 0.0;
      }
      local_output<triangle_plate> lo;
      std::array<double, 6> w{};
      element_context ctx("TRIPL", inst.name);
      ctx.work = w;
      inst.element.evaluate(in, lo, ctx);
      for (int r = 0; r < 12; ++r) f(inst.dofs[static_cast<std::size_t>(r)] - 1) += lo.f(r);
      const elements::detail::plate_geometry geo = inst.element.geometry();
      Eigen::Matrix<double, 3, 2> q;
      q << geo.e1, geo.e2;
      Eigen::Matrix2d ml, nl;
      ml << w[3], w[5], w[5], w[4];
      nl << w[0], w[2], w[2], w[1];
      mworst = std::max(mworst, (q * ml * q.transpose() - m_exact).norm() / m_exact.norm());
      nworst = std::max(nworst, (q * nl * q.transpose() - n_exact).norm() / n_exact.norm());
    }
    // Interior residual: every DOF but the boundary vertices' translations and boundary side rotations.
    const plate_fixity bnd = boundary_fixity(pt.mesh, pt.sides, true);
    double rworst = 0, fscale = 0;
    for (std::size_t i = 0; i < pt.mesh.vertices.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double fi = std::abs(f(pd.vertex[i][static_cast<std::size_t>(k)].index - 1));
        fscale = std::max(fscale, fi);
        if (!bnd.vertex[i][static_cast<std::size_t>(k)]) rworst = std::max(rworst, fi);
      }
    for (std::size_t k = 0; k < pt.sides.sides.size(); ++k) {
      const double fi = std::abs(f(pd.side[k].index - 1));
      fscale = std::max(fscale, fi);
      if (!bnd.side[k]) rworst = std::max(rworst, fi);
    }
    MESSAGE("patch: worst relative moment error ", mworst, ", membrane ", nworst, ", interior residual ",
            rworst / fscale, " of the largest boundary flow");
    CHECK(mworst < 1e-11);
    CHECK(nworst < 1e-11);
    CHECK(rworst < 1e-11 * fscale);
  }

  TEST_CASE("rigid-body motions: translations give zero flows exactly, a rotation by phi flows of order phi^2") {
    const triangle_plate el(triangle_plate::example());
    const elements::detail::plate_geometry g = el.geometry();
    const std::array<spatial::vec3, 3> p{spatial::vec3(el.p.x1, el.p.y1, el.p.z1), spatial::vec3(el.p.x2, el.p.y2, el.p.z2),
                                         spatial::vec3(el.p.x3, el.p.y3, el.p.z3)};
    const std::array<double, 3> sg{el.p.s12, el.p.s23, el.p.s31};
    triangle_plate::parameters q = el.p;
    q.pressure = 0;
    const triangle_plate free_el(q);
    const auto flows = [&](const local_input<triangle_plate>& in) {
      local_output<triangle_plate> lo;
      std::array<double, 6> w{};
      element_context ctx("TRIPL", "t");
      ctx.work = w;
      free_el.evaluate(in, lo, ctx);
      return lo;
    };
    local_input<triangle_plate> tr;
    for (int i = 0; i < 3; ++i) tr.u.segment<3>(3 * i) = spatial::vec3(0.3, -1.2, 0.7);
    const auto lt = flows(tr);
    CHECK(lt.f.norm() < 1e-12 * lt.K.norm());
    // Finite rotation R about the axis through P1: displacements (R - I)(P_i - P1); side rotations the
    // angle's component along each side's axis (s_k times its tangent). Linear theory: f = O(phi^2).
    const spatial::vec3 axis = spatial::vec3(0.3, -0.5, 0.8).normalized();
    std::array<double, 2> fn{};
    for (int j = 0; j < 2; ++j) {
      const double phi = j == 0 ? 1e-3 : 2e-3;
      const Eigen::Matrix3d r = Eigen::AngleAxisd(phi, axis).toRotationMatrix();
      local_input<triangle_plate> in;
      for (std::size_t i = 0; i < 3; ++i)
        in.u.segment<3>(static_cast<int>(3 * i)) = (r - Eigen::Matrix3d::Identity()) * (p[i] - p[0]);
      for (std::size_t k = 0; k < 3; ++k) {
        const spatial::vec3 t = (p[(k + 1) % 3] - p[k]).normalized();
        in.u(static_cast<int>(9 + k)) = sg[k] * phi * axis.dot(t);
      }
      fn[static_cast<std::size_t>(j)] = flows(in).f.norm();
      // first order: the flows are far below K times the displacements
      CHECK(fn[static_cast<std::size_t>(j)] < 1e-2 * lt.K.norm() * in.u.norm());
    }
    MESSAGE("rigid rotation: |f| = ", fn[0], " at 1e-3 rad, ", fn[1], " at 2e-3 rad (ratio ", fn[1] / fn[0],
            ", quadratic: 4)");
    CHECK(fn[1] / fn[0] == doctest::Approx(4).epsilon(1e-3));
    CHECK(g.area > 0);
  }

  TEST_CASE("a folded mesh: an infinitesimal rigid rotation gives zero flows in every triangle (shared side DOFs)") {
    // A 3 x 2 strip folded by 60 degrees along x = 1, its last cells skewed: the side DOF
    // is a rotation about the side line in space, so one value serves both triangles of a side, also
    // across a fold. A rigid rotation omega: d_i = omega x P_i, side DOF = omega . (unit axis from the
    // lower to the higher vertex number); every element's flows vanish to round-off.
    plate_mesh mesh = rectangular_plate_mesh(3, 1, 3, 2);
    for (auto& v : mesh.vertices) {
      const double x = v.x();
      if (x > 1) v = spatial::vec3(1 + (x - 1) * std::cos(pi / 3), v.y(), (x - 1) * std::sin(pi / 3));
      if (x > 2) v.y() += 0.2 * (x - 2);  // skewed last cells
    }
    const plate_sides sd = find_plate_sides(mesh);
    plate_model m;
    const plate_dofs pd = add_plate_mesh(m, mesh, sd, {1e5, 0.25, 0.05, 10, 0});
    const spatial::vec3 omega(0.3e-3, -0.7e-3, 0.4e-3);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(m.dof_count() - 1);
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      const spatial::vec3 d = omega.cross(mesh.vertices[i]);
      for (std::size_t c = 0; c < 3; ++c) u(pd.vertex[i][c].index - 1) = d(static_cast<int>(c));
    }
    for (std::size_t k = 0; k < sd.sides.size(); ++k) {
      const spatial::vec3 t = (mesh.vertices[static_cast<std::size_t>(sd.sides[k][1])] -
                               mesh.vertices[static_cast<std::size_t>(sd.sides[k][0])]).normalized();
      u(pd.side[k].index - 1) = omega.dot(t);
    }
    // The largest |f| / (|K| |u|) over the triangles at the DOF values u.
    const auto worst_ratio = [&] {
      double r_max = 0;
      for (const auto& inst : m.instances<triangle_plate>()) {
        local_input<triangle_plate> in;
        for (int r = 0; r < 12; ++r) in.u(r) = u(inst.dofs[static_cast<std::size_t>(r)] - 1);
        local_output<triangle_plate> lo;
        std::array<double, 6> w{};
        element_context ctx("TRIPL", inst.name);
        ctx.work = w;
        inst.element.evaluate(in, lo, ctx);
        r_max = std::max(r_max, lo.f.norm() / (lo.K.norm() * in.u.norm()));
      }
      return r_max;
    };
    const double worst = worst_ratio();
    MESSAGE("folded mesh, rigid rotation: worst |f| / (|K| |u|) over the triangles ", worst);
    CHECK(worst < 1e-13);
    // The same with one side DOF given the opposite sign: the triangles at that side bend. Bending
    // stiffness is h^2 / 12 = 2e-4 of the membrane stiffness that dominates |K|, so the measure is of
    // that order instead of round-off.
    u(pd.side[5].index - 1) = -u(pd.side[5].index - 1);
    REQUIRE(u(pd.side[5].index - 1) != 0.0);
    const double strained = worst_ratio();
    MESSAGE("  with one side DOF of the wrong sign: ", strained);
    CHECK(strained > 1e-6);
  }

  TEST_CASE("square plates under uniform pressure: centre deflection converges to Timoshenko's tables 8 and 35") {
    // Timoshenko & Woinowsky-Krieger, table 8 (simply supported, nu = 0.3): w = 0.00406 q a^4 / D, to more
    // digits 0.00406235 (the Navier series, eq. 137 there, summed to convergence); table 35 (clamped):
    // w = 0.00126 q a^4 / D (Timoshenko's truncated series), to more digits 0.00126532 (the converged series
    // value used throughout the plate-element literature). The tolerances are of the order of the tables' digits.
    for (const bool clamped : {false, true}) {
      const double exact = clamped ? 0.00126532 : 0.00406235;
      std::array<double, 3> err{};
      const std::array<int, 3> ns{8, 16, 32};
      for (std::size_t i = 0; i < 3; ++i) err[i] = centre_deflection(ns[i], clamped) / exact - 1;
      MESSAGE((clamped ? std::string("clamped") : std::string("simply supported")), ": centre deflection errors 8x8 ", err[0], ", 16x16 ",
              err[1], ", 32x32 ", err[2], "; ratios ", err[0] / err[1], ", ", err[1] / err[2]);
      // Second-order convergence (Morley: the deflection error is O(h^2)): the error falls about 4x per halving,
      // and the Richardson extrapolation w32 + (w32 - w16) / 3 removes the h^2 term.
      const double extrapolated = err[2] + (err[2] - err[1]) / 3;
      MESSAGE("  Richardson-extrapolated error ", extrapolated);
      CHECK(std::abs(err[1] / err[2]) > 3.5);
      CHECK(std::abs(err[1] / err[2]) < 4.5);
      CHECK(std::abs(err[0] / err[1]) > 3.5);
      CHECK(std::abs(extrapolated) < 1e-3);
      CHECK(std::abs(err[2]) < 0.025);
    }
  }

  TEST_CASE("square plates: first natural frequency converges to Navier (simply supported) and Leissa (clamped)") {
    for (const bool clamped : {false, true}) {
      const double exact = clamped ? 35.985 : 2 * pi * pi;
      std::array<double, 3> err{};
      const std::array<int, 3> ns{8, 16, 32};
      for (std::size_t i = 0; i < 3; ++i) err[i] = first_frequency(ns[i], clamped) / exact - 1;
      const double extrapolated = err[2] + (err[2] - err[1]) / 3;
      MESSAGE((clamped ? std::string("clamped") : std::string("simply supported")), ": first frequency errors 8x8 ", err[0], ", 16x16 ", err[1],
              ", 32x32 ", err[2], "; ratios ", err[0] / err[1], ", ", err[1] / err[2], "; Richardson-extrapolated ",
              extrapolated);
      CHECK(err[2] < 0);  // lumped mass and a soft element: from below
      CHECK(std::abs(err[1] / err[2]) > 3.5);
      CHECK(std::abs(err[1] / err[2]) < 4.5);
      CHECK(std::abs(extrapolated) < 2e-3);
    }
  }

  TEST_CASE("in the kernel: a plate without mass gives the static solution; with mass, energy is conserved") {
    // Simply supported square, 4x4 mesh, uniform pressure q from t = 0 (TRIPL's own load).
    const int n = 4;
    square_plate quasi(n, false);
    const assembled g0 = assemble(quasi.m);
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(g0.k);
    const Eigen::VectorXd u_static = solver.solve(g0.f);
    {
      // rho = 0: every M block is zero; each step solves K u = F.
      square_plate s(n, false);
      for (auto& inst : s.m.instances<triangle_plate>()) inst.element.p.rho = 0;
      simulation sim(s.m);
      sim.run({.end = 1.0, .smax = 0.5, .newton = pradis_element_tests::tight_newton});
      const double w = sim.u(s.centre(n)), w0 = u_static(s.centre(n).index - 1);
      MESSAGE("kernel without mass: centre deflection ", w, ", direct solve ", w0);
      CHECK(std::abs(w / w0 - 1) < 1e-8);
    }
    // With mass, Newmark's average acceleration on the linear system M a + K u = F conserves
    // E = v M v / 2 + u K u / 2 - F u exactly (the trapezoidal rule is symplectic and, for a quadratic
    // energy, energy-conserving: Hughes, The Finite Element Method, section 9.3), to the Newton tolerance.
    // The zero step starts the massless side rotations at 0, which is not their equilibrium under the
    // consistent pressure load (it has moments on the sides); the first step puts them there and E jumps
    // once, by a small amount. From then on E stays constant.
    square_plate s(n, false);
    const assembled g = assemble(s.m);
    simulation sim(s.m, newmark{});
    const double period = 2 * pi / (2 * pi * pi * std::sqrt(s.rigidity() / (s.rho * s.h)));  // a = 1
    const double h = period / 40;
    const auto state = [&](auto get) {
      Eigen::VectorXd x(g.m.size());
      for (int i = 0; i < x.size(); ++i) x(i) = get(dof{i + 1});
      return x;
    };
    double worst = 0, peak_strain = 0, peak_w = 0, e1 = 0;
    for (int k = 1; k <= 60; ++k) {
      sim.run({.end = k * h, .smax = h, .newton = pradis_element_tests::tight_newton});
      const Eigen::VectorXd u = state([&](dof d) { return sim.u(d); }), v = state([&](dof d) { return sim.v(d); });
      const double strain = 0.5 * u.dot(g.k * u);
      const double energy = 0.5 * v.dot(g.m.asDiagonal() * v) + strain - g.f.dot(u);
      peak_strain = std::max(peak_strain, strain);
      if (k == 1) e1 = energy;
      worst = std::max(worst, std::abs(energy - e1));
      peak_w = std::max(peak_w, sim.u(s.centre(n)));
    }
    const double w_static = u_static(s.centre(n).index - 1);
    MESSAGE("transient: E after the first step ", e1, ", then worst |E - E1| ", worst, " for a peak strain energy ",
            peak_strain, "; peak centre deflection ",
            peak_w / w_static, " x static");
    CHECK(worst < 1e-9 * peak_strain);
    CHECK(std::abs(e1) < 1e-2 * peak_strain);
    // A suddenly applied load: the first mode overshoots to twice its static part (about 97% of the
    // centre deflection), the higher modes less.
    CHECK(peak_w > 1.8 * w_static);
    CHECK(peak_w < 2.05 * w_static);
  }

  TEST_CASE("a side rotation coupled to a spatial rotational node through SHC3 (shaft coupling about the side axis)") {
    // The strip of examples/models/plate_strip.prd (L = 1 m by b = 0.5 m, two triangles, supported against
    // rigid motion only), its end side x = L (axis +Y, from vertex 1 to 3) coupled by SHC3 (axis +Y, stiffness
    // kc) to a spatial rotational node, which RSD3 (kr) holds to the ground and M3 loads with the moment P about
    // +Y. The plate alone is a rotational spring kp = b D (1 - nu^2) / L on its end side (pure bending, exact for
    // Morley), so the node turns by psi = P / (kr + kc kp / (kc + kp)) and the side by theta = kc psi / (kc + kp);
    // SHC3 and RSD3 are exact for a rotation about a fixed axis at any angle.
    using coupled_model = plate_model;
    coupled_model m;
    const double e = 2.1e11, nu = 0.3, h = 0.01, l = 1, b = 0.5, p = 10, kc = 1e6, kr = 1e3;
    const plate_mesh mesh = rectangular_plate_mesh(l, b, 1, 1);  // vertices 0 (0, 0), 1 (L, 0), 2 (0, b), 3 (L, b)
    const plate_sides sd = find_plate_sides(mesh);
    plate_fixity fix;
    fix.vertex = {{true, true, true}, {false, true, false}, {false, false, false}, {false, false, false}};
    fix.side.assign(sd.sides.size(), false);
    int end_side = -1;
    for (std::size_t k = 0; k < sd.sides.size(); ++k) {
      const auto [a0, a1] = sd.sides[k];
      if ((a0 == 0 && a1 == 1) || (a0 == 0 && a1 == 2)) fix.side[k] = true;  // slopes at y = 0 and x = 0
      if (a0 == 1 && a1 == 3) end_side = static_cast<int>(k);
    }
    REQUIRE(end_side >= 0);
    const plate_dofs pd = add_plate_mesh(m, mesh, sd, {e, nu, h, 0, 0}, fix);
    const rotation_node node = m.add_rotation_node("node");
    const rotation_node fixed = m.add_rotation_node("fixed", m.ground(), m.ground(), m.ground());
    m.add<shaft_coupling>("coupling", {0, 1, 0, kc, 0, 0}, pd.side[static_cast<std::size_t>(end_side)], node);
    m.add<rotational_spring_damper>("holder", {kr, 0}, fixed, node);
    m.add<spatial_torque>("moment", {0, p, 0, 0, 0, 0, 0, 0}, node);
    simulation sim(m);
    sim.run({.end = 1.0, .smax = 0.5, .newton = pradis_element_tests::tight_newton});
    const double d = e * h * h * h / (12 * (1 - nu * nu)), kp = b * d * (1 - nu * nu) / l;
    const double psi = p / (kr + kc * kp / (kc + kp)), theta = kc * psi / (kc + kp);
    const spatial::quaternion q = spatial::node_quaternion(sim, node);
    const double psi_sim = 2 * std::atan2(q(1), q(3));  // rotation about +Y
    const double theta_sim = sim.u(pd.side[static_cast<std::size_t>(end_side)]);
    // The strip's end deflection w = a L^2 / 2 with a = -theta / L (theta = -dw/dx at x = L).
    const double w_sim = sim.u(pd.vertex[1][2]);
    MESSAGE("SHC3 coupling: node ", psi_sim, " rad (exact ", psi, "), side ", theta_sim, " rad (exact ", theta,
            "), end deflection ", w_sim, " m (exact ", -theta * l / 2, ")");
    CHECK(std::abs(psi_sim / psi - 1) < 1e-8);
    CHECK(std::abs(theta_sim / theta - 1) < 1e-8);
    CHECK(std::abs(w_sim / (-theta * l / 2) - 1) < 1e-8);
  }

  TEST_CASE("TRIPL refuses bad parameters (100) and a wrong count (101); the mesh helper a bad mesh (110)") {
    const triangle_plate::parameters ok = triangle_plate::example();
    auto run = [](triangle_plate::parameters p) {
      plate_model m;
      const auto d = m.add_dofs(12);
      m.add<triangle_plate>("t1", p, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8], d[9], d[10], d[11]);
      simulation sim(m);
      return error_from([&] { sim.run({.end = 0.1, .smax = 0.05}); });
    };
    auto with = [&](auto change) {
      triangle_plate::parameters p = ok;
      change(p);
      return run(p);
    };
    const auto code = error_code::invalid_parameter;
    check_error(with([](auto& p) { p.e = 0; }), code, "TRIPL", "t1", "Young's modulus");
    check_error(with([](auto& p) { p.nu = 0.5; }), code, "TRIPL", "t1", "Poisson's ratio");
    check_error(with([](auto& p) { p.nu = -1; }), code, "TRIPL", "t1", "Poisson's ratio");
    check_error(with([](auto& p) { p.h = -0.01; }), code, "TRIPL", "t1", "thickness");
    check_error(with([](auto& p) { p.rho = -1; }), code, "TRIPL", "t1", "density");
    check_error(with([](auto& p) { p.z2 = std::nan(""); }), code, "TRIPL", "t1", "finite");
    check_error(with([](auto& p) { p.s23 = 0.5; }), code, "TRIPL", "t1", "side sign");
    check_error(with([](auto& p) {  // vertex 3 on the line through 1 and 2
                  p.x3 = 2 * p.x2 - p.x1;
                  p.y3 = 2 * p.y2 - p.y1;
                  p.z3 = 2 * p.z2 - p.z1;
                }),
                code, "TRIPL", "t1", "do not span a triangle");
    check_error(with([](auto& p) {  // vertices 1 and 2 coincide
                  p.x2 = p.x1;
                  p.y2 = p.y1;
                  p.z2 = p.z1;
                }),
                code, "TRIPL", "t1", "do not span a triangle");
    CHECK_FALSE(run(ok).has_value());
    plate_model m;
    const auto d = m.add_dofs(12);
    const std::array<double, 16> sixteen{};
    check_error(error_from([&] { m.add_by_name("TRIPL", "t2", d, sixteen); }), error_code::parameter_count, "TRIPL",
                "t2", "got 16 parameters");
    const auto e1 = error_from([] { (void)rectangular_plate_mesh(1, 1, 0, 2); });
    REQUIRE(e1.has_value());
    CHECK(e1->number() == 110);
    plate_mesh bad = rectangular_plate_mesh(1, 1, 1, 1);
    bad.triangles[1] = {0, 2, 2};
    const auto e2 = error_from([&] { (void)find_plate_sides(bad); });
    REQUIRE(e2.has_value());
    CHECK(e2->number() == 110);
    bad.triangles[1] = {0, 2, 7};
    CHECK(error_from([&] { (void)find_plate_sides(bad); }).has_value());
  }

  TEST_CASE("mesh helper: sides, signs and boundary DOFs of a structured mesh") {
    const plate_mesh mesh = rectangular_plate_mesh(2, 1, 4, 2);
    const plate_sides s = find_plate_sides(mesh);
    // Euler's formula for a triangulated disc: V - E + F = 1.
    CHECK(mesh.vertices.size() == 15);
    CHECK(mesh.triangles.size() == 16);
    CHECK(static_cast<int>(s.sides.size()) == 15 + 16 - 1);
    int boundary = 0;
    for (std::size_t k = 0; k < s.sides.size(); ++k) boundary += s.on_boundary(static_cast<int>(k)) ? 1 : 0;
    CHECK(boundary == 2 * (4 + 2));
    // A shared side: the two triangles traverse it in opposite directions, so their signs differ.
    for (std::size_t k = 0; k < s.sides.size(); ++k) {
      if (s.on_boundary(static_cast<int>(k))) continue;
      std::vector<double> sg;
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (std::size_t j = 0; j < 3; ++j)
          if (s.of_triangle[t][j] == static_cast<int>(k)) sg.push_back(s.signs[t][j]);
      REQUIRE(sg.size() == 2);
      CHECK(sg[0] == -sg[1]);
    }
    plate_model m;
    const plate_dofs pd = add_plate_mesh(m, mesh, s, {1e6, 0.3, 0.01, 1, 0}, boundary_fixity(mesh, s, true));
    CHECK(m.dof_count() == 1 + 3 * 3 + (30 - 12));  // ground, 3 interior vertices, the interior sides
    CHECK(pd.elements.size() == 16);
    CHECK(pd.vertex[0][2] == m.ground());
    CHECK(pd.vertex[6][2] != m.ground());
  }
}
