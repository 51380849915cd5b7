// SPDX-License-Identifier: MIT
// The constraint stage: the penalty springs of every constraint act on the bodies they join.
#pragma once

#include "constraints/constraint_world.h"
#include "dynamics/step_context.h"
#include "world/components.h"

namespace supermodal
{

/// The springs' forces into velocities for one substep; updates errors and breaks.
void apply_constraint_forces(const StepContext& ctx, Registry& bodies, ConstraintWorld& cw);

} // namespace supermodal
