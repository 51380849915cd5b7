// SPDX-License-Identifier: MIT
// The per-body "modal" block of `supermodal run`'s summary: accuracy report, stress, plasticity.
#pragma once

#include "supermodal/world.h"

#include <nlohmann/json.hpp>

namespace supermodal::cli
{

/// Adds a "modal" object to each modal body's entry of `io_bodies` (one entry per world_bodies(world),
/// in that order): energy, the accuracy report of the last substep, peak stress, plastic state, and for
/// "auto" bodies the modes chosen and the displacement left out.
void add_modal_summaries(const World& world, nlohmann::json& io_bodies);

} // namespace supermodal::cli
