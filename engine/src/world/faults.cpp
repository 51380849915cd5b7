// SPDX-License-Identifier: MIT
#include "world/faults.h"

#include "core/assert.h"
#include "world/world_impl.h"

namespace supermodal
{

void world_set_fault_callback(World& world, FaultEventFn fn, void* user_data)
{
    World::Impl& w = world.impl();
    SM_ASSERT(!w.locked, "world_set_fault_callback() called from inside a step");
    if (w.locked)
        return;
    w.faults.callback = fn;
    w.faults.user_data = user_data;
}

std::span<const FaultEvent> world_fault_events(const World& world)
{
    return world.impl().faults.events;
}

const char* fault_kind_name(FaultKind kind)
{
    switch (kind) {
    case FaultKind::BodyNonFinite:
        return "body_non_finite";
    case FaultKind::ModalNonFinite:
        return "modal_non_finite";
    }
    return "unknown";
}

} // namespace supermodal
