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
    IslandBuilder islands;           ///< Islands of `rows` (and the extra rows after them).
    size_t row_count = 0;            ///< Constraint rows of the last substep; extra rows follow.
    std::vector<IslandSlabs> slabs; ///< The large islands' splits (the first split_count are this substep's).
    size_t split_count = 0;
    std::vector<uint32_t> island_split; ///< Per island: its split in `slabs`, or k_not_split.
};

/// An island small enough for one thread (island_split).
inline constexpr uint32_t k_not_split = UINT32_MAX;
/// Rows per slab when a large island is split for threads, and the most slabs: an island of fewer than
/// two slabs' rows is solved whole on one thread. Islands under 2·512 rows keep the serial order (and
/// bits) they always had; 8 slabs are enough to keep 8 threads busy with three phases per pass.
inline constexpr size_t k_rows_per_slab = 512;
inline constexpr size_t k_max_slabs = 8;

/// Rows of another kind solved in the same Gauss–Seidel passes (the soft contacts). Row i joins the
/// islands through the bodies nodes(i) names (k_no_node for an end no impulse changes) and is solved,
/// after its island's constraint rows in every pass, by solve(i); rows of different islands run on
/// different threads, so solve(i) must write only row i and its two bodies.
struct ExtraRows {
    size_t count = 0;
    void (*nodes)(void* ctx, size_t i, uint32_t& out_a, uint32_t& out_b) = nullptr;
    void (*solve)(void* ctx, size_t i) = nullptr;
    void (*warm_start)(void* ctx, size_t i) = nullptr; ///< Optional; runs before the rows' own.
    void* ctx = nullptr;
};

/// The springs' forces into velocities for one substep; updates errors and breaks. Per island through
/// `par`; with `extra`, its rows join the islands and every pass.
void apply_constraint_forces(const StepContext& ctx, const Parallel& par, Registry& bodies,
                             ConstraintWorld& cw, ConstraintScratch& scratch, ExtraRows extra = {});

/// More passes over the extra rows alone, island by island on the islands of the last
/// apply_constraint_forces (which must have had the same extra rows): fn(ctx, i) once per pass and row.
void solve_extra_rows(const Parallel& par, const ConstraintScratch& scratch, size_t extra_count, int passes,
                      void (*fn)(void* ctx, size_t i), void* ctx);

/// Fewest rows worth a thread part: below this, waking a worker costs more than the passes save.
inline constexpr size_t k_min_rows_per_part = 32;

} // namespace supermodal
