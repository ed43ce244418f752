#pragma once
/// \file
/// Electric sources: current sources IDC, ISIN, ITAB between two nodes; voltage
/// sources VDC, VSIN, VTAB that prescribe the voltage of one node against the
/// ground; floating voltage sources VDC2, VSIN2, VTAB2 between two free nodes (their
/// current is an internal DOF). Each exists with a constant, a sine and a table
/// waveform (electric/waveforms.hpp); the kinds are in electric/source_kinds.hpp.

#include <string_view>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/electric/source_kinds.hpp"
#include "pradis/elements/electric/waveforms.hpp"

namespace pradis::elements {

namespace detail {
inline constexpr std::string_view current_dofs = "1 - node the current is delivered to (+) [V]\n"
                                                 "2 - node the current is drawn from (-) [V]";
inline constexpr std::string_view current_work = "1 - current I(t) delivered into node 1 [A]\n"
                                                 "2 - voltage v1 - v2 across the source [V]";
inline constexpr std::string_view floating_dofs = "1 - positive node (+) [V]\n2 - negative node (-) [V]";
inline constexpr std::string_view floating_work = "1 - current delivered into node 1 (out of the + terminal) [A]\n"
                                                  "2 - source voltage V(t) = v1 - v2 [V]";
inline constexpr std::string_view sine_parameters = "1 - amplitude A\n2 - frequency f [Hz] (>= 0)\n3 - phase [deg]\n"
                                                    "4 - constant part Y0";
inline constexpr std::string_view table_parameters = "1 - time t1 [s]\n2 - value y1\n3 - time t2 [s] (> t1)\n"
                                                     "4 - value y2\n(more pairs t_k, y_k may follow)";
inline constexpr std::string_view table_special =
    "code 100 if the count is not even, a value is not finite or the times do not increase strictly; linear "
    "interpolation, y1 before t1 and the last value after the last time";
}  // namespace detail

/// Descriptions of the electric source types (catalog name, help, domain, example).
namespace electric_source_text {
struct idc {
  static constexpr std::string_view name = "IDC", what = "current I0 [A]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "constant current source between two nodes",
                                     .name = "Ideal current source I(t) = I0",
                                     .field = "electric circuits",
                                     .dofs = detail::current_dofs,
                                     .parameters = "1 - current I0 [A]",
                                     .work = detail::current_work,
                                     .special = "code 100 if I0 is not finite"};
  static constant_wave::parameters example() { return {0.3}; }
};
struct isin {
  static constexpr std::string_view name = "ISIN", what = "current [A]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "harmonic current source between two nodes",
                                     .name = "Ideal current source I(t) = I0 + A sin(2 pi f t + phase)",
                                     .field = "electric circuits",
                                     .dofs = detail::current_dofs,
                                     .parameters = detail::sine_parameters,
                                     .work = detail::current_work,
                                     .special = "code 100 if f < 0 or a parameter is not finite; recommends a step "
                                                "of at most 1/(20 f). Units of A and Y0: [A]"};
  static sine_wave::parameters example() { return {0.2, 1.5, 30.0, 0.1}; }
};
struct itab {
  static constexpr std::string_view name = "ITAB", what = "current [A]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "tabulated current source between two nodes",
                                     .name = "Ideal current source I(t) interpolated in a table of (t, I) pairs",
                                     .field = "electric circuits",
                                     .dofs = detail::current_dofs,
                                     .parameters = detail::table_parameters,
                                     .work = detail::current_work,
                                     .special = detail::table_special};
  static table_wave::parameters example() { return {{0.0, 0.0, 0.5, 1.0, 1.5, -0.5, 2.5, 0.2}}; }
};
struct vdc {
  static constexpr std::string_view name = "VDC", what = "voltage V0 [V]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "constant voltage of a node against the ground",
                                     .name = "Ideal voltage source to ground: prescribes v(t) = V0 on its node",
                                     .field = "electric circuits",
                                     .dofs = "1 - the driven node [V]",
                                     .parameters = "1 - voltage V0 [V]",
                                     .work = "1 - current the source delivers into the node [A]",
                                     .special = "code 100 if V0 is not finite; code 90 if the node is the ground, is "
                                                "driven by another source or has an initial condition"};
  static constant_wave::parameters example() { return {12.0}; }
};
struct vsin {
  static constexpr std::string_view name = "VSIN", what = "voltage [V]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{
      .title = "harmonic voltage of a node against the ground",
      .name = "Ideal voltage source to ground: prescribes v(t) = V0 + A sin(2 pi f t + phase) on its node",
      .field = "electric circuits",
      .dofs = "1 - the driven node [V]",
      .parameters = detail::sine_parameters,
      .work = "1 - current the source delivers into the node [A]",
      .special = "code 100 if f < 0 or a parameter is not finite; code 90 if the node is the ground, is driven by "
                 "another source or has an initial condition; recommends a step of at most 1/(20 f). Units of A and "
                 "Y0: [V]"};
  static sine_wave::parameters example() { return {5.0, 50.0, 0.0, 1.0}; }
};
struct vtab {
  static constexpr std::string_view name = "VTAB", what = "voltage [V]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{
      .title = "tabulated voltage of a node against the ground",
      .name = "Ideal voltage source to ground: prescribes v(t) interpolated in a table of (t, V) pairs",
      .field = "electric circuits",
      .dofs = "1 - the driven node [V]",
      .parameters = detail::table_parameters,
      .work = "1 - current the source delivers into the node [A]",
      .special = "code 100 if the count is not even, a value is not finite or the times do not increase strictly; "
                 "code 90 if the node is the ground, is driven by another source or has an initial condition"};
  static table_wave::parameters example() { return {{0.0, 0.0, 1.0, 10.0, 2.0, 10.0}}; }
};
struct vdc2 {
  static constexpr std::string_view name = "VDC2", what = "voltage V0 [V]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "constant voltage source between two nodes",
                                     .name = "Ideal floating voltage source v1 - v2 = V0",
                                     .field = "electric circuits",
                                     .dofs = detail::floating_dofs,
                                     .parameters = "1 - voltage V0 [V]",
                                     .work = detail::floating_work,
                                     .special = "code 100 if V0 is not finite. The current is an internal DOF whose "
                                                "constraint row has a zero diagonal (factorised by static pivoting); "
                                                "a loop of ideal voltage sources is singular"};
  static constant_wave::parameters example() { return {9.0}; }
};
struct vsin2 {
  static constexpr std::string_view name = "VSIN2", what = "voltage [V]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "harmonic voltage source between two nodes",
                                     .name = "Ideal floating voltage source v1 - v2 = V0 + A sin(2 pi f t + phase)",
                                     .field = "electric circuits",
                                     .dofs = detail::floating_dofs,
                                     .parameters = detail::sine_parameters,
                                     .work = detail::floating_work,
                                     .special = "code 100 if f < 0 or a parameter is not finite; recommends a step of "
                                                "at most 1/(20 f). The current is an internal DOF whose constraint "
                                                "row has a zero diagonal (factorised by static pivoting); a loop of "
                                                "ideal voltage sources is singular. Units of A and Y0: [V]"};
  static sine_wave::parameters example() { return {3.0, 2.0, 45.0, 1.0}; }
};
struct vtab2 {
  static constexpr std::string_view name = "VTAB2", what = "voltage [V]";
  static constexpr domain dom = domain::electric;
  static constexpr element_help help{.title = "tabulated voltage source between two nodes",
                                     .name = "Ideal floating voltage source v1 - v2 interpolated in (t, V) pairs",
                                     .field = "electric circuits",
                                     .dofs = detail::floating_dofs,
                                     .parameters = detail::table_parameters,
                                     .work = detail::floating_work,
                                     .special = "code 100 if the count is not even, a value is not finite or the "
                                                "times do not increase strictly. The current is an internal DOF "
                                                "whose constraint row has a zero diagonal (factorised by static "
                                                "pivoting); a loop of ideal voltage sources is singular"};
  static table_wave::parameters example() { return {{0.0, 1.0, 1.0, 5.0, 2.0, -2.0}}; }
};
}  // namespace electric_source_text

/// IDC: constant current source.
using current_dc = flow_source<constant_wave, electric_source_text::idc>;
/// ISIN: harmonic current source.
using current_sine = flow_source<sine_wave, electric_source_text::isin>;
/// ITAB: tabulated current source.
using current_table = flow_source<table_wave, electric_source_text::itab>;
/// VDC: constant voltage of a node against the ground (prescribed potential).
using voltage_dc = potential_source<constant_wave, electric_source_text::vdc>;
/// VSIN: harmonic voltage of a node against the ground.
using voltage_sine = potential_source<sine_wave, electric_source_text::vsin>;
/// VTAB: tabulated voltage of a node against the ground.
using voltage_table = potential_source<table_wave, electric_source_text::vtab>;
/// VDC2: constant floating voltage source (current as an internal DOF).
using floating_voltage_dc = floating_potential_source<constant_wave, electric_source_text::vdc2>;
/// VSIN2: harmonic floating voltage source.
using floating_voltage_sine = floating_potential_source<sine_wave, electric_source_text::vsin2>;
/// VTAB2: tabulated floating voltage source.
using floating_voltage_table = floating_potential_source<table_wave, electric_source_text::vtab2>;

}  // namespace pradis::elements
