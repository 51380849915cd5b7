// SPDX-License-Identifier: MIT
// C API: setting a body's motion and applying forces (supermodal/supermodal.h).
#include "capi/capi_internal.h"

using namespace supermodal;
using namespace supermodal::capi;

extern "C" {

sm_status sm_body_set_position(sm_world* world, sm_body body, sm_vec3 position)
{
    return guard("sm_body_set_position", [&] {
        if (const sm_status s = check_body("sm_body_set_position", world, body); s != SM_OK)
            return s;
        if (!finite(position))
            return invalid_argument("sm_body_set_position", "position", "expected a finite vector [m]");
        set_body_position(world->world, to_entity(body), to_vec(position));
        return ok();
    });
}

sm_status sm_body_set_orientation(sm_world* world, sm_body body, sm_quat orientation)
{
    return guard("sm_body_set_orientation", [&] {
        if (const sm_status s = check_body("sm_body_set_orientation", world, body); s != SM_OK)
            return s;
        // norm() > 0 also refuses quaternions so small that their squared norm underflows.
        if (!finite(orientation) || !(norm(to_quat(orientation)) > 0.0))
            return invalid_argument("sm_body_set_orientation", "orientation",
                                    "expected a finite, non-zero quaternion");
        set_body_orientation(world->world, to_entity(body), to_quat(orientation));
        return ok();
    });
}

sm_status sm_body_set_velocity(sm_world* world, sm_body body, sm_vec3 linear, sm_vec3 angular)
{
    return guard("sm_body_set_velocity", [&] {
        if (const sm_status s = check_body("sm_body_set_velocity", world, body); s != SM_OK)
            return s;
        if (!finite(linear) || !finite(angular))
            return invalid_argument("sm_body_set_velocity", finite(linear) ? "angular" : "linear",
                                    "expected a finite vector");
        set_body_linear_velocity(world->world, to_entity(body), to_vec(linear));
        set_body_angular_velocity(world->world, to_entity(body), to_vec(angular));
        return ok();
    });
}

sm_status sm_body_apply_force(sm_world* world, sm_body body, sm_vec3 force, sm_vec3 point)
{
    return guard("sm_body_apply_force", [&] {
        if (const sm_status s = check_body("sm_body_apply_force", world, body); s != SM_OK)
            return s;
        if (!finite(force) || !finite(point))
            return invalid_argument("sm_body_apply_force", finite(force) ? "point" : "force",
                                    "expected a finite vector");
        apply_force(world->world, to_entity(body), to_vec(force), to_vec(point));
        return ok();
    });
}

sm_status sm_body_apply_force_at_center(sm_world* world, sm_body body, sm_vec3 force)
{
    return guard("sm_body_apply_force_at_center", [&] {
        if (const sm_status s = check_body("sm_body_apply_force_at_center", world, body); s != SM_OK)
            return s;
        if (!finite(force))
            return invalid_argument("sm_body_apply_force_at_center", "force", "expected a finite vector");
        apply_force_at_center(world->world, to_entity(body), to_vec(force));
        return ok();
    });
}

sm_status sm_body_apply_torque(sm_world* world, sm_body body, sm_vec3 torque)
{
    return guard("sm_body_apply_torque", [&] {
        if (const sm_status s = check_body("sm_body_apply_torque", world, body); s != SM_OK)
            return s;
        if (!finite(torque))
            return invalid_argument("sm_body_apply_torque", "torque", "expected a finite vector");
        apply_torque(world->world, to_entity(body), to_vec(torque));
        return ok();
    });
}

sm_status sm_body_apply_impulse(sm_world* world, sm_body body, sm_vec3 impulse, sm_vec3 point)
{
    return guard("sm_body_apply_impulse", [&] {
        if (const sm_status s = check_body("sm_body_apply_impulse", world, body); s != SM_OK)
            return s;
        if (!finite(impulse) || !finite(point))
            return invalid_argument("sm_body_apply_impulse", finite(impulse) ? "point" : "impulse",
                                    "expected a finite vector");
        apply_linear_impulse(world->world, to_entity(body), to_vec(impulse), to_vec(point));
        return ok();
    });
}

sm_status sm_body_apply_angular_impulse(sm_world* world, sm_body body, sm_vec3 impulse)
{
    return guard("sm_body_apply_angular_impulse", [&] {
        if (const sm_status s = check_body("sm_body_apply_angular_impulse", world, body); s != SM_OK)
            return s;
        if (!finite(impulse))
            return invalid_argument("sm_body_apply_angular_impulse", "impulse", "expected a finite vector");
        apply_angular_impulse(world->world, to_entity(body), to_vec(impulse));
        return ok();
    });
}

} // extern "C"
