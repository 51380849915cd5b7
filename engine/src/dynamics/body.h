// SPDX-License-Identifier: MIT
// A rigid body's components: its model (what it is, fixed while stepping) and its state (what step()
// changes: hashed, snapshotted).
#pragma once

#include "supermodal/body.h"
#include "supermodal/math.h"
#include "supermodal/shape.h"

#include <memory>
#include <string>

namespace supermodal
{

struct Collider; // contact/collider.h: the body's contact model, shared by identical shapes.

/// Model: what the body is. Changed only between steps (and by the non-finite guard).
struct BodyModel {
    std::string name;
    MotionType motion = MotionType::Dynamic;
    ShapeDef shape{};
    MassProperties mass{};
    double inv_mass = 0.0;   ///< [1/kg]; 0 for static and kinematic bodies.
    Vec3 inertia_body{};     ///< Principal moments [kg·m²], principal frame.
    Vec3 inv_inertia_body{}; ///< [1/(kg·m²)], principal frame; 0 for non-dynamic bodies.
    /// shape_from_principal: the principal frame's axes in the body (shape) frame. Identity unless a
    /// taper+bend or an oblique hyperquadric turns them; inertia terms must use principal_orientation().
    Quat principal = Quat::identity();
    double gravity_scale = 1.0;               ///< [-].
    double friction = 0.5;                    ///< Coulomb coefficient [-].
    double restitution = 0.2;                 ///< [-].
    double rolling_resistance = 0.0;          ///< Rolling lever arm [m].
    bool allow_sleep = true;                  ///< BodyDef::allow_sleep.
    double contact_compliance = 1e-9;         ///< (1 − ν²)/E [1/Pa], for Hertz contact.
    double curvature = 0.0;                   ///< 1/R [1/m] for Hertz contact: 1/smallest radius; 0 plane.
    std::shared_ptr<const Collider> collider; ///< Contact model (shared by identical shapes).
};

/// State: pose of the body frame, plus the pose before the last step (for render interpolation).
struct Pose {
    Vec3 position{};         ///< [m], world.
    Quat orientation{};      ///< world_from_body.
    Vec3 prev_position{};    ///< [m], world, before the last step.
    Quat prev_orientation{}; ///< world_from_body, before the last step.
};

/// State: velocities of the centre of mass.
struct Velocity {
    Vec3 linear{};  ///< [m/s], world.
    Vec3 angular{}; ///< [rad/s], world.
};

/// State: forces applied by the host for the next step; cleared after each step.
struct ForceAccumulator {
    Vec3 force{};  ///< [N], world, through the centre of mass.
    Vec3 torque{}; ///< [N·m], world, about the centre of mass.
};

/// world_from_principal: the frame in which inertia_body is diagonal. Exactly the pose's orientation
/// when principal is the identity (Hamilton product with 1 is exact), so aligned bodies step bit for bit
/// as before.
[[nodiscard]] inline Quat principal_orientation(const BodyModel& model, const Quat& world_from_body)
{
    return world_from_body * model.principal;
}

} // namespace supermodal
