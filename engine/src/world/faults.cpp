// SPDX-License-Identifier: MIT
#include "core/faults.h"

#include "core/assert.h"
#include "world/world_impl.h"

namespace supermodal
{

void world_set_fault_callback(World& world, FaultEventFn fn, void* user_data)
{
    World::Impl& w = impl_of(world);
    SM_ASSERT(!w.locked, "world_set_fault_callback() called from inside a step");
    if (w.locked)
        return;
    w.faults.callback = fn;
    w.faults.user_data = user_data;
}

std::span<const FaultEvent> world_fault_events(const World& world)
{
    return impl_of(world).faults.events;
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
