// Help text of every library element (manual section 3.4): the "special
// situations" entry names the code-100 situation the element checks, and the
// kinematic and initial-condition elements and LINKD also name their code 90 / 75.

#include <doctest/doctest.h>

#include <string>
#include <string_view>

#include "pradis/elements/library.hpp"

namespace {

/// The phrase each element's help.special must contain besides "code 100": its check.
constexpr std::string_view code100_situation(std::string_view name) {
  if (name == "MASS") return "m < 0";
  if (name == "SPRING") return "k < 0";
  if (name == "TSPRING") return "the deformations do not increase strictly";
  if (name == "FRICT") return "Fc > Fs";
  if (name == "GEAR") return "r = 0";
  if (name == "BELT") return "mu < 0";
  if (name == "DAMPER") return "c < 0";
  if (name == "F") return "not finite";
  if (name == "FSIN" || name == "XSRC" || name == "VSRC") return "f < 0";
  if (name == "X0") return "u0 is changed";
  if (name == "V0") return "v0 is changed";
  if (name == "MD") return "J < 0";
  if (name == "LINKD" || name == "LINKX") return "coincide";
  if (name == "MEKS") return "R < 0";
  if (name == "BODY3") return "not positive definite";
  if (name == "F3" || name == "M3" || name == "F3B" || name == "F3A" || name == "M3B") return "f < 0";
  if (name == "ROT0") return "changed after the zero step";
  if (name == "SD3" || name == "RSD3") return "k < 0";
  if (name == "SPH3") return "k <= 0";
  if (name == "REV3") return "kr <= 0";
  if (name == "SPH3X") return "a parameter is not finite";
  if (name == "REV3X") return "a hinge axis is zero";
  if (name == "UNI3X") return "a cross axis is zero";
  if (name == "CYL3X") return "an axis is zero";
  if (name == "PRI3X" || name == "FIX3X") return "a reference vector is parallel to its axis";
  if (name == "PTL3X") return "the direction is zero";
  if (name == "PTP3X") return "the normal is zero";
  if (name == "CSPHPL") return "R <= 0";
  if (name == "CSPHSP") return "R1 <= 0";
  if (name == "PIN2X") return "a parameter is not finite";
  if (name == "ELLPL") return "mu_k > mu_s";
  if (name == "CAM") return "k <= 0, c < 0";
  if (name == "TDAMPER") return "the velocities do not increase strictly";
  if (name == "SHC3") return "the axis is zero, k <= 0, c < 0";
  if (name == "BEAM3" || name == "BEAM3C" || name == "BEAMI3") return "coincide";
  if (name == "TRIPL") return "do not span a triangle";
  if (name == "THROW" || name == "THROWP") return "naming the part";
  if (name == "FLEX3") return "resists a rigid-body motion";
  if (name == "HVOL") return "V, B, pa or n is not positive";
  if (name == "HORL") return "R is not positive";
  if (name == "HORT") return "Cd, A, rho or dpt is not positive";
  if (name == "HLINE") return "a parameter is not positive";
  if (name == "HPUMP" || name == "HMOTOR") return "D is not positive";
  if (name == "HCYL") return "an area, the stroke, a dead volume, B or w is not positive";
  if (name == "HV22" || name == "HV43") return "Cd, Amax, rho, dpt or xmax is not positive";
  if (name == "HRELIEF" || name == "HCHECK") return "Cd, Amax, rho, dpt or dpo is not positive";
  if (name == "HACC") return "a parameter is not positive";
  if (name == "R") return "R <= 0";
  if (name == "C") return "C <= 0";
  if (name == "L") return "L <= 0";
  if (name == "IDC" || name == "VDC" || name == "VDC2" || name == "PNSRC" || name == "PNQ") return "not finite";
  if (name == "ISIN" || name == "VSIN" || name == "VSIN2") return "f < 0";
  if (name == "ITAB" || name == "VTAB" || name == "VTAB2") return "the count is not even";
  if (name == "D" || name == "PNVOL" || name == "PNCHP" || name == "PNCYL" || name == "PNORF")
    return "outside its range";
  if (name == "SW") return "t2 < t1 + tau";
  if (name == "DCM") return "both are zero";
  return "";
}

template <class E>
void check_special() {
  const std::string name(E::passport.name);
  const std::string special(E::help.special);
  CAPTURE(name);
  CAPTURE(special);
  REQUIRE_FALSE(code100_situation(name).empty());  // a new element needs its line in this table
  CHECK(special.find("code 100") != std::string::npos);
  CHECK(special.find(code100_situation(name)) != std::string::npos);
  if (name == "XSRC" || name == "VSRC" || name == "X0" || name == "V0" || name == "VDC" || name == "VSIN" ||
      name == "VTAB" || name == "PNSRC" || name == "PNVOL" || name == "PNCHP" || name == "PNCYL")
    CHECK(special.find("code 90") != std::string::npos);
  if (name == "LINKD" || name == "BODY3" || name == "F3B" || name == "F3A" || name == "M3B" || name == "SD3" ||
      name == "RSD3" || name == "SPH3" || name == "REV3" || name == "BEAM3" || name == "BEAM3C" || name == "BEAMI3" ||
      name == "SHC3" || name == "HVOL" || name == "HCYL" || name == "HACC" || name == "ELLPL" || name == "PNVOL" ||
      name == "PNCHP" || name == "PNCYL" ||
      name == "PNORF" || name == "CSPHPL" || name == "CSPHSP" || name == "THROW" || name == "THROWP" ||
      name == "FLEX3")
    CHECK(special.find("code 75") != std::string::npos);
  if (name == "ROT0") CHECK(special.find("code 90") != std::string::npos);
}

template <class... Es>
void check_all_special(pradis::type_list<Es...>) {
  (check_special<Es>(), ...);
}

}  // namespace

TEST_SUITE("elements/help") {
  TEST_CASE("the help text of every library element names its code-100 situations (and 90 / 75 where they apply)") {
    static_assert(pradis::elements::library_elements::size == 83);
    check_all_special(pradis::elements::library_elements{});
  }
}
