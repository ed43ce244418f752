#pragma once
/// \file
/// The three kinds of sources of the nodal circuit domains (electric, pneumatic),
/// as templates over a waveform W (constant_wave, sine_wave, table_wave) and a
/// description T (catalog name, help, domain, the quantity's name for messages,
/// example parameters):
///
/// - flow_source<W, T>: a flow y(t) (current, mass flow) delivered into node 1 and
///   drawn from node 2. Flows -y, +y.
/// - potential_source<W, T>: prescribes the potential of one node (its v = y(t),
///   u = the integral of y from 0, a = y'), like VSRC: the node leaves the unknowns
///   and W(1) is the flow the source delivers into the node (the reaction).
/// - floating_potential_source<W, T>: prescribes v1 - v2 = y(t) between two free
///   nodes. Its flow (the current through it, from node 2 to node 1 inside the
///   source, i.e. delivered into node 1) is an internal DOF j (v_j = i) with the
///   constraint equation F_j = y(t) - (v1 - v2) = 0, whose diagonal is zero: the
///   sparse LU factorises it by its static pivoting (a zero pivot is perturbed and
///   repaired by iterative refinement), tests/electric/test_sources.cpp.

#include <array>
#include <span>
#include <string_view>
#include <utility>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"
#include "pradis/elements/electric/waveforms.hpp"

namespace pradis::elements {

/// A flow source y(t) between two nodes: delivers y into node 1, draws it from node 2.
template <class W, class T>
struct flow_source {
  static constexpr pradis::passport passport{
      .name = T::name, .ext = 2, .par = W::par, .vpr = W::vpr, .wrk = 2, .adr = 1, .ign = 23};
  static constexpr std::array<domain, 2> domains{T::dom, T::dom};
  static constexpr element_help help = T::help;
  using parameters = typename W::parameters;
  parameters p;
  explicit flow_source(parameters q) : p(std::move(q)) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return T::example(); }
  static flow_source from_parameters(std::span<const double> v) { return flow_source(W::from(v)); }
  /// The parameter count (variable for tables).
  int parameter_count() const { return W::count(p); }
  void new_integration(element_context& ctx) const { W::check(p, ctx, T::what); }
  void evaluate(const local_input<flow_source>& in, local_output<flow_source>& out, element_context& ctx) const {
    const double y = W::at(p, in.t).value;
    out.f << -y, y;
    ctx.work[0] = y;
    ctx.work[1] = in.v(0) - in.v(1);
    ctx.recommend_step(W::resolving_step(p));
    if (out.want_jacobian) out.K.setZero();
  }
};

/// A source that prescribes the potential of its node: v = y(t), u = integral of y
/// from 0, a = y'(t). W(1) is the flow it delivers into the node (the reaction).
template <class W, class T>
struct potential_source {
  static constexpr pradis::passport passport{
      .name = T::name, .ext = 1, .par = W::par, .vpr = W::vpr, .wrk = 1, .adr = 1, .ign = 23};
  static constexpr std::array<domain, 1> domains{T::dom};
  static constexpr element_help help = T::help;
  using parameters = typename W::parameters;
  parameters p;
  explicit potential_source(parameters q) : p(std::move(q)) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return T::example(); }
  static potential_source from_parameters(std::span<const double> v) { return potential_source(W::from(v)); }
  /// The parameter count (variable for tables).
  int parameter_count() const { return W::count(p); }
  void new_integration(element_context& ctx) const { W::check(p, ctx, T::what); }
  /// The prescribed potential: u = integral, v = y(t), a = y'(t).
  kinematics motion(double t) const {
    const wave_sample s = W::at(p, t);
    return {s.integral, s.value, s.slope};
  }
  void evaluate(const local_input<potential_source>&, local_output<potential_source>& out, element_context& ctx) const {
    ctx.recommend_step(W::resolving_step(p));
    if (out.want_jacobian) out.K.setZero();
  }
};

/// A source that prescribes v1 - v2 = y(t) between two nodes; its flow i (delivered
/// into node 1, drawn from node 2) is the internal DOF's v. Flows -i, i, and the
/// constraint y(t) - (v1 - v2). Pure viscosity block (ADR=2, IGN=3).
template <class W, class T>
struct floating_potential_source {
  static constexpr pradis::passport passport{
      .name = T::name, .ext = 2, .ent = 1, .par = W::par, .vpr = W::vpr, .wrk = 2, .adr = 2, .ign = 3};
  static constexpr std::array<domain, 3> domains{T::dom, T::dom, T::dom};
  static constexpr element_help help = T::help;
  using parameters = typename W::parameters;
  parameters p;
  explicit floating_potential_source(parameters q) : p(std::move(q)) {}
  /// Example parameters (used by `pradis check` and the all-elements test).
  static parameters example() { return T::example(); }
  static floating_potential_source from_parameters(std::span<const double> v) {
    return floating_potential_source(W::from(v));
  }
  /// The parameter count (variable for tables).
  int parameter_count() const { return W::count(p); }
  void new_integration(element_context& ctx) const { W::check(p, ctx, T::what); }
  void evaluate(const local_input<floating_potential_source>& in, local_output<floating_potential_source>& out,
                element_context& ctx) const {
    const double y = W::at(p, in.t).value, i = in.v(2);
    out.f << -i, i, y - (in.v(0) - in.v(1));
    ctx.work[0] = i;
    ctx.work[1] = y;
    ctx.recommend_step(W::resolving_step(p));
    if (out.want_jacobian) out.C << 0, 0, -1, 0, 0, 1, -1, 1, 0;
  }
};

}  // namespace pradis::elements
