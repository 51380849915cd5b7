// SPDX-License-Identifier: MIT
// The World owns bodies and runs the fixed step. Its members are the whole-world verbs only;
// everything about one body is a free function in body.h.
#pragma once

#include "supermodal/api.h"
#include "supermodal/contact.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/result.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace supermodal
{

class ModalBasisCache; // supermodal/modal.h
class TaskSystem;      // supermodal/tasks.h

/// When bodies at rest stop being stepped (docs/sleeping.md). A body is slow while its speeds stay
/// under these; an island of touching or jointed dynamic bodies that have all been slow for `time`
/// sleeps: it is neither integrated nor collided until something wakes it.
struct SleepDef {
    bool enabled = true;        ///< False: no body ever sleeps (and sleeping ones wake).
    double linear_speed = 0.05; ///< [m/s], ≥ 0: a body is slow while |v| + ρ·|ω| (ρ: its largest
                                ///< radius, so the speed of its fastest point) stays under it; a modal
                                ///< body's modes also need √(|q̇|²/m) under it (their kinetic energy).
    double angular_speed = 1.0; ///< [rad/s], ≥ 0: and |ω| under this (small bodies turning in place).
    double time = 0.5;          ///< [s], > 0: how long an island stays slow before it sleeps.
};

/// How to make a world. Start from default_world_def() and change what differs.
struct WorldDef {
    double dt = 0.002;              ///< Fixed step [s], > 0. Penalty contact wants small steps.
    int substep_count = 1;          ///< Substeps per step [-], ≥ 1; each integrates dt / substep_count.
    Vec3 gravity{0.0, -9.81, 0.0};  ///< [m/s²], world frame (Y-up).
    int max_steps_per_advance = 64; ///< advance() runs at most this many steps per call [-], ≥ 1,
                                    ///< dropping the rest of the backlog so a slow frame cannot spiral.
    ContactDef contact{};           ///< Contact settings (solver, narrowphase).
    SleepDef sleep{};               ///< Sleeping of bodies at rest.
    int constraint_iterations = 4;  ///< Gauss–Seidel passes over the constraint springs per substep [-],
                                    ///< in [1, 100]; more lets chains of unequal masses hold tighter.
    int thread_count = 1;           ///< Threads of the built-in pool [-], in [1, 64]: the caller's thread
                          ///< plus thread_count − 1 workers (none for 1). Unused with a task_system.
                          ///< Results are bit-identical for any count; more than the free cores only
                          ///< adds waiting.
    /// Solve islands of at least 1024 rows (a pile of hundreds of touching bodies) in slabs that the
    /// threads share, instead of each island on one thread. Results stay bit-identical for any thread
    /// count, but differ from those without the split (another Gauss–Seidel order). Off by default: on
    /// one thread the split order costs up to ~10% more solver time on large piles (rows walked out of
    /// memory order); turn it on where a large island meets two or more free cores.
    bool split_islands = false;
    /// The host's scheduler for the step's parallel loops (supermodal/tasks.h), shared with the host and
    /// kept alive by the world. Null: the built-in pool of thread_count threads. Any scheduler and any
    /// concurrency give the same bits.
    std::shared_ptr<TaskSystem> task_system;
    /// Where the world finds and keeps its modal bases (supermodal/modal.h). Null: a cache of its own.
    /// Share one between worlds that rebuild the same scene (an editor reloading it, a test harness):
    /// a basis is keyed by every field of its def, so a shared one changes no result, only build time.
    std::shared_ptr<ModalBasisCache> modal_basis_cache;
};

/// The documented starting point: dt = 2 ms, one substep, Earth gravity along −Y.
[[nodiscard]] SM_API WorldDef default_world_def();

/// Checks dt > 0 and finite, substep_count in [1, 1000], finite gravity, max_steps_per_advance ≥ 1,
/// constraint_iterations in [1, 100], thread_count in [1, 64].
[[nodiscard]] SM_API Status validate(const WorldDef& def);

/// The named stages of one step, in the order step() runs them.
enum class Stage : uint8_t {
    Broadphase,         ///< Once per step: pairs from boxes swept over the step; picks the substeps.
    IntegrateForces,    ///< Gravity and applied forces into velocities.
    Narrowphase,        ///< Contact points per substep.
    PenaltyForces,      ///< Contact, then constraint springs into velocities.
    ModalUpdate,        ///< Modal amplitudes (modal issue).
    IntegratePositions, ///< Velocities into poses; implicit gyroscopic term.
    UpdateSurfaces,     ///< Derived data: deformed surfaces, world bounds.
    Events,             ///< Non-finite checks and host callbacks.
    Count
};

/// Human-readable stage name ("integrate_forces").
[[nodiscard]] SM_API std::string_view stage_name(Stage stage);

/// Time spent per stage, summed over the last step's substeps [ms].
struct StepProfile {
    std::array<double, static_cast<size_t>(Stage::Count)> stage_ms{};
    double total_ms = 0.0;     ///< Wall time of the last step [ms].
    size_t pair_count = 0;     ///< Candidate pairs of the last step's broadphase [-].
    size_t sleeping_count = 0; ///< Dynamic bodies asleep after the last step [-].
    /// Support-map evaluations of the support-map narrowphase over the last step's substeps, one body
    /// each (MPR's Minkowski support is two) [-]. Deterministic: the same for any thread count.
    uint64_t support_calls = 0;
    uint64_t touching_pairs = 0; ///< Pairs with contact points, summed over the last step's substeps [-].
    uint64_t touching_support_calls = 0; ///< The part of support_calls made by those pairs' queries [-].
};

/// Counts of run-time numerical trouble since the world was made; the step never fails.
struct StepWarnings {
    uint64_t non_finite_bodies = 0;         ///< Bodies frozen because their state turned NaN/Inf.
    Entity last_non_finite{};               ///< The last body frozen for that reason.
    uint64_t gyroscopic_fallbacks = 0;      ///< Spins too fast for the implicit midpoint solve (see docs).
    uint64_t contact_frequency_clamps = 0;  ///< Steps whose contact frequency, and pair-substeps whose
                                            ///< material stiffness, exceeded the cap 1/(10 h).
    uint64_t speculative_substeps = 0;      ///< Extra substeps added so fast bodies cannot tunnel.
    uint64_t modal_integrator_switches = 0; ///< Body-substeps in which central difference was unstable
                                            ///< (ω·h ≥ 2) for some modes, which were stepped exactly.
    uint64_t modal_non_finite = 0;          ///< Modal bodies whose amplitudes turned NaN/Inf: reset to rest.
};

/// A saved copy of a world's dynamic state: opaque bytes that begin with a layout version. Restore it
/// into the same world (or one built the same way, with the same build of the engine); keep the bytes
/// in a file or send them elsewhere and make a Snapshot of them again with from_bytes().
class SM_API Snapshot
{
  public:
    Snapshot() = default;
    /// The bytes: an 8-byte header ("SMSS", then the layout version), then the state.
    [[nodiscard]] std::span<const std::byte> bytes() const { return m_bytes; }
    /// A snapshot of bytes() kept earlier; World::restore() checks them (version, size, bodies).
    [[nodiscard]] static Snapshot from_bytes(std::span<const std::byte> bytes);
    /// The layout version in the header; 0 when the bytes are too short to hold a header.
    [[nodiscard]] uint32_t layout_version() const;
    [[nodiscard]] bool empty() const { return m_bytes.empty(); }

  private:
    friend class World;
    std::vector<std::byte> m_bytes;
};

/// Called at the start of every step, by step() and by each step advance() runs, before the world locks:
/// the place to apply this step's host forces (a drag spring, a controller), since forces last one step.
using StepListenerFn = void (*)(World& world, void* user_data);

/// A physics world: bodies, settings, the fixed-step clock. Several worlds may live side by side.
class SM_API World
{
  public:
    explicit World(const WorldDef& def = default_world_def());
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Advances the simulation by one fixed step of settings().dt.
    void step();
    /// Adds real_seconds [s] to the accumulator and runs the whole steps it holds (at most
    /// max_steps_per_advance). Returns the number of steps run.
    int advance(double real_seconds);
    /// Fraction of a step left in the accumulator [-], in [0, 1): blend previous and current poses.
    [[nodiscard]] double interpolation_alpha() const;

    /// FNV-1a over the dynamic state in entity-index order: same scene + same build → same hash.
    [[nodiscard]] uint64_t state_hash() const;
    [[nodiscard]] Snapshot snapshot() const;
    /// Restores a snapshot of this world. Refused, with the world unchanged, when the snapshot has another
    /// layout version, is damaged, or bodies or constraints were created or destroyed since.
    Status restore(const Snapshot& snapshot);

    [[nodiscard]] const WorldDef& settings() const;
    [[nodiscard]] double time() const;         ///< Simulated time [s].
    [[nodiscard]] uint64_t step_count() const; ///< Steps run since creation.
    [[nodiscard]] const StepProfile& profile() const;
    [[nodiscard]] const StepWarnings& warnings() const;

    /// Changes the settings between steps. Refused (world unchanged) when `def` is invalid, changes
    /// thread_count, task_system or modal_basis_cache (fixed at creation), or changes dt after the first
    /// step (time is step_count · dt).
    Status set_settings(const WorldDef& def);

    struct Impl; ///< Engine-internal; hosts use the free functions.

  private:
    friend void world_set_step_listener(World& world, StepListenerFn fn, void* user_data);
    friend Impl& impl_of(World& world);
    friend const Impl& impl_of(const World& world);
    std::unique_ptr<Impl> m_impl;
};

/// Sets (or with null, removes) the world's step listener; user_data is passed back to it.
SM_API void world_set_step_listener(World& world, StepListenerFn fn, void* user_data);

} // namespace supermodal
