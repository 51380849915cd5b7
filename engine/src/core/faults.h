// SPDX-License-Identifier: MIT
// The step's fault log: filled by the guards that run after each integrating stage, published to the
// host in the Events stage. Scratch per step, not state.
#pragma once

#include "supermodal/fault.h"

#include <vector>

namespace supermodal
{

struct FaultLog {
    std::vector<FaultEvent> events; ///< This step's faults, in detection order.
    FaultEventFn callback = nullptr;
    void* user_data = nullptr;
    uint64_t step = 0; ///< Step being run (set at its start).
    int substep = 0;   ///< Substep being run.

    void record(FaultKind kind, Entity body, Stage stage)
    {
        events.push_back(FaultEvent{kind, body, stage, step, substep});
    }
};

} // namespace supermodal
