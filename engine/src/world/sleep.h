// SPDX-License-Identifier: MIT
// Sleeping (Box2D v3 and Jolt alike): a dynamic body that stays slow for WorldDef::sleep.time, together
// with every dynamic body it touches or is jointed to (its island), stops being integrated and
// collided; its pairs' anchors, manifolds and touch records are parked (ContactWorld::parked) until it
// wakes. Islands are rebuilt once per step from the last substep's touching pairs and the unbroken
// constraints, with world/islands.h; an island's id is its lowest entity index, so it does not depend on
// the order bodies or rows are visited, nor on threads.
//
// A sleeping island wakes whole: when an awake body's swept box reaches one of its bodies, when a
// constraint joins it to an awake body, and when the host edits one of its bodies.
#pragma once

#include "constraints/constraint_world.h"
#include "core/parallel.h"
#include "supermodal/world.h"
#include "world/components.h"
#include "world/contact_system.h"
#include "world/islands.h"

#include <vector>

namespace supermodal
{

/// Scratch of update_sleep(), kept between steps.
struct SleepScratch {
    IslandBuilder islands;
    std::vector<double> island_timer; ///< Per root entity index: its island's shortest timer [s].
    std::vector<uint8_t> ripe;        ///< Per thread part: 1 when a body's timer has run [-].
};

[[nodiscard]] inline bool is_asleep(const Registry& reg, Entity e)
{
    const Sleep* s = reg.find<Sleep>(e);
    return s != nullptr && s->asleep;
}

/// Wakes the island of `body` (if it sleeps) and restarts its timer: a host edit of the body.
void wake_island_of(Registry& reg, ContactWorld& io, Entity body);
/// Wakes every sleeping body (sleeping turned off, settings changed).
void wake_every_body(Registry& reg, ContactWorld& io);
/// Before the broadphase: wakes sleeping islands that an unbroken constraint joins to an awake body.
void wake_jointed(const ConstraintWorld& cw, const Parallel& par, Registry& reg, ContactWorld& io);
/// After the broadphase: wakes the sleeping islands an awake or moving body may reach this step and
/// returns true (the broadphase runs again, so the woken bodies find their pairs with other sleepers);
/// else drops the pairs with no awake dynamic body and returns false.
[[nodiscard]] bool settle_sleeping_pairs(const Parallel& par, Registry& reg, ContactWorld& io);
/// After the step: sleep timers, islands, and the islands that fall asleep. Returns the bodies asleep.
/// The per-body timers run on `par`'s threads, each body writing only its own.
size_t update_sleep(const WorldDef& def, const Parallel& par, Registry& reg, ContactWorld& io,
                    const ConstraintWorld& cw, SleepScratch& scratch);

} // namespace supermodal
