// Compile-time facts of the passport (manual section 3.3): which Jacobian blocks
// each valid ADR/IGN combination declares, the PAR/VPR count rules, and the
// STR/STP and WRK/WRP lengths. These are static_asserts: the file compiling is the test.

#include <doctest/doctest.h>

#include "pradis/core/passport.hpp"
#include "pradis/elements/library.hpp"

namespace {
using pradis::passport;
constexpr passport full{.name = "P", .ext = 1, .adr = 1, .ign = 0};
constexpr passport stiff_inertia{.name = "P", .ext = 1, .adr = 1, .ign = 2};
constexpr passport stiff_visc{.name = "P", .ext = 1, .adr = 1, .ign = 3};
constexpr passport stiff{.name = "P", .ext = 1, .adr = 1, .ign = 23};
constexpr passport visc_inertia{.name = "P", .ext = 1, .adr = 2, .ign = 0};
constexpr passport visc{.name = "P", .ext = 1, .adr = 2, .ign = 3};
constexpr passport inertia{.name = "P", .ext = 1, .adr = 3};

// The seven valid combinations of the manual and their blocks (K = dF/du, C = dF/dv, M = dF/da).
static_assert(full.has_k() && full.has_c() && full.has_m());
static_assert(stiff_inertia.has_k() && !stiff_inertia.has_c() && stiff_inertia.has_m());
static_assert(stiff_visc.has_k() && stiff_visc.has_c() && !stiff_visc.has_m());
static_assert(stiff.has_k() && !stiff.has_c() && !stiff.has_m());
static_assert(!visc_inertia.has_k() && visc_inertia.has_c() && visc_inertia.has_m());
static_assert(!visc.has_k() && visc.has_c() && !visc.has_m());
static_assert(!inertia.has_k() && !inertia.has_c() && inertia.has_m());
static_assert(pradis::passport_problem(full) == nullptr && pradis::passport_problem(visc) == nullptr &&
              pradis::passport_problem(inertia) == nullptr);

// Invalid combinations are named.
static_assert(pradis::passport_problem(passport{.name = "P", .ext = 1, .adr = 2, .ign = 2}) != nullptr);
static_assert(pradis::passport_problem(passport{.name = "P", .ext = 1, .adr = 3, .ign = 3}) != nullptr);
static_assert(pradis::passport_problem(passport{.name = "P", .ext = 0}) != nullptr);
static_assert(pradis::passport_problem(passport{.name = "", .ext = 1}) != nullptr);
static_assert(pradis::passport_problem(passport{.name = "P", .ext = 1, .vpr = 5}) != nullptr);
static_assert(pradis::passport_problem(passport{.name = "P", .ext = 1, .wrp = 1}) != nullptr);

// PAR/VPR: fixed count, variable (>= PAR), odd (11), even (21).
constexpr passport fixed3{.name = "P", .ext = 1, .par = 3};
constexpr passport var3{.name = "P", .ext = 1, .par = 3, .vpr = 1};
constexpr passport odd3{.name = "P", .ext = 1, .par = 3, .vpr = 11, .str = 1, .stp = 2, .wrk = 2, .wrp = 3};
constexpr passport even2{.name = "P", .ext = 1, .par = 2, .vpr = 21};
static_assert(fixed3.parameter_count_ok(3) && !fixed3.parameter_count_ok(4) && !fixed3.parameter_count_ok(2));
static_assert(var3.parameter_count_ok(3) && var3.parameter_count_ok(8) && !var3.parameter_count_ok(2));
static_assert(odd3.parameter_count_ok(3) && odd3.parameter_count_ok(5) && !odd3.parameter_count_ok(4) &&
              !odd3.parameter_count_ok(1));
static_assert(even2.parameter_count_ok(2) && even2.parameter_count_ok(6) && !even2.parameter_count_ok(5) &&
              !even2.parameter_count_ok(0));
// Lengths: STR + (npar - PAR) * STP and WRK + (npar - PAR) * WRP.
static_assert(odd3.state_size(3) == 1 && odd3.state_size(7) == 1 + 4 * 2);
static_assert(odd3.work_size(3) == 2 && odd3.work_size(5) == 2 + 2 * 3);

// The library's passports follow the manual's examples.
using namespace pradis::elements;
// Manual 3.6.6: EXT=4, PAR=5, WRK=3, ADR=1, IGN=23; pradis adds STR=2 (direction of the last accepted step).
static_assert(planar_link::passport ==
              passport{.name = "LINKD", .ext = 4, .par = 5, .str = 2, .wrk = 3, .adr = 1, .ign = 23});
static_assert(eccentric_mass::passport == passport{.name = "MEKS", .ext = 3, .par = 3, .adr = 1, .ign = 0});
static_assert(pradis::element_traits<planar_link>::has_k && !pradis::element_traits<planar_link>::has_c);
static_assert(pradis::element_traits<planar_inertia>::has_m && !pradis::element_traits<planar_inertia>::has_k);
// Absent blocks take no storage in the local output.
static_assert(sizeof(pradis::local_output<linear_spring>) < sizeof(pradis::local_output<eccentric_mass>));
// 50 mechanical + 12 hydraulic + 15 electric + 6 pneumatic
static_assert(pradis::library_model::element_types::size == 83);
// Two rotational nodes: SD3 has a's q1..q3 at 3..5 (q4 at 12) and b's at 9..11 (q4 at 13).
static_assert(pradis::element_traits<spatial_spring_damper>::rotations == 2);
static_assert(pradis::element_traits<spatial_spring_damper>::rotation_nodes[1] == pradis::rotation_slot{9, 13});
// Rotational nodes: BODY3 has q1..q3 at local 3..5 and the hidden q4 as its internal DOF 6.
static_assert(pradis::element_traits<rigid_body>::rotations == 1);
static_assert(pradis::element_traits<rigid_body>::rotation_nodes[0] == pradis::rotation_slot{3, 6});
static_assert(pradis::element_traits<planar_link>::rotations == 0);
static_assert(pradis::rotation_slots_problem(std::array<pradis::rotation_slot, 1>{{{4, 6}}}, 6, 1) != nullptr);
static_assert(pradis::rotation_slots_problem(std::array<pradis::rotation_slot, 1>{{{3, 5}}}, 6, 1) != nullptr);
static_assert(pradis::rotation_slots_problem(std::array<pradis::rotation_slot, 2>{{{0, 6}, {2, 7}}}, 6, 2) != nullptr);
}  // namespace

TEST_CASE("static/passport: the compile-time passport facts hold (see static_asserts in this file)") {
  CHECK(pradis::help_lines("a\nb\nc") == 3);
  CHECK(pradis::help_lines("") == 0);
  CHECK(pradis::help_lines("a\n") == 1);
}
