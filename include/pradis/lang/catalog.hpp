#pragma once
/// \file
/// The catalog of the model language: integration programs, their keys, output
/// programs and display programs, each with a one-line purpose. Elements come
/// from the element library itself (passport and help), never from a copy here.

#include <string>
#include <string_view>
#include <vector>

#include "pradis/elements/library.hpp"

namespace pradis::lang {

/// A program of the language other than an element: integration, output or display.
struct program_info {
  std::string_view name;
  std::string_view purpose;
  std::string_view usage;  ///< example call
  std::string_view keys;   ///< one "KEY - meaning (default)" per line
};

/// Integration programs ($RUN).
inline const std::vector<program_info>& integration_programs() {
  static const std::vector<program_info> v{
      {"SHTERM", "Stoermer scheme of PRADIS (Newmark beta = 1/2, gamma = 1): first order, dissipative",
       "Calculation 'SHTERM (END=1, SMAX=1e-3)", ""},
      {"NEWMARK", "Newmark scheme, velocity as the Newton unknown (default average acceleration, second order)",
       "Calculation 'NEWMARK (END=1, BETA=0.25, GAMMA=0.5)",
       "BETA - displacement weight, 0 < BETA <= 1/2 (0.25)\nGAMMA - velocity weight, 1/2 <= GAMMA <= 1 (0.5)\n"},
      {"HHT", "Hilber-Hughes-Taylor alpha scheme: second order, damps high frequencies (more for ALPHA nearer -1/3)",
       "Calculation 'HHT (END=1, ALPHA=-0.1)",
       "ALPHA - -1/3 <= ALPHA <= 0; spectral radius at infinite frequency (1 + ALPHA) / (1 - ALPHA) (-0.05)\n"},
      {"GALPHA", "generalized-alpha scheme: second order, high-frequency damping set by RHOINF",
       "Calculation 'GALPHA (END=1, RHOINF=0.8)",
       "RHOINF - spectral radius at infinite frequency, 0 <= RHOINF <= 1; 1 is undamped (0.8)\n"},
      {"BDF", "variable-order (1..5), variable-step BDF with local error control (as DASSL and IDA): the fastest "
              "choice for smooth motions at tight tolerances; damps undamped oscillations slightly",
       "Calculation 'BDF (END=1, DRLTX=1e-6, MAXORD=5)",
       "MAXORD - highest order, 1..5 (5)\n"
       "LQBAND - a rotational node whose quaternion norm left [1 - LQBAND, 1 + LQBAND] is scaled back to 1 after a "
       "step (exact); 0: every step, >= 0.1: never (0.01)\n"
       "INDEX2 - exact joints: 1 stabilised index-2 form, 0 plain index-3 form (1)\n"
       "TURN - the kept Newton matrix turned with the rotational nodes: 2 in the body frame of nodes whose elements "
       "all turn with them (BODY3 centred, M3B), else global; 1 global frame only; 0 not turned (2)\n"
       "TURNMAX - the kept Newton matrix is refreshed when a node turned in the global frame has turned by more "
       "than TURNMAX [rad] since its factorisation; >= pi: never (1)\n"
       "RATES - rotational nodes: 1 body rates in the BDF history (more accurate with fixed steps), 0 q' (0)\n"
       "REFORM - 1: when only c changed, the kept Newton matrix is formed again from its element blocks where the "
       "driver allows it; 0: the elements are evaluated at every refresh (1)\n"
       "BDF always controls its error with DRLTX and DABSX (and CONTROL); "
       "DABSU, DRLTU, DABSI, DRLTI, SECOND and PREDICT do not apply\n"},
  };
  return v;
}

/// Node programs (#STRUCTURE, written like an element): nodes whose equation slaves some of their
/// DOFs to the others, with no element of their own (a PIVOT's outputs, W:Name(1..3), are its
/// force on the body). `keys` holds the nodes, the parameters and the outputs, as an element's
/// help does.
inline const std::vector<program_info>& node_programs() {
  static const std::vector<program_info> v{
      {"PIVOT",
       "ground pivot: SPH3X from the ground to body b in reduced form, without multipliers; the body's "
       "translations follow its rotation (docs/joints.md)",
       "Tip 'PIVOT (1 2 3 4 5 6; Geometry)    (the 12 parameters of SPH3X, body a the ground)",
       "Nodes (6): body b's x y z (slaved: they follow q) and q1 q2 q3\n"
       "Parameters (12, as SPH3X's; A is a fixed point of the ground, whose rotation is the identity):\n"
       PRADIS_JOINT_GEOMETRY_HELP
       "Outputs: 'X (W:Tip(k); 1), k = 1, 2, 3: the pivot's force on the body along X, Y, Z [N] (at the last "
       "evaluation of the step, as an element's work vector)\n"
       "A node of the body on the ground, a body DOF that is already slaved by another PIVOT, or a parameter "
       "that is not finite is an error; the body's initial translations are put on the pivot (a warning names "
       "any initial condition this replaces)\n"},
  };
  return v;
}

/// Keys every integration program accepts.
inline std::string_view common_run_keys() {
  return "END - end time of the stage (required)\n"
         "OUT - output interval (0: after every step) (0)\n"
         "SMAX - maximum step (0.01)\n"
         "SMIN - minimum step; below it the run fails (1e-11)\n"
         "IGNORE - 1: ignore steps recommended by elements (0)\n"
         "DABSU - Newton: absolute tolerance on the velocity correction (0.01)\n"
         "DRLTU - Newton: relative tolerance on the velocity correction (0.001)\n"
         "DABSI - Newton: absolute tolerance on the residual per DOF (0.1)\n"
         "DRLTI - Newton: relative tolerance on the residual per DOF (0.001)\n"
         "ITR - Newton: maximum iterations per step (5)\n"
         "SECOND - 1: force at least a second Newton iteration (0)\n"
         "DABSX - error control: absolute tolerance of the local error, velocity units (DRLTX); "
         "giving DABSX, DRLTX, CONTROL or PREDICT turns error control on\n"
         "DRLTX - error control: relative tolerance of the local error (0.001)\n"
         "CONTROL - error control: no error-driven step reduction below this step (0)\n"
         "PREDICT - error control: 1 = linear prediction of the acceleration in the estimate (0)\n"
         "SAVE - write a checkpoint <stem>.t<time>.chk at every multiple of SAVE in the stage (none)\n"
         "OPTIM - ordering of the sparse elimination: 0 natural, 1 row count, 2 initial fill, 3 minimum degree, "
         "4 minimum fill (by model size)\n"
         "NSTEPMAX - the most steps the stage may accept; reached before END, the run stops with error 142 and "
         "keeps its rows (0: no limit) (0)\n";
}

/// Keys of PRADIS integration programs that pradis does not implement yet.
inline const std::vector<std::string>& unimplemented_run_keys() {
  static const std::vector<std::string> v{"WEIGHT", "CHECKM", "DEBUG", "FLAG", "SCHEME"};
  return v;
}

/// Output programs (#OUTPUT).
inline const std::vector<program_info>& output_programs() {
  static const std::vector<program_info> v{
      {"X", "potential of a node (order 1 displacement, 2 velocity, 3 acceleration), a work-vector entry or a "
            "PIVOT's force on its body (W:Name(1..3))",
       "Body 2 X 'X (4; 1)    Link force 'X (W:Connection(3); 1)", ""},
      {"W", "global angular velocity of a spatial rotational node about X, Y or Z (k = 1, 2, 3) [rad/s]; the node "
            "by its three rotation nodes q1 q2 q3 (0 for a fixed one)",
       "Crank speed 'W (4 5 6; 1)", ""},
      {"LQ", "quaternion norm Lq = |q| of a spatial rotational node (its hidden q4 included); the node by its "
             "three rotation nodes",
       "Norm 'LQ (4 5 6)", ""},
      {"NSTEP", "number of accepted integration steps so far", "Steps 'NSTEP ()", ""},
      {"NITER", "Newton iterations of the last accepted step", "Iterations 'NITER ()", ""},
      {"STEP", "size of the last accepted step", "Step 'STEP ()", ""},
      {"NREJ", "number of rejected (cut) steps so far", "Rejected 'NREJ ()", ""},
      {"NFACT", "number of numeric factorisations so far", "Factorisations 'NFACT ()", ""},
      {"NITTOT", "total Newton iterations so far", "Newton 'NITTOT ()", ""},
  };
  return v;
}

/// Display programs ($PRINT).
inline const std::vector<program_info>& display_programs() {
  static const std::vector<program_info> v{
      {"TABL", "table of outputs over time, written as CSV", "Table 'TABL (Body 2 X, Body 2 Y; START=0, END=1)",
       "START - first time shown (start of the run)\nEND - last time shown (end of the run)\n"},
      {"DISP", "graphs of outputs over time, one panel each, written as PNG (needs gnuplot)", "Graphs 'DISP ()",
       "START - first time shown (start of the run)\nEND - last time shown (end of the run)\n"},
      {"PEAK", "peak of each output and, with THRESHOLD, the longest and the total time at or above it (crossings "
               "interpolated linearly), written as CSV and to the log",
       "Head 'PEAK (Deceleration; THRESHOLD=80, START=0, END=0.05)",
       "THRESHOLD - level for the time above it (none: the peak only)\nMAGNITUDE - 1: peak of |y| instead of the "
       "largest y (0)\nSTART - first time used (start of the run)\nEND - last time used (end of the run)\n"},
      {"VTK", "animation of the model's spatial elements (beams, springs, joints, contacts, plates) as a VTK time "
              "series for ParaView: <dir>/vtk/<stem>.<label>.pvd and one .vtu per output time",
       "Animation 'VTK (START=0, END=1)",
       "START - first time written (start of the run)\nEND - last time written (end of the run)\n"},
  };
  return v;
}

/// Catalog names of every element type of the library, in library order.
inline std::vector<std::string> element_names() {
  std::vector<std::string> out;
  library_model::for_each_type([&]<class E>(std::type_identity<E>) { out.emplace_back(E::passport.name); });
  return out;
}

/// Names of a program list.
inline std::vector<std::string> names_of(const std::vector<program_info>& v) {
  std::vector<std::string> out;
  for (const auto& p : v) out.emplace_back(p.name);
  return out;
}

/// Finds a program by name in a list (nullptr if absent).
inline const program_info* find_program(const std::vector<program_info>& v, std::string_view name) {
  for (const auto& p : v)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace pradis::lang
