// SPDX-License-Identifier: MIT
// Generational handles: a slot index plus the generation the slot had when the handle was made.
// Destroying an entity bumps its slot's generation, so an old handle is detected, never aliased.
#pragma once

#include <compare>
#include <cstdint>

namespace supermodal
{

/// Opaque handle to a body (or any entity) of a World. Entity{} is null: slot 0 is never handed out.
struct Entity {
    uint32_t index = 0;      ///< Slot in the world's entity pool [-].
    uint32_t generation = 0; ///< Generation of that slot when this handle was made [-].

    [[nodiscard]] constexpr bool is_null() const { return index == 0; }
    friend constexpr auto operator<=>(const Entity&, const Entity&) = default;
};

} // namespace supermodal
