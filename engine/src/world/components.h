// SPDX-License-Identifier: MIT
// The body registry: every component a body can have, from the areas below (dynamics: model, pose,
// velocity, forces; modal: deformation). Systems that walk it live in world/.
#pragma once

#include "core/registry.h"
#include "dynamics/body.h"
#include "modal/modal_body.h"

namespace supermodal
{

using Registry = BasicRegistry<BodyModel, Pose, Velocity, ForceAccumulator, ModalBody>;

} // namespace supermodal
