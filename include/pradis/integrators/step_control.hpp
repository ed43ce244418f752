#pragma once
/// \file
/// Step-size control of pradis::simulation: the local error test of a
/// converged step (PRADIS's velocity-based estimate, per-DOF tolerances scaled
/// by the DOFs' nominal potentials), the three-branch rule for the next step,
/// the growth of the nominal step without error control and the choice of a
/// step that meets the next output time.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/domain.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis {

/// The result of the local error test of one step.
struct error_test {
  bool passed = true;    ///< the local error is within the tolerance on every DOF
  double h_next = 0;     ///< the step the rule proposes next (or for the redo)
  int worst = -1;        ///< the DOF with the smallest tolerance / error ratio, or -1
  double worst_error = 0, worst_tolerance = 0;  ///< its estimate and tolerance
};

/// The largest factor by which pradis::simulation's error control lets the step grow from
/// one accepted step to the next once the run has had an error rejection (before it, PRADIS's
/// rule alone, which proposes SMAX at once where the estimate vanishes, so that a run started
/// at SMIN reaches its step in one or two steps). A ball falling under error control onto a
/// contact whose step recommendation ends the step that reaches it inside the contact
/// otherwise alternated between that step, rejected with an estimate 1.7e4 times the
/// tolerance, and a step of 4.6e-5 of it, accepted with no error in the free flight: 16,999
/// rejections in 20,203 steps (tests/spatial/test_sphere_contact.cpp, "CSPHPL: the
/// Hunt-Crossley rebound ..."); with the bound 11 in 3,236. PRADIS's rule proposes more
/// than 10 h only where the estimate is below 1/24,414 of the tolerance ((10 / 0.8)^4).
inline constexpr double max_step_growth = 10.0;

/// The round-off floor of the error test (local_error_test, `floor_on`) serves steps at the
/// scale the stage has reached, such as its first steps from SMIN; a step that fell below this
/// fraction of the stage's largest accepted step is tested without it. A pendulum chain of ten
/// LINKX links under NEWMARK at DRLTX = 1e-4, whose undamped multiplier alternation no step
/// resolves, shrank its step from 1e-3 s to SMIN = 1e-12 s, passed there on the floor and then
/// took 6.6 million steps of about 2e-8 s to a state 8.7e-2 off the reference; without
/// the floor there it ends with code 141, naming the alternation (tests/integrators/test_error_control.cpp).
inline constexpr double roundoff_floor_drop = 1e-3;

/// Local error test of a converged step from s0 to s (step h).
/// First-order schemes (Stoermer, Newmark with gamma != 1/2, and schemes
/// outside the alpha family): predictor v_p = v_n + h a_n (PREDICT: with a
/// linearly extrapolated from a_prev over h_prev), lp = |v_p - v| / 2.
/// Second-order members of the alpha family: lp = h |beta - 1/6| |a_{n+1} - a_n|,
/// the displacement error estimate of the Newmark family per unit step
/// (velocity units, O(h^2) like PRADIS's), with a_{n+1} - a_n taken as the
/// two-step difference (a_{n+1} - a_{n-1}) h / (h + h_prev) once the previous
/// step is known (filters unresolved stiff ringing). Per DOF lp <= DABSX potential +
/// DRLTX |v|; r = min tolerance / lp; next step c h r (r < 1/4), c h sqrt(r)
/// (r <= 7), c h r^(1/4), c = 0.8, clamped to [max(SMIN, CONTROL), SMAX].
/// DOFs marked in `skip` (per DOF index; empty: none) are left out: the
/// multipliers of index-3 constraints. The tolerance of a DOF marked in
/// `constrained` (held by an index-3 constraint, or massless) also holds the round-off floor of
/// its estimate, 4 eps |u| / h (velocity units), which matters only at steps far
/// below the motion's time scale (first steps of SMIN); with `floor_on` false it does not
/// (the driver's rule: roundoff_floor_drop).
template <Integrator Scheme, class Assembler>
error_test local_error_test(const Scheme& scheme, const Assembler& as, const global_state& s, const global_state& s0,
                            const Eigen::VectorXd& a_prev, double h_prev, double h, const run_options& opt,
                            const std::vector<dof_scale>& scales, const std::vector<char>& skip = {},
                            const std::vector<char>& constrained = {}, bool floor_on = true) {
  bool second = false;
  double beta = 0;
  if constexpr (AlphaFamilyIntegrator<Scheme>) {
    const alpha_parameters q = scheme.coefficients_set();
    second = std::abs(q.gamma - 0.5 - (q.alpha_f - q.alpha_m)) < 1e-12;
    beta = q.beta;
  }
  error_test out;
  const double dabsx = effective_dabsx(opt);
  constexpr double roundoff_floor = 4 * std::numeric_limits<double>::epsilon();
  // Two-step difference for the second-order estimate when the previous step is known:
  // (a_{n+1} - a_{n-1}) h / (h + h_prev) equals a_{n+1} - a_n to leading order for a
  // smooth motion, but cancels the alternating (period 2h) ringing of stiff modes that
  // the step does not resolve and that the trapezoidal rule keeps undamped (a penalty
  // joint, a stiff link): those made the one-step difference erratic and the step
  // controller reject 20-30 % of the steps (docs/architecture.md, "Error control").
  const bool two_step = opt.two_step_estimate && second && h_prev > 0 && a_prev.size() == s0.a.size();
  double r = std::numeric_limits<double>::infinity();
  for (int i = 0; i < as.equations(); ++i) {
    const auto d = as.dof_of(i);
    if (static_cast<std::size_t>(d) < skip.size() && skip[static_cast<std::size_t>(d)]) continue;
    double lp;
    if (second) {
      lp = two_step ? h * std::abs(beta - 1.0 / 6.0) * std::abs(s.a(d) - a_prev(d)) * h / (h + h_prev)
                    : h * std::abs(beta - 1.0 / 6.0) * std::abs(s.a(d) - s0.a(d));
    } else {
      double ap = s0.a(d);
      if (opt.predict && h_prev > 0 && a_prev.size() == s0.a.size()) ap += (s0.a(d) - a_prev(d)) * h / h_prev;
      lp = 0.5 * std::abs(s0.v(d) + h * ap - s.v(d));
    }
    // On a DOF that an index-3 constraint holds, plus the estimate's round-off floor: Newton puts
    // its position on the constraint to round-off, eps |u|, which reaches its velocity and
    // acceleration, and lp, as about eps |u| / h. A failed test below that floor would shrink the
    // step and raise the floor: the heavy top on SPH3X started at SMIN = 1e-12 s under HHT at
    // DRLTX = 1e-8 had lp = 2.8e-6 on q1 and stopped at SMIN.
    const bool held =
        floor_on && static_cast<std::size_t>(d) < constrained.size() && constrained[static_cast<std::size_t>(d)];
    const double tol = dabsx * scales[static_cast<std::size_t>(d)].potential + opt.drltx * std::abs(s.v(d)) +
                       (held ? roundoff_floor * std::abs(s.u(d)) / h : 0.0);
    if (lp > 0 && tol / lp < r) {
      r = tol / lp;
      out.worst = d;
      out.worst_error = lp;
      out.worst_tolerance = tol;
    }
  }
  constexpr double c = 0.8;
  const double f = r < 0.25 ? r : (r <= 7.0 ? std::sqrt(r) : std::pow(r, 0.25));
  const double floor = std::max(opt.smin, opt.control);
  out.h_next = std::clamp(std::isfinite(f) ? c * h * f : opt.smax, std::min(floor, opt.smax), opt.smax);
  out.passed = r >= 1.0;
  return out;
}

/// Nominal step without error control: doubled (up to SMAX) after three
/// successive full steps.
inline void grow_nominal_step(double& h_nominal, int& successes, double smax) {
  if (h_nominal < smax && ++successes >= 3) {
    h_nominal = std::min(2 * h_nominal, smax);
    successes = 0;
  }
}

/// The step to take from t towards `target` (the next output time or END):
/// the nominal step, or the element-recommended one (STEPMD, unless IGNORE),
/// ended exactly at the target when it would reach it, and two equal steps
/// rather than a full one and a sliver. `clipped`: the step ends at the target.
inline double choose_step(double t, double target, double h_nominal, double recommended, const run_options& opt,
                          bool& clipped) {
  double h = h_nominal;
  if (!opt.ignore && recommended < h) h = std::max(recommended, opt.smin);
  clipped = false;
  const double remaining = target - t;
  if (t + h >= target - 1e-9 * h) {
    h = remaining;
    clipped = true;
  } else if (remaining < 2 * h) {
    h = 0.5 * remaining;
  }
  return h;
}

}  // namespace pradis
