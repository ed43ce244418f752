#pragma once
// The spun-up free steel bar of the FLEX3 tests and benchmarks: a bar of 20 mm x
// 20 mm, 1 m long along X, driven about Z at its root by the torque
// M0 (1 - cos(2 pi 5 t)), either as n BEAM3 + BEAMI3 or as one FLEX3 made from the
// same n elements (straight_beam_matrices) reduced to the two ends and NM
// fixed-interface modes. Used by tests/spatial/test_reduced_body.cpp (the
// rotating-beam comparison), tests/lang/test_craig_bampton_files.cpp (the steel
// section) and bench/bench_reduction.cpp (time per simulated second against the
// number of elements).

#include <cmath>
#include <string>
#include <vector>

#include "pradis/elements/spatial/beam.hpp"
#include "pradis/elements/spatial/beam_inertia.hpp"
#include "pradis/elements/spatial/beam_matrices.hpp"
#include "pradis/elements/spatial/loads.hpp"
#include "pradis/elements/spatial/reduced_body.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/linalg/reduction.hpp"
#include "pradis/model/model.hpp"
#include "pradis/spatial/node_state.hpp"

namespace spun_bar {

/// Steel, 20 mm x 20 mm square (free-free first bending frequency of the 1 m bar
/// about 106 Hz); J of the square 0.1406 a^4.
inline constexpr pradis::elements::beam_section steel{.e = 2.1e11,
                                                      .g = 8.1e10,
                                                      .a = 4e-4,
                                                      .iy = 0.02 * 0.02 * 0.02 * 0.02 / 12,
                                                      .iz = 0.02 * 0.02 * 0.02 * 0.02 / 12,
                                                      .j = 2.25e-8,
                                                      .rho = 7850,
                                                      .ip = 2 * 0.02 * 0.02 * 0.02 * 0.02 / 12};

/// K and M of the bar from the origin along X (section axis v = Y) in n elements.
inline pradis::elements::beam_matrices bar_matrices(int n, double length = 1.0) {
  return pradis::elements::straight_beam_matrices(steel, {0, 0, 0}, {length, 0, 0}, {0, 1, 0}, n);
}

/// FLEX3's parameters of the bar of n elements reduced to its two ends and NM modes.
template <int NM>
typename pradis::elements::reduced_body<2, NM>::parameters reduced_bar(int n, double length = 1.0) {
  const pradis::elements::beam_matrices bm = bar_matrices(n, length);
  std::vector<int> b;
  for (int j = 0; j < 6; ++j) b.push_back(j);
  for (int j = 0; j < 6; ++j) b.push_back(6 * n + j);
  return pradis::elements::reduced_body<2, NM>::from_part(pradis::linalg::craig_bampton(bm.k, bm.m, b, NM),
                                                          {pradis::spatial::vec3::Zero(), pradis::spatial::vec3(length, 0, 0)});
}

/// The driving torque about Z at the root: M0 (1 - cos(2 pi f t)), f = 5 Hz (smooth start, far below the bar's modes).
inline pradis::elements::spatial_torque::parameters drive(double m0) { return {0, 0, m0, 0, 0, -m0, 5.0, 90}; }

/// Newton tolerances below the accuracy compared (flows of the bar up to ~1e3 N).
inline constexpr pradis::newton_options newton{.dabsu = 1e-10, .drltu = 0, .dabsi = 1e-6, .drlti = 0, .itr = 10};

/// One sample: time, the tip's deflection across the bar in the root's frame, the root's angle.
struct sample {
  double t = 0, deflection = 0, angle = 0;
};

template <class Sim>
sample sample_of(const Sim& sim, const std::vector<pradis::dof>& root, pradis::rotation_node r0,
                 const std::vector<pradis::dof>& tip) {
  using pradis::spatial::vec3;
  const vec3 c(1.0 + sim.u(tip[0]) - sim.u(root[0]), sim.u(tip[1]) - sim.u(root[1]), sim.u(tip[2]) - sim.u(root[2]));
  const vec3 local = pradis::spatial::node_rotation(sim, r0).transpose() * c;
  const pradis::spatial::quaternion q = pradis::spatial::node_quaternion(sim, r0);
  return {sim.time(), local(1), 2 * std::atan2(q(2), q(3))};
}

/// Runs `sim` with step h up to `end`, sampling every 10 ms.
template <class Sim>
std::vector<sample> samples(Sim& sim, double end, double h, const std::vector<pradis::dof>& root,
                            pradis::rotation_node r0, const std::vector<pradis::dof>& tip) {
  std::vector<sample> out;
  for (int k = 1; k * 0.01 <= end + 1e-12; ++k) {
    sim.run({.end = k * 0.01, .smax = h, .smin = h / 64, .newton = newton});
    out.push_back(sample_of(sim, root, r0, tip));
  }
  return out;
}

/// The spun bar as one FLEX3 with the parameters `p` (reduced_bar).
template <int NM>
std::vector<sample> spin_reduced(double m0, double end, double h,
                                 const typename pradis::elements::reduced_body<2, NM>::parameters& p) {
  using body = pradis::elements::reduced_body<2, NM>;
  pradis::model<body, pradis::elements::spatial_torque> m;
  const auto x0 = m.add_dofs(3, "x0");
  const auto r0 = m.add_rotation_node("r0");
  const auto x1 = m.add_dofs(3, "x1");
  const auto r1 = m.add_rotation_node("r1");
  m.template add<body>("bar", p, x0[0], x0[1], x0[2], r0, x1[0], x1[1], x1[2], r1);
  m.template add<pradis::elements::spatial_torque>("drive", drive(m0), r0);
  pradis::simulation sim(m);
  return samples(sim, end, h, x0, r0, x1);
}

/// The spun bar as one FLEX3 (the ends and NM modes of n elements).
template <int NM>
std::vector<sample> spin_reduced(double m0, double end, double h, int n) {
  return spin_reduced<NM>(m0, end, h, reduced_bar<NM>(n));
}

/// The spun bar as n BEAM3 + BEAMI3.
inline std::vector<sample> spin_beams(double m0, double end, double h, int n) {
  using namespace pradis::elements;
  pradis::model<elastic_beam, beam_inertia, spatial_torque> m;
  std::vector<std::vector<pradis::dof>> x;
  std::vector<pradis::rotation_node> r;
  for (int i = 0; i <= n; ++i) {
    x.push_back(m.add_dofs(3, "x" + std::to_string(i)));
    r.push_back(m.add_rotation_node("r" + std::to_string(i)));
  }
  const double le = 1.0 / n;
  const beam_section& s = steel;
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
    const double xa = static_cast<double>(i) * le, xb = xa + le;
    const auto &a = x[i], &b = x[i + 1];
    m.add<elastic_beam>("b" + std::to_string(i), {s.e, s.g, s.a, s.iy, s.iz, s.j, xa, 0, 0, xb, 0, 0, 0, 1, 0}, a[0], a[1],
                        a[2], r[i], b[0], b[1], b[2], r[i + 1]);
    m.add<beam_inertia>("m" + std::to_string(i), {s.rho, s.a, s.iy, s.iz, s.ip, xa, 0, 0, xb, 0, 0, 0, 1, 0}, a[0], a[1],
                        a[2], r[i], b[0], b[1], b[2], r[i + 1]);
  }
  m.add<spatial_torque>("drive", drive(m0), r[0]);
  pradis::simulation sim(m);
  return samples(sim, end, h, x[0], r[0], x[static_cast<std::size_t>(n)]);
}

/// The largest difference of the tip deflection of `b` from `a`'s, relative to a's peak.
inline double deflection_difference(const std::vector<sample>& a, const std::vector<sample>& b) {
  double peak = 0, diff = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    peak = std::max(peak, std::abs(a[i].deflection));
    diff = std::max(diff, std::abs(a[i].deflection - b[i].deflection));
  }
  return peak > 0 ? diff / peak : 0.0;
}

}  // namespace spun_bar
