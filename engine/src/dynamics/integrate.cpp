// SPDX-License-Identifier: MIT
#include "dynamics/integrate.h"

#include "dynamics/rotation.h"

#include <cmath>

namespace supermodal
{

StepContext make_step_context(const WorldDef& def)
{
    return {.h = def.dt / def.substep_count, .gravity = def.gravity, .substep_count = def.substep_count};
}

void integrate_forces(const StepContext& ctx, Registry& reg)
{
    // Writes only the visited entity's Velocity, so view order cannot change the result.
    reg.each<BodyModel, ForceAccumulator, Velocity, Pose>(
        [&](Entity, const BodyModel& body, const ForceAccumulator& acc, Velocity& vel, const Pose& pose) {
            if (body.motion != MotionType::Dynamic)
                return;
            vel.linear += ctx.h * (body.gravity_scale * ctx.gravity + body.inv_mass * acc.force);
            // Torque kick on the angular momentum; the torque-free flow follows in integrate_positions.
            // In the principal frame, where the inertia is diagonal.
            const Quat q = principal_orientation(body, pose.orientation);
            const Vec3 torque_body = inv_rotate(q, acc.torque);
            const Vec3 w_body = inv_rotate(q, vel.angular);
            const Vec3 momentum_body = hadamard(body.inertia_body, w_body) + ctx.h * torque_body;
            vel.angular = rotate(q, hadamard(body.inv_inertia_body, momentum_body));
        });
}

void integrate_positions(const StepContext& ctx, Registry& reg, StepWarnings& io_warnings)
{
    reg.each<BodyModel, Velocity, Pose>([&](Entity, const BodyModel& body, Velocity& vel, Pose& pose) {
        switch (body.motion) {
        case MotionType::Static:
            return;
        case MotionType::Kinematic:
            pose.position += ctx.h * vel.linear;
            pose.orientation = normalized(quat_from_rotation_vector(ctx.h * vel.angular) * pose.orientation);
            return;
        case MotionType::Dynamic:
            break;
        }
        pose.position += ctx.h * vel.linear;
        // The torque-free flow in the principal frame; the pose keeps the shape frame (q·p⁻¹).
        const Quat q = principal_orientation(body, pose.orientation);
        const Vec3 momentum_body = hadamard(body.inertia_body, inv_rotate(q, vel.angular));
        const RotationStep rot = rotate_torque_free(q, momentum_body, body.inertia_body, ctx.h);
        if (rot.used_fallback)
            ++io_warnings.gyroscopic_fallbacks;
        pose.orientation = rot.orientation * conjugate(body.principal);
        vel.angular = rotate(rot.orientation, hadamard(body.inv_inertia_body, rot.momentum_body));
    });
}

void store_previous_poses(Registry& reg)
{
    for (Pose& pose : reg.store<Pose>().values()) {
        pose.prev_position = pose.position;
        pose.prev_orientation = pose.orientation;
    }
}

void freeze_non_finite(const StepContext& ctx, Stage stage, Registry& reg, StepWarnings& io_warnings)
{
    reg.each<BodyModel, Velocity, Pose>([&](Entity e, BodyModel& body, Velocity& vel, Pose& pose) {
        if (is_finite(pose.position) && is_finite(pose.orientation) && is_finite(vel.linear) &&
            is_finite(vel.angular))
            return;
        // Back to the last finite pose; if even that is gone, the origin is the only sane place left.
        const bool prev_ok = is_finite(pose.prev_position) && is_finite(pose.prev_orientation);
        pose.position = prev_ok ? pose.prev_position : Vec3{};
        pose.orientation = prev_ok ? pose.prev_orientation : Quat::identity();
        pose.prev_position = pose.position;
        pose.prev_orientation = pose.orientation;
        vel = Velocity{};
        body.motion = MotionType::Kinematic;
        body.inv_mass = 0.0;
        body.inv_inertia_body = Vec3{};
        ++io_warnings.non_finite_bodies;
        io_warnings.last_non_finite = e;
        if (ctx.faults != nullptr)
            ctx.faults->record(FaultKind::BodyNonFinite, e, stage);
    });
}

void clear_forces(Registry& reg)
{
    for (ForceAccumulator& acc : reg.store<ForceAccumulator>().values())
        acc = ForceAccumulator{};
}

} // namespace supermodal
