#pragma once
/// \file
/// Loss of precision of the displacement in a step of an alpha-family scheme.
///
/// The schemes compute the displacement at t + h from the velocity unknown v as
///     u = u0 + h ((1 - r) v0 + r v) + h^2 (1/2 - r) p0,   r = beta / gamma,
/// (newmark.hpp), so u carries a round-off of about
///     eps (|u0| + h (|1 - r| |v0| + r |v|) + h^2 |1/2 - r| |p0|).
/// On a DOF whose element frequencies are far above the step (omega h >> 1),
/// h |v| and h^2 |p| can exceed |u| by many orders of magnitude (with HHT and
/// generalized-alpha, whose gamma != 2 beta; Newmark's u = u0 + h (v0 + v) / 2 is
/// immune to the p0 term), and u is then resolved only to that round-off: the
/// result is silently wrong. The simulation compares the bound with the
/// displacement counterpart of the error-control tolerance, DABSX (times the
/// DOF's nominal potential) + DRLTX |u|, after every accepted step and writes
/// a warning to the diagnostics log, once per stage, for the first DOF where the
/// bound exceeds it.

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/domain.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis::detail {

/// A DOF whose displacement is resolved only to `roundoff` in this step.
struct precision_loss {
  int dof = -1;            ///< global DOF index
  double roundoff = 0;     ///< round-off bound of u
  double tolerance = 0;    ///< DABSX potential + DRLTX |u| of that DOF
  double magnitude = 0;    ///< h |v| + h^2 |p0|: the terms u is computed from
};

/// The first DOF (in equation order) whose displacement round-off after the step
/// from s0 to s (step h) exceeds its displacement tolerance; none for a scheme
/// outside the alpha family (its update formula is unknown here).
template <class Scheme, class Assembler>
std::optional<precision_loss> displacement_precision_loss(const Scheme& scheme, const Assembler& as,
                                                          const global_state& s, const global_state& s0, double h,
                                                          const run_options& opt,
                                                          const std::vector<dof_scale>& scales) {
  if constexpr (!AlphaFamilyIntegrator<Scheme>) {
    return std::nullopt;
  } else {
    const alpha_parameters q = scheme.coefficients_set();
    const double r = q.beta / q.gamma, eps = std::numeric_limits<double>::epsilon();
    const double dabsx = effective_dabsx(opt);
    for (int i = 0; i < as.equations(); ++i) {
      const auto d = as.dof_of(i);
      const double big = h * (std::abs(1.0 - r) * std::abs(s0.v(d)) + r * std::abs(s.v(d))) +
                         h * h * std::abs(0.5 - r) * std::abs(s0.p(d));
      const double bound = eps * (std::abs(s0.u(d)) + big);
      const double tol = dabsx * scales[static_cast<std::size_t>(d)].potential + opt.drltx * std::abs(s.u(d));
      if (bound > tol) return precision_loss{static_cast<int>(d), bound, tol, big};
    }
    return std::nullopt;
  }
}

/// The warning for a loss of precision on DOF `name` at time t with step h.
inline std::string precision_warning_text(const precision_loss& l, const std::string& name, double t, double h) {
  return "warning: loss of precision: at t = " + num(t) + " with step " + num(h) + " the displacement of DOF '" +
         name + "' is resolved only to " + num(l.roundoff) + " (above its tolerance DABSX + DRLTX |u| = " +
         num(l.tolerance) + "): it is computed from h |v| + h^2 |a| = " + num(l.magnitude) +
         ", an element far stiffer than the step resolves (omega h >> 1); take a smaller step, or NEWMARK, whose "
         "displacement does not depend on the acceleration";
}

/// The warning at the end of an error-controlled stage in which SMAX, not the
/// tolerance, decided at least 90 % of the steps.
inline std::string smax_warning_text(long steps_at_smax, long controlled_steps, const run_options& opt) {
  return "warning: error control: " + std::to_string(steps_at_smax) + " of " + std::to_string(controlled_steps) +
         " steps were SMAX = " + num(opt.smax) + ": the local error stayed below DABSX = " +
         num(effective_dabsx(opt)) + " + DRLTX = " + num(opt.drltx) +
         " |v|, so SMAX, not the tolerance, set the accuracy of this stage";
}

/// Whether a scheme has no numerical damping (the alpha family with alpha_m =
/// alpha_f = 0 and gamma = 1/2: NEWMARK's average acceleration); false for
/// schemes outside the family.
template <class Scheme>
bool undamped(const Scheme& s) noexcept {
  if constexpr (AlphaFamilyIntegrator<Scheme>) {
    const alpha_parameters q = s.coefficients_set();
    return q.alpha_m == 0.0 && q.alpha_f == 0.0 && q.gamma == 0.5;
  } else {
    return false;
  }
}

/// The note at the end of a stage whose model has constraint rows (zero diagonal:
/// Lagrange multipliers) integrated by an undamped scheme (docs/joints.md).
inline std::string undamped_constraint_note(std::string_view scheme) {
  return "note: the model has constraint equations (Lagrange multipliers, e.g. LINKX, SPH3X, VDC2) and " +
         std::string(scheme) +
         " has no numerical damping: their multipliers (joint forces, source currents) may alternate from step "
         "to step; HHT or GALPHA damp the alternation (the motion is not affected)";
}

/// Cut steps of one stage after which an undamped scheme on a model with massless DOFs is warned about.
inline constexpr long undamped_massless_cuts = 50;

/// The warning when a stage of an undamped scheme has cut `cuts` steps and the model has `count` DOFs with neither
/// mass nor viscosity, the first named `example` (docs/rotations.md, "Quasi-static large deflection").
inline std::string undamped_massless_warning(std::string_view scheme, long cuts, int count, const std::string& example) {
  return "warning: " + std::to_string(cuts) + " steps of this stage were cut and " + std::to_string(count) +
         " DOFs have neither mass nor viscosity (the first: '" + example + "'); " + std::string(scheme) +
         " has no numerical damping, so the velocities of such DOFs alternate from step to step and the predictor "
         "extrapolates them: a quasi-static run (loads ramped on massless DOFs) converges with GALPHA and "
         "RHOINF = 0, or HHT";
}

/// The warning of bdf_simulation on a model with index-3 constraints in the plain index-3 form
/// (bdf_options::stabilised_index2 off, or a constraint on a driven DOF).
inline constexpr std::string_view bdf_index3_warning =
    "warning: the model has index-3 constraints (exact joints such as LINKX, SPH3X, REV3X) in the plain index-3 "
    "form: BDF tests the velocities of the constrained DOFs against tolerances divided by the step (index 2), so "
    "the motion is less accurate than DRLTX suggests and the joints are met to the Newton tolerance; the stabilised "
    "index-2 form (bdf_options::stabilised_index2, the default) or pradis::simulation with HHT or GALPHA under "
    "error control keeps both tighter (docs/joints.md)";

/// The note of bdf_simulation when a constraint moves with a driven DOF: the stabilised form is not used.
inline std::string bdf_driven_constraint_note(const std::string& instance, const std::string& dof) {
  return "note: the index-3 constraint '" + instance + "' acts on the driven DOF '" + dof +
         "'; its velocity constraint would need the source's motion, so BDF uses the plain index-3 form for this "
         "model";
}

}  // namespace pradis::detail
