// SPDX-License-Identifier: MIT
// World-space bounding boxes. An undeformed superquadric is centrally symmetric, so its extent along
// world axis i is ± h(Rᵀe_i) with h the support function: exact for any pose, convex or not (the
// support map gives the convex hull's for concave shapes, which has the same extents). Deformed
// superquadrics and hyperquadrics have no closed-form support: their box bounds the vertices of a
// tessellation plus a margin for the surface bulging between vertices.
//
// The broadphase asks for every body's box every step, so the vertex set is computed once per distinct
// shape and kept in a process-wide cache keyed by the bit patterns of the ShapeDef's parameters (NaN
// and −0 included, so lookups never depend on floating-point comparison). The cache is guarded by a
// mutex (safe from several threads and worlds), and what it returns is bit-identical to recomputing,
// so whether a shape was cached never changes a result: determinism does not depend on cache state.
// An entry holds the ~3·10³ vertices of a 64-segment mesh (~70 KB); at most k_bounds_cache_capacity
// entries are kept.
#include "geometry/aabb.h"
#include "geometry/bounds_internal.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace supermodal
{
namespace
{

constexpr double k_unbounded = 1e300;
// Segments around the equator of the tessellation that bounds deformed shapes and hyperquadrics.
constexpr int k_bound_resolution = 64;
// Margin for the surface between tessellation vertices, as a fraction of the mesh's largest half
// extent. A circle cut into 64 chords bulges by (1 − cos(π/64)) ≈ 1.2e-3 of its radius beyond them;
// 2e-2 leaves an order of magnitude for uneven vertex spacing, aspect ratios and bending.
constexpr double k_mesh_margin_rel = 2e-2;

/// What a pose needs to bound a tessellated shape: its vertices and the margin [m].
struct LocalVertices {
    std::vector<Vec3> points;
    double margin = 0.0;
};

Aabb unbounded()
{
    return {{-k_unbounded, -k_unbounded, -k_unbounded}, {k_unbounded, k_unbounded, k_unbounded}};
}

LocalVertices make_local_vertices(const ShapeDef& shape)
{
    LocalVertices out;
    out.points = tessellate(shape, k_bound_resolution).positions;
    const Aabb box = bounds_of(out.points);
    double extent = 0.0;
    for (int i = 0; i < 3; ++i)
        extent = std::max(extent, 0.5 * (box.max[i] - box.min[i]));
    out.margin = k_mesh_margin_rel * extent;
    return out;
}

using Key = std::vector<uint64_t>;

Key key_of(const ShapeDef& s)
{
    Key k;
    auto put = [&](double v) { k.push_back(std::bit_cast<uint64_t>(v)); };
    k.push_back(uint64_t(s.type));
    for (double v : {s.radii.x, s.radii.y, s.radii.z, s.epsilon1, s.epsilon2, s.taper.kx, s.taper.ky,
                     s.bend.curvature, s.bend.angle})
        put(v);
    for (const HyperquadricTerm& t : s.terms)
        for (double v : {t.normal.x, t.normal.y, t.normal.z, t.offset, t.exponent})
            put(v);
    return k;
}

struct Cache {
    std::mutex mutex;
    std::map<Key, std::shared_ptr<const LocalVertices>> entries;
    size_t next_victim = 0; ///< Rotating position in key order of the entry to evict when full.
};

Cache& cache()
{
    static Cache c;
    return c;
}

std::shared_ptr<const LocalVertices> cached_vertices(const ShapeDef& shape)
{
    Key key = key_of(shape);
    Cache& c = cache();
    {
        const std::lock_guard lock(c.mutex);
        if (const auto it = c.entries.find(key); it != c.entries.end())
            return it->second;
    }
    // Tessellate outside the lock; two threads racing on one new shape compute the same set.
    auto made = std::make_shared<const LocalVertices>(make_local_vertices(shape));
    const std::lock_guard lock(c.mutex);
    if (const auto it = c.entries.find(key); it != c.entries.end())
        return it->second; // another thread got there first
    if (c.entries.size() >= k_bounds_cache_capacity) {
        // Evict one entry at a rotating position: unrelated to the access order, so a world with more
        // distinct shapes than the capacity still hits most of the time instead of thrashing (as
        // clearing, FIFO or LRU would on the broadphase's cyclic access). O(capacity) walk, only on a
        // miss, which costs a tessellation anyway.
        c.next_victim = (c.next_victim + 1) % c.entries.size();
        c.entries.erase(std::next(c.entries.begin(), std::ptrdiff_t(c.next_victim)));
    }
    return c.entries.emplace(std::move(key), std::move(made)).first->second;
}

Aabb vertices_aabb(const LocalVertices& local, const Vec3& position, const Quat& q)
{
    if (local.points.empty())
        return unbounded();
    const Mat3 r = to_mat3(q);
    Aabb turned = empty_box();
    for (const Vec3& v : local.points)
        grow(turned, r * v);
    const Vec3 pad{local.margin, local.margin, local.margin};
    const Aabb box{position + turned.min - pad, position + turned.max + pad};
    return is_finite(box.min) && is_finite(box.max) ? box : unbounded();
}

Aabb support_aabb(const ShapeDef& shape, const Vec3& position, const Quat& q)
{
    const Mat3 r = to_mat3(q);
    Vec3 half;
    for (int i = 0; i < 3; ++i) {
        // Row i of R is Rᵀe_i, world axis i seen in the shape frame.
        const Vec3 axis_shape = r.row(i);
        half[i] = dot(axis_shape, support_point(shape, axis_shape));
    }
    return {position - half, position + half};
}

bool needs_vertices(const ShapeDef& shape)
{
    return shape.type == ShapeType::Hyperquadric || is_deformed(shape);
}

} // namespace

Aabb world_aabb(const ShapeDef& shape, const Vec3& position, const Quat& orientation)
{
    if (shape.type == ShapeType::Plane)
        return unbounded();
    const Quat q = normalized(orientation);
    if (needs_vertices(shape))
        return vertices_aabb(*cached_vertices(shape), position, q);
    return support_aabb(shape, position, q);
}

Aabb world_aabb_uncached(const ShapeDef& shape, const Vec3& position, const Quat& orientation)
{
    if (shape.type == ShapeType::Plane)
        return unbounded();
    const Quat q = normalized(orientation);
    if (needs_vertices(shape))
        return vertices_aabb(make_local_vertices(shape), position, q);
    return support_aabb(shape, position, q);
}

size_t bounds_cache_size()
{
    Cache& c = cache();
    const std::lock_guard lock(c.mutex);
    return c.entries.size();
}

void clear_bounds_cache()
{
    Cache& c = cache();
    const std::lock_guard lock(c.mutex);
    c.entries.clear();
}

} // namespace supermodal
