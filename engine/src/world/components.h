// SPDX-License-Identifier: MIT
// The body registry: every component a body can have, from the areas below (dynamics: model, pose,
// velocity, forces; modal: deformation). Systems that walk it live in world/.
#pragma once

#include "core/registry.h"
#include "dynamics/body.h"
#include "modal/modal_body.h"

namespace supermodal
{

/// State: how long a body has been slow enough to sleep, and whether it sleeps (world/sleep.h).
struct Sleep {
    double timer = 0.0;           ///< [s] slow so far; hashed.
    bool asleep = false;          ///< Hashed.
    uint32_t island = UINT32_MAX; ///< While asleep: its island (lowest entity index in it at sleep time).
};

using Registry = BasicRegistry<BodyModel, Pose, Velocity, ForceAccumulator, ModalBody, Sleep>;

} // namespace supermodal
