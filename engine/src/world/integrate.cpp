// SPDX-License-Identifier: MIT
#include "world/integrate.h"

#include "dynamics/rotation.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace supermodal
{

namespace
{

// Velocities into the pose of one body over h [s]; true when the gyroscopic solve fell back.
bool integrate_body(double h, const BodyModel& body, Velocity& vel, Pose& pose)
{
    switch (body.motion) {
    case MotionType::Static:
        return false;
    case MotionType::Kinematic:
        pose.position += h * vel.linear;
        pose.orientation = normalized(quat_from_rotation_vector(h * vel.angular) * pose.orientation);
        return false;
    case MotionType::Dynamic:
        break;
    }
    pose.position += h * vel.linear;
    // The torque-free flow in the principal frame; the pose keeps the shape frame (q·p⁻¹).
    const Quat q = principal_orientation(body, pose.orientation);
    const Vec3 momentum_body = hadamard(body.inertia_body, inv_rotate(q, vel.angular));
    const RotationStep rot = rotate_torque_free(q, momentum_body, body.inertia_body, h);
    pose.orientation = rot.orientation * conjugate(body.principal);
    vel.angular = rotate(rot.orientation, hadamard(body.inv_inertia_body, rot.momentum_body));
    return rot.used_fallback;
}

bool body_finite(const Velocity& vel, const Pose& pose)
{
    return is_finite(pose.position) && is_finite(pose.orientation) && is_finite(vel.linear) &&
           is_finite(vel.angular);
}

// Zero velocity, the last finite pose, kinematic: a fault never spreads.
void freeze_body(BodyModel& body, Velocity& vel, Pose& pose)
{
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
}

} // namespace

StepContext make_step_context(const WorldDef& def)
{
    return {.h = def.dt / def.substep_count, .gravity = def.gravity, .substep_count = def.substep_count};
}

void integrate_forces(const StepContext& ctx, const Parallel& par, Registry& reg)
{
    // Writes only the visited entity's Velocity, so neither view order nor threads change the result.
    par.for_parts(
        reg.store<BodyModel>().size(), k_min_bodies_per_part, [&](size_t, size_t begin, size_t end) {
            reg.each_in<BodyModel, ForceAccumulator, Velocity, Pose, Sleep>(
                begin, end,
                [&](Entity, const BodyModel& body, const ForceAccumulator& acc, Velocity& vel,
                    const Pose& pose, const Sleep& sleep) {
                    if (body.motion != MotionType::Dynamic || sleep.asleep)
                        return;
                    vel.linear += ctx.h * (body.gravity_scale * ctx.gravity + body.inv_mass * acc.force);
                    // Torque kick on the angular momentum; the torque-free flow follows in
                    // integrate_positions. In the principal frame, where the inertia is diagonal.
                    const Quat q = principal_orientation(body, pose.orientation);
                    const Vec3 torque_body = inv_rotate(q, acc.torque);
                    const Vec3 w_body = inv_rotate(q, vel.angular);
                    const Vec3 momentum_body = hadamard(body.inertia_body, w_body) + ctx.h * torque_body;
                    vel.angular = rotate(q, hadamard(body.inv_inertia_body, momentum_body));
                });
        });
}

void integrate_positions(const StepContext& ctx, const Parallel& par, Registry& reg,
                         IntegrateScratch& scratch, StepWarnings& io_warnings)
{
    // Each body writes only its own pose and velocity; the fallbacks are counted per part, summed after.
    std::vector<uint64_t>& fallbacks = scratch.fallbacks;
    fallbacks.assign(par.part_capacity(), 0);
    par.for_parts(reg.store<BodyModel>().size(), k_min_bodies_per_part,
                  [&](size_t part, size_t begin, size_t end) {
                      reg.each_in<BodyModel, Velocity, Pose, Sleep>(
                          begin, end,
                          [&](Entity, const BodyModel& body, Velocity& vel, Pose& pose, const Sleep& sleep) {
                              if (!sleep.asleep && integrate_body(ctx.h, body, vel, pose))
                                  ++fallbacks[part];
                          });
                  });
    for (uint64_t n : fallbacks)
        io_warnings.gyroscopic_fallbacks += n;
}

void store_previous_poses(const Parallel& par, Registry& reg)
{
    std::vector<Pose>& poses = reg.store<Pose>().values();
    par.for_parts(poses.size(), k_min_bodies_per_part, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            poses[i].prev_position = poses[i].position;
            poses[i].prev_orientation = poses[i].orientation;
        }
    });
}

void freeze_non_finite(const StepContext& ctx, Stage stage, const Parallel& par, Registry& reg,
                       IntegrateScratch& scratch, StepWarnings& io_warnings)
{
    // Looked for on any thread, each part noting its first bad body; frozen on this thread in store
    // order, so the fault log's order does not depend on threads. A clean substep reads every body once.
    const std::vector<Entity>& bodies = reg.store<BodyModel>().entities();
    std::vector<size_t>& first_bad = scratch.first_bad;
    first_bad.assign(par.part_capacity(), bodies.size());
    par.for_parts(bodies.size(), k_min_bodies_per_part, [&](size_t part, size_t begin, size_t end) {
        for (size_t i = begin; i < end && first_bad[part] == bodies.size(); ++i)
            if (!body_finite(reg.get<Velocity>(bodies[i]), reg.get<Pose>(bodies[i])))
                first_bad[part] = i;
    });
    const size_t start = *std::min_element(first_bad.begin(), first_bad.end());
    reg.each_in<BodyModel, Velocity, Pose>(start, bodies.size(),
                                           [&](Entity e, BodyModel& body, Velocity& vel, Pose& pose) {
                                               if (body_finite(vel, pose))
                                                   return;
                                               freeze_body(body, vel, pose);
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
