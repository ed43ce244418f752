#pragma once
/// \file
/// Umbrella header: the kernel, the built-in element library and the integrators.

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/error.hpp"
#include "pradis/core/passport.hpp"
#include "pradis/elements/condensed.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/elements/spatial/plate_mesh.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/integrators/statistics_io.hpp"
#include "pradis/integrators/tolerance_ladder.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/linalg/sparse_lu.hpp"
#include "pradis/model/model.hpp"
#include "pradis/spatial/node_state.hpp"
#include "pradis/spatial/quaternion.hpp"
