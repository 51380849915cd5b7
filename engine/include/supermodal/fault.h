// SPDX-License-Identifier: MIT
// Numerical faults: a body whose state turns NaN/Inf inside a step is caught in the substep where it
// happens, frozen (kinematic, last finite pose, zero velocity) before any other stage reads it, and
// reported to the host as an event. The step itself never fails.
#pragma once

#include "supermodal/api.h"
#include "supermodal/entity.h"
#include "supermodal/world.h"

#include <cstdint>
#include <span>

namespace supermodal
{

enum class FaultKind : uint8_t {
    BodyNonFinite,  ///< Pose or velocity turned NaN/Inf: the body is frozen (now kinematic).
    ModalNonFinite, ///< Modal amplitudes or rates turned NaN/Inf: reset to the rest shape.
};

/// One numerical fault, reported once per body and occurrence.
struct FaultEvent {
    FaultKind kind = FaultKind::BodyNonFinite;
    Entity body{};
    Stage stage = Stage::IntegratePositions; ///< The stage after which it was detected.
    uint64_t step = 0;                       ///< Index of the step (0 = the world's first step).
    int substep = 0;                         ///< Substep of that step, from 0.
};

/// Host callback for fault events, called serially in the step's Events stage (after the contact
/// events), in detection order.
using FaultEventFn = void (*)(const FaultEvent& event, void* user_data);

/// Registers fn (user_data handed back on each call); a null fn removes it. Not from inside a step.
SM_API void world_set_fault_callback(World& world, FaultEventFn fn, void* user_data);
/// The fault events of the last step.
[[nodiscard]] SM_API std::span<const FaultEvent> world_fault_events(const World& world);
/// "body_non_finite" / "modal_non_finite".
[[nodiscard]] SM_API const char* fault_kind_name(FaultKind kind);

} // namespace supermodal
