// SPDX-License-Identifier: MIT
// C API: making, finding and querying bodies (supermodal/supermodal.h); setters and forces are in
// motion_api.cpp, deformation in deform_api.cpp.
#include "capi/capi_internal.h"

#include <algorithm>
#include <cstring>
#include <vector>

using namespace supermodal;
using namespace supermodal::capi;

namespace
{

// Every number checked here or by validate(BodyDef); the enum range here, since C lets any int through.
sm_status to_body_def(const char* fn, const sm_body_def& d, BodyDef& def)
{
    const long long motion = enum_value(d.motion), shape = enum_value(d.shape);
    if (motion < SM_MOTION_STATIC || motion > SM_MOTION_DYNAMIC)
        return invalid_argument(fn, "motion", "expected SM_MOTION_STATIC, _KINEMATIC or _DYNAMIC");
    if (shape != SM_SHAPE_SUPERQUADRIC && shape != SM_SHAPE_PLANE)
        return invalid_argument(fn, "shape", "expected SM_SHAPE_SUPERQUADRIC or SM_SHAPE_PLANE");
    if (d.modal_mode_count < 0 || d.modal_mode_count > k_max_modes)
        return invalid_argument(fn, "modal_mode_count", "expected an integer in [0, 256]");
    def = default_body_def();
    def.name = d.name != nullptr ? d.name : "";
    def.motion = static_cast<MotionType>(d.motion); // the enums share their values
    def.shape = default_shape_def();
    if (d.shape == SM_SHAPE_PLANE) {
        def.shape.type = ShapeType::Plane;
        def.shape.plane_normal = to_vec(d.plane_normal);
        def.shape.plane_offset = d.plane_offset;
    } else {
        def.shape.radii = to_vec(d.radii);
        def.shape.epsilon1 = d.epsilon1;
        def.shape.epsilon2 = d.epsilon2;
    }
    def.density = d.density;
    def.position = to_vec(d.position);
    def.orientation = to_quat(d.orientation);
    def.linear_velocity = to_vec(d.linear_velocity);
    def.angular_velocity = to_vec(d.angular_velocity);
    def.gravity_scale = d.gravity_scale;
    def.friction = d.friction;
    def.restitution = d.restitution;
    def.young = d.young;
    def.poisson = d.poisson;
    // Fields the engine ignores for this body (plane for a superquadric, modal for a rigid body) must be
    // finite too: one rule, whatever the body.
    const double numbers[] = {d.radii.x,      d.radii.y,        d.radii.z,        d.epsilon1,
                              d.epsilon2,     d.plane_normal.x, d.plane_normal.y, d.plane_normal.z,
                              d.plane_offset, d.density,        d.gravity_scale,  d.young,
                              d.poisson,      d.damping_ratio};
    for (double x : numbers)
        if (!std::isfinite(x))
            return invalid_argument(fn, "def", "expected finite numbers in every field");
    if (d.modal_mode_count > 0) {
        def.modal.enabled = true;
        def.modal.mode_count = d.modal_mode_count;
        def.modal.damping_ratio = d.damping_ratio;
    }
    if (const Status s = validate(def); !s)
        return invalid_argument(fn, s.error().where.empty() ? "def" : s.error().where.c_str(),
                                s.error().what.c_str());
    return SM_OK;
}

// The two-call buffer convention: the count always; a NULL buffer with capacity 0 is a size query (SM_OK);
// a real buffer that is too short gets its first `capacity` entries and SM_ERROR_BUFFER_TOO_SMALL.
sm_status check_buffer(const char* fn, const void* buffer, size_t capacity)
{
    if (buffer == nullptr && capacity > 0)
        return null_argument(fn, "buffer (with capacity > 0)");
    return SM_OK;
}

sm_status too_small(const char* fn, size_t capacity, size_t needed)
{
    return set_error(SM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": capacity " + std::to_string(capacity) +
                                                    " is less than the " + std::to_string(needed) +
                                                    " needed");
}

} // namespace

extern "C" {

sm_body_def sm_body_def_default(void)
{
    const BodyDef b = default_body_def();
    sm_body_def d{};
    d.name = nullptr;
    d.motion = SM_MOTION_DYNAMIC;
    d.shape = SM_SHAPE_SUPERQUADRIC;
    d.radii = to_c(b.shape.radii);
    d.epsilon1 = b.shape.epsilon1;
    d.epsilon2 = b.shape.epsilon2;
    d.plane_normal = to_c(b.shape.plane_normal);
    d.plane_offset = b.shape.plane_offset;
    d.density = b.density;
    d.position = to_c(b.position);
    d.orientation = to_c(b.orientation);
    d.linear_velocity = to_c(b.linear_velocity);
    d.angular_velocity = to_c(b.angular_velocity);
    d.gravity_scale = b.gravity_scale;
    d.friction = b.friction;
    d.restitution = b.restitution;
    d.modal_mode_count = 0;
    d.young = b.young;
    d.poisson = b.poisson;
    d.damping_ratio = b.modal.damping_ratio;
    return d;
}

sm_status sm_world_create_body(sm_world* world, const sm_body_def* def, sm_body* out_body)
{
    constexpr const char* fn = "sm_world_create_body";
    return guard(fn, [&] {
        if (const sm_status s = check_world(fn, world); s != SM_OK)
            return s;
        if (def == nullptr)
            return null_argument(fn, "def");
        if (out_body == nullptr)
            return null_argument(fn, "out_body");
        BodyDef d;
        if (const sm_status s = to_body_def(fn, *def, d); s != SM_OK)
            return s;
        if (d.modal.enabled) { // learn why a basis cannot be built before create_body asserts on it
            if (auto basis = modal_basis_for(world->world, d); !basis)
                return invalid_argument(fn, "modal", basis.error().message().c_str());
        }
        const Entity e = create_body(world->world, d);
        if (e.is_null())
            return set_error(SM_ERROR_INTERNAL, std::string(fn) + ": the world refused the body");
        *out_body = to_body(e);
        return ok();
    });
}

sm_status sm_world_destroy_body(sm_world* world, sm_body body)
{
    return guard("sm_world_destroy_body", [&] {
        if (const sm_status s = check_body("sm_world_destroy_body", world, body); s != SM_OK)
            return s;
        destroy_body(world->world, to_entity(body));
        std::erase_if(world->rest_meshes, [&](const auto& entry) { return entry.first.first == body.id; });
        return ok();
    });
}

sm_status sm_world_find_body(const sm_world* world, const char* name, sm_body* out_body)
{
    constexpr const char* fn = "sm_world_find_body";
    return guard(fn, [&] {
        if (const sm_status s = check_world(fn, world); s != SM_OK)
            return s;
        if (name == nullptr)
            return null_argument(fn, "name");
        if (out_body == nullptr)
            return null_argument(fn, "out_body");
        const Entity e = find_body(world->world, name);
        if (e.is_null())
            return set_error(SM_ERROR_NOT_FOUND, std::string(fn) + ": no body named \"" + name + "\"");
        *out_body = to_body(e);
        return ok();
    });
}

sm_status sm_world_get_body_count(const sm_world* world, size_t* out_count)
{
    return guard("sm_world_get_body_count", [&] {
        if (const sm_status s = check_world("sm_world_get_body_count", world); s != SM_OK)
            return s;
        if (out_count == nullptr)
            return null_argument("sm_world_get_body_count", "out_count");
        *out_count = world_bodies(world->world).size();
        return ok();
    });
}

sm_status sm_world_get_bodies(const sm_world* world, sm_body* bodies, size_t capacity, size_t* out_count)
{
    constexpr const char* fn = "sm_world_get_bodies";
    return guard(fn, [&] {
        if (const sm_status s = check_world(fn, world); s != SM_OK)
            return s;
        if (out_count == nullptr)
            return null_argument(fn, "out_count");
        if (const sm_status s = check_buffer(fn, bodies, capacity); s != SM_OK)
            return s;
        const std::vector<Entity> all = world_bodies(world->world);
        *out_count = all.size();
        for (size_t i = 0; i < std::min(capacity, all.size()); ++i)
            bodies[i] = to_body(all[i]);
        return capacity < all.size() && bodies != nullptr ? too_small(fn, capacity, all.size()) : ok();
    });
}

int sm_body_is_valid(const sm_world* world, sm_body body)
{
    return live_world(world) && body.id != 0 && world_valid(world->world, to_entity(body)) ? 1 : 0;
}

sm_status sm_body_get_name(const sm_world* world, sm_body body, char* buffer, size_t capacity,
                           size_t* out_length)
{
    return guard("sm_body_get_name", [&] {
        constexpr const char* fn = "sm_body_get_name";
        if (const sm_status s = check_body(fn, world, body); s != SM_OK)
            return s;
        if (const sm_status s = check_buffer(fn, buffer, capacity); s != SM_OK)
            return s;
        const std::string& name = body_name(world->world, to_entity(body));
        if (out_length != nullptr)
            *out_length = name.size();
        if (capacity > 0) {
            const size_t n = std::min(capacity - 1, name.size());
            std::memcpy(buffer, name.data(), n);
            buffer[n] = '\0';
        }
        return capacity > name.size() || buffer == nullptr ? ok() : too_small(fn, capacity, name.size() + 1);
    });
}

sm_status sm_body_get_motion(const sm_world* world, sm_body body, sm_motion* out_motion)
{
    return guard("sm_body_get_motion", [&] {
        if (const sm_status s = check_body("sm_body_get_motion", world, body); s != SM_OK)
            return s;
        if (out_motion == nullptr)
            return null_argument("sm_body_get_motion", "out_motion");
        *out_motion = static_cast<sm_motion>(body_motion(world->world, to_entity(body)));
        return ok();
    });
}

sm_status sm_body_get_mass(const sm_world* world, sm_body body, double* out_mass)
{
    return guard("sm_body_get_mass", [&] {
        if (const sm_status s = check_body("sm_body_get_mass", world, body); s != SM_OK)
            return s;
        if (out_mass == nullptr)
            return null_argument("sm_body_get_mass", "out_mass");
        *out_mass = body_mass_properties(world->world, to_entity(body)).mass;
        return ok();
    });
}

sm_status sm_body_get_pose(const sm_world* world, sm_body body, sm_vec3* out_position,
                           sm_quat* out_orientation)
{
    return guard("sm_body_get_pose", [&] {
        if (const sm_status s = check_body("sm_body_get_pose", world, body); s != SM_OK)
            return s;
        if (out_position == nullptr || out_orientation == nullptr)
            return null_argument("sm_body_get_pose",
                                 out_position == nullptr ? "out_position" : "out_orientation");
        *out_position = to_c(body_position(world->world, to_entity(body)));
        *out_orientation = to_c(body_orientation(world->world, to_entity(body)));
        return ok();
    });
}

sm_status sm_body_get_interpolated_pose(const sm_world* world, sm_body body, sm_vec3* out_position,
                                        sm_quat* out_orientation)
{
    return guard("sm_body_get_interpolated_pose", [&] {
        constexpr const char* fn = "sm_body_get_interpolated_pose";
        if (const sm_status s = check_body(fn, world, body); s != SM_OK)
            return s;
        if (out_position == nullptr || out_orientation == nullptr)
            return null_argument(fn, out_position == nullptr ? "out_position" : "out_orientation");
        *out_position = to_c(body_interpolated_position(world->world, to_entity(body)));
        *out_orientation = to_c(body_interpolated_orientation(world->world, to_entity(body)));
        return ok();
    });
}

sm_status sm_body_get_velocity(const sm_world* world, sm_body body, sm_vec3* out_linear, sm_vec3* out_angular)
{
    return guard("sm_body_get_velocity", [&] {
        if (const sm_status s = check_body("sm_body_get_velocity", world, body); s != SM_OK)
            return s;
        if (out_linear == nullptr || out_angular == nullptr)
            return null_argument("sm_body_get_velocity",
                                 out_linear == nullptr ? "out_linear" : "out_angular");
        *out_linear = to_c(body_linear_velocity(world->world, to_entity(body)));
        *out_angular = to_c(body_angular_velocity(world->world, to_entity(body)));
        return ok();
    });
}

} // extern "C"
