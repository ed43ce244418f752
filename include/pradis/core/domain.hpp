#pragma once
/// \file
/// Physical domains of DOFs and the nominal magnitudes that scale the absolute
/// tolerances per DOF.
///
/// In the nodal method every DOF carries a potential at the velocity level (the
/// unknown of Newton) and a flow (its residual): speed and force in mechanics,
/// pressure and volume flow in hydraulics, pressure and mass flow in pneumatics,
/// voltage and current in electric circuits (docs/domains.md). One absolute
/// tolerance for all of them would be meaningless: DABSI = 0.1 is a tight force
/// residual in newtons but lets a volume flow of 1e-4 m^3/s pass unchecked. So the
/// absolute tolerances DABSU (Newton correction), DABSI (Newton residual) and DABSX
/// (local error) are multiplied per DOF by that DOF's nominal potential or flow.
/// The mechanical nominal values are 1, so mechanical models keep PRADIS's
/// tolerances unchanged.

#include <array>
#include <cmath>
#include <cstddef>
#include <string_view>
#include <type_traits>

namespace pradis {

/// The physical domain of a DOF. `unspecified` behaves as `mechanical`; an element
/// that declares the domain of a slot gives an unspecified DOF that domain.
enum class domain : unsigned char { unspecified, mechanical, hydraulic, pneumatic, electric };

/// Name of a domain as used in messages ("hydraulic").
constexpr std::string_view to_string(domain d) noexcept {
  switch (d) {
    case domain::unspecified: return "unspecified";
    case domain::mechanical: return "mechanical";
    case domain::hydraulic: return "hydraulic";
    case domain::pneumatic: return "pneumatic";
    case domain::electric: return "electric";
  }
  return "unknown";
}

/// Nominal magnitudes of a DOF: of its potential at the velocity level (the Newton
/// unknown) and of its flow (the residual). The absolute tolerances are multiplied by
/// them: |dv| <= DABSU * potential + DRLTU |v|, |F| <= DABSI * flow + DRLTI sum|f|,
/// local error <= DABSX * potential + DRLTX |v|.
struct dof_scale {
  double potential = 1.0;  ///< nominal potential (m/s, rad/s, Pa, V)
  double flow = 1.0;       ///< nominal flow (N, N m, m^3/s, kg/s, A)
  friend constexpr bool operator==(const dof_scale&, const dof_scale&) = default;
  /// True when both magnitudes are finite and positive.
  bool valid() const noexcept {
    return std::isfinite(potential) && std::isfinite(flow) && potential > 0 && flow > 0;
  }
};

/// The default nominal magnitudes of a domain (docs/domains.md has the table):
/// mechanical 1 m/s and 1 N; hydraulic 1 bar = 1e5 Pa and 1e-5 m^3/s (0.6 l/min);
/// pneumatic 1e5 Pa and 1e-5 kg/s; electric 1 V and 1 mA.
constexpr dof_scale default_scale(domain d) noexcept {
  switch (d) {
    case domain::hydraulic: return {1e5, 1e-5};
    case domain::pneumatic: return {1e5, 1e-5};
    case domain::electric: return {1.0, 1e-3};
    case domain::unspecified:
    case domain::mechanical: break;
  }
  return {1.0, 1.0};
}

namespace detail {
template <class E>
concept declares_domains = requires {
  { E::domains.size() } -> std::convertible_to<std::size_t>;
  { E::domains[0] } -> std::convertible_to<domain>;
};
}  // namespace detail

/// The domain an element declares for its local DOF k (external first, then
/// internal): `E::domains[k]` when the element has a `static constexpr
/// std::array<domain, M> domains` (M = EXT or EXT + ENT; missing slots are
/// unspecified), else unspecified. Mechanical elements need not declare anything.
template <class E>
constexpr domain declared_domain(int k) noexcept {
  if constexpr (detail::declares_domains<E>) {
    if (k >= 0 && static_cast<std::size_t>(k) < E::domains.size()) return E::domains[static_cast<std::size_t>(k)];
  }
  return domain::unspecified;
}

}  // namespace pradis
