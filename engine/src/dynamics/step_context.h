// SPDX-License-Identifier: MIT
// What every stage of one substep needs to know.
#pragma once

#include "core/faults.h"
#include "supermodal/math.h"

namespace supermodal
{

struct StepContext {
    double h = 0.0; ///< Substep length [s].
    Vec3 gravity{}; ///< [m/s²], world.
    int substep_count = 1;
    FaultLog* faults = nullptr; ///< Where the guards report NaN/Inf, or null.
};

} // namespace supermodal
