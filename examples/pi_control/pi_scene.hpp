#pragma once
// The scene of examples/pi_control: a mass on a spring and damper under a constant
// disturbance, held at 0 by the PI controller PICTRL and its integral node.

#include <pradis/pradis.hpp>

#include "pi_controller.hpp"
#include "pi_exact.hpp"

namespace pradis_examples {

/// The element types of the scene (PICTRL brings the integral node kind).
using pi_model = pradis::model<pradis::elements::point_mass, pradis::elements::linear_spring,
                               pradis::elements::linear_damper, pradis::elements::constant_force, pi_controller>;

/// The controlled oscillator of plant p: x the mass's displacement, h its time integral
/// (the hidden DOF of the integral node on x).
struct pi_scene {
  pi_model m;
  pradis::dof x, h;
  explicit pi_scene(const pi_plant& p) {
    using namespace pradis::elements;
    x = m.add_dof("x");
    h = m.add_dof("h");
    m.add<point_mass>("mass", {p.m}, x);
    m.add<linear_spring>("spring", {p.k}, x, m.ground());
    m.add<linear_damper>("damper", {p.c}, x, m.ground());
    m.add<constant_force>("disturbance", {p.f0}, x);
    m.add<pi_controller>("controller", {p.kp, p.ki}, x, h);
    m.add_node<integral_node>({{x.index, h.index}});
  }
  pi_scene(const pi_scene&) = delete;
  pi_scene& operator=(const pi_scene&) = delete;
};

}  // namespace pradis_examples
