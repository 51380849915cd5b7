// SPDX-License-Identifier: MIT
#include "core/assert.h"
#include "supermodal/contact.h"
#include "world/world_impl.h"

namespace supermodal
{

std::span<const ContactInfo> world_contacts(const World& world)
{
    return impl_of(world).contact.contacts;
}

double world_max_penetration(const World& world)
{
    return impl_of(world).contact.max_penetration;
}

void world_set_contact_callback(World& world, ContactEventFn fn, void* user_data)
{
    World::Impl& w = impl_of(world);
    SM_ASSERT(!w.locked, "world_set_contact_callback() called from inside a step");
    if (w.locked)
        return;
    w.contact.events.callback = fn;
    w.contact.events.user_data = user_data;
}

std::span<const ContactEvent> world_contact_events(const World& world)
{
    return impl_of(world).contact.events.events;
}

} // namespace supermodal
