// SPDX-License-Identifier: MIT
// Constraint storage: model (the def and what creation fixed) and state (broken flag), kept apart from
// the bodies in a registry of their own so constraint handles never alias body handles.
#pragma once

#include "core/registry.h"
#include "dynamics/body.h"
#include "supermodal/constraint.h"
#include "supermodal/shape.h"

#include <vector>

namespace supermodal
{

/// Model: fixed between steps. Local anchors are re-resolved when a body's shape changes.
struct ConstraintModel {
    ConstraintDef def{};
    Vec3 local_a{};           ///< Anchor on a [m], shape frame (resolved from def.anchor_a).
    Vec3 local_b{};           ///< Anchor on b [m], shape frame, or a world point when b is null.
    double rest_length = 0.0; ///< Distance [m].
    Quat rest_relative{};     ///< q_a⁻¹·q_b at creation (weld, joint limits).
    Vec3 axis_a{0, 0, 1};     ///< Unit limit axis, a's frame.
};

/// State and derived values. `broken` and the impulses (which warm-start the next substep) are state:
/// hashed and snapshotted; the rest is recomputed.
struct ConstraintState {
    bool broken = false;
    Vec3 impulse{};          ///< Linear impulse on a in the last substep [N·s], world.
    Vec3 ang_impulse{};      ///< Angular impulse on b (weld) [N·m·s], world.
    Vec3 limit_impulse[2]{}; ///< Swing, twist limit angular impulses on a [N·m·s], world (λ·axis).
    ConstraintError error{}; ///< Derived: after the last substep.
    Vec3 force_on_a{};       ///< Derived: last substep [N].
};

using ConstraintRegistry = BasicRegistry<ConstraintModel, ConstraintState>;

struct ConstraintWorld {
    ConstraintRegistry reg;
    uint64_t broken_count = 0;  ///< Constraints broken since creation.
    std::vector<Entity> parent; ///< Model: parent by child entity index (null = none); see hierarchy.h.
    int iterations = 4;         ///< Gauss–Seidel passes per substep (WorldDef::constraint_iterations).
    bool split_islands = false; ///< Large islands in slabs for the threads (WorldDef::split_islands).
    double max_error = 0.0;     ///< Derived: largest linear error after the last substep [m].
};

[[nodiscard]] inline Entity to_entity(Constraint c)
{
    return Entity{c.index, c.generation};
}
[[nodiscard]] inline Constraint to_constraint(Entity e)
{
    return Constraint{e.index, e.generation};
}

/// The anchor in the shape frame of `shape` [m]; never NaN (falls back to the origin).
[[nodiscard]] Vec3 resolve_anchor(const ShapeDef& shape, const AnchorDef& anchor);
/// World point of a shape-frame point on a body [m].
[[nodiscard]] Vec3 world_point(const BodyModel& m, const Pose& p, const Vec3& local);
/// Re-resolves surface anchors on `body` after its shape changed to `shape`.
void refresh_anchors(ConstraintWorld& cw, Entity body, const ShapeDef& shape);
/// Destroys the constraints that hold `body` and its parent links (called when the body is destroyed).
void drop_constraints_of(ConstraintWorld& cw, Entity body);
/// Sorted keys (lower index << 32 | higher index) of body pairs that must not collide.
void non_colliding_pairs(const ConstraintWorld& cw, std::vector<uint64_t>& out_keys);

} // namespace supermodal
