// SPDX-License-Identifier: MIT
// Bodies: creation from a BodyDef, queries and forces. Handles are generational: every function
// except world_valid() asserts that the handle is live.
#pragma once

#include "supermodal/api.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/result.h"
#include "supermodal/shape.h"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal
{

class World;

/// How a body moves.
enum class MotionType : uint8_t {
    Static,    ///< Never moves; infinite mass.
    Kinematic, ///< Moves with its set velocity; unaffected by forces; infinite mass.
    Dynamic,   ///< Moves under forces.
};

/// How a modal body's amplitudes are stepped (docs/modal.md).
enum class ModalIntegrator : uint8_t {
    Exact,             ///< Exact per-mode solution for a force held over the (sub)step; any step size.
    CentralDifference, ///< The paper's explicit scheme; stable for h·ω < 2: modes past it are stepped
                       ///< exactly instead and counted in StepWarnings::modal_integrator_switches.
};

/// Deformation through the body's lowest free vibration modes (Williams & Pentland 1992). The rigid
/// motion stays in the body; the modes ride in its co-rotating frame. Dynamic superquadrics and
/// hyperquadrics only. The basis (engine/include/supermodal/modal.h) is built once per distinct
/// shape + material + lattice + mode count and shared by every such body of the world.
struct ModalBodyDef {
    bool enabled = false;         ///< False: a rigid body (the other fields are ignored).
    int mode_count = 12;          ///< Elastic modes kept, r ∈ [1, 256]; 0 (k_all_modes): every elastic
                                  ///< mode of the lattice, the full model (scene "full").
    std::array<int, 3> lattice{}; ///< Lattice cells per axis, each in [0, 128]; 0 = from the aspect ratio.
    ModalIntegrator integrator = ModalIntegrator::Exact;
    double damping_ratio = 0.01; ///< ζ of every mode [-], ≥ 0 (1 = critical). The stiffness and density
                                 ///< are the body's material: BodyDef::young, poisson, density.
    /// von Mises yield stress σ_y [Pa], > 0; past it the rest shape moves (plastic relief, the paper's
    /// clay moulding, docs/modal.md). ∞ (the default): elastic.
    double yield_stress = std::numeric_limits<double>::infinity();
    double hardening =
        0.0; ///< Linear hardening modulus H [Pa], ≥ 0: yield grows by H per unit plastic strain.
    /// Accumulated equivalent plastic strain [-], > 0, past which the body flows no more; ∞: no limit.
    double max_plastic_strain = std::numeric_limits<double>::infinity();
    /// Adaptive modes (scene "dynamics": "auto", docs/modal.md "Adaptive modes") [m], finite, ≥ 0.
    /// 0: every mode is stepped always. > 0: the body starts rigid and steps only the lowest modes its
    /// loads need for the surface displacement left out to stay under this; mode_count is the most.
    double adaptive_tolerance = 0.0;
    /// Plastic bodies: the rest-shape change [-] past which the modes are rebuilt for the moulded shape
    /// (docs/modal.md "Remoulding"): the largest rest offset of a lattice node since the last build,
    /// over the lattice's largest side. 0: never rebuilt (the modes stay those of the first shape).
    double remould_threshold = 0.02;
    /// Steps [-], in [1, 1000], from the step that asks for the rebuild (it builds on a thread of its
    /// own meanwhile) to the step boundary where the new modes take over; that step waits for the
    /// build if it is not done, so results do not depend on how long it takes.
    int remould_delay_steps = 4;
    /// Mode acceleration (docs/modal.md "Static correction in the world"): after each substep the full
    /// lattice's static response to that substep's contact and host loads, less what the kept modes
    /// carry, is added to the body's surface, so a point load dents it locally as the full lattice
    /// would (contact loads follow over about 0.02 s). Costs a factorisation of the full lattice at
    /// creation, then per loaded substep one stored flexibility column per loaded degree of freedom.
    bool static_correction = false;
};

/// How to make a body. Start from default_body_def() and change what differs.
struct BodyDef {
    std::string name; ///< Optional; unique names are looked up by find_body().
    MotionType motion = MotionType::Dynamic;
    ShapeDef shape{};                    ///< Shape in the body frame (origin at the centre of mass).
    double density = 1000.0;             ///< [kg/m³], > 0; ignored for static and kinematic bodies.
    Vec3 position{};                     ///< Shape origin [m], world frame; the centre of mass unless a
                                         ///< taper or bend moves it (MassProperties::center_of_mass).
    Quat orientation = Quat::identity(); ///< world_from_body rotation, unit [w, x, y, z].
    Vec3 linear_velocity{};              ///< Of the centre of mass [m/s], world frame.
    Vec3 angular_velocity{};             ///< [rad/s], world frame.
    double gravity_scale = 1.0;          ///< Multiplies the world's gravity [-].
    double friction = 0.5;               ///< Coulomb coefficient [-], ≥ 0; a pair uses √(μa·μb).
    double restitution = 0.2;            ///< [-], in [0, 1]; a pair uses the larger of the two.
    double young = 1e9;   ///< Young's modulus E [Pa], > 0: the modes' stiffness (modal bodies) and the
                          ///< Hertz stiffness of ContactStiffness::Material contact.
    double poisson = 0.3; ///< Poisson's ratio ν [-], in (−1, 0.5); used with young.
    double rolling_resistance = 0.0; ///< Rolling lever arm ℓ [m], ≥ 0: a rolling contact is resisted
                                     ///< by a torque up to ℓ·F_n; a pair uses the larger of the two.
    ModalBodyDef modal{};            ///< Deformation; rigid unless modal.enabled.
    bool allow_sleep = true;         ///< False: never sleeps, and keeps every body it touches or is
                                     ///< jointed to awake (WorldDef::sleep).
};

/// The documented starting point: a dynamic water-density sphere of radius 0.5 m at the origin.
[[nodiscard]] SM_API BodyDef default_body_def();

/// Checks the shape, density > 0, finite pose and velocities, a non-zero orientation, that planes
/// are static, and for modal bodies the ModalBodyDef ranges and a dynamic motion.
[[nodiscard]] SM_API Status validate(const BodyDef& def);

/// Creates a body; asserts validate(def). In Release a refused def returns a null Entity. A modal body
/// builds (or reuses) its basis here; if that build fails, the body is refused the same way: call
/// modal_basis_for() first to get the reason.
[[nodiscard]] SM_API Entity create_body(World& world, const BodyDef& def);
/// Destroys a body; its handle (and every copy) becomes stale.
SM_API void destroy_body(World& world, Entity body);
/// True if `body` is a live body of `world`; the only function that accepts stale handles.
[[nodiscard]] SM_API bool world_valid(const World& world, Entity body);
/// Live bodies in entity-index order (the deterministic order used by hashes and summaries).
[[nodiscard]] SM_API std::vector<Entity> world_bodies(const World& world);
/// The body with this name, or a null Entity.
[[nodiscard]] SM_API Entity find_body(const World& world, std::string_view name);

[[nodiscard]] SM_API const std::string& body_name(const World& world, Entity body);
[[nodiscard]] SM_API MotionType body_motion(const World& world, Entity body);
[[nodiscard]] SM_API const ShapeDef& body_shape(const World& world, Entity body);
[[nodiscard]] SM_API const MassProperties& body_mass_properties(const World& world, Entity body);
/// Shape origin [m], world (as BodyDef::position).
[[nodiscard]] SM_API Vec3 body_position(const World& world, Entity body);
/// Centre of mass [m], world.
[[nodiscard]] SM_API Vec3 body_center_of_mass(const World& world, Entity body);
[[nodiscard]] SM_API Quat body_orientation(const World& world, Entity body);      ///< world_from_body.
[[nodiscard]] SM_API Vec3 body_linear_velocity(const World& world, Entity body);  ///< [m/s], world.
[[nodiscard]] SM_API Vec3 body_angular_velocity(const World& world, Entity body); ///< [rad/s], world.
/// Angular momentum about the centre of mass [kg·m²/s], world frame.
[[nodiscard]] SM_API Vec3 body_angular_momentum(const World& world, Entity body);
/// Translational + rotational kinetic energy [J]; zero for static bodies.
[[nodiscard]] SM_API double body_kinetic_energy(const World& world, Entity body);
/// Gravitational potential energy −m·g·x relative to the world origin [J]; zero for non-dynamic bodies.
[[nodiscard]] SM_API double body_potential_energy(const World& world, Entity body);
/// Pose blended between the last two steps by World::interpolation_alpha(), for rendering.
[[nodiscard]] SM_API Vec3 body_interpolated_position(const World& world, Entity body);
[[nodiscard]] SM_API Quat body_interpolated_orientation(const World& world, Entity body);

SM_API void set_body_position(World& world, Entity body, const Vec3& position);
SM_API void set_body_orientation(World& world, Entity body, const Quat& orientation);
SM_API void set_body_linear_velocity(World& world, Entity body, const Vec3& velocity);
SM_API void set_body_angular_velocity(World& world, Entity body, const Vec3& angular_velocity);

/// Adds a force [N] at a point [m] (both world frame) for the next step; the force also makes a
/// torque about the centre of mass. Forces are cleared after each step. Ignored for non-dynamic bodies.
/// On a modal body it also loads the modes: φ(point)ᵀ Rᵀ force, mapped at the pose of this call.
SM_API void apply_force(World& world, Entity body, const Vec3& force, const Vec3& point);
/// Adds a force [N], world frame, through the centre of mass for the next step; a body force like
/// gravity, so it does not deform a modal body.
SM_API void apply_force_at_center(World& world, Entity body, const Vec3& force);
/// Adds a torque [N·m], world frame, for the next step.
SM_API void apply_torque(World& world, Entity body, const Vec3& torque);
/// Changes momentum at once by an impulse [N·s] at a point [m], world frame; on a modal body also the
/// modal rates, q̇ += φ(point)ᵀ Rᵀ impulse.
SM_API void apply_linear_impulse(World& world, Entity body, const Vec3& impulse, const Vec3& point);
/// Changes angular momentum at once by an angular impulse [N·m·s], world frame.
SM_API void apply_angular_impulse(World& world, Entity body, const Vec3& impulse);

/// False while `body` sleeps (WorldDef::sleep); static bodies are always awake.
[[nodiscard]] SM_API bool body_is_awake(const World& world, Entity body);
/// Wakes `body` and every body of its sleeping island; resets its sleep timer either way.
SM_API void wake_body(World& world, Entity body);
/// Dynamic bodies asleep now [-].
[[nodiscard]] SM_API size_t world_sleeping_count(const World& world);

} // namespace supermodal
