// SPDX-License-Identifier: MIT
// Part hierarchies (ThingWorld): a part may have a parent; an assembly is a part and everything
// below it. Parents do not move children by themselves — the constraints between parts do that —
// but an assembly can be moved as one, a parent and its child never collide (they usually overlap
// at a joint), and a part can be resized or reshaped while the world runs: its mass properties and
// contact model are rebuilt and the surface anchors of its constraints follow the new surface.
#pragma once

#include "supermodal/api.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/result.h"
#include "supermodal/shape.h"

#include <vector>

namespace supermodal
{

class World;

/// Makes `parent` the parent of `child` (a null parent detaches). Fails for stale handles, a body
/// that is its own ancestor (cycles), or while the world steps.
SM_API Status set_body_parent(World& world, Entity child, Entity parent);
/// The parent of a body, or null.
[[nodiscard]] SM_API Entity body_parent(const World& world, Entity body);
/// The direct children of a body, in entity-index order.
[[nodiscard]] SM_API std::vector<Entity> body_children(const World& world, Entity body);
/// `root` and all its descendants, in entity-index order.
[[nodiscard]] SM_API std::vector<Entity> assembly_of(const World& world, Entity root);

/// Moves `root`'s shape origin to `position` [m] with `orientation` (world_from_body) and carries the
/// whole assembly along rigidly: every descendant keeps its pose relative to root, and velocities are
/// rotated with it.
SM_API void move_assembly(World& world, Entity root, const Vec3& position, const Quat& orientation);

/// Replaces a body's shape between steps (resize, new ε, taper, bend). The shape origin stays where
/// it is; mass and inertia are recomputed with the body's density; the contact model is rebuilt;
/// direction and surface anchors of its constraints are re-resolved on the new surface, so attached
/// parts are pulled along. Fails for a stale handle, an invalid shape, a change of shape type
/// to or from a plane, or while the world steps.
SM_API Status set_body_shape(World& world, Entity body, const ShapeDef& shape);

} // namespace supermodal
