// Error paths of the spatial elements not reached by the other spatial tests:
// non-finite geometry of SD3 and SPH3, a non-finite inertia tensor or centre-of-mass
// offset of BODY3, non-finite parameters of BEAMI3 and non-finite reduced matrices of
// FLEX3 (all code 100 at the new integration, in a run), and the SD3 length AB close
// to zero (code 75: in a run whose attachment points coincide, and by direct
// evaluations). Each error names the element type, the instance and the cause.

#include <doctest/doctest.h>

#include <array>
#include <limits>
#include <optional>
#include <string>

#include "../elements/element_test_support.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/elements/spatial/reduced_body.hpp"

using namespace pradis;
using namespace pradis::elements;
using pradis_element_tests::check_error;
using pradis_element_tests::error_from;

namespace {
constexpr double ee_nan = std::numeric_limits<double>::quiet_NaN();
constexpr double ee_inf = std::numeric_limits<double>::infinity();

// A good free body: unit mass and inertia, centre of mass at the reference point.
const rigid_body::parameters ee_body{1, 1, 1, 1, 0, 0, 0, 0, 0, 0};

// Runs a short simulation and returns the error it throws, or nothing.
template <class Model>
std::optional<pradis::error> ee_run(Model& m) {
  simulation sim(m);
  return error_from([&] { sim.run({.end = 0.02, .smax = 0.01}); });
}

/// One model type, with the element types of this file's tests but ee_flex, for them: each model
/// type compiles the drivers anew.
using element_errors_model = pradis::model<rigid_body, spatial_spring_damper, spherical_joint, beam_inertia>;
// A body "body" hung by SD3 "sd" from a ground point; returns the run's error.
std::optional<pradis::error> ee_sd3_error(const spatial_spring_damper::parameters& p) {
  element_errors_model m;
  const auto x = m.add_dofs(3, "x");
  const rotation_node r = m.add_rotation_node("r");
  const dof G = m.ground();
  m.add<rigid_body>("body", ee_body, x[0], x[1], x[2], r);
  m.add<spatial_spring_damper>("sd", p, G, G, G, G, G, G, x[0], x[1], x[2], r);
  return ee_run(m);
}

// A body "body" on SPH3 "ball" to the ground; returns the run's error.
std::optional<pradis::error> ee_sph3_error(const spherical_joint::parameters& p) {
  element_errors_model m;
  const auto x = m.add_dofs(3, "x");
  const rotation_node r = m.add_rotation_node("r");
  const dof G = m.ground();
  m.add<rigid_body>("body", ee_body, x[0], x[1], x[2], r);
  m.add<spherical_joint>("ball", p, G, G, G, G, G, G, x[0], x[1], x[2], r);
  return ee_run(m);
}

// A single free BODY3 "body"; returns the run's error.
std::optional<pradis::error> ee_body_error(const rigid_body::parameters& p) {
  element_errors_model m;
  const auto x = m.add_dofs(3, "x");
  const rotation_node r = m.add_rotation_node("r");
  m.add<rigid_body>("body", p, x[0], x[1], x[2], r);
  return ee_run(m);
}

// A single BEAMI3 "m1" between two free nodes; returns the run's error.
std::optional<pradis::error> ee_beami3_error(const beam_inertia::parameters& p) {
  element_errors_model m;
  const auto d = m.add_dofs(6);
  m.add<beam_inertia>("m1", p, d[0], d[1], d[2], m.add_rotation_node("ra"), d[3], d[4], d[5],
                      m.add_rotation_node("rb"));
  return ee_run(m);
}
// A good steel-like beam of 1 m along X, section axis y along Y.
const beam_inertia::parameters ee_beami3{7800, 1e-4, 1e-9, 1e-9, 2e-9, 0, 0, 0, 1, 0, 0, 0, 1, 0};

// FLEX3 with two boundary nodes and no modes.
using ee_flex = reduced_body<2, 0>;
// A single FLEX3 "bar" on two free nodes; returns the run's error.
std::optional<pradis::error> ee_flex3_error(const ee_flex::parameters& p) {
  model<ee_flex> m;
  const auto d = m.add_dofs(6);
  m.add<ee_flex>("bar", p, d[0], d[1], d[2], m.add_rotation_node("ra"), d[3], d[4], d[5], m.add_rotation_node("rb"));
  return ee_run(m);
}
// Good FLEX3 parameters: nodes at (0, 0, 0) and (1, 0, 0), K = 0 (free of every rigid motion),
// M = identity (positive definite).
ee_flex::parameters ee_flex3() {
  ee_flex::parameters p;
  p.x0 = {0, 0, 0, 1, 0, 0};
  return p;
}

// SD3 evaluated directly (identity quaternions) with the body end displaced by `xb`.
std::optional<pradis::error> ee_sd3_evaluate(const spatial_spring_damper::parameters& p, const spatial::vec3& xb) {
  const spatial_spring_damper e(p);
  element_context ctx("SD3", "sd");
  std::array<double, 3> work{};
  ctx.work = work;
  e.new_integration(ctx);
  local_input<spatial_spring_damper> in;
  in.u(12) = in.u(13) = 1.0;  // the hidden q4 of both ends: identity rotations
  in.u.segment<3>(6) = xb;
  local_output<spatial_spring_damper> out;
  return error_from([&] { e.evaluate(in, out, ctx); });
}
}  // namespace

TEST_SUITE("spatial/element errors") {
  TEST_CASE("SD3: non-finite positions or offsets are code 100") {
    // Ground point (0, 0, 1), body at the origin: a good spring.
    const spatial_spring_damper::parameters ok{0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 100.0, 1.0, 0.0};
    CHECK_FALSE(ee_sd3_error(ok).has_value());
    // PAR 1 (X of a), 6 (z of A), 8 (Y of b), 11 (y of B): a position and an offset of each end.
    for (const std::size_t i : {std::size_t{0}, std::size_t{5}, std::size_t{7}, std::size_t{10}}) {
      CAPTURE(i);
      std::array<double, 15> v{ok.xa0, ok.ya0, ok.za0, ok.rax, ok.ray, ok.raz, ok.xb0, ok.yb0,
                               ok.zb0, ok.rbx, ok.rby, ok.rbz, ok.k, ok.l0, ok.c};
      v[i] = i % 2 == 0 ? ee_nan : -ee_inf;
      check_error(ee_sd3_error(spatial_spring_damper::from_parameters(v).p), error_code::invalid_parameter, "SD3",
                  "sd", "positions and offsets must be finite");
    }
  }

  TEST_CASE("SD3: attachment points that coincide make the length AB close to zero: code 75") {
    // In a run: the ground point and the body's point are both at the origin from the start (NEWINT
    // accepts that; the first evaluation finds no direction).
    const spatial_spring_damper::parameters at_origin{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 100.0, 0.0, 0.0};
    const auto e = ee_sd3_error(at_origin);
    check_error(e, error_code::singular_situation, "SD3", "sd", "the length AB has become close to zero");
    REQUIRE(e.has_value());
    CHECK(std::string(e->what()).find("sd") != std::string::npos);
    // Through the offsets: the body's point (0, 0, 1) + (0, 0, -1) is the ground point.
    const spatial_spring_damper::parameters by_offset{0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, -1, 100.0, 0.0, 0.0};
    check_error(ee_sd3_error(by_offset), error_code::singular_situation, "SD3", "sd", "close to zero");
    // Directly: a spring from (0, 0, 1) to the origin, the body end moved onto the ground point, or
    // within 1e-9 max(1, L0) of it.
    const spatial_spring_damper::parameters p{0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 100.0, 1.0, 0.0};
    CHECK_FALSE(ee_sd3_evaluate(p, {0, 0, 0.5}).has_value());
    check_error(ee_sd3_evaluate(p, {0, 0, 1}), error_code::singular_situation, "SD3", "sd", "length AB");
    check_error(ee_sd3_evaluate(p, {0, 5e-10, 1}), error_code::singular_situation, "SD3", "sd", "close to zero");
    CHECK_FALSE(ee_sd3_evaluate(p, {0, 1e-6, 1}).has_value());
  }

  TEST_CASE("SPH3: non-finite positions or offsets are code 100") {
    const spherical_joint::parameters ok{{0, 0, 0, 0, 0, 0, 0, 0, -0.5, 0, 0, 0.5}, 1e5, 100.0};
    CHECK_FALSE(ee_sph3_error(ok).has_value());
    for (int which = 0; which < 4; ++which) {
      CAPTURE(which);
      spherical_joint::parameters bad = ok;
      if (which == 0) bad.geo.xa0 = ee_nan;
      if (which == 1) bad.geo.raz = ee_inf;
      if (which == 2) bad.geo.zb0 = -ee_inf;
      if (which == 3) bad.geo.rby = ee_nan;
      check_error(ee_sph3_error(bad), error_code::invalid_parameter, "SPH3", "ball",
                  "positions and offsets must be finite");
    }
  }

  TEST_CASE("BODY3: a non-finite inertia tensor or centre-of-mass offset is code 100") {
    CHECK_FALSE(ee_body_error(ee_body).has_value());
    auto with = [](auto f) {
      rigid_body::parameters p = ee_body;
      f(p);
      return p;
    };
    for (const auto& p : {with([](auto& q) { q.jxx = ee_nan; }), with([](auto& q) { q.jzz = ee_inf; }),
                          with([](auto& q) { q.jxy = ee_nan; }), with([](auto& q) { q.jyz = -ee_inf; })})
      check_error(ee_body_error(p), error_code::invalid_parameter, "BODY3", "body", "the inertia tensor must be finite");
    for (const auto& p : {with([](auto& q) { q.cx = ee_nan; }), with([](auto& q) { q.cy = ee_inf; }),
                          with([](auto& q) { q.cz = -ee_inf; })})
      check_error(ee_body_error(p), error_code::invalid_parameter, "BODY3", "body",
                  "the offset of the centre of mass must be finite");
    // A finite offset is fine.
    CHECK_FALSE(ee_body_error(with([](auto& q) { q.cz = 0.3; })).has_value());
  }

  TEST_CASE("BEAMI3: a non-finite parameter is code 100") {
    CHECK_FALSE(ee_beami3_error(ee_beami3).has_value());
    for (std::size_t i : {std::size_t{0}, std::size_t{4}, std::size_t{5}, std::size_t{10}, std::size_t{13}}) {
      CAPTURE(i);
      std::array<double, 14> v{ee_beami3.rho, ee_beami3.a,  ee_beami3.iy, ee_beami3.iz, ee_beami3.ip,
                               ee_beami3.xa,  ee_beami3.ya, ee_beami3.za, ee_beami3.xb, ee_beami3.yb,
                               ee_beami3.zb,  ee_beami3.vx, ee_beami3.vy, ee_beami3.vz};
      v[i] = i % 2 == 0 ? ee_nan : ee_inf;
      check_error(ee_beami3_error(beam_inertia::from_parameters(v).p), error_code::invalid_parameter, "BEAMI3", "m1",
                  "the parameters must be finite");
    }
  }

  TEST_CASE("FLEX3: a non-finite K or M is code 100") {
    CHECK_FALSE(ee_flex3_error(ee_flex3()).has_value());
    {
      ee_flex::parameters p = ee_flex3();
      p.k(0, 0) = ee_nan;
      check_error(ee_flex3_error(p), error_code::invalid_parameter, "FLEX3", "bar", "K and M must be finite");
    }
    {
      ee_flex::parameters p = ee_flex3();
      p.k(3, 7) = p.k(7, 3) = ee_inf;
      check_error(ee_flex3_error(p), error_code::invalid_parameter, "FLEX3", "bar", "K and M must be finite");
    }
    {
      ee_flex::parameters p = ee_flex3();
      p.m(11, 11) = ee_inf;
      check_error(ee_flex3_error(p), error_code::invalid_parameter, "FLEX3", "bar", "K and M must be finite");
    }
    {
      ee_flex::parameters p = ee_flex3();
      p.m(2, 5) = p.m(5, 2) = ee_nan;
      check_error(ee_flex3_error(p), error_code::invalid_parameter, "FLEX3", "bar", "K and M must be finite");
    }
  }
}
