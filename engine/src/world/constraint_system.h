// SPDX-License-Identifier: MIT
// The constraint stage: the penalty springs of every constraint act on the bodies they join.
#pragma once

#include "constraints/constraint_world.h"
#include "dynamics/step_context.h"
#include "world/components.h"

namespace supermodal
{

/// Rows of other kinds solved in the same Gauss–Seidel passes (the soft contacts): after each pass
/// over the constraints, fn(ctx) runs one pass over them.
struct ExtraPass {
    void (*fn)(void* ctx) = nullptr;
    void* ctx = nullptr;
};

/// The springs' forces into velocities for one substep; updates errors and breaks. With `extra`, its
/// rows join every pass.
void apply_constraint_forces(const StepContext& ctx, Registry& bodies, ConstraintWorld& cw,
                             ExtraPass extra = {});

} // namespace supermodal
