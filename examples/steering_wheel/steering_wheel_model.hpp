#pragma once
/// \file
/// The steering-wheel impact of the PRADIS paper, built in code: a rigid head of
/// 6.8 kg and 165 mm diameter hits the junction of a spoke and the rim at 7 m/s.
/// Used by examples/steering_wheel/main.cpp and tests/examples/test_steering_wheel.cpp;
/// docs/steering_wheel.md describes the model and its results.
///
/// What is modelled (SI units; the numbers are in `parameters`):
///  - The wheel lies in the global X-Y plane with its centre at the origin; the
///    steering column is the Z axis (a flat wheel: no dish).
///  - Rim: a ring of radius R through `rim_segments` nodes, joined by BEAM3
///    (stiffness) + BEAMI3 (mass) elements; steel tube section.
///  - Spokes: at the angles `spoke_angles` (0, 180 and 270 degrees: the common T
///    layout), each from the hub radius to the rim node at its angle, in
///    `spoke_segments` BEAM3 + BEAMI3 elements of solid round steel. The hub end of
///    every spoke is on the ground (translations and rotations): the hub and the
///    column are rigid.
///  - Head: a rigid body (BODY3), mass 6.8 kg, a solid sphere's inertia 2/5 m r^2,
///    starting a gap of 1 mm above the junction of the first spoke (angle 0) with
///    the rim and moving at 7 m/s along -Z: perpendicular to the wheel plane, along
///    the column axis. No gravity (it changes the head's speed by 0.2 % during the
///    impact).
///  - Contact: a penalty approximation. Every wheel node within `contact_reach` of
///    the impact point carries a sphere of the member's radius (the half tube or
///    rod diameter) centred at the node; a CSPHSP element (sphere-sphere contact,
///    linear law k delta, frictionless) joins it to the head's sphere. CSPHSP's
///    second "body" is the beam node itself: a BEAM3 node has the same DOFs as a
///    BODY3 (x, y, z and a rotational node), and a sphere centred at the node's
///    reference point (offset 0) needs nothing else. The head can touch the
///    structure only at these nodes (between two rim nodes 75 mm apart its surface
///    lies 9 mm lower than at the nodes, less than the rim's 11 mm radius, so it
///    cannot slip between them). The contact stiffness (5e6 N/m, 14 times the
///    wheel's static stiffness at the junction) stands for the head's skin and
///    the local crushing of the tube; its damping (1500 N s/m, about critical for
///    a rim node's 0.1 kg on that spring) stops the light rim node from rattling
///    on the head (with c = 0 the node bounces off and back every ~0.5 ms and the
///    force trace is a train of spikes).
///  - Optionally (the static stiffness): no inertia, no head, a force at the
///    impact node along -Z: each step of the integrator is then a static solution.

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "pradis/elements/library.hpp"
#include "pradis/integrators/simulation.hpp"

namespace steering_wheel {

using namespace pradis;
using namespace pradis::elements;

/// The numbers of the model.
struct parameters {
  // Wheel geometry.
  double rim_radius = 0.19;         ///< rim radius (centre line) [m]
  int rim_segments = 16;            ///< beam elements around the rim (a multiple of 4)
  double rim_d = 0.022, rim_t = 0.002;  ///< rim tube: outer diameter, wall [m]
  double hub_radius = 0.035;        ///< radius where the spokes leave the (rigid) hub [m]
  int spoke_segments = 3;           ///< beam elements per spoke
  double spoke_d = 0.012;           ///< spokes: solid round rod, diameter [m]
  std::vector<double> spoke_angles{0, 180, 270};  ///< spoke angles [deg] (multiples of 360 / rim_segments); the first is hit
  // Steel.
  double e = 2.1e11, g = 8.1e10, rho = 7850;  ///< E, G [Pa], density [kg/m^3]
  // Head.
  double head_mass = 6.8;           ///< [kg]
  double head_diameter = 0.165;     ///< [m]
  double v0 = 7.0;                  ///< impact speed along -Z [m/s]
  double gap = 1e-3;                ///< initial gap between the head and the junction's contact sphere [m]
  // Contact.
  double k_contact = 5e6;           ///< linear penalty stiffness [N/m] (the head's skin and the local crushing)
  double c_contact = 1500;          ///< contact damping [N s/m] (about critical for a rim node's 0.1 kg on k_contact; 0: elastic)
  double contact_reach = 0.16;      ///< nodes within this distance of the impact point get a contact sphere [m]
  // Variants.
  bool inertia = true;              ///< with the BEAMI3 masses
  bool head = true;                 ///< with the head and its contacts
  double static_load = 0;           ///< a constant force along -Z on the impact node [N] (for the stiffness)

  double head_radius() const { return head_diameter / 2; }
  double head_inertia() const { return 0.4 * head_mass * head_radius() * head_radius(); }
};

using model_type = model<elastic_beam, beam_inertia, rigid_body, sphere_sphere_contact, spatial_force, initial_velocity>;

/// A node of the wheel (its hub-end nodes are on the ground).
struct node {
  std::array<double, 3> pos{};   ///< initial position
  std::array<dof, 3> x{};        ///< translations (ground at the hub)
  rotation_node r{};             ///< rotational node (unused at the hub)
  bool ground = false;           ///< a hub node
  double radius = 0;             ///< contact-sphere radius of the member it belongs to [m]
};

/// A beam element of the wheel (its two nodes).
struct member {
  int a = 0, b = 0;
  element_ref<elastic_beam> beam;
  element_ref<beam_inertia> mass;  ///< valid only with inertia
};

/// The handles the example and the tests read.
struct handles {
  std::vector<node> nodes;
  std::vector<member> members;
  int impact = 0;                                   ///< the junction node that the head hits
  std::array<dof, 3> head_x{};                      ///< head translations
  rotation_node head_r{};
  std::array<double, 3> head_pos{};                 ///< head centre at the start
  element_ref<rigid_body> head;
  std::vector<element_ref<sphere_sphere_contact>> contacts;
  std::vector<int> contact_node;                    ///< node of each contact
};

/// Builds the steering wheel into m (an empty model) and returns the handles.
inline handles build(model_type& m, const parameters& P) {
  const double pi = std::numbers::pi;
  const dof G = m.ground();
  handles h;
  auto add_node = [&](double x, double y, bool ground, double radius, const std::string& name) {
    node n;
    n.pos = {x, y, 0};
    n.ground = ground;
    n.radius = radius;
    if (ground) {
      n.x = {G, G, G};
    } else {
      const auto d = m.add_dofs(3, name);
      n.x = {d[0], d[1], d[2]};
      n.r = m.add_rotation_node(name + "q");
    }
    h.nodes.push_back(n);
    return static_cast<int>(h.nodes.size()) - 1;
  };
  // Sections: a tube (outer D, wall t) or a rod (t = 0); round: Iy = Iz = I, J = 2 I.
  struct section { double a, i; };
  auto tube = [&](double d, double t) {
    const double di = t > 0 ? d - 2 * t : 0.0;
    return section{pi / 4 * (d * d - di * di), pi / 64 * (d * d * d * d - di * di * di * di)};
  };
  const section rim = tube(P.rim_d, P.rim_t), spoke = tube(P.spoke_d, 0);
  auto add_member = [&](int a, int b, const section& s, const std::string& name) {
    const node& A = h.nodes[static_cast<std::size_t>(a)];
    const node& B = h.nodes[static_cast<std::size_t>(b)];
    member mb{a, b, {}, {}};
    // The section's local y axis: global Z (normal to every member of the flat wheel).
    const std::array<double, 15> bp{P.e, P.g, s.a, s.i, s.i, 2 * s.i, A.pos[0], A.pos[1], A.pos[2],
                                    B.pos[0], B.pos[1], B.pos[2], 0, 0, 1};
    const std::array<double, 14> ip{P.rho, s.a, s.i, s.i, 2 * s.i, A.pos[0], A.pos[1], A.pos[2],
                                    B.pos[0], B.pos[1], B.pos[2], 0, 0, 1};
    auto add = [&]<class E>(const std::string& n, const auto& par) {
      if (A.ground)
        return m.add<E>(n, E::from_parameters(par).p, G, G, G, G, G, G, B.x[0], B.x[1], B.x[2], B.r);
      return m.add<E>(n, E::from_parameters(par).p, A.x[0], A.x[1], A.x[2], A.r, B.x[0], B.x[1], B.x[2], B.r);
    };
    mb.beam = add.template operator()<elastic_beam>("beam_" + name, bp);
    if (P.inertia) mb.mass = add.template operator()<beam_inertia>("mass_" + name, ip);
    h.members.push_back(mb);
  };
  // Rim nodes 0 .. n-1 at the angles 2 pi i / n.
  const int n = P.rim_segments;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * pi * i / n;
    add_node(P.rim_radius * std::cos(phi), P.rim_radius * std::sin(phi), false, P.rim_d / 2, "rim" + std::to_string(i));
  }
  for (int i = 0; i < n; ++i) add_member(i, (i + 1) % n, rim, "rim" + std::to_string(i));
  // Spokes from the hub (ground) to the rim node at their angle.
  for (std::size_t s = 0; s < P.spoke_angles.size(); ++s) {
    const int k = static_cast<int>(std::lround(P.spoke_angles[s] / 360 * n)) % n;
    const double phi = 2 * pi * k / n, c = std::cos(phi), sn = std::sin(phi);
    const std::string name = "spoke" + std::to_string(s) + "_";
    int prev = add_node(P.hub_radius * c, P.hub_radius * sn, true, P.spoke_d / 2, name + "hub");
    for (int j = 1; j <= P.spoke_segments; ++j) {
      const int next = j == P.spoke_segments
                           ? k
                           : add_node((P.hub_radius + (P.rim_radius - P.hub_radius) * j / P.spoke_segments) * c,
                                      (P.hub_radius + (P.rim_radius - P.hub_radius) * j / P.spoke_segments) * sn, false,
                                      P.spoke_d / 2, name + std::to_string(j));
      add_member(prev, next, spoke, name + std::to_string(j));
      prev = next;
    }
    if (s == 0) h.impact = k;
  }
  const node& hit = h.nodes[static_cast<std::size_t>(h.impact)];
  if (P.static_load != 0)
    m.add<spatial_force>("load", {0, 0, -P.static_load, 0, 0, 0, 0, 0}, hit.x[0], hit.x[1], hit.x[2]);
  if (!P.head) return h;
  // Head: centre above the impact node, its surface `gap` above the node's contact sphere.
  const double rh = P.head_radius(), j = P.head_inertia();
  h.head_pos = {hit.pos[0], hit.pos[1], rh + hit.radius + P.gap};
  const auto xh = m.add_dofs(3, "head");
  h.head_x = {xh[0], xh[1], xh[2]};
  h.head_r = m.add_rotation_node("headq");
  h.head = m.add<rigid_body>("head", {P.head_mass, j, j, j, 0, 0, 0, 0, 0, 0}, xh[0], xh[1], xh[2], h.head_r);
  m.add<initial_velocity>("head_v0", {-P.v0}, xh[2]);
  for (std::size_t i = 0; i < h.nodes.size(); ++i) {
    const node& nd = h.nodes[i];
    const double dist = std::hypot(nd.pos[0] - hit.pos[0], nd.pos[1] - hit.pos[1]);
    if (nd.ground || dist > P.contact_reach) continue;
    const auto& hp = h.head_pos;
    h.contacts.push_back(m.add<sphere_sphere_contact>(
        "contact" + std::to_string(i),
        {hp[0], hp[1], hp[2], 0, 0, 0, rh, nd.pos[0], nd.pos[1], nd.pos[2], 0, 0, 0, nd.radius, 0, P.k_contact,
         P.c_contact, 0, 0, 0},
        xh[0], xh[1], xh[2], h.head_r, nd.x[0], nd.x[1], nd.x[2], nd.r));
    h.contact_node.push_back(static_cast<int>(i));
  }
  return h;
}

/// Position of node i in state s (initial position + displacement).
template <class S>
std::array<double, 3> position(const S& s, const handles& h, std::size_t i) {
  const node& n = h.nodes[i];
  return {n.pos[0] + s.u(n.x[0]), n.pos[1] + s.u(n.x[1]), n.pos[2] + s.u(n.x[2])};
}

/// The total contact force on the head in state s, from each contact's normal force
/// (work 2) along the line of centres from the node to the head.
template <class S>
std::array<double, 3> head_force(const S& s, model_type& m, const handles& h) {
  std::array<double, 3> f{0, 0, 0};
  const std::array<double, 3> c{h.head_pos[0] + s.u(h.head_x[0]), h.head_pos[1] + s.u(h.head_x[1]),
                                h.head_pos[2] + s.u(h.head_x[2])};
  for (std::size_t k = 0; k < h.contacts.size(); ++k) {
    const double nforce = m.work(h.contacts[k])[1];
    if (nforce == 0) continue;
    const auto p = position(s, h, static_cast<std::size_t>(h.contact_node[k]));
    const double d[3] = {c[0] - p[0], c[1] - p[1], c[2] - p[2]}, l = std::hypot(d[0], d[1], d[2]);
    for (int i = 0; i < 3; ++i) f[static_cast<std::size_t>(i)] += nforce * d[i] / l;
  }
  return f;
}

/// The energies in state s: kinetic (head and beams), elastic (beams) and in the
/// contact springs (1/2 k delta^2 of the linear law), from the work vectors.
struct energies {
  double kinetic = 0, elastic = 0, contact = 0;
  double total() const { return kinetic + elastic + contact; }
};
inline energies energy(model_type& m, const handles& h, const parameters& P) {
  energies e;
  if (P.head) e.kinetic += m.work(h.head)[0];
  for (const member& mb : h.members) {
    e.elastic += m.work(mb.beam)[2];
    if (P.inertia) e.kinetic += m.work(mb.mass)[0];
  }
  for (const auto& c : h.contacts) {
    const double delta = m.work(c)[0];
    if (delta > 0) e.contact += 0.5 * P.k_contact * delta * delta;
  }
  return e;
}

/// The static stiffness of the wheel at the impact node along Z [N/m]: the same
/// wheel without inertia and head, a force `load` along -Z on the node; with no
/// mass, the one step of the integrator solves the static equilibrium (Newton on
/// the corotational beams: geometrically nonlinear, so use a small load).
inline double static_stiffness(parameters P, double load) {
  P.inertia = false;
  P.head = false;
  P.static_load = load;
  model_type m;
  const handles h = build(m, P);
  simulation sim(m);
  sim.run({.end = 1, .out = 0, .smax = 1});
  return -load / sim.u(h.nodes[static_cast<std::size_t>(h.impact)].x[2]);
}

}  // namespace steering_wheel
