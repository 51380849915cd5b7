// SPDX-License-Identifier: MIT
#include "supermodal/contact.h"
#include "world/world_impl.h"

namespace supermodal
{

std::span<const ContactInfo> world_contacts(const World& world)
{
    return world.impl().contact.contacts;
}

double world_max_penetration(const World& world)
{
    return world.impl().contact.max_penetration;
}

} // namespace supermodal
