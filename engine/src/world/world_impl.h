// SPDX-License-Identifier: MIT
#pragma once

#include "constraints/constraint_world.h"
#include "core/faults.h"
#include "core/parallel.h"
#include "supermodal/world.h"
#include "world/components.h"
#include "world/constraint_system.h"
#include "world/contact_system.h"
#include "world/integrate.h"
#include "world/modal_system.h"
#include "world/sleep.h"

namespace supermodal
{

/// Buffers the step's stages keep from substep to substep, so a warm step allocates nothing.
struct StepScratch {
    IntegrateScratch integrate;
    ModalScratch modal;
    ConstraintScratch constraints;
    SleepScratch sleep;
};

struct World::Impl {
    WorldDef def{};
    Registry reg;
    double time = 0.0; ///< [s].
    uint64_t step_count = 0;
    double accumulator = 0.0; ///< Real time not yet stepped [s].
    StepProfile profile{};
    StepWarnings warnings{};
    FaultLog faults;                                        ///< Scratch: this step's NaN/Inf faults.
    ConstraintWorld constraints;                            ///< Penalty constraints (model + state).
    ContactWorld contact;                                   ///< Friction anchors (state) and contact scratch.
    std::vector<std::shared_ptr<const Collider>> colliders; ///< Model: one per distinct shape.
    std::shared_ptr<ModalBasisCache> modal_bases; ///< Model: one basis per distinct modal def (maybe shared).
    std::vector<ModalShared>
        modal_models; ///< Model: per distinct modal body (basis, collider, ModalBodyDef).
    StepListenerFn step_listener = nullptr; ///< Host hook before each step, or null.
    void* step_listener_data = nullptr;
    bool locked = false;               ///< True inside step(): mutations assert.
    std::shared_ptr<TaskSystem> tasks; ///< The host's task system, the built-in pool, or null (one thread).
    Parallel parallel;                 ///< The step's loops over `tasks`.
    StepScratch scratch;               ///< The stages' reusable buffers.

    void step();
    /// A substep's solve with the soft contact solver (after the narrowphase); `run` times the stages.
    template <class Run> void soft_substep(const StepContext& ctx, Run& run, bool reuse, bool last);
};

/// The engine's access to a world's insides (World::m_impl); hosts have only the public functions.
[[nodiscard]] inline World::Impl& impl_of(World& world)
{
    return *world.m_impl;
}
[[nodiscard]] inline const World::Impl& impl_of(const World& world)
{
    return *world.m_impl;
}

/// Mass, inverse mass and inertia of a body from its shape and density (zero inverses unless dynamic).
void set_mass_model(BodyModel& model, const ShapeDef& shape, double density);
/// Part of an auto body's displacement budget its contact samples may take (their sampling gap) [-]:
/// a quarter, as much as the modes it leaves out keep to when quiet (modal/adaptive.h).
inline constexpr double k_sampling_share_of_budget = 0.25;
/// The shared contact model for a shape whose centre of mass is `com` (shape frame) [m]; a
/// sampling_tolerance > 0 [m] chooses the sample spacing from it (contact/sample_density.h) unless the
/// world sets ContactDef::sample_spacing.
[[nodiscard]] std::shared_ptr<const Collider> collider_for(World::Impl& w, const ShapeDef& shape,
                                                           const Vec3& com, double sampling_tolerance = 0.0);

} // namespace supermodal
