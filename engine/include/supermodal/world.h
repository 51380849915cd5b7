// SPDX-License-Identifier: MIT
// The World owns bodies and runs the fixed step. Its members are the whole-world verbs only;
// everything about one body is a free function in body.h.
#pragma once

#include "supermodal/contact.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/result.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

namespace supermodal
{

class ModalBasisCache; // supermodal/modal.h

/// How to make a world. Start from default_world_def() and change what differs.
struct WorldDef {
    double dt = 0.002;              ///< Fixed step [s], > 0. Penalty contact wants small steps.
    int substep_count = 1;          ///< Substeps per step [-], ≥ 1; each integrates dt / substep_count.
    Vec3 gravity{0.0, -9.81, 0.0};  ///< [m/s²], world frame (Y-up).
    int max_steps_per_advance = 64; ///< advance() runs at most this many steps per call [-], ≥ 1,
                                    ///< dropping the rest of the backlog so a slow frame cannot spiral.
    ContactDef contact{};           ///< Penalty contact settings.
    int constraint_iterations = 4;  ///< Gauss–Seidel passes over the constraint springs per substep [-],
                                    ///< in [1, 100]; more lets chains of unequal masses hold tighter.
    int thread_count = 1;           ///< Threads for the step's per-pair work [-], in [1, 64]; the caller's
                          ///< thread plus thread_count − 1 pool threads. Results are bit-identical
                          ///< for any count; more than the free cores only adds waiting.
    /// Where the world finds and keeps its modal bases (supermodal/modal.h). Null: a cache of its own.
    /// Share one between worlds that rebuild the same scene (an editor reloading it, a test harness):
    /// a basis is keyed by every field of its def, so a shared one changes no result, only build time.
    std::shared_ptr<ModalBasisCache> modal_basis_cache;
};

/// The documented starting point: dt = 2 ms, one substep, Earth gravity along −Y.
[[nodiscard]] WorldDef default_world_def();

/// Checks dt > 0 and finite, substep_count in [1, 1000], finite gravity, max_steps_per_advance ≥ 1,
/// constraint_iterations in [1, 100], thread_count in [1, 64].
[[nodiscard]] Status validate(const WorldDef& def);

/// The named stages of one step, in the order step() runs them.
enum class Stage : uint8_t {
    Broadphase,         ///< Once per step: pairs from boxes swept over the step; picks the substeps.
    IntegrateForces,    ///< Gravity and applied forces into velocities.
    Narrowphase,        ///< Contact points per substep.
    PenaltyForces,      ///< Contact (and, with issue #7, constraint) springs into velocities.
    ModalUpdate,        ///< Modal amplitudes (modal issue).
    IntegratePositions, ///< Velocities into poses; implicit gyroscopic term.
    UpdateSurfaces,     ///< Derived data: deformed surfaces, world bounds.
    Events,             ///< Non-finite checks and host callbacks.
    Count
};

/// Human-readable stage name ("integrate_forces").
[[nodiscard]] std::string_view stage_name(Stage stage);

/// Time spent per stage, summed over the last step's substeps [ms].
struct StepProfile {
    std::array<double, static_cast<size_t>(Stage::Count)> stage_ms{};
    double total_ms = 0.0; ///< Wall time of the last step [ms].
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

/// A saved copy of the world's dynamic state. Treat as opaque; restore() it into the same world.
struct Snapshot {
    double time = 0.0;
    uint64_t step_count = 0;
    double accumulator = 0.0;
    std::vector<Entity> entities;         ///< Bodies in index order.
    std::vector<double> values;           ///< Packed per-body state, k_values_per_body each.
    std::vector<uint64_t> anchor_keys;    ///< Friction anchors: pair keys, sorted.
    std::vector<Vec3> anchor_springs;     ///< Friction anchors: tangential spring extensions [m].
    std::vector<double> anchor_twists;    ///< Friction anchors: torsional spring angles [rad].
    std::vector<Vec3> anchor_rolls;       ///< Friction anchors: rolling spring angles [rad].
    std::vector<double> anchor_stiffness; ///< Contact anchors: normal stiffness per point area held [N/m³].
    std::vector<double> anchor_credits;   ///< Contact anchors: dissipated energy not spent on stiffening [J].
    std::vector<Entity> constraints;      ///< Constraint handles (as entities) in index order.
    std::vector<double> constraint_values; ///< Packed per-constraint state (broken flag, impulses).
    uint64_t broken_constraint_count = 0;

    // Contact manifolds of support-map pairs, sorted by pair key; per point, the point on A then the
    // point on B, each in its own body frame [m].
    std::vector<uint64_t> manifold_keys;
    std::vector<int> manifold_counts;
    std::vector<Vec3> manifold_points;
    std::vector<double> modal_values; ///< Modal bodies in index order: amplitudes, rates, host forces,
                                      ///< plastic offsets (r each), accumulated plastic strain.
};

/// A physics world: bodies, settings, the fixed-step clock. Several worlds may live side by side.
class World
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
    /// Restores a snapshot of this world; fails if bodies were created or destroyed since.
    Status restore(const Snapshot& snapshot);

    [[nodiscard]] const WorldDef& settings() const;
    [[nodiscard]] double time() const;         ///< Simulated time [s].
    [[nodiscard]] uint64_t step_count() const; ///< Steps run since creation.
    [[nodiscard]] const StepProfile& profile() const;
    [[nodiscard]] const StepWarnings& warnings() const;

    struct Impl;
    /// Engine-internal access; hosts use the free functions instead.
    [[nodiscard]] Impl& impl() { return *m_impl; }
    [[nodiscard]] const Impl& impl() const { return *m_impl; }

  private:
    std::unique_ptr<Impl> m_impl;
};

} // namespace supermodal
