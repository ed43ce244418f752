#pragma once
/// \file
/// Options of the variable-order BDF driver pradis::bdf_simulation (docs/bdf.md)
/// and their check. The stage options (END, OUT, SMAX, SMIN, DRLTX, DABSX,
/// ERROR_CONTROL, IGNORE, the Newton limits ITR and max_rate) come from
/// pradis::run_options as for pradis::simulation; these are the options that
/// only the BDF method has (its Jacobian refresh rule among them: the
/// newton_options::coefficient_change of run_options is not used).

#include <limits>
#include <optional>
#include <string>

#include "pradis/integrators/options.hpp"

namespace pradis {

/// The highest order of the BDF driver (BDF6 and above are not zero-stable).
inline constexpr int bdf_highest_order = 5;

/// Options of the BDF method, set once for a bdf_simulation.
struct bdf_options {
  /// MAXORD: the highest order used, 1..5 (IDA's default 5). With error control
  /// the order varies between 1 and max_order; without it every step is taken
  /// at max_order once the start has raised the order. BDF3 and BDF4 amplify
  /// undamped oscillations whose period the step resolves, and the order selection
  /// does not leave max_order for it: a model with undamped modes should not run with
  /// 3 or 4 (docs/bdf.md, "Undamped modes and the order", with what it did to an
  /// undamped mode under error control).
  int max_order = bdf_highest_order;
  /// Keep the order at max_order once reached (no lowering by the order
  /// selection; the start still raises it from 1 one step at a time). For tests
  /// of the convergence order and for comparisons.
  bool fixed_order = false;
  /// The Newton iteration stops when the estimated remaining error of the
  /// corrector, rate / (1 - rate) times the last correction in the weighted RMS
  /// norm of the error test, is below this fraction of the error tolerance
  /// (IDA's epcon, default 0.33).
  double newton_tolerance = 0.33;
  /// The Newton tolerance, as newton_tolerance, of a step whose correction
  /// enters the test for raising the order (with error control, every k + 2
  /// steps of equal size at order k < max_order). That test weighs the
  /// difference of two successive corrections, which the corrector's remaining
  /// error disturbs more than the error test itself. Default 0.033, a tenth of
  /// newton_tolerance; equal to newton_tolerance: no such step is treated
  /// apart (the measurements are in docs/bdf.md, "The order-raise test").
  double raise_test_tolerance = 0.033;
  /// The first step of a stage: 0 selects it as IDA does (0.001 of the stage,
  /// at most 0.5 / |y'| in the weighted norm); else this step (clamped to
  /// [SMIN, SMAX]). Used only with error control: without it the run starts at
  /// SMIN and doubles the step up to SMAX.
  double initial_step = 0;
  /// The kept Jacobian is refreshed when c = alpha_s / h moved out of
  /// [c_J (1 - x) / (1 + x), c_J (1 + x) / (1 - x)] since its factorisation,
  /// x = this value. Default 0: at every change of c (of the step or the
  /// order); constant-step runs keep it. IDA's window (x = 0.25) suits its
  /// first-order form J = G_y + c G_y'. The Newton matrix of the nodal form,
  /// K / c + C + c M, moves further with c, and with rotational nodes M
  /// depends on the orientation, so a kept Jacobian ages with the rotation as
  /// well; the measurements against IDA are in docs/bdf.md ("Newton"). x >= 1
  /// refreshes only on a Newton failure.
  double coefficient_change = 0;
  /// Index-3 constraints (exact joints: LINKX, SPH3X, REV3X, ...) in the
  /// stabilised index-2 form of Gear, Gupta and Leimkuhler: the velocity
  /// constraint G v = 0 is met with the position constraint, and the velocities
  /// are tested against DRLTX like every other velocity (docs/bdf.md,
  /// "Index-3 constraints"). false: the plain index-3 form, with the velocities
  /// of the constrained DOFs tested against tolerances divided by the step. The
  /// driver uses the index-3 form anyway when a constraint moves with a driven
  /// DOF (a kinematic source), and says so in its log.
  bool stabilised_index2 = true;
  /// After every accepted step, a rotational node whose quaternion norm Lq left
  /// [1 - x, 1 + x], x = this value, is scaled back to Lq = 1 with its history;
  /// exact, since the rotational formulas are scale invariant (docs/bdf.md,
  /// "Rotational nodes"). 0 renormalises at every step; at or above 0.1 (the
  /// drift that is code 75) never.
  double lq_renormalise = 0.01;
  /// The rate form of the rotational nodes: the velocity half of the BDF
  /// history holds each node's body angular velocity and norm rate instead of
  /// q' (docs/bdf.md, "Rotational nodes"; rate_form.hpp). false: q' (the
  /// second-order form of every other DOF).
  bool rotation_rates = false;
  /// The kept Newton matrix is turned with the rotational nodes: a solve with
  /// the factorisation made at the orientations q0 maps the node's entries of
  /// the solution (its columns) from q0 to the current orientations; its rows,
  /// global moments and the norm equation, do not turn (docs/bdf.md, "Newton";
  /// rotated_jacobian.hpp). false: used as it is.
  bool rotated_jacobian = true;
  /// With rotated_jacobian: a node whose every element has body-fixed flows (a
  /// rigid body with its centre of mass on the node, body-fixed torques:
  /// core/element.hpp, HasBodyFixedFlows) is turned in its body frame, rows and
  /// columns, which fits the inertia of any tumbling body; the others in the
  /// global frame (docs/bdf.md, "Newton"). false: every node in the global frame.
  bool body_frame = true;
  /// With rotated_jacobian: the kept Newton matrix is evaluated and factorised
  /// again when a node turned in the global frame (not in its body frame) has
  /// turned by more than this angle [rad] since the factorisation. The turn in
  /// the global frame is exact only for what depends on the global angular
  /// velocity alone; the rest, such as the inertia of a body held by a joint,
  /// ages as the body turns, and the first Newton corrections that the rate
  /// test accepts then leave a small error of one sign that adds up over the
  /// steps (docs/bdf.md, "Newton"). Newton's rate estimate is kept across such
  /// a refresh. A number >= 0; at or above pi never (the angle is at most pi).
  double turn_refresh = 1.0;
  /// When c changed but the kept Newton matrix is otherwise still good (no turn
  /// beyond turn_refresh, no failure), it is made again at the new c from the
  /// element blocks K, C, M of its evaluation, J = K / c + C + c M, and
  /// factorised, without evaluating the elements' Jacobians (the assembler
  /// keeps the blocks, assembler::keep_blocks). Only where the kept matrix's age
  /// in the state is made up for: a model without rotational nodes, or whose
  /// every free rotational node is turned in its body frame (rotated_jacobian,
  /// body_frame); not with index-3 constraints (in either form) or the rate form.
  /// docs/bdf.md, "Newton". false: the elements are evaluated at every refresh.
  bool reform_jacobian = true;

  /// Equal options (the language keeps a BDF driver across stages whose options are equal).
  bool operator==(const bdf_options&) const = default;
};

/// Checks bdf_options; returns the message of the first invalid one (the
/// driver throws it as invalid_option, prefixed by "BDF: ").
inline std::optional<std::string> check_bdf_options(const bdf_options& o) {
  using detail::num;
  if (o.max_order < 1 || o.max_order > bdf_highest_order)
    return "the maximum order MAXORD = " + std::to_string(o.max_order) + " is outside 1.." +
           std::to_string(bdf_highest_order);
  if (!(o.newton_tolerance > 0 && o.newton_tolerance <= 1))
    return "the Newton tolerance " + num(o.newton_tolerance) + " must be in (0, 1]";
  if (!(o.raise_test_tolerance > 0 && o.raise_test_tolerance <= 1))
    return "the Newton tolerance of the order-raise test " + num(o.raise_test_tolerance) + " must be in (0, 1]";
  if (!(o.initial_step >= 0) || o.initial_step == std::numeric_limits<double>::infinity())
    return "the initial step " + num(o.initial_step) + " must be a finite number >= 0";
  if (!(o.coefficient_change >= 0) || o.coefficient_change == std::numeric_limits<double>::infinity())
    return "the Jacobian coefficient change " + num(o.coefficient_change) + " must be a finite number >= 0";
  if (!(o.turn_refresh >= 0))
    return "the turn angle turn_refresh = " + num(o.turn_refresh) + " of a Jacobian refresh must be a number >= 0";
  if (!(o.lq_renormalise >= 0))
    return "the quaternion norm band lq_renormalise = " + num(o.lq_renormalise) + " must be a number >= 0";
  return std::nullopt;
}

}  // namespace pradis
