// SPDX-License-Identifier: MIT
// Shared by the C API's translation units: the opaque structs, the per-thread error message, and the
// boundary guard that turns every C++ exception into an sm_status.
#pragma once

#include "supermodal/supermodal.h"
#include "supermodal/supermodal.hpp"

#include <cmath>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace supermodal::capi
{
/// A body's rest mesh at one resolution, and for a modal body its vertices' lattice weights: what
/// sm_body_get_mesh would otherwise recompute every frame (about half its cost, bench/capi_bench.cpp).
struct RestMesh {
    TriangleMesh mesh;
    std::vector<LatticeWeights> weights; ///< Per vertex; empty for a rigid body.
};
} // namespace supermodal::capi

struct sm_world {
    // Tells a real world from garbage or a pointer of another type cast to sm_world*; cleared on destroy.
    static constexpr uint64_t k_tag = 0x736d5f776f726c64; // "sm_world"
    uint64_t tag = k_tag;
    supermodal::World world;
    // Keyed by (body id, resolution). Body ids are never reused and the C API cannot change a body's
    // shape, so an entry stays right until its body is destroyed (sm_world_destroy_body drops it).
    // Mutable: filled by the const query; a world is used from one thread at a time.
    mutable std::map<std::pair<uint64_t, int>, supermodal::capi::RestMesh> rest_meshes;
};

// The C side stores enums as int (every ABI the engine targets); enum_value below relies on it.
static_assert(sizeof(sm_status) == sizeof(int) && sizeof(sm_motion) == sizeof(int) &&
              sizeof(sm_shape_type) == sizeof(int));

struct sm_snapshot {
    supermodal::Snapshot snapshot;
};

namespace supermodal::capi
{

/// Records the outcome of the current call for sm_last_error(); returns `status`.
sm_status set_error(sm_status status, const std::string& message);
inline sm_status ok()
{
    return set_error(SM_OK, {});
}

/// SM_ERROR_INTERNAL with "function: what"; never throws (out of memory leaves a short fixed message).
sm_status internal_error(const char* function, const char* what) noexcept;

/// Runs `body` (which returns an sm_status); any exception becomes SM_ERROR_INTERNAL with its text.
template <class F> sm_status guard(const char* function, F&& body) noexcept
{
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return internal_error(function, "out of memory");
    } catch (const std::exception& e) {
        return internal_error(function, e.what());
    } catch (...) {
        return internal_error(function, "unknown exception");
    }
}

inline bool live_world(const sm_world* world)
{
    return world != nullptr && world->tag == sm_world::k_tag;
}
inline Entity to_entity(sm_body body)
{
    return Entity{static_cast<uint32_t>(body.id & 0xffffffffu), static_cast<uint32_t>(body.id >> 32)};
}
inline sm_body to_body(Entity e)
{
    return sm_body{(static_cast<uint64_t>(e.generation) << 32) | e.index};
}
inline Vec3 to_vec(sm_vec3 v)
{
    return {v.x, v.y, v.z};
}
inline sm_vec3 to_c(const Vec3& v)
{
    return {v.x, v.y, v.z};
}
inline Quat to_quat(sm_quat q)
{
    return {q.w, q.x, q.y, q.z};
}
inline sm_quat to_c(const Quat& q)
{
    return {q.w, q.x, q.y, q.z};
}
inline bool finite(sm_vec3 v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline bool finite(sm_quat q)
{
    return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

/// The integer a C caller stored in an enum: C allows any int there, while loading an out-of-range
/// value as the C++ enum type is undefined behaviour, so the bytes are read as the underlying type.
template <class E> long long enum_value(const E& e)
{
    std::underlying_type_t<E> v;
    std::memcpy(&v, &e, sizeof v);
    return static_cast<long long>(v);
}

/// SM_ERROR_INVALID_HANDLE (with the function's name) unless `world` is a live world.
sm_status check_world(const char* function, const sm_world* world);
/// As check_world, and `body` must be a live body of it.
sm_status check_body(const char* function, const sm_world* world, sm_body body);
/// SM_ERROR_NULL_ARGUMENT naming the parameter.
sm_status null_argument(const char* function, const char* parameter);
/// SM_ERROR_INVALID_ARGUMENT: "function: parameter: expected ...".
sm_status invalid_argument(const char* function, const char* parameter, const char* expected);

} // namespace supermodal::capi
