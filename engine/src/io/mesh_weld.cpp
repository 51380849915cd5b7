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

TriangleMesh weld_mesh(const TriangleMesh& mesh)
{
    TriangleMesh out;
    std::unordered_map<Key, uint32_t, KeyHash> index_of;
    std::vector<uint32_t> remap(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const auto [it, added] =
            index_of.try_emplace(key_of(mesh.positions[i]), uint32_t(out.positions.size()));
        if (added)
            out.positions.push_back(mesh.positions[i]);
        remap[i] = it->second;
    }
    out.normals.assign(out.positions.size(), Vec3{});
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = remap[mesh.indices[t]], b = remap[mesh.indices[t + 1]],
                       c = remap[mesh.indices[t + 2]];
        if (a == b || b == c || a == c)
            continue;
        out.indices.insert(out.indices.end(), {a, b, c});
        // |cross| is twice the area: the sum is area-weighted.
        const Vec3 n = cross(out.positions[b] - out.positions[a], out.positions[c] - out.positions[a]);
        for (uint32_t v : {a, b, c})
            out.normals[v] += n;
    }
    for (Vec3& n : out.normals) {
        n = normalized(n);
        if (n == Vec3{})
            n = {0, 1, 0};
    }
    return out;
}

} // namespace supermodal
