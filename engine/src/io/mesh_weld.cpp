// SPDX-License-Identifier: MIT
#include "io/mesh_weld.h"

#include <bit>
#include <cstdint>
#include <unordered_map>

namespace supermodal
{
namespace
{

struct Key {
    uint64_t x, y, z;
    friend bool operator==(const Key&, const Key&) = default;
};
struct KeyHash {
    size_t operator()(const Key& k) const
    {
        // FNV-style mix; only the lookup speed depends on it, never the output order.
        uint64_t h = 1469598103934665603ull;
        for (uint64_t v : {k.x, k.y, k.z})
            h = (h ^ v) * 1099511628211ull;
        return size_t(h);
    }
};
Key key_of(const Vec3& p)
{
    // + 0.0 turns −0.0 into +0.0 so both weld together.
    return {std::bit_cast<uint64_t>(p.x + 0.0), std::bit_cast<uint64_t>(p.y + 0.0),
            std::bit_cast<uint64_t>(p.z + 0.0)};
}

} // namespace

TriangleMesh weld_mesh(const TriangleMesh& mesh, MeshLook* look)
{
    const bool uv = look != nullptr && look->texcoords.size() == 2 * mesh.positions.size();
    TriangleMesh out;
    std::vector<double> texcoords;
    std::unordered_map<Key, uint32_t, KeyHash> group_of; // position → position group
    std::unordered_map<Key, uint32_t, KeyHash> index_of; // (group, u, v) → output vertex
    std::vector<uint32_t> remap(mesh.positions.size()), out_group;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const auto g = group_of.try_emplace(key_of(mesh.positions[i]), uint32_t(group_of.size())).first;
        const Key k = uv ? Key{g->second, std::bit_cast<uint64_t>(look->texcoords[2 * i] + 0.0),
                               std::bit_cast<uint64_t>(look->texcoords[2 * i + 1] + 0.0)}
                         : Key{g->second, 0, 0};
        const auto [it, added] = index_of.try_emplace(k, uint32_t(out.positions.size()));
        if (added) {
            out.positions.push_back(mesh.positions[i]);
            out_group.push_back(g->second);
            if (uv)
                texcoords.insert(texcoords.end(), {look->texcoords[2 * i], look->texcoords[2 * i + 1]});
        }
        remap[i] = it->second;
    }
    std::vector<Vec3> group_normals(group_of.size());
    std::vector<uint32_t> materials;
    const bool per_triangle = look != nullptr && look->triangle_materials.size() * 3 == mesh.indices.size();
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = remap[mesh.indices[t]], b = remap[mesh.indices[t + 1]],
                       c = remap[mesh.indices[t + 2]];
        const uint32_t ga = out_group[a], gb = out_group[b], gc = out_group[c];
        if (ga == gb || gb == gc || ga == gc)
            continue;
        out.indices.insert(out.indices.end(), {a, b, c});
        if (per_triangle)
            materials.push_back(look->triangle_materials[t / 3]);
        // |cross| is twice the area: the sum is area-weighted.
        const Vec3 n = cross(out.positions[b] - out.positions[a], out.positions[c] - out.positions[a]);
        for (uint32_t g : {ga, gb, gc})
            group_normals[g] += n;
    }
    out.normals.resize(out.positions.size());
    for (size_t v = 0; v < out.positions.size(); ++v) {
        out.normals[v] = normalized(group_normals[out_group[v]]);
        if (out.normals[v] == Vec3{})
            out.normals[v] = {0, 1, 0};
    }
    if (look != nullptr) {
        look->texcoords = std::move(texcoords);
        if (per_triangle)
            look->triangle_materials = std::move(materials);
    }
    return out;
}

} // namespace supermodal
