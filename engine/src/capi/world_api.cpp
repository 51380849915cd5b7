// SPDX-License-Identifier: MIT
// C API: errors, the version, worlds, stepping, snapshots (supermodal/supermodal.h).
#include "capi/capi_internal.h"
#include "supermodal/version.h"

#include <memory>
#include <utility>

using namespace supermodal;
using namespace supermodal::capi;

namespace supermodal::capi
{
namespace
{
thread_local std::string t_last_error;
} // namespace

sm_status set_error(sm_status status, const std::string& message)
{
    t_last_error = message;
    return status;
}

sm_status internal_error(const char* function, const char* what) noexcept
{
    try {
        t_last_error = std::string(function) + ": " + what;
    } catch (...) {
        t_last_error.clear(); // keeps its capacity: no allocation, no throw
        t_last_error.append("out of memory", 13);
    }
    return SM_ERROR_INTERNAL;
}

sm_status check_world(const char* function, const sm_world* world)
{
    if (world == nullptr)
        return set_error(SM_ERROR_INVALID_HANDLE, std::string(function) + ": world is NULL");
    if (!live_world(world))
        return set_error(SM_ERROR_INVALID_HANDLE, std::string(function) + ": world is not a live sm_world");
    return SM_OK;
}

sm_status check_body(const char* function, const sm_world* world, sm_body body)
{
    if (const sm_status s = check_world(function, world); s != SM_OK)
        return s;
    if (body.id == 0)
        return set_error(SM_ERROR_INVALID_HANDLE, std::string(function) + ": body is the null handle");
    if (!world_valid(world->world, to_entity(body)))
        return set_error(SM_ERROR_INVALID_HANDLE, std::string(function) + ": body " +
                                                      std::to_string(body.id) +
                                                      " is not a live body of this world (destroyed?)");
    return SM_OK;
}

sm_status null_argument(const char* function, const char* parameter)
{
    return set_error(SM_ERROR_NULL_ARGUMENT, std::string(function) + ": " + parameter + " is NULL");
}

sm_status invalid_argument(const char* function, const char* parameter, const char* expected)
{
    return set_error(SM_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + parameter + ": " + expected);
}

} // namespace supermodal::capi

namespace
{

WorldDef from_c(const sm_world_def& d)
{
    WorldDef def = default_world_def();
    def.dt = d.dt;
    def.substep_count = d.substep_count;
    def.gravity = to_vec(d.gravity);
    def.max_steps_per_advance = d.max_steps_per_advance;
    def.constraint_iterations = d.constraint_iterations;
    def.thread_count = d.thread_count;
    def.split_islands = d.split_islands != 0;
    return def;
}

sm_world_def to_c(const WorldDef& def)
{
    return {def.dt,
            def.substep_count,
            capi::to_c(def.gravity),
            def.max_steps_per_advance,
            def.constraint_iterations,
            def.thread_count,
            def.split_islands ? 1 : 0};
}

sm_status adopt(Result<World> built, sm_world** out_world)
{
    if (!built)
        return set_error(SM_ERROR_SCENE, built.error().message());
    auto world = std::make_unique<sm_world>(sm_world{sm_world::k_tag, std::move(*built), {}});
    *out_world = world.release();
    return ok();
}

// Scene files and JSON go through the same two stages; either one's error names the file and pointer.
template <class Load> sm_status create_from_scene(Load&& load, sm_world** out_world)
{
    Result<Scene> scene = load();
    if (!scene)
        return set_error(SM_ERROR_SCENE, scene.error().message());
    return adopt(build_world(*scene), out_world);
}

} // namespace

extern "C" {

const char* sm_status_string(sm_status status)
{
    switch (enum_value(status)) { // any int may come from C
    case SM_OK:
        return "SM_OK";
    case SM_ERROR_NULL_ARGUMENT:
        return "SM_ERROR_NULL_ARGUMENT";
    case SM_ERROR_INVALID_HANDLE:
        return "SM_ERROR_INVALID_HANDLE";
    case SM_ERROR_INVALID_ARGUMENT:
        return "SM_ERROR_INVALID_ARGUMENT";
    case SM_ERROR_SCENE:
        return "SM_ERROR_SCENE";
    case SM_ERROR_NOT_FOUND:
        return "SM_ERROR_NOT_FOUND";
    case SM_ERROR_BUFFER_TOO_SMALL:
        return "SM_ERROR_BUFFER_TOO_SMALL";
    case SM_ERROR_SNAPSHOT_MISMATCH:
        return "SM_ERROR_SNAPSHOT_MISMATCH";
    case SM_ERROR_INTERNAL:
        return "SM_ERROR_INTERNAL";
    case SM_STATUS_MAX_ENUM:
        break;
    }
    return "SM_UNKNOWN_STATUS";
}

const char* sm_last_error(void)
{
    return t_last_error.c_str();
}

const char* sm_version(void)
{
    return version();
}

sm_world_def sm_world_def_default(void)
{
    return to_c(default_world_def());
}

sm_status sm_world_create(const sm_world_def* def, sm_world** out_world)
{
    return guard("sm_world_create", [&] {
        if (def == nullptr)
            return null_argument("sm_world_create", "def");
        if (out_world == nullptr)
            return null_argument("sm_world_create", "out_world");
        const WorldDef d = from_c(*def);
        if (const Status s = validate(d); !s)
            return invalid_argument("sm_world_create", s.error().where.c_str(), s.error().what.c_str());
        auto world = std::make_unique<sm_world>(sm_world{sm_world::k_tag, World(d), {}});
        *out_world = world.release();
        return ok();
    });
}

sm_status sm_world_create_from_file(const char* path, sm_world** out_world)
{
    return guard("sm_world_create_from_file", [&] {
        if (path == nullptr)
            return null_argument("sm_world_create_from_file", "path");
        if (out_world == nullptr)
            return null_argument("sm_world_create_from_file", "out_world");
        return create_from_scene([&] { return load_scene(path); }, out_world);
    });
}

sm_status sm_world_create_from_json(const char* json, sm_world** out_world)
{
    return guard("sm_world_create_from_json", [&] {
        if (json == nullptr)
            return null_argument("sm_world_create_from_json", "json");
        if (out_world == nullptr)
            return null_argument("sm_world_create_from_json", "out_world");
        return create_from_scene([&] { return parse_scene(json); }, out_world);
    });
}

void sm_world_destroy(sm_world* world)
{
    if (!live_world(world))
        return;
    world->tag = 0;
    delete world; // ~World does not throw
}

sm_status sm_world_get_def(const sm_world* world, sm_world_def* out_def)
{
    return guard("sm_world_get_def", [&] {
        if (const sm_status s = check_world("sm_world_get_def", world); s != SM_OK)
            return s;
        if (out_def == nullptr)
            return null_argument("sm_world_get_def", "out_def");
        *out_def = to_c(world->world.settings());
        return ok();
    });
}

sm_status sm_world_set_def(sm_world* world, const sm_world_def* def)
{
    return guard("sm_world_set_def", [&] {
        if (const sm_status s = check_world("sm_world_set_def", world); s != SM_OK)
            return s;
        if (def == nullptr)
            return null_argument("sm_world_set_def", "def");
        WorldDef next = world->world.settings();
        const WorldDef asked = from_c(*def);
        if (const Status s = validate(asked); !s)
            return invalid_argument("sm_world_set_def", s.error().where.c_str(), s.error().what.c_str());
        next.dt = asked.dt;
        next.thread_count = asked.thread_count;
        next.substep_count = asked.substep_count;
        next.gravity = asked.gravity;
        next.max_steps_per_advance = asked.max_steps_per_advance;
        next.constraint_iterations = asked.constraint_iterations;
        next.split_islands = asked.split_islands;
        if (const Status s = world->world.set_settings(next); !s)
            return invalid_argument("sm_world_set_def", s.error().where.c_str(), s.error().what.c_str());
        return ok();
    });
}

sm_status sm_world_set_gravity(sm_world* world, sm_vec3 gravity)
{
    return guard("sm_world_set_gravity", [&] {
        if (const sm_status s = check_world("sm_world_set_gravity", world); s != SM_OK)
            return s;
        if (!finite(gravity))
            return invalid_argument("sm_world_set_gravity", "gravity", "expected a finite vector");
        WorldDef next = world->world.settings();
        next.gravity = to_vec(gravity);
        if (const Status s = world->world.set_settings(next); !s)
            return invalid_argument("sm_world_set_gravity", s.error().where.c_str(), s.error().what.c_str());
        return ok();
    });
}

sm_status sm_world_step(sm_world* world)
{
    return guard("sm_world_step", [&] {
        if (const sm_status s = check_world("sm_world_step", world); s != SM_OK)
            return s;
        world->world.step();
        return ok();
    });
}

sm_status sm_world_advance(sm_world* world, double seconds, int* out_steps)
{
    return guard("sm_world_advance", [&] {
        if (const sm_status s = check_world("sm_world_advance", world); s != SM_OK)
            return s;
        if (!(std::isfinite(seconds) && seconds >= 0.0))
            return invalid_argument("sm_world_advance", "seconds", "expected a finite time >= 0 s");
        const int steps = world->world.advance(seconds);
        if (out_steps != nullptr)
            *out_steps = steps;
        return ok();
    });
}

sm_status sm_world_get_interpolation_alpha(const sm_world* world, double* out_alpha)
{
    return guard("sm_world_get_interpolation_alpha", [&] {
        if (const sm_status s = check_world("sm_world_get_interpolation_alpha", world); s != SM_OK)
            return s;
        if (out_alpha == nullptr)
            return null_argument("sm_world_get_interpolation_alpha", "out_alpha");
        *out_alpha = world->world.interpolation_alpha();
        return ok();
    });
}

sm_status sm_world_get_time(const sm_world* world, double* out_seconds)
{
    return guard("sm_world_get_time", [&] {
        if (const sm_status s = check_world("sm_world_get_time", world); s != SM_OK)
            return s;
        if (out_seconds == nullptr)
            return null_argument("sm_world_get_time", "out_seconds");
        *out_seconds = world->world.time();
        return ok();
    });
}

sm_status sm_world_get_step_count(const sm_world* world, uint64_t* out_steps)
{
    return guard("sm_world_get_step_count", [&] {
        if (const sm_status s = check_world("sm_world_get_step_count", world); s != SM_OK)
            return s;
        if (out_steps == nullptr)
            return null_argument("sm_world_get_step_count", "out_steps");
        *out_steps = world->world.step_count();
        return ok();
    });
}

sm_status sm_world_get_state_hash(const sm_world* world, uint64_t* out_hash)
{
    return guard("sm_world_get_state_hash", [&] {
        if (const sm_status s = check_world("sm_world_get_state_hash", world); s != SM_OK)
            return s;
        if (out_hash == nullptr)
            return null_argument("sm_world_get_state_hash", "out_hash");
        *out_hash = world->world.state_hash();
        return ok();
    });
}

sm_status sm_world_snapshot(const sm_world* world, sm_snapshot** out_snapshot)
{
    return guard("sm_world_snapshot", [&] {
        if (const sm_status s = check_world("sm_world_snapshot", world); s != SM_OK)
            return s;
        if (out_snapshot == nullptr)
            return null_argument("sm_world_snapshot", "out_snapshot");
        auto snap = std::make_unique<sm_snapshot>(sm_snapshot{world->world.snapshot()});
        *out_snapshot = snap.release();
        return ok();
    });
}

sm_status sm_world_restore(sm_world* world, const sm_snapshot* snapshot)
{
    return guard("sm_world_restore", [&] {
        if (const sm_status s = check_world("sm_world_restore", world); s != SM_OK)
            return s;
        if (snapshot == nullptr)
            return null_argument("sm_world_restore", "snapshot");
        if (const Status s = world->world.restore(snapshot->snapshot); !s)
            return set_error(SM_ERROR_SNAPSHOT_MISMATCH, "sm_world_restore: " + s.error().message());
        return ok();
    });
}

void sm_snapshot_destroy(sm_snapshot* snapshot)
{
    delete snapshot;
}

} // extern "C"
