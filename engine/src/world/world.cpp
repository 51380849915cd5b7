// SPDX-License-Identifier: MIT
#include "supermodal/world.h"

#include "core/assert.h"
#include "supermodal/tasks.h"
#include "world/constraint_system.h"
#include "world/contact_system.h"
#include "world/integrate.h"
#include "world/modal_system.h"
#include "world/remould.h"
#include "world/world_impl.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace supermodal
{
namespace
{

constexpr int k_max_substeps = 1000;
// More threads than this is a mistake for per-pair loops on one machine, not a setting.
constexpr int k_max_threads = 64;

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Status validate_soft(const SoftContactDef& soft)
{
    if (!(soft.frequency_hz >= 0.0) || !std::isfinite(soft.frequency_hz))
        return Error{"", "contact.soft.frequency_hz", "expected a finite frequency >= 0 Hz"};
    if (!(soft.damping_ratio >= 0.0) || !std::isfinite(soft.damping_ratio))
        return Error{"", "contact.soft.damping_ratio", "expected a finite ratio >= 0"};
    if (!(soft.push_out_speed > 0.0) || !std::isfinite(soft.push_out_speed))
        return Error{"", "contact.soft.push_out_speed", "expected a finite speed > 0 m/s"};
    if (!(soft.restitution_speed >= 0.0) || !std::isfinite(soft.restitution_speed))
        return Error{"", "contact.soft.restitution_speed", "expected a finite speed >= 0 m/s"};
    if (soft.iterations < 1 || soft.iterations > 100)
        return Error{"", "contact.soft.iterations", "expected an integer in [1, 100]"};
    if (soft.relax_iterations < 0 || soft.relax_iterations > 100)
        return Error{"", "contact.soft.relax_iterations",
                     "expected an integer in [0, 100] (0: as iterations)"};
    if (soft.substeps < 0 || soft.substeps > 64)
        return Error{"", "contact.soft.substeps", "expected an integer in [0, 64] (0: automatic)"};
    return {};
}

} // namespace

WorldDef default_world_def()
{
    return WorldDef{};
}

Status validate(const WorldDef& def)
{
    if (!(def.dt > 0.0) || !std::isfinite(def.dt))
        return Error{"", "dt", "expected a finite step > 0 s"};
    if (def.substep_count < 1 || def.substep_count > k_max_substeps)
        return Error{"", "substep_count", "expected an integer in [1, 1000]"};
    if (!is_finite(def.gravity))
        return Error{"", "gravity", "expected a finite vector"};
    if (def.max_steps_per_advance < 1)
        return Error{"", "max_steps_per_advance", "expected an integer >= 1"};
    if (def.constraint_iterations < 1 || def.constraint_iterations > 100)
        return Error{"", "constraint_iterations", "expected an integer in [1, 100]"};
    if (def.thread_count < 1 || def.thread_count > k_max_threads)
        return Error{"", "thread_count", "expected an integer in [1, 64]"};
    if (!(def.sleep.linear_speed >= 0.0) || !std::isfinite(def.sleep.linear_speed))
        return Error{"", "sleep.linear_speed", "expected a finite speed >= 0 m/s"};
    if (!(def.sleep.angular_speed >= 0.0) || !std::isfinite(def.sleep.angular_speed))
        return Error{"", "sleep.angular_speed", "expected a finite angular speed >= 0 rad/s"};
    if (!(def.sleep.time > 0.0) || !std::isfinite(def.sleep.time))
        return Error{"", "sleep.time", "expected a finite time > 0 s"};
    return validate_soft(def.contact.soft);
}

std::string_view stage_name(Stage stage)
{
    switch (stage) {
    case Stage::IntegrateForces:
        return "integrate_forces";
    case Stage::Broadphase:
        return "broadphase";
    case Stage::Narrowphase:
        return "narrowphase";
    case Stage::PenaltyForces:
        return "penalty_forces";
    case Stage::ModalUpdate:
        return "modal_update";
    case Stage::IntegratePositions:
        return "integrate_positions";
    case Stage::UpdateSurfaces:
        return "update_surfaces";
    case Stage::Events:
        return "events";
    case Stage::Count:
        break;
    }
    return "unknown";
}

World::World(const WorldDef& def) : m_impl(std::make_unique<Impl>())
{
    SM_ASSERT(validate(def).ok(), "invalid WorldDef");
    m_impl->def = validate(def).ok() ? def : default_world_def();
    m_impl->modal_bases =
        m_impl->def.modal_basis_cache ? m_impl->def.modal_basis_cache : std::make_shared<ModalBasisCache>();
    m_impl->tasks = m_impl->def.task_system;
    if (!m_impl->tasks && m_impl->def.thread_count > 1)
        m_impl->tasks = make_thread_pool(m_impl->def.thread_count);
    m_impl->parallel = Parallel(m_impl->tasks.get());
}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

// The step, stage by stage. Pairs come once per step from swept boxes, which also tells how many
// substeps keep fast bodies from tunnelling; every other stage runs per substep.
void World::Impl::step()
{
    SM_ASSERT(!locked, "step() re-entered from a callback");
    locked = true;
    const auto step_start = Clock::now();
    profile = StepProfile{};
    auto run = [this](Stage stage, auto&& fn) {
        const auto start = Clock::now();
        fn();
        profile.stage_ms[static_cast<size_t>(stage)] += ms_since(start);
    };
    store_previous_poses(parallel, reg);
    int substeps = def.substep_count;
    run(Stage::Broadphase, [&] {
        non_colliding_pairs(constraints, contact.excluded_pairs);
        wake_jointed(constraints, parallel, reg, contact);
        substeps = update_pairs(def, parallel, reg, contact);
        profile.pair_count = contact.pairs.size();
    });
    // Modal bodies that just joined a pair get their deformed samples before the narrowphase reads them.
    run(Stage::UpdateSurfaces, [&] { update_modal_surfaces(parallel, reg, contact.pairs, scratch.modal); });
    if (substeps > def.substep_count)
        warnings.speculative_substeps += static_cast<uint64_t>(substeps - def.substep_count);
    // The soft solver's own substeps reuse each narrowphase's points (Box2D v3's soft step).
    const int solver_substeps = def.contact.solver == ContactSolver::Soft
                                    ? soft_solver_substeps(def.contact.soft, def.dt / substeps)
                                    : 1;
    StepContext ctx = make_step_context(def);
    ctx.substep_count = substeps * solver_substeps;
    ctx.h = def.dt / ctx.substep_count;
    ctx.faults = &faults;
    faults.events.clear();
    faults.step = step_count;
    // Guards run after every stage that writes velocities or poses, so a body that turns NaN/Inf is
    // frozen before any later stage (or neighbour) reads it.
    for (int i = 0; i < ctx.substep_count; ++i) {
        faults.substep = i;
        run(Stage::IntegrateForces, [&] {
            integrate_forces(ctx, parallel, reg);
            freeze_non_finite(ctx, Stage::IntegrateForces, parallel, reg, scratch.integrate, warnings);
        });
        const bool collide = i % solver_substeps == 0;
        if (collide)
            run(Stage::Narrowphase, [&] { collide_pairs(def, reg, parallel, contact); });
        if (def.contact.solver == ContactSolver::Soft) {
            soft_substep(ctx, run, !collide, (i + 1) % solver_substeps == 0);
            continue;
        }
        run(Stage::PenaltyForces, [&] {
            apply_penalty_forces(def, ctx, reg, parallel, contact, warnings);
            constraints.iterations = def.constraint_iterations;
            constraints.split_islands = def.split_islands;
            apply_constraint_forces(ctx, parallel, reg, constraints, scratch.constraints);
            freeze_non_finite(ctx, Stage::PenaltyForces, parallel, reg, scratch.integrate, warnings);
            update_contact_anchors(ctx, reg, parallel, contact);
        });
        run(Stage::ModalUpdate, [&] { update_modal_bodies(ctx, parallel, reg, scratch.modal, warnings); });
        run(Stage::IntegratePositions, [&] {
            integrate_positions(ctx, parallel, reg, scratch.integrate, warnings);
            freeze_non_finite(ctx, Stage::IntegratePositions, parallel, reg, scratch.integrate, warnings);
        });
        run(Stage::UpdateSurfaces,
            [&] { update_modal_surfaces(parallel, reg, contact.pairs, scratch.modal); });
    }
    profile.support_calls = contact.support_calls;
    profile.touching_pairs = contact.touching_pairs;
    profile.touching_support_calls = contact.touching_support_calls;
    run(Stage::Events, [&] {
        clear_forces(reg);
        clear_modal_forces(reg);
        publish_events(contact.events, contact.pairs, contact.contacts);
        if (faults.callback != nullptr)
            for (const FaultEvent& f : faults.events)
                faults.callback(f, faults.user_data);
        // After the events, so a pair that falls asleep keeps its touch record parked, not ended.
        profile.sleeping_count = update_sleep(def, parallel, reg, contact, constraints, scratch.sleep);
    });
    // Whole-step time from the step count, so rounding does not accumulate over long runs.
    ++step_count;
    time = static_cast<double>(step_count) * def.dt;
    remould_modal_bodies(*this); // at the step boundary, on this thread
    profile.total_ms = ms_since(step_start);
    locked = false;
}

// The rest of a substep with the soft contact solver: contact and constraint rows solved together with
// the push-out, the positions moved, the contact rows relaxed without it (so the push-out leaves no
// speed behind); the modes then take the substep's impulses. `reuse`: the rows of the last substep
// carry on (no narrowphase ran); `last`: the last substep before the next narrowphase or the step's
// end, which bounces the rows and brings the surfaces up to date.
template <class Run> void World::Impl::soft_substep(const StepContext& ctx, Run& run, bool reuse, bool last)
{
    const uint64_t frozen = warnings.non_finite_bodies;
    run(Stage::PenaltyForces, [&] {
        if (reuse)
            refresh_soft_contacts(ctx, parallel, reg, contact);
        else
            prepare_soft_contacts(def.contact, ctx, parallel, reg, contact);
        constraints.iterations = std::max(def.constraint_iterations, def.contact.soft.iterations);
        constraints.split_islands = def.split_islands;
        apply_constraint_forces(ctx, parallel, reg, constraints, scratch.constraints,
                                soft_contact_rows(contact.soft, true));
        freeze_non_finite(ctx, Stage::PenaltyForces, parallel, reg, scratch.integrate, warnings);
    });
    run(Stage::IntegratePositions, [&] {
        integrate_positions(ctx, parallel, reg, scratch.integrate, warnings);
        freeze_non_finite(ctx, Stage::IntegratePositions, parallel, reg, scratch.integrate, warnings);
    });
    run(Stage::PenaltyForces, [&] {
        advance_soft_separations(parallel, contact.soft);
        if (warnings.non_finite_bodies != frozen)
            note_frozen_bodies(contact.soft);
        // The islands of the solve above: the relax and the bounce touch the same bodies.
        const ExtraRows relax = soft_contact_rows(contact.soft, false);
        const SoftContactDef& soft = def.contact.soft;
        solve_extra_rows(parallel, scratch.constraints, relax.count,
                         soft.relax_iterations > 0 ? soft.relax_iterations : soft.iterations, relax.solve,
                         relax.ctx);
        if (last)
            solve_extra_rows(parallel, scratch.constraints, relax.count, 1, &restitute_soft_pair,
                             &contact.soft);
        finish_soft_contacts(ctx, parallel, reg, contact);
        freeze_non_finite(ctx, Stage::PenaltyForces, parallel, reg, scratch.integrate, warnings);
    });
    run(Stage::ModalUpdate, [&] { update_modal_bodies(ctx, parallel, reg, scratch.modal, warnings); });
    if (last)
        run(Stage::UpdateSurfaces,
            [&] { update_modal_surfaces(parallel, reg, contact.pairs, scratch.modal); });
}

void World::step()
{
    if (m_impl->step_listener != nullptr)
        m_impl->step_listener(*this, m_impl->step_listener_data);
    m_impl->step();
}

void world_set_step_listener(World& world, StepListenerFn fn, void* user_data)
{
    SM_ASSERT(!world.m_impl->locked, "the step listener cannot change while the world steps");
    world.m_impl->step_listener = fn;
    world.m_impl->step_listener_data = user_data;
}

int World::advance(double real_seconds)
{
    SM_ASSERT(std::isfinite(real_seconds) && real_seconds >= 0.0, "advance() needs a finite time >= 0");
    if (!(std::isfinite(real_seconds) && real_seconds >= 0.0))
        return 0;
    Impl& w = *m_impl;
    w.accumulator += real_seconds;
    int steps = 0;
    while (w.accumulator >= w.def.dt && steps < w.def.max_steps_per_advance) {
        step();
        w.accumulator -= w.def.dt;
        ++steps;
    }
    // A backlog beyond the cap is dropped: the simulation runs slower than real time instead of
    // spiralling into ever longer frames.
    if (w.accumulator >= w.def.dt)
        w.accumulator = std::fmod(w.accumulator, w.def.dt);
    return steps;
}

Status World::set_settings(const WorldDef& def)
{
    Impl& w = *m_impl;
    SM_ASSERT(!w.locked, "settings cannot change while the world steps");
    if (w.locked)
        return Error{"", "settings", "cannot change while the world steps"};
    if (const Status s = validate(def); !s)
        return s;
    if (def.thread_count != w.def.thread_count)
        return Error{"", "thread_count", "cannot change after creation"};
    if (def.task_system != w.def.task_system)
        return Error{"", "task_system", "cannot change after creation"};
    if (def.modal_basis_cache != w.def.modal_basis_cache)
        return Error{"", "modal_basis_cache", "cannot change after creation"};
    if (def.dt != w.def.dt && w.step_count > 0)
        return Error{"", "dt", "can change only before the first step (time is step_count * dt)"};
    // The step reads the settings afresh each time, so changing them between steps is safe. Sleeping
    // bodies rested under the old ones (gravity, sleep limits): they wake to feel the new.
    w.def = def;
    wake_every_body(w.reg, w.contact);
    return {};
}

double World::interpolation_alpha() const
{
    return m_impl->accumulator / m_impl->def.dt;
}
const WorldDef& World::settings() const
{
    return m_impl->def;
}
double World::time() const
{
    return m_impl->time;
}
uint64_t World::step_count() const
{
    return m_impl->step_count;
}
const StepProfile& World::profile() const
{
    return m_impl->profile;
}
const StepWarnings& World::warnings() const
{
    return m_impl->warnings;
}

} // namespace supermodal
