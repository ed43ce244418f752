#pragma once
/// \file
/// The built-in example model run by `pradis run` without a file: the manual's
/// two-body system (section 3.6.9). The same text is examples/models/two_bodies.prd
/// (a test checks that they are identical).

#include <string_view>

namespace pradis::lang {

/// File name under which the built-in example is reported.
inline constexpr std::string_view builtin_example_name = "two_bodies.prd";

/// Text of the built-in example model.
inline constexpr std::string_view builtin_example = R"PRADIS(* The two-body system of the PRADIS element developer's manual (Fig. 3.3,
* section 3.6.9): two bodies in plane motion (MD) joined at their centres of
* gravity by an ideal elastic link (LINKD), a force of 1e3 N downward on body 2.
* Same parameters and run options as examples/two_bodies/main.cpp.
$DATA:
    Center of gravity of body 1 = 1, 1
    Center of gravity of body 2 = 2, 2
    Mass and the moment of the inertia of body 1 = 1, 0.1
    Mass and the moment of the inertia of body 2 = 2, 0.1
    Hardness of connection = 5E3
    Force = -1.E3
$FRAGMENT:
#BASE:
#STRUCTURE:
    Body 1 'MD (1 2 3; Mass and the moment of the inertia of body 1)
    Body 2 'MD (4 5 6; Mass and the moment of the inertia of body 2)
    Connection 'LINKD (1 2 4 5; Center of gravity of body 1,
                                Center of gravity of body 2,
                                Hardness of connection)
    Force 'F (5; Force)
#OUTPUT:
    Displacement of body 2X 'X (4; 1)
    Displacement of body 2Y 'X (5; 1)
    Bond length 'X (W:Connection(2); 1)
    Effort of deformation 'X (W:Connection(3); 1)
$RUN:
    Calculation 'SHTERM (END=1, OUT=0.005, SMAX=1E-4,
                         DABSU=1E-8, DRLTU=1E-8, DABSI=1E-6, DRLTI=1E-8)
$PRINT:
    Results of calculation 'DISP ()
$END
)PRADIS";

}  // namespace pradis::lang
