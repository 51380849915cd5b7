// SPDX-License-Identifier: MIT
// Rigid-body integration: semi-implicit (symplectic) Euler for translation, and for rotation a
// torque kick followed by the torque-free flow solved by the implicit midpoint rule (see rotation.h).
#pragma once

#include "core/parallel.h"
#include "dynamics/step_context.h"
#include "supermodal/math.h"
#include "supermodal/world.h"
#include "world/components.h"

#include <vector>

namespace supermodal
{

[[nodiscard]] StepContext make_step_context(const WorldDef& def);

/// Per-part slots of the stages below, kept between substeps (one slot per thread part).
struct IntegrateScratch {
    std::vector<uint64_t> fallbacks; ///< integrate_positions: gyroscopic fallbacks per part.
    std::vector<size_t> first_bad;   ///< freeze_non_finite: first non-finite body per part.
};

/// Gravity and host forces into linear velocity; host torques into angular momentum (dynamic bodies).
void integrate_forces(const StepContext& ctx, const Parallel& par, Registry& reg);
/// Velocities into poses; the gyroscopic term is solved implicitly. Kinematic bodies follow their
/// velocities; static bodies never move.
void integrate_positions(const StepContext& ctx, const Parallel& par, Registry& reg,
                         IntegrateScratch& scratch, StepWarnings& io_warnings);
/// Remembers each pose at the start of a step: render interpolation blends from it, and the
/// non-finite guard falls back to it.
void store_previous_poses(const Parallel& par, Registry& reg);
/// Freezes bodies whose state is no longer finite (zero velocity, last finite pose, kinematic), so a
/// fault never spreads; counts each in io_warnings and logs it (as found after `stage`) when ctx has a log.
void freeze_non_finite(const StepContext& ctx, Stage stage, const Parallel& par, Registry& reg,
                       IntegrateScratch& scratch, StepWarnings& io_warnings);
/// Clears host forces once a step has used them.
void clear_forces(Registry& reg);

/// Fewest bodies worth a thread part in the per-body stages: below this, waking a worker costs more.
inline constexpr size_t k_min_bodies_per_part = 128;

} // namespace supermodal
