// BEAM3's flows and exact tangent (the closed-form gradient of the strain energy,
// differentiated once with first-order dual numbers) against an independent
// reference: the second derivatives of the same energy by nested dual numbers
// (tests/spatial/beam_reference.hpp), at random states with large rigid rotations of
// the whole beam and large relative rotations of its ends. Both are exact
// derivatives, so they agree to round-off. Also: the flows of the flows-only call
// (the zero step) are those of the call with the Jacobian, and the strain energy is
// invariant under a rigid rotation of the whole beam (the corotational frame
// removes it, Crisfield vol. 2, ch. 17) while its gradient turns with it.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "beam_reference.hpp"
#include "pradis/elements/library.hpp"

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

/// The crankshaft's journal section (examples/crankshaft): steel, diameter 50 mm, 30 mm
/// long; E A / (E I / L^2) = 5.8 (a short element), the other, the example's oblique beam.
elastic_beam journal() {
  const double dia = 0.05, a = std::numbers::pi * dia * dia / 4, i = std::numbers::pi * std::pow(dia, 4) / 64;
  return elastic_beam({2.1e11, 8.1e10, a, i, i, 2 * i, 0.05, 0, 0, 0.08, 0, 0, 0, 1, 0});
}

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
}
