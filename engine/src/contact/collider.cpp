// SPDX-License-Identifier: MIT
#include "contact/collider.h"

#include "geometry/aabb.h"

#include <algorithm>
#include <cmath>

namespace supermodal
{
namespace
{

// 6 buckets per axis: a resting contact touches one face layer (~1/6 of the samples, fewer at a corner)
// while the per-bucket box test stays cheaper than the samples it skips.
constexpr int k_buckets_per_axis = 6;

std::shared_ptr<const SampleSet> bucket_samples(std::vector<SurfaceSample> raw, double spacing)
{
    auto set = std::make_shared<SampleSet>();
    set->spacing = spacing;
    Aabb all = empty_box();
    for (const SurfaceSample& s : raw)
        grow(all, s.point);
    const Vec3 size = all.max - all.min;
    auto bucket_of = [&](const Vec3& p) {
        int idx[3];
        for (int i = 0; i < 3; ++i) {
            const double t = size[i] > 0.0 ? (p[i] - all.min[i]) / size[i] : 0.0;
            idx[i] = std::clamp(static_cast<int>(t * k_buckets_per_axis), 0, k_buckets_per_axis - 1);
        }
        return (idx[2] * k_buckets_per_axis + idx[1]) * k_buckets_per_axis + idx[0];
    };
    constexpr int k_count = k_buckets_per_axis * k_buckets_per_axis * k_buckets_per_axis;
    std::vector<uint32_t> count(k_count + 1, 0);
    for (const SurfaceSample& s : raw)
        ++count[bucket_of(s.point) + 1];
    // Keep only non-empty buckets so a query loops over few boxes.
    std::vector<uint32_t> offset(k_count + 1, 0);
    for (int b = 0; b < k_count; ++b)
        offset[b + 1] = offset[b] + count[b + 1];
    set->samples.resize(raw.size());
    std::vector<uint32_t> cursor(offset.begin(), offset.end() - 1);
    for (const SurfaceSample& s : raw) {
        set->samples[cursor[bucket_of(s.point)]++] = s;
        set->total_area += s.area;
    }
    set->start.push_back(0);
    for (int b = 0; b < k_count; ++b) {
        if (offset[b + 1] == offset[b])
            continue;
        Aabb box = empty_box();
        for (uint32_t i = offset[b]; i < offset[b + 1]; ++i)
            grow(box, set->samples[i].point);
        set->bucket_box.push_back(box);
        set->start.push_back(offset[b + 1]);
    }
    return set;
}

} // namespace

double default_sample_spacing(const ShapeDef& shape)
{
    // Half-extents from the shape's own box, so hyperquadrics (which have no radii) are covered too.
    const Aabb box = world_aabb(shape, {}, Quat::identity());
    const Vec3 half = 0.5 * (box.max - box.min);
    return 0.25 * std::min({half.x, half.y, half.z});
}

Collider make_collider(const ShapeDef& shape, const Vec3& com_shape, double spacing, int max_samples)
{
    Collider c;
    c.shape = shape;
    c.com_shape = com_shape;
    if (shape.type == ShapeType::Plane)
        return c;
    c.deformed = is_deformed(shape);
    c.convex = shape.type == ShapeType::Superquadric && !c.deformed && shape.epsilon1 <= 2.0 &&
               shape.epsilon2 <= 2.0;
    const double h = spacing > 0.0 ? spacing : default_sample_spacing(shape);
    std::vector<SurfaceSample> raw = sample_surface(shape, h, max_samples);
    c.local_box = empty_box();
    for (SurfaceSample& s : raw) {
        s.point -= com_shape;
        grow(c.local_box, s.point);
    }
    // The exact box of the shape (support map / tessellation), not the samples' box: axis extremes
    // are rarely samples, and at ε ≥ 2 they can lie several spacings beyond the nearest one.
    const Aabb exact = world_aabb(shape, -com_shape, Quat::identity());
    grow(c.local_box, exact);
    const Vec3 extent = c.local_box.max - c.local_box.min;
    c.thickness = std::min({extent.x, extent.y, extent.z});
    c.samples = bucket_samples(std::move(raw), h);
    return c;
}

} // namespace supermodal
