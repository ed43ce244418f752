// Rotational nodes under the BDF driver (include/pradis/integrators/bdf/rotations.hpp,
// docs/bdf.md "Rotational nodes"): the quaternion norm Lq is brought back to 1 by
// scaling the node's potentials and their history.
//  * Exactness: every formula of the rotational nodes is invariant under q -> l q
//    (docs/rotations.md), so renormalising at every step must give the motion of the
//    run that never renormalises, up to the Newton tolerance. Checked on the torque-free
//    body of Hairer, Lubich and Wanner (Geometric Numerical Integration, section IV.1;
//    inertias (2, 1, 2/3)), whose body angular velocity is periodic with
//    T = 10.7314652348828 (omega_b(T) = omega_b(0) exactly).
//  * The heavy symmetric top on the exact spherical joint (examples/spinning_top,
//    SPH3X) at DRLTX = 1e-2: without renormalisation BDF's low-order steps shrink Lq
//    (a BDF1 step by h^2 |q'|^2 / 2) until it leaves [0.9, 1.1] (code 75); with it the
//    run reaches its end. The spin omega_3 about the symmetry axis is an exact invariant
//    of the symmetric top (gravity and the joint act on the axis: no moment about it;
//    Goldstein, Classical Mechanics, section 5.7).

#include <doctest/doctest.h>

#include <cmath>

#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/spatial/node_state.hpp"
#include "rigid_body_problems.hpp"

using namespace pradis;

TEST_SUITE("integrators/bdf") {
  TEST_CASE("rotational nodes: renormalising Lq at every step gives the motion of the run that never does") {
    namespace rigid = wp::rigid;
    using pradis::spatial::vec3;
    const vec3 w0 = rigid::hlw_omega0();
    struct result {
      vec3 w;             // body angular velocity at T
      Eigen::Matrix3d r;  // orientation at T
      double lq = 0;
    };
    auto run = [&](int k, double band) {
      rigid::freebody_model b;
      bdf_simulation sim(b.m, bdf_options{.max_order = k, .fixed_order = true, .lq_renormalise = band});
      run_options o;
      o.end = rigid::hlw_period;
      o.smax = rigid::hlw_period / 400;
      o.smin = 1e-6 * o.smax;
      o.error_control = false;
      o.drltx = 1e-11;  // Newton tolerance far below the discretisation error
      o.dabsx = 1e-11;
      sim.run(o);
      const Eigen::Matrix3d r = spatial::node_rotation(sim, b.r);
      return result{r.transpose() * spatial::node_angular_velocity(sim, b.r), r,
                    spatial::node_quaternion(sim, b.r).norm()};
    };
    for (int k : {2, 3}) {
      CAPTURE(k);
      const result every = run(k, 0.0), never = run(k, 1.0);
      const double scale = w0.lpNorm<Eigen::Infinity>();
      const double discretisation = (never.w - w0).lpNorm<Eigen::Infinity>() / scale;
      const double dw = (every.w - never.w).lpNorm<Eigen::Infinity>() / scale;
      const double dr = (every.r - never.r).lpNorm<Eigen::Infinity>();
      MESSAGE("BDF" << k << ": |w(T) - w(0)| " << discretisation << "; renormalised against not: w " << dw << ", R "
                    << dr << "; Lq " << every.lq << " against " << never.lq);
      CHECK(std::abs(every.lq - 1) < 1e-12);
      CHECK(std::abs(never.lq - 1) > 1e-6);  // the run without renormalisation did drift
      CHECK(dw < 1e-7);
      CHECK(dr < 1e-7);
      CHECK(dw < 1e-3 * discretisation);
    }
  }

  TEST_CASE("rotational nodes: the heavy top on SPH3X at DRLTX = 1e-2 runs with Lq kept near 1 (code 75 without)") {
    struct outcome {
      double lq_max = 0;  // max |Lq - 1| after the accepted steps
      double w3 = 0;      // spin about the symmetry axis at the end
      double w3_0 = 0;
    };
    auto run = [](double tol, double band) {
      pradis_examples::top_parameters tp;
      tp.exact_joint = true;
      pradis_examples::spinning_top t(tp);
      bdf_simulation sim(t.m, bdf_options{.lq_renormalise = band});
      outcome r;
      r.w3_0 = t.w3;
      sim.on_step([&](const auto& s) {
        r.lq_max = std::max(r.lq_max, std::abs(spatial::node_quaternion(s, t.r).norm() - 1));
      });
      run_options o;
      o.end = 1.0;
      o.smax = 0.05;
      o.smin = 1e-12;
      o.error_control = true;
      o.drltx = tol;
      o.dabsx = tol;
      sim.run(o);
      r.w3 = (spatial::node_rotation(sim, t.r).transpose() * spatial::node_angular_velocity(sim, t.r))(2);
      return r;
    };
    for (double tol : {1e-2, 1e-3}) {
      CAPTURE(tol);
      const outcome r = run(tol, bdf_options{}.lq_renormalise);
      MESSAGE("DRLTX " << tol << ": max |Lq - 1| " << r.lq_max << ", spin " << r.w3 << " (exact " << r.w3_0 << ")");
      CHECK(r.lq_max <= 0.011);  // the band 0.01, plus at most one step's drift
      CHECK(std::abs(r.w3 - r.w3_0) < 20 * tol * r.w3_0);
    }
    try {
      run(1e-2, 1.0);
      FAIL("the run without renormalisation did not fail");
    } catch (const error& e) {
      CHECK(e.code() == error_code::singular_situation);
      CHECK(std::string(e.what()).find("Lq far from 1") != std::string::npos);
    }
  }
}
