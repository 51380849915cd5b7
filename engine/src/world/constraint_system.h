// SPDX-License-Identifier: MIT
// The constraint stage: the penalty springs of every constraint act on the bodies they join.
//
// Threads: one row per constraint in constraint index order, each prepared on any thread (it reads the
// bodies and writes only itself), then grouped into islands (world/islands.h) of rows that share a body
// their impulses change; each island is warm-started and solved on one thread, its rows in that same
// order, and breaking and write-back follow serially. Rows of different islands share no written state,
// so results are bit-identical for any thread count.
#pragma once

#include "constraints/constraint_world.h"
#include "core/parallel.h"
#include "dynamics/step_context.h"
#include "world/components.h"
#include "world/constraint_row.h"
#include "world/islands.h"

#include <vector>

namespace supermodal
{

/// The constraint stage's buffers, kept from substep to substep so a warm step allocates nothing.
struct ConstraintScratch {
    std::vector<Entity> order;       ///< Constraints by entity index.
    std::vector<ConstraintRow> rows; ///< This substep's rows, in `order`.
    IslandBuilder islands;           ///< Islands of `rows`.
};

/// Rows of another kind solved in the same Gauss–Seidel passes (the soft contacts): after each pass over
/// the constraints, fn(ctx) runs one pass over them.
struct ExtraPass {
    void (*fn)(void* ctx) = nullptr;
    void* ctx = nullptr;
};

/// The springs' forces into velocities for one substep; updates errors and breaks. Per island through
/// `par`; with `extra`, whose rows may join any island, every row on this thread.
void apply_constraint_forces(const StepContext& ctx, const Parallel& par, Registry& bodies,
                             ConstraintWorld& cw, ConstraintScratch& scratch, ExtraPass extra = {});

/// Fewest rows worth a thread part: below this, waking a worker costs more than the passes save.
inline constexpr size_t k_min_rows_per_part = 32;

} // namespace supermodal
