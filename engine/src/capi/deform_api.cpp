// SPDX-License-Identifier: MIT
// C API: deformed points, meshes and modal amplitudes (supermodal/supermodal.h).
#include "capi/capi_internal.h"

#include <algorithm>

using namespace supermodal;
using namespace supermodal::capi;

namespace
{

const RestMesh& rest_mesh(const sm_world& world, sm_body body, int resolution)
{
    resolution = std::clamp(resolution, 4, 2048); // tessellate()'s range: equal keys for equal meshes
    auto [it, added] = world.rest_meshes.try_emplace({body.id, resolution});
    if (added) {
        const Entity e = to_entity(body);
        try {
            it->second.mesh = tessellate(body_shape(world.world, e), resolution);
            if (const ModalBasis* basis = body_modal_basis(world.world, e))
                for (const Vec3& p : it->second.mesh.positions)
                    it->second.weights.push_back(modal_weights(*basis, p));
        } catch (...) {
            world.rest_meshes.erase(it); // no half-filled entry
            throw;
        }
    }
    return it->second;
}

} // namespace

extern "C" {

sm_status sm_body_get_deformed_points(const sm_world* world, sm_body body, const sm_vec3* rest_points,
                                      size_t count, sm_vec3* out_points)
{
    constexpr const char* fn = "sm_body_get_deformed_points";
    return guard(fn, [&] {
        if (const sm_status s = check_body(fn, world, body); s != SM_OK)
            return s;
        if (count > 0 && (rest_points == nullptr || out_points == nullptr))
            return null_argument(fn, rest_points == nullptr ? "rest_points" : "out_points");
        for (size_t i = 0; i < count; ++i)
            if (!finite(rest_points[i]))
                return invalid_argument(fn, ("rest_points[" + std::to_string(i) + "]").c_str(),
                                        "expected a finite point [m]");
        // All checked before any is written: on failure out_points is untouched.
        const Entity e = to_entity(body);
        for (size_t i = 0; i < count; ++i)
            out_points[i] = to_c(body_deformed_point(world->world, e, to_vec(rest_points[i])));
        return ok();
    });
}

sm_status sm_body_get_mesh(const sm_world* world, sm_body body, int resolution, sm_vec3* positions,
                           size_t vertex_capacity, uint32_t* indices, size_t index_capacity,
                           size_t* out_vertex_count, size_t* out_index_count)
{
    constexpr const char* fn = "sm_body_get_mesh";
    return guard(fn, [&] {
        if (const sm_status s = check_body(fn, world, body); s != SM_OK)
            return s;
        if (out_vertex_count == nullptr || out_index_count == nullptr)
            return null_argument(fn, out_vertex_count == nullptr ? "out_vertex_count" : "out_index_count");
        if ((positions == nullptr && vertex_capacity > 0) || (indices == nullptr && index_capacity > 0))
            return null_argument(fn, positions == nullptr ? "positions (with capacity > 0)"
                                                          : "indices (with capacity > 0)");
        const Entity e = to_entity(body);
        const RestMesh& rest = rest_mesh(*world, body, resolution);
        const TriangleMesh& mesh = rest.mesh;
        *out_vertex_count = mesh.positions.size();
        *out_index_count = mesh.indices.size();
        if (vertex_capacity < mesh.positions.size() || index_capacity < mesh.indices.size()) {
            if (positions == nullptr && indices == nullptr)
                return ok(); // a size query
            return set_error(SM_ERROR_BUFFER_TOO_SMALL,
                             std::string(fn) + ": the mesh has " + std::to_string(mesh.positions.size()) +
                                 " vertices and " + std::to_string(mesh.indices.size()) + " indices");
        }
        // body_deformed_point's formula with the cached weights: bit-identical to it (tests/capi).
        const Vec3 centre = body_center_of_mass(world->world, e);
        const Quat orientation = body_orientation(world->world, e);
        const Vec3 com = body_mass_properties(world->world, e).center_of_mass;
        const ModalBasis* basis = body_modal_basis(world->world, e);
        const std::vector<double> q =
            basis ? body_modal_state(world->world, e).amplitudes : std::vector<double>{};
        const std::vector<Vec3> moulded =
            basis ? body_remould(world->world, e).rest_offsets : std::vector<Vec3>{};
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            Vec3 local = mesh.positions[i] - com;
            if (basis != nullptr)
                local += modal_displacement(*basis, rest.weights[i], q);
            if (!moulded.empty())
                local += interpolate_nodal(rest.weights[i], moulded);
            positions[i] = to_c(centre + rotate(orientation, local));
        }
        std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
        return ok();
    });
}

sm_status sm_body_get_modal_amplitudes(const sm_world* world, sm_body body, double* amplitudes,
                                       size_t capacity, size_t* out_count)
{
    constexpr const char* fn = "sm_body_get_modal_amplitudes";
    return guard(fn, [&] {
        if (const sm_status s = check_body(fn, world, body); s != SM_OK)
            return s;
        if (out_count == nullptr)
            return null_argument(fn, "out_count");
        if (amplitudes == nullptr && capacity > 0)
            return null_argument(fn, "amplitudes (with capacity > 0)");
        const BodyModalState state = body_modal_state(world->world, to_entity(body));
        const size_t n = state.amplitudes.size();
        *out_count = n;
        std::copy_n(state.amplitudes.begin(), std::min(capacity, n), amplitudes);
        if (capacity < n && amplitudes != nullptr)
            return set_error(SM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": capacity " +
                                                            std::to_string(capacity) + " is less than the " +
                                                            std::to_string(n) + " modes");
        return ok();
    });
}

} // extern "C"
