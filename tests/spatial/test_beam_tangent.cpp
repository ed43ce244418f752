// BEAM3's flows and exact tangent (the closed-form gradient of the strain energy,
// differentiated once with first-order dual numbers) against an independent
// reference: the second derivatives of the same energy by nested dual numbers
// (tests/spatial/beam_reference.hpp), at random states with large rigid rotations of
// the whole beam and large relative rotations of its ends. Both are exact
// derivatives, so they agree to round-off. Also: the flows of the flows-only call
// (the zero step) are those of the call with the Jacobian, and the strain energy is
// invariant under a rigid rotation of the whole beam (the corotational frame
// removes it, Crisfield vol. 2, ch. 17) while its gradient turns with it. And in a
// transient with large 3D bending (a cantilever of BEAM3 + BEAMI3 under a tip force
// and a tip moment), the element and the reference (as a test-only element type)
// give the same motion.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "beam_reference.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis::spatial;

namespace {

/// A random unit quaternion of a rotation by up to max_angle about a random axis.
quaternion random_rotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  vec3 axis(uni(rng), uni(rng), uni(rng));
  while (axis.norm() < 1e-3) axis = vec3(uni(rng), uni(rng), uni(rng));
  return from_axis_angle(axis.normalized(), max_angle * uni(rng));
}

/// Random admissible states of e: the whole beam turned by a rotation up to pi (chord
/// and both nodes), the chord stretched and tilted, the ends turned relative to it by
/// up to `relative` rad, the nodal quaternions scaled by norms 0.5 .. 2.
template <class F>
int for_random_states(const elastic_beam& e, double relative, F&& f) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const auto g = e.geometry();
  int n = 0;
  for (int trial = 0; trial < 200 && n < 60; ++trial) {
    const quaternion rigid = random_rotation(rng, std::numbers::pi);
    const mat3 r = rotation_matrix(rigid);
    const vec3 chord0 = g.b - g.a;
    const vec3 chord = r * (chord0 * (1 + 0.2 * uni(rng)) + 0.2 * chord0.norm() * vec3(uni(rng), uni(rng), uni(rng)));
    const quaternion qa = multiply(rigid, random_rotation(rng, relative)) * (1.25 + 0.75 * uni(rng));
    const quaternion qb = multiply(rigid, random_rotation(rng, relative)) * (1.25 + 0.75 * uni(rng));
    local_input<elastic_beam> in;
    in.u.head<3>() = vec3(uni(rng), uni(rng), uni(rng));
    in.u.segment<3>(6) = in.u.head<3>() + chord - chord0;
    in.u.segment<3>(3) = qa.head<3>();
    in.u(12) = qa(3);
    in.u.segment<3>(9) = qb.head<3>();
    in.u(13) = qb(3);
    if (!e.admissible(in)) continue;
    ++n;
    f(in);
  }
  return n;
}

/// max |a - b| over the rows' largest |b| (each row relative to its own scale).
template <class A, class B>
double row_relative_difference(const A& a, const B& b) {
  double worst = 0;
  for (int i = 0; i < a.rows(); ++i) {
    const double scale = b.row(i).cwiseAbs().maxCoeff();
    if (scale == 0) {
      worst = std::max(worst, a.row(i).cwiseAbs().maxCoeff());
      continue;
    }
    worst = std::max(worst, (a.row(i) - b.row(i)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

/// A short steel element like the crankshaft's journals (examples/crankshaft): diameter
/// 50 mm, 30 mm long, A L^2 / I = 5.8 (the other beam tested: BEAM3's example, oblique,
/// with an unsymmetric section).
elastic_beam journal() {
  const double dia = 0.05, a = std::numbers::pi * dia * dia / 4, i = std::numbers::pi * std::pow(dia, 4) / 64;
  return elastic_beam({2.1e11, 8.1e10, a, i, i, 2 * i, 0.05, 0, 0, 0.08, 0, 0, 0, 1, 0});
}

/// BEAM3 with the reference flows and tangent (beam_reference.hpp): a test-only element type.
struct reference_beam {
  static constexpr pradis::passport passport{.name = "BEAM3REF", .ext = 12, .ent = 2, .par = 15, .wrk = 3, .adr = 1, .ign = 23};
  static constexpr std::array<rotation_slot, 2> rotation_nodes = elastic_beam::rotation_nodes;
  static constexpr element_help help = elastic_beam::help;
  using parameters = elastic_beam::parameters;
  elastic_beam beam;
  explicit reference_beam(parameters q) : beam(q) {}
  static reference_beam from_parameters(std::span<const double> v) {
    return reference_beam(elastic_beam::from_parameters(v).p);
  }
  void new_integration(element_context& ctx) const { beam.new_integration(ctx); }
  void evaluate(const local_input<reference_beam>& in, local_output<reference_beam>& out, element_context& ctx) const {
    local_input<elastic_beam> bin;
    bin.u = in.u;
    local_output<elastic_beam> flows;  // the singularity checks and the work
    flows.want_jacobian = false;
    beam.evaluate(bin, flows, ctx);
    const auto r = pradis_beam_reference::evaluate(beam, in.u);
    out.f = r.f;
    if (out.want_jacobian) out.K = r.K;
  }
};

/// A cantilever of 4 elements Beam + BEAMI3 along X (L = 1 m), clamped at the root,
/// with a tip force in Z and a tip moment about Y, both ramped in: large 3D bending.
template <class Beam>
struct bent_cantilever {
  model<Beam, beam_inertia, spatial_force, body_torque> m;
  std::vector<dof> watched;  // every translation and rotation potential
  bent_cantilever() {
    const double e = 1e4, g = 4e3, a = 0.03, iy = 1e-4, iz = 2e-4, j = 1.5e-4, rho = 100;
    const dof gr = m.ground();
    rotation_node ra = m.add_rotation_node("r0", gr, gr, gr);
    std::array<dof, 3> xa{gr, gr, gr};
    constexpr int n = 4;
    for (int i = 0; i < n; ++i) {
      const auto x = m.add_dofs(3, "x" + std::to_string(i + 1));
      const std::array<dof, 3> xb{x[0], x[1], x[2]};
      const rotation_node rb = m.add_rotation_node("r" + std::to_string(i + 1));
      const double x0 = static_cast<double>(i) / n, x1 = static_cast<double>(i + 1) / n;
      m.template add<Beam>("beam" + std::to_string(i + 1), {e, g, a, iy, iz, j, x0, 0, 0, x1, 0, 0, 0, 1, 0}, xa[0],
                           xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
      m.template add<beam_inertia>("mass" + std::to_string(i + 1),
                                   {rho, a, iy, iz, iy + iz, x0, 0, 0, x1, 0, 0, 0, 1, 0}, xa[0], xa[1], xa[2], ra,
                                   xb[0], xb[1], xb[2], rb);
      for (dof d : xb) watched.push_back(d);
      for (dof d : {rb.q1, rb.q2, rb.q3, rb.q4}) watched.push_back(d);
      xa = xb;
      ra = rb;
    }
    // P(t) = P/2 (1 - cos(2 pi t)), ramped over 0.5 s: 3 E Iy P / L^3 at the end (a tip deflection of 1 L
    // in the linear theory) and a moment about Y of half the one that rolls the bar into a circle.
    const double p = 3 * e * iy, mo = std::numbers::pi * e * iz;
    m.template add<spatial_force>("force", {0, 0, p / 2, 0, 0, p / 2, 1, -90}, xa[0], xa[1], xa[2]);
    m.template add<body_torque>("moment", {0, mo / 2, 0, 0, mo / 2, 0, 1, -90}, ra);
  }
};

}  // namespace

TEST_SUITE("spatial/beam") {
  TEST_CASE("BEAM3 tangent and flows equal the nested-dual Hessian of the strain energy at large rotations") {
    for (const elastic_beam& e : {elastic_beam(elastic_beam::example()), journal()}) {
      for (double relative : {0.3, 2.5}) {
        CAPTURE(relative);
        element_context ctx("BEAM3", "b");
        std::array<double, 3> work{};
        ctx.work = work;
        e.new_integration(ctx);
        double worst_f = 0, worst_k = 0, worst_flows_only = 0;
        const int n = for_random_states(e, relative, [&](const local_input<elastic_beam>& in) {
          local_output<elastic_beam> out;
          e.evaluate(in, out, ctx);
          const auto ref = pradis_beam_reference::evaluate(e, in.u);
          worst_f = std::max(worst_f, (out.f - ref.f).cwiseAbs().maxCoeff() / ref.f.cwiseAbs().maxCoeff());
          worst_k = std::max(worst_k, row_relative_difference(out.K, ref.K));
          local_output<elastic_beam> flows;
          flows.want_jacobian = false;
          e.evaluate(in, flows, ctx);
          worst_flows_only = std::max(worst_flows_only, (flows.f - out.f).cwiseAbs().maxCoeff() / out.f.cwiseAbs().maxCoeff());
        });
        MESSAGE(n, " states: flows ", worst_f, ", tangent ", worst_k, " (row-relative), flows-only call ",
                worst_flows_only);
        CHECK(n >= 40);
        CHECK(worst_f < 1e-11);
        CHECK(worst_k < 1e-10);
        CHECK(worst_flows_only < 1e-13);
      }
    }
  }

  TEST_CASE("BEAM3 under a rigid rotation: the same strain energy, the flows turned with the beam") {
    const elastic_beam e(elastic_beam::example());
    element_context ctx("BEAM3", "b");
    std::array<double, 3> work{};
    ctx.work = work;
    e.new_integration(ctx);
    std::mt19937 rng(7);
    for_random_states(e, 1.0, [&](const local_input<elastic_beam>& in) {
      const quaternion rot = random_rotation(rng, 3.0);
      const mat3 r = rotation_matrix(rot);
      const auto g = e.geometry();
      const vec3 chord = g.b - g.a + in.u.segment<3>(6) - in.u.head<3>();
      local_input<elastic_beam> turned = in;
      turned.u.segment<3>(6) = turned.u.head<3>() + r * chord - (g.b - g.a);
      for (int node : {0, 1}) {
        const int i1 = node == 0 ? 3 : 9, i4 = node == 0 ? 12 : 13;
        const quaternion q = multiply(rot, quaternion(in.u(i1), in.u(i1 + 1), in.u(i1 + 2), in.u(i4)));
        turned.u.segment<3>(i1) = q.head<3>();
        turned.u(i4) = q(3);
      }
      local_output<elastic_beam> a, b;
      e.evaluate(in, a, ctx);
      const double ua = ctx.work[2];
      e.evaluate(turned, b, ctx);
      const double ub = ctx.work[2];
      CHECK(std::abs(ub - ua) <= 1e-12 * std::max(ua, 1e-300));
      const double scale = a.f.cwiseAbs().maxCoeff();
      for (int i : {0, 3, 6, 9}) CHECK((b.f.segment<3>(i) - r * a.f.segment<3>(i)).norm() <= 1e-11 * scale);
    });
  }

  TEST_CASE("BEAM3 in a transient with large 3D bending: the same motion as with the nested-dual reference tangent") {
    // Both tangents are exact: Newton converges along the same path; the motions agree to round-off.
    bent_cantilever<elastic_beam> a;
    bent_cantilever<reference_beam> b;
    simulation sa(a.m);
    simulation sb(b.m);
    constexpr newton_options tight{.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-10, .drlti = 0, .itr = 10};
    double worst = 0;  // over the translations [m] (L = 1 m) and the quaternion potentials (|q| = 1 initially)
    for (int k = 1; k <= 20; ++k) {
      sa.run({.end = 0.025 * k, .smax = 0.025, .newton = tight});
      sb.run({.end = 0.025 * k, .smax = 0.025, .newton = tight});
      for (std::size_t i = 0; i < a.watched.size(); ++i)
        worst = std::max(worst, std::abs(sa.u(a.watched[i]) - sb.u(b.watched[i])));
    }
    const std::size_t tip = a.watched.size() - 7;  // x, y, z, q1..q4 of the last node
    const double tip_move = std::hypot(sa.u(a.watched[tip]), sa.u(a.watched[tip + 1]), sa.u(a.watched[tip + 2]));
    MESSAGE("tip displacement ", tip_move, " m, largest difference ", worst, "; Newton iterations ",
            sa.statistics().newton_iterations, " and ", sb.statistics().newton_iterations);
    CHECK(tip_move > 0.2);  // large deformation: the tip moves by a good part of L
    CHECK(worst <= 1e-10);
    CHECK(sa.statistics().newton_iterations == sb.statistics().newton_iterations);
  }
}
