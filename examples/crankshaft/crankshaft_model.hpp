#pragma once
/// \file
/// The crankshaft of the PRADIS paper (Fig. 3), built in code: a single-cylinder
/// crank mechanism run up from rest to 5000 rev/min, with the radial runout of the
/// main bearings as the result. Used by examples/crankshaft/main.cpp.
///
/// What is modelled (all numbers below; SI units):
///  - The crankshaft along the global X axis as a chain of eight BEAM3 (stiffness)
///    + BEAMI3 (mass and rotary inertia) elements through nine nodes:
///      0 front stub end with the belt pulley (X = 0),
///      1 front main journal, in main bearing 1 (X = 0.05),
///      2 root of the front crank web (X = 0.08),
///      3 front end of the crank pin (X = 0.08, Y = r),
///      4 middle of the crank pin, where the connecting rod sits (X = 0.10, Y = r),
///      5 rear end of the crank pin (X = 0.12, Y = r),
///      6 root of the rear crank web (X = 0.12),
///      7 rear main journal, in main bearing 2 (X = 0.15),
///      8 rear stub end with the flywheel (X = 0.22).
///    No counterweights: the webs and the pin are an unbalanced mass at the crank.
///    Or, with cb_model_type, the same shaft as one Craig-Bampton body (FLEX3) on the
///    nodes 0, 1, 4, 7, 8 with 6 fixed-interface modes of the others (docs/reduction.md).
///  - Main bearings: SPH3 from the ground to nodes 1 and 7 (a penalty spring-damper
///    on the journal's displacement, k_bearing; the shaft turns freely about X).
///    The radial runout of a journal sqrt(y^2 + z^2) is the bearing gap, the bearing
///    force over k_bearing.
///  - Flywheel: BODY3 at node 8; belt pulley: BODY3 at node 0.
///  - Connecting rod: a BODY3 (reference point at its centre of mass), joined to the
///    crank pin (node 4) and to the piston pin by SPH3.
///  - Piston: a MASS on a DOF py, its displacement along the cylinder axis (global
///    Y, cylinder head at +Y): the lateral translations and all rotations of the
///    piston end of the lower SPH3 are on the ground, so it slides along the cylinder.
///  - Drive: a 1D angle DOF phi driven by VSRC, v(t) = W sin(2 pi f t), f = 1/(4 T_run)
///    (a quarter sine reaching W = 5000 rev/min = 523.6 rad/s at T_run), coupled to the
///    flywheel node through SHC3 (elastic coupling / clutch about X).
///  - Camshaft: SHC3 from the pulley node to a 1D angle DOF with a MASS (camshaft
///    inertia, reduced to crankshaft speed, 1:1: the 2:1 gear is not modelled) and a
///    DAMPER to the ground (viscous resistance torque c_cam * omega).
///  - Belt: a constant lateral force F3 on the pulley node in -Z (cantilever load).
///  - Combustion: the element GASF below, a gas force on the piston that depends on
///    the piston's distance s from top dead centre, F = p_peak A exp(-(s/s_w)^2),
///    pushing the piston towards the crank. It depends on the position only (the
///    same pulse at every top dead centre: a two-stroke-like cycle, and conservative:
///    it does no net work per revolution, the drive supplies the power). It is a
///    documented approximation of a cylinder pressure trace, not a combustion model.
///    It is switched on smoothly over the first t_ignition = 50 ms (the crank starts
///    at top dead centre, where a sudden full gas force would be a step load).

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <numbers>
#include <span>
#include <array>
#include <vector>
#include <string>

#include "pradis/elements/library.hpp"
#include "pradis/elements/spatial/beam_matrices.hpp"
#include "pradis/integrators/simulation.hpp"

namespace crankshaft {

using namespace pradis;
using namespace pradis::elements;

/// GASF: gas force on the piston, a function of its displacement u along the
/// cylinder axis (u = 0 at top dead centre, u < 0 towards the crank):
/// P(u) = -p_peak A exp(-(u / s_w)^2) (towards the crank), flow -P.
struct gas_force {
  static constexpr pradis::passport passport{.name = "GASF", .ext = 1, .par = 4, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr element_help help{
      .title = "gas force on a piston",
      .name = "Gas force P(u) = -p_peak A exp(-(u/s_w)^2) on the piston DOF (u = 0 at top dead centre)",
      .field = "mechanics (crankshaft example)",
      .dofs = "1 - piston displacement along the cylinder axis from top dead centre [m]",
      .parameters = "1 - peak pressure p_peak [Pa] (>= 0)\n2 - piston area A [m^2] (> 0)\n"
                    "3 - width s_w of the pressure pulse [m] (> 0)\n"
                    "4 - ignition time t_in [s] (>= 0): the force is switched on as (1 - cos(pi t/t_in))/2",
      .work = "1 - current force P on the piston [N]",
      .special = "code 100 if a parameter is out of range or not finite"};
  struct parameters {
    double p_peak = 0;  ///< peak cylinder pressure [Pa]
    double area = 0;    ///< piston area [m^2]
    double width = 0;   ///< width of the pulse in piston travel [m]
    double t_in = 0;    ///< ignition time: smooth switch-on over [0, t_in] [s]
  };
  parameters p;
  explicit gas_force(parameters q) : p(q) {}
  static parameters example() { return {5e6, 5e-3, 0.01, 0.1}; }
  static gas_force from_parameters(std::span<const double> v) { return gas_force({v[0], v[1], v[2], v[3]}); }
  void new_integration(element_context& ctx) const {
    if (!(p.p_peak >= 0) || !std::isfinite(p.p_peak)) ctx.invalid_parameter("p_peak = " + to_text(p.p_peak) + " must be finite and >= 0");
    if (!(p.area > 0) || !std::isfinite(p.area)) ctx.invalid_parameter("A = " + to_text(p.area) + " must be finite and > 0");
    if (!(p.width > 0) || !std::isfinite(p.width)) ctx.invalid_parameter("s_w = " + to_text(p.width) + " must be finite and > 0");
    if (!(p.t_in >= 0) || !std::isfinite(p.t_in)) ctx.invalid_parameter("t_in = " + to_text(p.t_in) + " must be finite and >= 0");
  }
  /// The switch-on factor at time t.
  double ignition(double t) const {
    return t >= p.t_in ? 1.0 : 0.5 * (1 - std::cos(std::numbers::pi * t / p.t_in));
  }
  void evaluate(const local_input<gas_force>& in, local_output<gas_force>& out, element_context& ctx) const {
    const double x = in.u(0) / p.width, e = ignition(in.t) * std::exp(-x * x);
    const double force = -p.p_peak * p.area * e;  // on the piston, towards the crank
    out.f(0) = -force;
    ctx.work[0] = force;
    if (out.want_jacobian) out.K(0, 0) = p.p_peak * p.area * e * (-2 * x / p.width);
  }
};

/// The numbers of the model (a single-cylinder engine of about 0.45 l).
struct parameters {
  // Crank geometry.
  double r = 0.040;            ///< crank radius [m] (stroke 80 mm)
  double l = 0.140;            ///< connecting-rod length, pin to pin [m]
  double bore = 0.084;         ///< cylinder bore [m]
  // Steel.
  double e = 2.1e11, g = 8.1e10, rho = 7850;  ///< E, G [Pa], density [kg/m^3]
  double d_journal = 0.050;    ///< main journals and stubs: round, diameter [m]
  double d_pin = 0.045;        ///< crank pin: round, diameter [m]
  double web_b = 0.080, web_t = 0.020;  ///< crank web: rectangle, width (along Z) and thickness (along X) [m]
  // Bearings, bodies.
  double k_bearing = 2e8;      ///< main bearing stiffness (oil film), SPH3 penalty [N/m]
  double c_bearing = 4e3;      ///< main bearing damping [N s/m]
  double k_pin = 5e8;          ///< rod bearings (big and small end), SPH3 penalty [N/m]
  double c_pin = 4e3;          ///< their damping [N s/m]
  double m_fly = 8.0, j_fly = 0.10, j_fly_d = 0.05;    ///< flywheel mass [kg], polar and diametral inertia [kg m^2]
  double m_pulley = 1.0, j_pulley = 3e-3, j_pulley_d = 1.5e-3;  ///< belt pulley
  double m_rod = 0.50;         ///< connecting rod mass [kg], centre of mass at mid-length
  double j_rod = 8.2e-4, j_rod_axis = 5e-5;  ///< rod inertia about its centre: transverse (m l^2/12), about its own axis
  double m_piston = 0.40;      ///< piston with pin and rings [kg]
  // Drive, camshaft, belt, gas.
  double w_end = 5000 * 2 * std::numbers::pi / 60;  ///< final speed W [rad/s] (5000 rev/min)
  double t_run = 0.5;          ///< run-up time T_run [s]
  double k_drive = 1e5, c_drive = 40;  ///< drive coupling SHC3 (clutch) [N m/rad, N m s/rad]
  double k_cam = 5e3, c_cam_coupling = 1.0;  ///< camshaft drive SHC3 (chain) [N m/rad, N m s/rad]
  double j_cam = 2e-3;         ///< camshaft inertia at crankshaft speed [kg m^2]
  double c_cam = 0.01;         ///< camshaft viscous resistance [N m s/rad] (5.2 N m at 5000 rev/min)
  double belt_force = 1500;    ///< belt pull on the pulley, -Z [N]
  double p_peak = 4e6;         ///< peak gas pressure [Pa] (40 bar)
  double s_w = 0.012;          ///< width of the pressure pulse in piston travel [m] (0.15 stroke)
  double t_ignition = 0.05;    ///< smooth switch-on of the gas force [s]

  double piston_area() const { return std::numbers::pi * bore * bore / 4; }
};

using model_type = model<elastic_beam, beam_inertia, rigid_body, spherical_joint, spatial_force, shaft_coupling,
                         velocity_source, point_mass, linear_damper, gas_force>;

/// The shaft as one Craig-Bampton body (FLEX3, docs/reduction.md) instead of the eight
/// BEAM3 + BEAMI3: its boundary nodes are the shaft nodes where other elements attach
/// (cb_nodes: pulley, bearing 1, crank pin middle, bearing 2, flywheel), the inner
/// nodes 2, 3, 5, 6 are condensed with cb_modes fixed-interface modes. Its matrices are
/// those of the same eight beams linearised at rest (shaft_matrices).
inline constexpr std::array<int, 5> cb_nodes{0, 1, 4, 7, 8};
inline constexpr int cb_modes = 6;
using cb_shaft = reduced_body<5, cb_modes>;
using cb_model_type = model<cb_shaft, rigid_body, spherical_joint, spatial_force, shaft_coupling, velocity_source,
                            point_mass, linear_damper, gas_force>;

/// The initial positions of the shaft nodes 0..8.
inline std::vector<std::array<double, 3>> shaft_positions(const parameters& P) {
  const double r = P.r;
  return {{0, 0, 0}, {0.05, 0, 0}, {0.08, 0, 0}, {0.08, r, 0}, {0.10, r, 0}, {0.12, r, 0}, {0.12, 0, 0}, {0.15, 0, 0}, {0.22, 0, 0}};
}

/// One shaft segment: from node i to node i + 1, its section and the vector of its local y axis.
struct shaft_segment {
  int i = 0;
  double a = 0, iy = 0, iz = 0, j = 0;
  double vx = 0, vy = 0, vz = 0;
};

/// The eight segments: stub, journal, web, pin (two pieces), web, journal, stub.
inline std::array<shaft_segment, 8> shaft_segments(const parameters& P) {
  const double pi = std::numbers::pi;
  // Sections: round a (diameter d): A = pi d^2/4, I = pi d^4/64, J = 2 I;
  // the web (b along Z, t along X, length along Y): local y axis = global X.
  auto round = [&](int i, double d) {
    const double a = pi * d * d / 4, in = pi * d * d * d * d / 64;
    return shaft_segment{i, a, in, in, 2 * in, 0, 1, 0};
  };
  const double b = P.web_b, t = P.web_t;
  // Web along Y, local y = X (thickness t), local z = x_local x y_local = Y x X = -Z (width b).
  // Iy (about local y = X, bending in the plane of local x and z) = t b^3/12, Iz = b t^3/12,
  // J of a thin-ish rectangle: b t^3/3 (1 - 0.63 t/b).
  auto web = [&](int i) {
    return shaft_segment{i, b * t, t * b * b * b / 12, b * t * t * t / 12, b * t * t * t / 3 * (1 - 0.63 * t / b), 1, 0, 0};
  };
  return {round(0, P.d_journal), round(1, P.d_journal), web(2), round(3, P.d_pin),
          round(4, P.d_pin),     web(5),                round(6, P.d_journal), round(7, P.d_journal)};
}

/// K and M of the shaft (nodes 0..8, 6 DOFs each): the eight segments as one linear beam
/// element each, BEAM3 and BEAMI3 linearised at rest (straight_beam_matrices).
inline beam_matrices shaft_matrices(const parameters& P) {
  const auto pos = shaft_positions(P);
  beam_matrices all{Eigen::MatrixXd::Zero(54, 54), Eigen::MatrixXd::Zero(54, 54)};
  for (const shaft_segment& s : shaft_segments(P)) {
    const auto& a = pos[static_cast<std::size_t>(s.i)];
    const auto& b = pos[static_cast<std::size_t>(s.i + 1)];
    const beam_matrices e = straight_beam_matrices({P.e, P.g, s.a, s.iy, s.iz, s.j, P.rho, s.iy + s.iz}, {a[0], a[1], a[2]},
                                                   {b[0], b[1], b[2]}, {s.vx, s.vy, s.vz}, 1);
    all.k.block<12, 12>(6 * s.i, 6 * s.i) += e.k;
    all.m.block<12, 12>(6 * s.i, 6 * s.i) += e.m;
  }
  return all;
}

/// The typed parameters of the Craig-Bampton shaft.
inline cb_shaft::parameters cb_shaft_parameters(const parameters& P) {
  const beam_matrices km = shaft_matrices(P);
  const auto pos = shaft_positions(P);
  std::vector<int> boundary;
  std::array<spatial::vec3, 5> nodes;
  for (std::size_t k = 0; k < cb_nodes.size(); ++k) {
    const auto& x = pos[static_cast<std::size_t>(cb_nodes[k])];
    nodes[k] = {x[0], x[1], x[2]};
    for (int j = 0; j < 6; ++j) boundary.push_back(6 * cb_nodes[k] + j);
  }
  return cb_shaft::from_part(linalg::craig_bampton(km.k, km.m, boundary, cb_modes), nodes);
}

/// The handles the example reads.
struct handles {
  std::vector<std::array<dof, 3>> x;   ///< translations of the shaft nodes 0..8 (absent inner nodes: ground)
  std::vector<rotation_node> r;        ///< rotational nodes of the shaft nodes 0..8
  std::vector<bool> present;           ///< whether node i is a node of the model (not condensed)
  std::vector<std::array<double, 3>> pos;  ///< their initial positions
  std::array<dof, 3> rod_x{};          ///< translations of the rod's centre of mass
  rotation_node rod_r{};               ///< the rod's rotational node
  std::array<double, 3> rod_pos{};     ///< its initial position
  dof py;                              ///< piston displacement along Y from top dead centre
  dof phi, cam;                        ///< drive and camshaft angles
  element_ref<shaft_coupling> drive, camshaft;
  element_ref<spherical_joint> bearing1, bearing2, big_end;
  element_ref<gas_force> gas;
};

/// Builds the crankshaft into m (an empty model_type, or cb_model_type for the
/// Craig-Bampton shaft) and returns the handles.
template <class Model>
handles build(Model& m, const parameters& P) {
  constexpr bool cb = std::is_same_v<Model, cb_model_type>;
  static_assert(cb || std::is_same_v<Model, model_type>, "crankshaft::build: model_type or cb_model_type");
  handles h;
  const double r = P.r;
  h.pos = shaft_positions(P);
  const dof G = m.ground();
  for (std::size_t i = 0; i < h.pos.size(); ++i) {
    const bool present = !cb || std::find(cb_nodes.begin(), cb_nodes.end(), static_cast<int>(i)) != cb_nodes.end();
    h.present.push_back(present);
    if (!present) {
      h.x.push_back({G, G, G});
      h.r.push_back(rotation_node{});
      continue;
    }
    const auto d = m.add_dofs(3, "x" + std::to_string(i));
    h.x.push_back({d[0], d[1], d[2]});
    h.r.push_back(m.add_rotation_node("r" + std::to_string(i)));
  }
  if constexpr (cb) {
    const auto& x = h.x;
    const auto& q = h.r;
    m.template add<cb_shaft>("shaft", cb_shaft_parameters(P), x[0][0], x[0][1], x[0][2], q[0], x[1][0], x[1][1], x[1][2],
                             q[1], x[4][0], x[4][1], x[4][2], q[4], x[7][0], x[7][1], x[7][2], q[7], x[8][0], x[8][1],
                             x[8][2], q[8]);
  } else {
    for (const shaft_segment& s : shaft_segments(P)) {
      const auto i = static_cast<std::size_t>(s.i);
      const auto& A = h.pos[i];
      const auto& B = h.pos[i + 1];
      const auto& xa = h.x[i];
      const auto& xb = h.x[i + 1];
      const auto ra = h.r[i], rb = h.r[i + 1];
      const std::string n = std::to_string(i) + std::to_string(i + 1);
      m.template add<elastic_beam>("beam" + n,
                                   {P.e, P.g, s.a, s.iy, s.iz, s.j, A[0], A[1], A[2], B[0], B[1], B[2], s.vx, s.vy, s.vz},
                                   xa[0], xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
      m.template add<beam_inertia>(
          "mass" + n, {P.rho, s.a, s.iy, s.iz, s.iy + s.iz, A[0], A[1], A[2], B[0], B[1], B[2], s.vx, s.vy, s.vz}, xa[0],
          xa[1], xa[2], ra, xb[0], xb[1], xb[2], rb);
    }
  }
  // Main bearings at the journals 1 and 7: ground point at the journal's initial position.
  for (int i : {1, 7}) {
    const auto& p = h.pos[static_cast<std::size_t>(i)];
    const auto& x = h.x[static_cast<std::size_t>(i)];
    const auto ref = m.template add<spherical_joint>("bearing" + std::to_string(i == 1 ? 1 : 2),
                                            {{p[0], p[1], p[2], 0, 0, 0, p[0], p[1], p[2], 0, 0, 0}, P.k_bearing, P.c_bearing},
                                            G, G, G, G, G, G, x[0], x[1], x[2], h.r[static_cast<std::size_t>(i)]);
    (i == 1 ? h.bearing1 : h.bearing2) = ref;
  }
  // Flywheel and pulley (centres of mass on the nodes).
  m.template add<rigid_body>("flywheel", {P.m_fly, P.j_fly, P.j_fly_d, P.j_fly_d, 0, 0, 0, 0, 0, 0}, h.x[8][0], h.x[8][1], h.x[8][2], h.r[8]);
  m.template add<rigid_body>("pulley", {P.m_pulley, P.j_pulley, P.j_pulley_d, P.j_pulley_d, 0, 0, 0, 0, 0, 0}, h.x[0][0], h.x[0][1],
                    h.x[0][2], h.r[0]);
  // Connecting rod: reference point = centre of mass at (0.10, r + l/2, 0), axis along Y.
  const auto xr = m.add_dofs(3, "rod");
  const rotation_node rr = m.add_rotation_node("rodq");
  const double xc = 0.10, yc = r + P.l / 2;
  m.template add<rigid_body>("rod", {P.m_rod, P.j_rod, P.j_rod_axis, P.j_rod, 0, 0, 0, 0, 0, 0}, xr[0], xr[1], xr[2], rr);
  h.rod_x = {xr[0], xr[1], xr[2]};
  h.rod_r = rr;
  h.rod_pos = {xc, yc, 0};
  // Big end: crank pin node 4 (a) and the rod point -l/2 along body Y (b).
  h.big_end = m.template add<spherical_joint>("big_end", {{0.10, r, 0, 0, 0, 0, xc, yc, 0, 0, -P.l / 2, 0}, P.k_pin, P.c_pin}, h.x[4][0],
                         h.x[4][1], h.x[4][2], h.r[4], xr[0], xr[1], xr[2], rr);
  // Piston: only its Y translation is free (cylinder walls and its fixed orientation on the ground).
  h.py = m.add_dof("piston");
  m.template add<point_mass>("piston_mass", {P.m_piston}, h.py);
  m.template add<spherical_joint>("small_end", {{xc, yc, 0, 0, P.l / 2, 0, xc, r + P.l, 0, 0, 0, 0}, P.k_pin, P.c_pin}, xr[0],
                         xr[1], xr[2], rr, G, h.py, G, G, G, G);
  h.gas = m.template add<gas_force>("gas", {P.p_peak, P.piston_area(), P.s_w, P.t_ignition}, h.py);
  // Drive: VSRC quarter sine on phi, SHC3 to the flywheel node.
  h.phi = m.add_dof("phi");
  m.template add<velocity_source>("speed", {P.w_end, 1 / (4 * P.t_run), 0, 0}, h.phi);
  h.drive = m.template add<shaft_coupling>("drive", {1, 0, 0, P.k_drive, P.c_drive, 0}, h.phi, h.r[8]);
  // Camshaft: SHC3 from the pulley node to the camshaft angle, inertia and viscous resistance.
  h.cam = m.add_dof("cam");
  h.camshaft = m.template add<shaft_coupling>("cam_drive", {1, 0, 0, P.k_cam, P.c_cam_coupling, 0}, h.cam, h.r[0]);
  m.template add<point_mass>("cam_inertia", {P.j_cam}, h.cam);
  m.template add<linear_damper>("cam_resistance", {P.c_cam}, h.cam, G);
  // Belt: constant lateral pull on the pulley.
  m.template add<spatial_force>("belt", {0, 0, -P.belt_force, 0, 0, 0, 0, 0}, h.x[0][0], h.x[0][1], h.x[0][2]);
  return h;
}

/// Sets the nominal potential of the angular DOFs (q1..q4 of the rotational nodes,
/// the drive and camshaft angles phi, cam) to w [rad/s]: under error control their
/// absolute tolerance is DABSX w. With the default 1 rad/s the variable-order BDF
/// driver resolves the crank pin's vibration (about 5 kHz) in the rates of the nodes' q
/// (docs/bdf.md, "Stiff, excited modes: the crankshaft"); 100 rad/s, about a fifth
/// of the final speed, leaves it to the relative tolerance.
template <class Model>
void scale_angular_dofs(Model& m, const handles& h, double w) {
  auto set = [&](dof d) { m.set_scale(d, {w, m.scale(d).flow}); };
  auto set_node = [&](const rotation_node& r) {
    for (const dof d : {r.q1, r.q2, r.q3, r.q4}) set(d);
  };
  for (std::size_t i = 0; i < h.r.size(); ++i)
    if (h.present[i]) set_node(h.r[i]);
  set_node(h.rod_r);
  set(h.phi);
  set(h.cam);
}

/// The radial runout sqrt(y^2 + z^2) of the two main journals (nodes 1 and 7) at every
/// step of the first `end` seconds of the run-up, h = 0.1 ms as the example, on a model
/// of type Model (model_type or cb_model_type).
template <class Model>
std::vector<std::array<double, 2>> bearing_runouts(double end, const parameters& P = {}) {
  Model m;
  const handles h = build(m, P);
  simulation sim(m);
  std::vector<std::array<double, 2>> out;
  sim.on_output([&](const auto& s) {
    const auto r = [&](int i) {
      const auto& x = h.x[static_cast<std::size_t>(i)];
      return std::hypot(s.u(x[1]), s.u(x[2]));
    };
    out.push_back({r(1), r(7)});
  });
  sim.run({.end = end, .out = 0, .smax = 1e-4});
  return out;
}

}  // namespace crankshaft
