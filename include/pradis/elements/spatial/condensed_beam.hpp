#pragma once
/// \file
/// BEAM3C: an elastic beam for large deflection between two spatial nodes. It is BEAM3 cut into N equal segments
/// whose inner nodes are condensed inside the element (elements/condensed.hpp): the model sees the two end nodes
/// only, while the deflected shape has N corotational segments. Parameters as BEAM3's. docs/super-elements.md,
/// "BEAM3C".

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <tuple>
#include <utility>

#include "pradis/elements/condensed.hpp"
#include "pradis/elements/spatial/beam.hpp"

namespace pradis::elements {

namespace condensed_beam_detail {

/// The composition of a BEAM3 cut into N segments (2 <= N <= 8).
///
/// Local DOFs of the underlying composite: the end nodes A (x y z 0..2, q1..q3 3..5) and B (6..8, 9..11) as in
/// BEAM3, the hidden q4 of A at 12 and of B at 13, then the N - 1 inner nodes j = 1..N-1 from A to B, each
/// x y z q1 q2 q3 q4 at 14 + 7 (j - 1). Segment i runs from node i to node i + 1 (node 0 is A, node N is B).
template <int N>
struct spec {
  static_assert(N >= 2 && N <= 8, "pradis: BEAM3C has 2 to 8 segments");
  static constexpr std::string_view name = "BEAM3C";
  static constexpr std::string_view title = "elastic beam for large deflection (BEAM3 in segments, inner nodes condensed)";
  static constexpr std::string_view field = "mechanics, spatial motion";
  static constexpr int ext = 12;
  static constexpr int ent = 2 + 7 * (N - 1);
  static constexpr std::array<std::string_view, N> labels = [] {
    constexpr std::array<std::string_view, 8> all{"segment 1", "segment 2", "segment 3", "segment 4",
                                                  "segment 5", "segment 6", "segment 7", "segment 8"};
    std::array<std::string_view, N> a{};
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = all[i];
    return a;
  }();
  static constexpr std::string_view special =
      "code 100 if E, G, A, Iy, Iz or J is not positive, A and B coincide, the section vector is parallel to A -> B "
      "or a parameter is not finite (as BEAM3, with BEAM3C's parameter numbers); code 75 if a segment reports one (a quaternion norm or a "
      "chord near zero, a local rotation of a segment reaching 180 degrees), if the condensed inner nodes' Newton "
      "iterations do not converge in 30 steps or their stiffness is singular (the step is cut). The inner nodes are "
      "quasi-static: the element has no mass (add BEAMI3 between the same nodes). Run static or slow loading with a "
      "damped scheme (GALPHA), as for any massless DOFs (docs/rotations.md)";
  /// First composite DOF of node j (0: A, N: B) and its q4.
  static constexpr int node(int j) { return j == 0 ? 0 : (j == N ? 6 : 14 + 7 * (j - 1)); }
  static constexpr int q4(int j) { return j == 0 ? 12 : (j == N ? 13 : 14 + 7 * (j - 1) + 6); }
  /// The composite DOFs of segment i's 14 local DOFs (BEAM3's layout: A x y z q1 q2 q3, B x y z q1 q2 q3, qa4, qb4).
  static constexpr std::array<int, 14> segment(int i) {
    std::array<int, 14> m{};
    for (int k = 0; k < 6; ++k) {
      m[static_cast<std::size_t>(k)] = node(i) + k;
      m[static_cast<std::size_t>(6 + k)] = node(i + 1) + k;
    }
    m[12] = q4(i);
    m[13] = q4(i + 1);
    return m;
  }
};

template <int N, int I, std::size_t... K>
part<elastic_beam, spec<N>::segment(I)[K]...> segment_part(std::index_sequence<K...>);
template <int N, std::size_t... I>
condensed<spec<N>, decltype(segment_part<N, static_cast<int>(I)>(std::make_index_sequence<14>{}))...> chain_of(
    std::index_sequence<I...>);

/// The condensed composite of N BEAM3 segments.
template <int N>
using chain = decltype(chain_of<N>(std::make_index_sequence<static_cast<std::size_t>(N)>{}));

}  // namespace condensed_beam_detail

/// BEAM3C with N segments: a BEAM3 (same 15 parameters, same external DOFs and hidden q4 slots) whose length is cut
/// into N equal corotational segments; the N - 1 nodes between them (x y z q1 q2 q3 q4 each) are eliminated in every
/// call by nonlinear static condensation (condensed<...>), so the beam bends far beyond one corotational element's
/// small local rotations while the model has only its two end nodes. The catalog entry BEAM3C is N = 4
/// (`condensed_beam`); C++ models may use any N from 2 to 8.
///
/// The state vector holds the condensed DOFs of the last accepted step (the inner nodes' x y z q1 q2 q3 q4, node 1
/// first); the work vector, each segment's BEAM3 work (L0, N, strain energy) and the condensation's Newton counts.
/// No mass: pair it with BEAMI3 between the same nodes.
template <int N>
class condensed_beam_t {
  using chain_type = condensed_beam_detail::chain<N>;

 public:
  /// Number of segments.
  static constexpr int segments = N;
  static constexpr pradis::passport passport{.name = "BEAM3C",
                                             .ext = 12,
                                             .ent = 2,
                                             .par = 15,
                                             .str = chain_type::passport.str,
                                             .wrk = chain_type::passport.wrk,
                                             .adr = chain_type::passport.adr,
                                             .ign = chain_type::passport.ign};
  static_assert(chain_type::passport.ext == 12 && chain_type::passport.ent == 2, "pradis: BEAM3C keeps A, B and their q4");
  /// As BEAM3: q1..q3 of A at 3..5 with q4 at 12, of B at 9..11 with q4 at 13.
  static constexpr auto rotation_nodes = chain_type::rotation_nodes;
  static constexpr auto domains = chain_type::domains;
  static constexpr element_help help{
      .title = condensed_beam_detail::spec<N>::title,
      .name = "Elastic beam with axial, torsional and bending stiffness between two spatial nodes, cut into equal "
              "corotational BEAM3 segments whose inner nodes are condensed (large deflection with two nodes)",
      .field = condensed_beam_detail::spec<N>::field,
      .dofs = elastic_beam::help.dofs,
      .parameters = elastic_beam::help.parameters,
      .work = chain_type::help.work,
      .special = condensed_beam_detail::spec<N>::special};

  /// BEAM3's parameters, for the whole beam.
  using parameters = elastic_beam::parameters;

  explicit condensed_beam_t(parameters q) : p_(q), chain_(split(q)) {}
  static condensed_beam_t from_parameters(std::span<const double> v) {
    return condensed_beam_t(elastic_beam::from_parameters(v).p);
  }
  /// BEAM3's example (an oblique beam with an unsymmetric section).
  static parameters example() { return elastic_beam::example(); }

  /// The whole beam's parameters.
  const parameters& whole() const noexcept { return p_; }
  /// The condensed composite of the segments.
  const chain_type& chain() const noexcept { return chain_; }
  /// Segment i's BEAM3 parameters: the same section and section vector, ends at i/N and (i+1)/N of A -> B.
  static elastic_beam::parameters segment(const parameters& q, int i) {
    elastic_beam::parameters r = q;
    const double t0 = static_cast<double>(i) / N, t1 = static_cast<double>(i + 1) / N;
    r.xa = q.xa + (q.xb - q.xa) * t0;
    r.ya = q.ya + (q.yb - q.ya) * t0;
    r.za = q.za + (q.zb - q.za) * t0;
    r.xb = q.xa + (q.xb - q.xa) * t1;
    r.yb = q.ya + (q.yb - q.ya) * t1;
    r.zb = q.za + (q.zb - q.za) * t1;
    return r;
  }

  /// NEWINT: BEAM3's parameter checks on the whole beam (code 100 with BEAM3C's parameter numbers), then the
  /// segments'.
  void new_integration(element_context& ctx) {
    std::array<double, elastic_beam::passport.wrk> w{};
    const std::span<double> keep = ctx.work;
    ctx.work = w;
    try {
      elastic_beam(p_).new_integration(ctx);
    } catch (...) {
      ctx.work = keep;
      throw;
    }
    ctx.work = keep;
    chain_.new_integration(ctx);
  }

  /// The condensed flows and stiffness of the segments (condensed::evaluate).
  void evaluate(const local_input<condensed_beam_t>& in, local_output<condensed_beam_t>& out,
                element_context& ctx) const {
    local_input<chain_type> ci;
    ci.u = in.u;
    ci.v = in.v;
    ci.a = in.a;
    ci.t = in.t;
    local_output<chain_type> co;
    co.want_jacobian = out.want_jacobian;
    chain_.evaluate(ci, co, ctx);
    out.f = co.f;
    if (out.want_jacobian) out.K = co.K;
  }

  /// States at which the condensation converges and every segment admits its state (the checks' filter).
  bool admissible(const local_input<condensed_beam_t>& in) const {
    local_input<chain_type> ci;
    ci.u = in.u;
    ci.v = in.v;
    ci.a = in.a;
    ci.t = in.t;
    return chain_.admissible(ci);
  }

  /// Animation geometry (io/model_scene.hpp): a line between the end points, as BEAM3.
  template <class Drawer>
  void draw(Drawer& d) const {
    elastic_beam(p_).draw(d);
  }

 private:
  static typename chain_type::parameters split(const parameters& q) {
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return typename chain_type::parameters{std::tuple{segment(q, static_cast<int>(I))...}};
    }(std::make_index_sequence<static_cast<std::size_t>(N)>{});
  }

  parameters p_;
  chain_type chain_;
};

/// BEAM3C, the catalog entry: four segments (21 condensed DOFs).
using condensed_beam = condensed_beam_t<4>;

}  // namespace pradis::elements
