// SPDX-License-Identifier: MIT
// Contact events: what each pair did during a step (begin, persist, end), with the impulse it
// exchanged. Gathered per pair while the substeps run, turned into events once per step in the Events
// stage, in pair-key order, and handed to the host's callback there, serially.
//
// "Touching at the end of a step" means touching in its last substep. The previous step's touching
// pairs are kept here (not in the world's state): after restore() the first step's events are
// relative to what the host was last told, so its Begin/End bookkeeping stays balanced.
#pragma once

#include "contact/broadphase.h"
#include "supermodal/contact.h"

#include <span>
#include <vector>

namespace supermodal
{

/// What one candidate pair did over the step's substeps. A slot whose `step` is not the current
/// ContactEvents::step holds an earlier step's record and reads as untouched: the slots need no reset
/// per step (a serial write of every candidate pair's record, ~1 MB on a 4000-body pile).
struct PairTouch {
    uint64_t step = 0; ///< ContactEvents::step when written.
    bool touched = false;
    Vec3 point{}, normal{};    ///< At the last substep the pair touched [m], world.
    Vec3 impulse_on_a{};       ///< Σ h·F on a [N·s], world.
    double normal_impulse = 0; ///< Σ h·F_n [N·s].
    double depth = 0.0;        ///< Deepest over the step [m].
};

/// A pair touching at the end of a step, remembered for the next step's events.
struct TouchRecord {
    uint64_t key = 0;
    Entity a{}, b{};
    Vec3 point{}, normal{};
};

struct ContactEvents {
    std::vector<PairTouch> touch;      ///< Scratch: per candidate pair of this step (see PairTouch::step).
    uint64_t step = 0;                 ///< Scratch: counts begin_step_events calls.
    std::vector<TouchRecord> touching; ///< Derived: touching at the end of the last step, by key.
    std::vector<TouchRecord> next;     ///< Scratch.
    std::vector<ContactEvent> events;  ///< Derived: the last step's events.
    ContactEventFn callback = nullptr; ///< Host callback, or null.
    void* user_data = nullptr;         ///< Handed back to the callback.
};

/// Resets the per-pair accumulators for a step with pair_count candidate pairs.
void begin_step_events(ContactEvents& io_events, size_t pair_count);
/// Adds one substep of a touching pair (index into the step's pairs) lasting h [s].
void accumulate_touch(ContactEvents& io_events, size_t pair_index, const ContactInfo& info,
                      double normal_force, double h);
/// Builds the step's events from the step's pairs and the pairs touching in its last substep
/// (last_contacts, in pair order), then calls the host's callback for each, in order.
void publish_events(ContactEvents& io_events, std::span<const BodyPair> pairs,
                    std::span<const ContactInfo> last_contacts);

} // namespace supermodal
