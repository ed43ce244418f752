// MD, LINKD and MEKS: planar elements. Analytic answers through real
// simulations (rigid-body motion, static stretch of a link, uniform rotation of
// an eccentric mass and its centripetal reactions) and the code-101 / code-100
// / code-75 checks.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "element_test_support.hpp"

using namespace pradis;
using namespace pradis::elements;
using namespace pradis_element_tests;

/// The one model type of this file's tests (every element type they use), so that the drivers are
/// compiled once for them all.
using planar_model = pradis::model<planar_inertia, constant_force, initial_displacement, initial_velocity, planar_link,
    point_mass, linear_damper, displacement_source, eccentric_mass>;
TEST_SUITE("elements/MD") {
  TEST_CASE("a free MD body under constant forces and a constant moment moves on exact parabolas") {
    // m x'' = Fx, m y'' = Fy, J theta'' = Mz (Newton-Euler for a free rigid body, forces at the
    // centre of mass): each coordinate is q0 + q0' t + (load / inertia) t^2 / 2. Newmark
    // integrates constant accelerations exactly.
    const double m = 2.0, j = 0.25, fx = 3.0, fy = -2.0, mz = 0.5, x0 = 0.1, vy0 = 0.4, w0 = -1.0;
    planar_model md;
    const auto q = md.add_dofs(3, "q");
    md.add<planar_inertia>("body", {m, j}, q[0], q[1], q[2]);
    md.add<constant_force>("fx", {fx}, q[0]);
    md.add<constant_force>("fy", {fy}, q[1]);
    md.add<constant_force>("mz", {mz}, q[2]);
    md.add<initial_displacement>("x0", {x0}, q[0]);
    md.add<initial_velocity>("vy0", {vy0}, q[1]);
    md.add<initial_velocity>("w0", {w0}, q[2]);
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time();
      worst = std::max({worst, std::abs(s.u(q[0]) - (x0 + fx / m * t * t / 2)),
                        std::abs(s.u(q[1]) - (vy0 * t + fy / m * t * t / 2)),
                        std::abs(s.u(q[2]) - (w0 * t + mz / j * t * t / 2)), std::abs(s.a(q[2]) - mz / j)});
    });
    sim.run(fixed_step(2.0, 0.01));
    CHECK(worst < 1e-11);
    CHECK(sim.u(q[2]) == doctest::Approx(w0 * 2 + mz / j * 2).epsilon(1e-12));
  }

  TEST_CASE("a flat MD with a wrong parameter count is refused with code 101 naming MD and the instance") {
    planar_model md;
    const auto q = md.add_dofs(3);
    const std::array<double, 3> three{1.0, 2.0, 3.0};
    check_error(flat_add_error<planar_inertia>(md, "body", q, three), error_code::parameter_count, "MD", "body",
                "got 3 parameters");
  }

  TEST_CASE("a negative mass or moment of inertia stops the run with code 100 naming the instance and the parameter") {
    struct bad_case {
      planar_inertia::parameters p;
      const char* mention;
    };
    for (const auto& b : {bad_case{{-1.0, 0.1}, "mass m"}, bad_case{{1.0, -0.1}, "moment of inertia J"},
                          bad_case{{not_a_number, 0.1}, "mass m"}, bad_case{{1.0, not_a_number}, "moment of inertia J"}}) {
      const std::string mention = b.mention;
      CAPTURE(mention);
      planar_model md;
      const auto q = md.add_dofs(3);
      md.add<planar_inertia>("body", b.p, q[0], q[1], q[2]);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "MD", "body",
                  b.mention);
    }
  }

  TEST_CASE("an infinite mass or moment of inertia stops the run with code 100") {
    struct bad_case {
      planar_inertia::parameters p;
      const char* mention;
    };
    for (const auto& b : {bad_case{{inf, 0.1}, "mass m"}, bad_case{{1.0, inf}, "moment of inertia J"}}) {
      const std::string mention = b.mention;
      CAPTURE(mention);
      planar_model md;
      const auto q = md.add_dofs(3);
      md.add<planar_inertia>("body", b.p, q[0], q[1], q[2]);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "MD", "body",
                  b.mention);
    }
  }
}

namespace {
/// Result of the LINKD stretch scene.
struct stretch_run {
  std::vector<double> axial, transverse;  // displacement of B along and across the link, per output
  std::vector<double> times;
  std::array<double, 3> work{};           // W(1..3) at the end
  double axial_error_ratio = 0;           // max |axial - exact| / (Peano bound), see below
};

/// Link A-B of length l0 at angle `angle` (A fixed at (1, 2)); B carries a mass m and dampers c
/// on both axes (critically damped along the link) and an axial pull P along the link.
stretch_run run_stretch(double angle) {
  const double l0 = 2.0, k = 100.0, m = 1.0, c = 20.0, p = 5.0, h = 0.01, end = 5.0;
  const double xa = 1.0, ya = 2.0, ex = std::cos(angle), ey = std::sin(angle);
  planar_model md;
  const dof bx = md.add_dof("bx"), by = md.add_dof("by");
  const auto link =
      md.add<planar_link>("link", {xa, ya, xa + l0 * ex, ya + l0 * ey, k}, md.ground(), md.ground(), bx, by);
  md.add<point_mass>("mx", {m}, bx);
  md.add<point_mass>("my", {m}, by);
  md.add<linear_damper>("cx", {c}, bx, md.ground());
  md.add<linear_damper>("cy", {c}, by, md.ground());
  md.add<constant_force>("px", {p * ex}, bx);
  md.add<constant_force>("py", {p * ey}, by);
  simulation sim(md);
  stretch_run r;
  // Along the link: m u'' + c u' + k u = P, c = 2 sqrt(k m): u = P/k [1 - (1 + wt) exp(-wt)], w = 10.
  // Trapezoidal error: in the energy norm |y| = sqrt(u^2 + u'^2/w^2) the damped flow, the Cayley
  // step and (I - hA/2)^-1 are contractions, so the Peano form of the local error gives
  // |u_n - u(t_n)| <= sum_j (t_j+1 - t_j)^3/12 sup_[t_j, t_j+1] |y'''|, and
  // |y'''(t)| = (P/k) w^3 g(wt), g(x) = exp(-x) sqrt((x - 2)^2 + (3 - x)^2), decreasing on x >= 0.
  const double w = std::sqrt(k / m);
  auto g = [](double x) { return std::exp(-x) * std::sqrt((x - 2) * (x - 2) + (3 - x) * (3 - x)); };
  double bound = 0, last_t = 0;
  sim.on_output([&](const auto& s) {
    const double t = s.time(), ux = s.u(bx), uy = s.u(by);
    bound += std::pow(t - last_t, 3) / 12 * (p / k) * std::pow(w, 3) * g(w * last_t);
    last_t = t;
    const double axial = ux * ex + uy * ey;
    r.times.push_back(t);
    r.axial.push_back(axial);
    r.transverse.push_back(-ux * ey + uy * ex);
    const double exact = p / k * (1 - (1 + w * t) * std::exp(-w * t));
    r.axial_error_ratio = std::max(r.axial_error_ratio, std::abs(axial - exact) / (bound + 1e-12));
  });
  sim.run(fixed_step(end, h));
  for (int i = 0; i < 3; ++i) r.work[static_cast<std::size_t>(i)] = md.work(link)[static_cast<std::size_t>(i)];
  return r;
}
}  // namespace

TEST_SUITE("elements/LINKD") {
  TEST_CASE("a link pulled by an axial force P settles at the elongation P/k with W(2) = L0 + P/k and W(3) = P") {
    // Manual Fig. 3.5 (static stretch of the ideal elastic link): elongation P/k, axial force P.
    const double l0 = 2.0, k = 100.0, p = 5.0;
    const stretch_run r = run_stretch(0.0);
    CHECK(r.axial.back() == doctest::Approx(p / k).epsilon(1e-10));
    CHECK(std::abs(r.transverse.back()) < 1e-14);
    CHECK(r.work[0] == doctest::Approx(l0).epsilon(1e-15));
    CHECK(r.work[1] == doctest::Approx(l0 + p / k).epsilon(1e-12));
    CHECK(r.work[2] == doctest::Approx(p).epsilon(1e-9));
    // The whole transient is the critically damped step response within the trapezoidal bound.
    CHECK(r.axial_error_ratio <= 1.0);
  }

  TEST_CASE("a rotated link behaves exactly like the aligned one: same axial motion, no transverse motion") {
    // The link's response is frame-independent: rotating the whole scene by 35 degrees must give the
    // same motion along the link at every output and none across it (both axes carry the same mass
    // and damper, the pull is along the link, and its transverse stiffness P/L is positive).
    const double l0 = 2.0, k = 100.0, p = 5.0;
    const stretch_run aligned = run_stretch(0.0);
    const stretch_run rotated = run_stretch(35 * deg);
    REQUIRE(aligned.times.size() == rotated.times.size());
    double worst_axial = 0, worst_transverse = 0;
    for (std::size_t i = 0; i < aligned.times.size(); ++i) {
      worst_axial = std::max(worst_axial, std::abs(rotated.axial[i] - aligned.axial[i]));
      worst_transverse = std::max(worst_transverse, std::abs(rotated.transverse[i]));
    }
    CHECK(worst_axial < 1e-12);
    CHECK(worst_transverse < 1e-12);
    CHECK(rotated.work[0] == doctest::Approx(l0).epsilon(1e-15));
    CHECK(rotated.work[1] == doctest::Approx(l0 + p / k).epsilon(1e-12));
    CHECK(rotated.work[2] == doctest::Approx(p).epsilon(1e-9));
    CHECK(rotated.axial_error_ratio <= 1.0);
  }

  TEST_CASE("a link whose ends are driven into each other stops the run with code 75 naming the instance") {
    // XSRC on the x of A and of B: xA = 0.5 sin(pi t / 2), xB = 1 - 0.5 sin(pi t / 2): the length
    // 1 - sin(pi t / 2) reaches zero at t = 1 (a step lands there: 100 steps of 0.01).
    planar_model md;
    const dof ax = md.add_dof("ax"), bx = md.add_dof("bx");
    md.add<planar_link>("link", {0.0, 0.0, 1.0, 0.0, 100.0}, ax, md.ground(), bx, md.ground());
    md.add<displacement_source>("pa", {0.5, 0.25, 0.0, 0.0}, ax);
    md.add<displacement_source>("pb", {-0.5, 0.25, 0.0, 0.0}, bx);
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(2.0, 0.01)); }), error_code::singular_situation, "LINKD", "link",
                "close to zero");
    CHECK(sim.time() == doctest::Approx(1.0).epsilon(1e-5));
  }

  TEST_CASE("a link whose ends are driven through each other between two steps stops the run with code 75") {
    // xA = 0.75 sin(pi t / 2), xB = 1 - 0.75 sin(pi t / 2): the length 1 - 1.5 sin(pi t / 2) passes
    // through zero at t = (2/pi) asin(2/3) = 0.4646, between the steps 0.46 and 0.47; afterwards B
    // is on the other side of A and the link's direction has flipped. The link went through zero
    // length during the run (help: "code 75 if the current length becomes close to zero").
    planar_model md;
    const dof ax = md.add_dof("ax"), bx = md.add_dof("bx");
    md.add<planar_link>("link", {0.0, 0.0, 1.0, 0.0, 100.0}, ax, md.ground(), bx, md.ground());
    md.add<displacement_source>("pa", {0.75, 0.25, 0.0, 0.0}, ax);
    md.add<displacement_source>("pb", {-0.75, 0.25, 0.0, 0.0}, bx);
    simulation sim(md);
    check_error(error_from([&] { sim.run(fixed_step(1.0, 0.01)); }), error_code::singular_situation, "LINKD", "link",
                "close to zero");
    CHECK(sim.time() < 0.47);
  }

  TEST_CASE("a flat LINKD with a wrong parameter count is refused with code 101 naming LINKD and the instance") {
    planar_model md;
    const std::array<dof, 4> d{md.add_dof(), md.add_dof(), md.add_dof(), md.add_dof()};
    const std::array<double, 4> four{0.0, 0.0, 1.0, 0.0};
    check_error(flat_add_error<planar_link>(md, "link", d, four), error_code::parameter_count, "LINKD", "link",
                "got 4 parameters");
  }

  TEST_CASE("coincident points or a negative stiffness stop the run with code 100 naming the instance") {
    struct bad_case {
      planar_link::parameters p;
      const char* mention;
    };
    for (const auto& b : {bad_case{{0.5, -0.25, 0.5, -0.25, 100.0}, "coincide"},
                          bad_case{{0.0, 0.0, 1.0, 0.0, -100.0}, "stiffness k"},
                          bad_case{{0.0, 0.0, 1.0, 0.0, not_a_number}, "stiffness k"}}) {
      const std::string mention = b.mention;
      CAPTURE(mention);
      planar_model md;
      const auto q = md.add_dofs(3);
      md.add<planar_inertia>("body", {1.0, 1.0}, q[0], q[1], q[2]);
      md.add<planar_link>("link", b.p, md.ground(), md.ground(), q[0], q[1]);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "LINKD", "link",
                  b.mention);
    }
  }

  TEST_CASE("a non-finite LINKD stiffness or coordinate stops the run with code 100") {
    struct bad_case {
      planar_link::parameters p;
      const char* mention;
    };
    for (const auto& b : {bad_case{{0.0, 0.0, 1.0, 0.0, inf}, "stiffness k"},
                          bad_case{{0.0, 0.0, inf, 0.0, 100.0}, "finite"},
                          bad_case{{0.0, not_a_number, 1.0, 0.0, 100.0}, "finite"}}) {
      CAPTURE(b.p.k);
      CAPTURE(b.p.xb0);
      CAPTURE(b.p.ya0);
      planar_model md;
      const auto q = md.add_dofs(3);
      md.add<planar_inertia>("body", {1.0, 1.0}, q[0], q[1], q[2]);
      md.add<planar_link>("link", b.p, md.ground(), md.ground(), q[0], q[1]);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "LINKD", "link",
                  b.mention);
    }
  }
}

TEST_SUITE("elements/MEKS") {
  TEST_CASE("an eccentric mass on a fixed pivot set spinning by V0 rotates uniformly: theta = w0 t") {
    // Fixed axis, no torque: m R^2 theta'' = 0 (the M_z row with a_x = a_y = 0), so theta = w0 t.
    const double w0 = 3.0;
    planar_model md;
    const dof th = md.add_dof("theta");
    md.add<eccentric_mass>("rotor", {1.5, 0.2, 30.0}, md.ground(), md.ground(), th);
    md.add<initial_velocity>("spin", {w0}, th);
    simulation sim(md);
    double worst = 0;
    sim.on_output([&](const auto& s) {
      worst = std::max({worst, std::abs(s.u(th) - w0 * s.time()), std::abs(s.v(th) - w0), std::abs(s.a(th))});
    });
    sim.run(fixed_step(2.0, 0.01));
    CHECK(worst < 1e-12);
  }

  TEST_CASE("the pivot sources of a spinning eccentric mass carry the centripetal force -m R w^2 (cos phi, sin phi)") {
    // Uniform rotation phi = w0 t + alpha about a pivot held at (0, 0) by two XSRC: the point mass
    // needs the centripetal force -m R w0^2 (cos phi, sin phi), supplied through the pivot DOFs:
    // W(1) of each source = the MEKS flow on its DOF (F_x, F_y of eccentric_mass.hpp with a = 0).
    const double m = 1.5, r = 0.2, alpha_deg = 30.0, w0 = 3.0;
    planar_model md;
    const dof x = md.add_dof("x"), y = md.add_dof("y"), th = md.add_dof("theta");
    md.add<eccentric_mass>("rotor", {m, r, alpha_deg}, x, y, th);
    md.add<initial_velocity>("spin", {w0}, th);
    const auto sx = md.add<displacement_source>("hold x", {0.0, 0.0, 0.0, 0.0}, x);
    const auto sy = md.add<displacement_source>("hold y", {0.0, 0.0, 0.0, 0.0}, y);
    simulation sim(md);
    double worst_theta = 0, worst_reaction = 0;
    int outputs = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), phi = w0 * t + alpha_deg * deg, fc = m * r * w0 * w0;
      worst_theta = std::max(worst_theta, std::abs(s.u(th) - w0 * t));
      worst_reaction = std::max({worst_reaction, std::abs(md.work(sx)[0] + fc * std::cos(phi)),
                                 std::abs(md.work(sy)[0] + fc * std::sin(phi))});
      ++outputs;
    });
    sim.run(fixed_step(2.0, 0.01));
    CHECK(outputs == 201);
    CHECK(worst_theta < 1e-12);
    CHECK(worst_reaction < 1e-10);
  }

  TEST_CASE("a free body made of MD and MEKS spins uniformly while its pivot circles the drifting centre of mass") {
    // Rigid body: MD (mass M, inertia J at the pivot) plus MEKS (m at radius R). No external load:
    // the centre of mass x_c = x + rho cos(phi), y_c = y + rho sin(phi), rho = m R / (M + m), moves
    // uniformly and the angular velocity stays w0. Exactly: eliminating a_x, a_y from the three
    // balances leaves (J + m R^2 M / (M + m)) theta'' = 0, so theta = w0 t also for the scheme, and
    //   x = x0 + rho cos(alpha) - rho cos(phi) + (vx0 - rho w0 sin(alpha)) t,
    //   y = y0 + rho sin(alpha) - rho sin(phi) + (vy0 + rho w0 cos(alpha)) t,   phi = w0 t + alpha.
    // The scheme then integrates x'' = rho w0^2 cos(phi(t)) (known at every step) by the trapezoidal
    // rule twice: |v error| <= t h^2/12 rho w0^4 and
    // |x error| <= t h^2/12 rho w0^3 + sum_j h (t_j+1 h^2/12 rho w0^4) <= h^2/12 rho w0^3 (t + w0 (t^2 + t h)/2).
    const double big_m = 2.0, j = 0.05, m = 1.5, r = 0.2, alpha = 30 * deg, vx0 = 0.3, w0 = 2.0, h = 0.01;
    const double rho = m * r / (big_m + m);
    planar_model md;
    const auto q = md.add_dofs(3, "q");
    md.add<planar_inertia>("hub", {big_m, j}, q[0], q[1], q[2]);
    md.add<eccentric_mass>("rotor", {m, r, 30.0}, q[0], q[1], q[2]);
    md.add<initial_velocity>("vx0", {vx0}, q[0]);
    md.add<initial_velocity>("spin", {w0}, q[2]);
    simulation sim(md);
    double worst_theta = 0, worst_ratio = 0, worst_error = 0;
    sim.on_output([&](const auto& s) {
      const double t = s.time(), phi = w0 * t + alpha;
      const double x = rho * std::cos(alpha) - rho * std::cos(phi) + (vx0 - rho * w0 * std::sin(alpha)) * t;
      const double y = rho * std::sin(alpha) - rho * std::sin(phi) + rho * w0 * std::cos(alpha) * t;
      const double bound = h * h / 12 * rho * std::pow(w0, 3) * (t + w0 * (t * t + t * h) / 2) + 1e-11;
      worst_theta = std::max(worst_theta, std::abs(s.u(q[2]) - w0 * t));
      worst_ratio = std::max({worst_ratio, std::abs(s.u(q[0]) - x) / bound, std::abs(s.u(q[1]) - y) / bound});
      worst_error = std::max({worst_error, std::abs(s.u(q[0]) - x), std::abs(s.u(q[1]) - y)});
    });
    sim.run(fixed_step(3.0, h));
    CHECK(worst_theta < 1e-11);
    CHECK(worst_ratio <= 1.0);
    CHECK(worst_error > 1e-8);  // the scheme's error is visible: the comparison is not vacuous
  }

  TEST_CASE("a flat MEKS with a wrong parameter count is refused with code 101 naming MEKS and the instance") {
    planar_model md;
    const auto q = md.add_dofs(3);
    const std::array<double, 2> two{1.0, 0.2};
    check_error(flat_add_error<eccentric_mass>(md, "rotor", q, two), error_code::parameter_count, "MEKS", "rotor",
                "got 2 parameters");
  }

  TEST_CASE("a negative mass or eccentricity or a non-finite angle stops the run with code 100 naming the instance") {
    struct bad_case {
      eccentric_mass::parameters p;
      const char* mention;
    };
    for (const auto& b : {bad_case{{-1.0, 0.2, 0.0}, "mass m"}, bad_case{{1.0, -0.2, 0.0}, "eccentricity R"},
                          bad_case{{1.0, 0.2, not_a_number}, "angle alpha"}, bad_case{{1.0, 0.2, inf}, "angle alpha"},
                          bad_case{{not_a_number, 0.2, 0.0}, "mass m"}}) {
      const std::string mention = b.mention;
      CAPTURE(mention);
      planar_model md;
      const auto q = md.add_dofs(3);
      md.add<planar_inertia>("hub", {1.0, 1.0}, q[0], q[1], q[2]);
      md.add<eccentric_mass>("rotor", b.p, q[0], q[1], q[2]);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "MEKS", "rotor",
                  b.mention);
    }
  }

  TEST_CASE("an infinite MEKS mass or eccentricity stops the run with code 100") {
    struct bad_case {
      eccentric_mass::parameters p;
      const char* mention;
    };
    for (const auto& b : {bad_case{{inf, 0.2, 0.0}, "mass m"}, bad_case{{1.0, inf, 0.0}, "eccentricity R"}}) {
      const std::string mention = b.mention;
      CAPTURE(mention);
      planar_model md;
      const auto q = md.add_dofs(3);
      md.add<planar_inertia>("hub", {1.0, 1.0}, q[0], q[1], q[2]);
      md.add<eccentric_mass>("rotor", b.p, q[0], q[1], q[2]);
      simulation sim(md);
      check_error(error_from([&] { sim.run(fixed_step(0.1, 0.01)); }), error_code::invalid_parameter, "MEKS", "rotor",
                  b.mention);
    }
  }
}
