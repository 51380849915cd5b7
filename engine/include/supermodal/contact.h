// SPDX-License-Identifier: MIT
// Contact: settings, and what the host can read back after a step.
//
// Two solvers. Soft (the default): each contact point is a spring–damper given by a frequency and a
// damping ratio, solved implicitly as a velocity constraint together with the joints (warm started,
// relaxed after the positions move), so its stability does not depend on the step; friction is a velocity
// constraint bounded by the Coulomb cone. Penalty (the paper's): an explicit spring–damper force
// whose stiffness comes from a natural frequency and the pair's effective mass (k = m_eff·(2πf)²,
// c = 2ζ·m_eff·2πf), stable while 2πf·h stays small; friction is a tangential spring anchored where
// the contact started to stick (Cundall–Strack), clamped to the Coulomb cone. Either way the per-pair
// memory (anchors, last loads) is part of the world's state.
#pragma once

#include "supermodal/api.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"

#include <cmath>
#include <cstdint>
#include <span>

namespace supermodal
{

class World;

/// Which narrowphase finds contact points.
enum class ContactPath : uint8_t {
    Auto,       ///< Support map (MPR) for convex, undeformed superquadric pairs; sampling otherwise.
    Sampling,   ///< Surface samples of each body tested with the other's inside-outside function.
    SupportMap, ///< libccd MPR with the analytic support map where both bodies are convex (else sampling).
};

/// What sets the normal spring's stiffness.
enum class ContactStiffness : uint8_t {
    Frequency, ///< k = m_eff·(2πf)² from ContactDef::frequency_hz: one setting for any mass ratio.
    Material,  ///< Hertz: F = (4/3)·E*·√(R*·δ)·δ from the bodies' Young's moduli, Poisson ratios and
               ///< curvature radii; clamped to the stability cap (1/(10·h)) on its tangent stiffness.
};

/// How contact forces are found.
enum class ContactSolver : uint8_t {
    Soft,    ///< Implicit soft constraints, solved with the joints (the default): stable at any step.
    Penalty, ///< Explicit penalty springs (the paper's): needs 2πf·h small, so small steps or substeps.
};

/// Settings of the soft solver. The spring of a point acts on the point's effective mass, so one
/// frequency behaves alike for any masses; a static partner doubles it (the point's mass is the
/// moving body's alone, so it would otherwise sag twice as far).
struct SoftContactDef {
    double frequency_hz = 0.0;      ///< Contact spring frequency [Hz]; 0 = min(1/(2·h), 60 Hz). Higher sinks
                                    ///< less under load; the solve stays stable.
    double damping_ratio = 5.0;     ///< [-]: heavily damped, so a spring pushes out without bouncing;
                                    ///< twice it at a point on a modal body.
    double push_out_speed = 3.0;    ///< Fastest separation the spring may cause [m/s].
    double restitution_speed = 1.0; ///< Approach speed [m/s] below which a contact does not bounce.
    int iterations = 10;      ///< Gauss–Seidel passes per substep over the contacts [-], in [1, 100]: the
                              ///< joints join them (max with WorldDef::constraint_iterations), and as many
                              ///< relax passes follow the position update. More holds taller stacks.
    int relax_iterations = 0; ///< Relax passes per substep [-], in [0, 100]; 0 = as many as `iterations`.
                              ///< They take the push-out's speed back out of the velocities; fewer are
                              ///< cheaper and left a loose pile shallower, while a tall stack's first
                              ///< steps and very unequal masses settle slower (docs/contact.md).
    int substeps = 0; ///< Solver substeps per narrowphase [-], in [0, 64]: the contact points found once
                      ///< are solved this many times over shorter substeps, their gaps carried by the
                      ///< bodies' motion (Box2D v3's soft step). Cheaper than WorldDef::substep_count,
                      ///< which runs the narrowphase every substep. 0 = as many as keep a solver
                      ///< substep at or under 1/240 s (4 at a 1/60 s step, 1 at 1/240 s and below).
};

/// Solver substeps at or under this length [s] when SoftContactDef::substeps is 0: a 20-box column
/// and a 55-box pyramid stand at it, while one 1/60 s substep drops the column (docs/contact.md).
inline constexpr double k_auto_solver_substep = 1.0 / 240.0;

/// The solver substeps per narrowphase for a world substep h [s] (SoftContactDef::substeps, or 0's).
[[nodiscard]] inline int soft_solver_substeps(const SoftContactDef& soft, double h)
{
    if (soft.substeps > 0)
        return soft.substeps;
    // A relative allowance, so h = 1/240 s rounds to one substep, not two.
    const double n = std::ceil(h / k_auto_solver_substep * (1.0 - 1e-9));
    return n >= 64.0 ? 64 : n <= 1.0 ? 1 : static_cast<int>(n);
}

/// World-wide contact settings. Start from the defaults and change what differs.
struct ContactDef {
    bool enabled = true;
    ContactSolver solver = ContactSolver::Soft;
    SoftContactDef soft{}; ///< The soft solver's settings (solver == Soft).
    ContactPath path = ContactPath::Auto;
    double frequency_hz = 0.0;       ///< Penalty natural frequency [Hz]; 0 = the stability cap 1/(10·h)
                                     ///< with h the substep. Higher is stiffer (less penetration) but
                                     ///< clamped to the cap; every clamp is counted.
    double damping_ratio = -1.0;     ///< Normal damping ratio ζ [-]; < 0 = from the pair's restitution e:
                                     ///< ζ = −ln e / √(π² + ln² e).
    double sample_spacing = 0.0;     ///< Surface sample spacing [m]; 0 = a quarter of each body's
                                     ///< smallest radius. Smaller is more accurate and slower.
    int max_samples_per_body = 4000; ///< Cap on samples per body [-]; spacing widens to fit.
    double speculative_speed_factor = 0.5; ///< Substep the world when a body would move more than this
                                           ///< fraction of the thinnest body it may hit in one substep [-].
    int max_auto_substeps = 64;            ///< Cap on the extra substeps that rule may add [-].
    ContactStiffness stiffness = ContactStiffness::Frequency; ///< Frequency (default) or material (Hertz).
    /// Sampling path: a point tested against a modal body meets its deformed shape (the point mapped back
    /// through the body's deformation, the normal and depth carried forward), so both bodies' dents
    /// count; false (the default): against its rest shape (only the sampled body's own dent counts).
    bool deformed_inside_test = false;
};

/// One contact after a step: where two bodies touch, summed over the pair's points.
struct ContactInfo {
    Entity a{};          ///< Lower entity index of the pair.
    Entity b{};          ///< Higher entity index (or the plane / static body).
    Vec3 point{};        ///< Force-weighted contact point [m], world.
    Vec3 normal{};       ///< Unit normal from b towards a, world.
    double depth = 0.0;  ///< Deepest penetration of the pair [m].
    Vec3 force_on_a{};   ///< Total contact force on a (normal + friction) [N], world; b gets the opposite.
    int point_count = 0; ///< Contact points (samples or manifold points) behind this contact [-].
};

/// What happened to a pair during one step.
enum class ContactEventKind : uint8_t {
    Begin,   ///< Touching this step, not at the end of the previous one.
    Persist, ///< Touching at the end of the previous step and again this step.
    End,     ///< Not touching at the end of this step, but was during it or at the end of the previous.
};

/// One contact event of a step. A pair that touches and lets go within one step (fast bodies, several
/// substeps) gets a Begin and an End in that step.
struct ContactEvent {
    ContactEventKind kind = ContactEventKind::Begin;
    Entity a{};              ///< Lower entity index of the pair.
    Entity b{};              ///< Higher entity index (or the plane / static body).
    Vec3 point{};            ///< Contact point [m], world, at the last substep the pair touched.
    Vec3 normal{};           ///< Unit normal from b towards a, world, at that substep.
    Vec3 impulse_on_a{};     ///< Contact impulse on a over the step, Σ h·F over the substeps (normal +
                             ///< friction) [N·s], world; b gets the opposite. Reported once per pair
                             ///< and step: on its Begin or Persist, else on its End (zero when the
                             ///< pair did not touch this step).
    double normal_impulse{}; ///< Normal part of that impulse, Σ h·F_n over the substeps [N·s], ≥ 0.
    double depth = 0.0;      ///< Deepest penetration of the pair during the step [m].
};

/// Host callback for contact events, called in the step's Events stage once per event, serially, in
/// (a index, b index, kind) order. It must not step the world (asserted).
using ContactEventFn = void (*)(const ContactEvent& event, void* user_data);

/// Registers fn (with user_data handed back on each call) for the world's contact events; a null fn
/// removes it. Not allowed from inside a callback (asserted).
SM_API void world_set_contact_callback(World& world, ContactEventFn fn, void* user_data);
/// The contact events of the last step, in the order the callback receives them.
[[nodiscard]] SM_API std::span<const ContactEvent> world_contact_events(const World& world);

/// The contacts found in the last step (the last substep), sorted by (a, b) index.
[[nodiscard]] SM_API std::span<const ContactInfo> world_contacts(const World& world);
/// The deepest penetration in the last step [m].
[[nodiscard]] SM_API double world_max_penetration(const World& world);

} // namespace supermodal
