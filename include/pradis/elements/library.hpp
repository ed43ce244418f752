#pragma once
/// \file
/// The built-in element library as a compile-time list. `library_elements` is the
/// type list of every element type; `library_model` is a model that can hold all
/// of them (what the model language and the `pradis` command use). A scene that
/// needs only some types lists just those in its own pradis::model<...>.

#include "pradis/core/type_list.hpp"
#include "pradis/elements/hydraulic/accumulator.hpp"
#include "pradis/elements/hydraulic/cylinder.hpp"
#include "pradis/elements/hydraulic/line.hpp"
#include "pradis/elements/hydraulic/machines.hpp"
#include "pradis/elements/hydraulic/orifices.hpp"
#include "pradis/elements/hydraulic/valves.hpp"
#include "pradis/elements/hydraulic/volume.hpp"
#include "pradis/elements/electric/dc_motor.hpp"
#include "pradis/elements/electric/passive.hpp"
#include "pradis/elements/electric/semiconductors.hpp"
#include "pradis/elements/electric/sources.hpp"
#include "pradis/elements/mech1d/belt.hpp"
#include "pradis/elements/mech1d/cam.hpp"
#include "pradis/elements/mech1d/forces.hpp"
#include "pradis/elements/mech1d/friction.hpp"
#include "pradis/elements/mech1d/gear.hpp"
#include "pradis/elements/mech1d/initial_conditions.hpp"
#include "pradis/elements/mech1d/linear_damper.hpp"
#include "pradis/elements/mech1d/linear_spring.hpp"
#include "pradis/elements/mech1d/point_mass.hpp"
#include "pradis/elements/mech1d/sources.hpp"
#include "pradis/elements/mech1d/table_damper.hpp"
#include "pradis/elements/mech1d/table_spring.hpp"
#include "pradis/elements/planar/eccentric_mass.hpp"
#include "pradis/elements/planar/ellipse_contact.hpp"
#include "pradis/elements/pneumatic/chambers.hpp"
#include "pradis/elements/pneumatic/orifice.hpp"
#include "pradis/elements/planar/planar_inertia.hpp"
#include "pradis/elements/planar/planar_link.hpp"
#include "pradis/elements/planar/planar_pin_joint.hpp"
#include "pradis/elements/planar/planar_rigid_link.hpp"
#include "pradis/elements/spatial/beam.hpp"
#include "pradis/elements/spatial/beam_inertia.hpp"
#include "pradis/elements/spatial/condensed_beam.hpp"
#include "pradis/elements/spatial/coupling.hpp"
#include "pradis/elements/spatial/crank_throw.hpp"
#include "pradis/elements/spatial/reduced_body.hpp"
#include "pradis/elements/spatial/initial_rotation.hpp"
#include "pradis/elements/spatial/plate.hpp"
#include "pradis/elements/spatial/loads.hpp"
#include "pradis/elements/spatial/rigid_body.hpp"
#include "pradis/model/model.hpp"
// --- spatial connecting elements (SD3, RSD3, SPH3, REV3) ---
#include "pradis/elements/spatial/joints.hpp"
#include "pradis/elements/spatial/exact_frame_joints.hpp"
#include "pradis/elements/spatial/exact_joints.hpp"
#include "pradis/elements/spatial/spring_damper.hpp"
#include "pradis/elements/spatial/sphere_contact.hpp"
// --- end of spatial connecting elements ---

namespace pradis::elements {

/// 1D mechanics (with friction, gear pair and belt on a drum: docs/friction.md).
using mech1d_elements =
    type_list<point_mass, linear_spring, linear_damper, table_spring, table_damper, cam, constant_force, sine_force,
              displacement_source, velocity_source, initial_displacement, initial_velocity, friction, gear, belt>;
/// Planar mechanics.
using planar_elements =
    type_list<planar_inertia, planar_link, eccentric_mass, planar_rigid_link, planar_pin_joint, ellipse_contact>;
/// Spatial mechanics (rotational nodes with the hidden fourth potential, docs/rotations.md).
using spatial_elements =
    type_list<rigid_body, spatial_force, spatial_torque, body_force, offset_force, body_torque, initial_rotation>;
// --- spatial connecting elements (SD3, RSD3, SPH3, REV3, SHC3 and the exact joints) ---
/// Spatial connecting elements: spring-dampers and penalty joints between bodies, the
/// shaft coupling from a one-dimensional rotation to a spatial node (docs/rotations.md),
/// and the exact joints with Lagrange multipliers (docs/joints.md).
using spatial_connector_elements =
    type_list<spatial_spring_damper, rotational_spring_damper, spherical_joint, revolute_joint, shaft_coupling,
              exact_spherical_joint, exact_revolute_joint, exact_universal_joint, exact_cylindrical_joint,
              exact_prismatic_joint, exact_fixed_joint, exact_point_on_line, exact_point_on_plane>;
// --- end of spatial connecting elements ---
/// Spatial contact: a body-fixed sphere against a fixed plane (with Coulomb friction) or
/// against another sphere (docs/contact.md).
using spatial_contact_elements = type_list<sphere_plane_contact, sphere_sphere_contact>;
/// Spatial beams: the corotational elastic beam and its inertia (docs/rotations.md), the
/// super-elements made of them (THROW, and THROWP with the middle of the pin external;
/// BEAM3C, a BEAM3 in four segments with the inner nodes condensed, for large deflection;
/// docs/super-elements.md), and the reduced elastic body FLEX3 with two boundary nodes and
/// two modes (docs/reduction.md).
using beam_elements =
    type_list<elastic_beam, beam_inertia, condensed_beam, crank_throw, crank_throw_pin, reduced_body_2x2>;
/// Plates: the 12-DOF triangle plate with side rotations (docs/plates.md).
using plate_elements = type_list<triangle_plate>;
/// Hydraulics (docs/domains.md): pressure is the velocity-level unknown, volume flow the flow.
using hydraulic_elements =
    type_list<hydraulic_volume, laminar_orifice, turbulent_orifice, hydraulic_line, hydraulic_pump, hydraulic_motor,
              hydraulic_cylinder, valve_22, valve_43, relief_valve, check_valve, accumulator>;
/// Electric circuits and electromechanics (docs/domains-electric-pneumatic.md).
using electric_elements =
    type_list<resistor, capacitor, inductor, current_dc, current_sine, current_table, voltage_dc, voltage_sine,
              voltage_table, floating_voltage_dc, floating_voltage_sine, floating_voltage_table, diode, time_switch,
              dc_motor>;
/// Pneumatics: gauge pressures and mass flows (docs/domains-electric-pneumatic.md).
using pneumatic_elements = type_list<gas_chamber, gas_piston_chamber, pneumatic_cylinder, pneumatic_orifice,
                                     pneumatic_pressure_source, pneumatic_flow_source>;
/// Every element type of the built-in library.
using library_elements = concat_t<mech1d_elements, planar_elements, spatial_elements, spatial_connector_elements,
                                  spatial_contact_elements, beam_elements, plate_elements, hydraulic_elements, electric_elements, pneumatic_elements>;

}  // namespace pradis::elements

namespace pradis {
/// A model that can hold every element type of the built-in library.
using library_model = model_of<elements::library_elements>;
}  // namespace pradis
