// SPDX-License-Identifier: MIT
// What contact needs to know about a body's shape, built once per shape and shared by identical bodies:
// surface samples in the body frame, grouped into buckets so a query touches only the samples near an
// overlap (O(samples near the overlap), not O(all samples)).
#pragma once

#include "contact/sample_density.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace supermodal
{

/// Surface samples of one shape, body frame (origin at the centre of mass), bucketed on a coarse grid.
struct SampleSet {
    std::vector<SurfaceSample> samples; ///< Grouped by bucket; bucket b is [start[b], start[b+1]).
    std::vector<uint32_t> start;        ///< Bucket offsets (bucket_count + 1).
    std::vector<Aabb> bucket_box;       ///< Tight box of each bucket's samples [m], body frame.
    double total_area = 0.0;            ///< [m²].
    double spacing = 0.0;               ///< Sample spacing used [m].
};

/// A body's contact model.
struct Collider {
    ShapeDef shape{};                         ///< Shape, shape frame.
    Vec3 com_shape{};                         ///< Centre of mass in the shape frame [m].
    std::shared_ptr<const SampleSet> samples; ///< Null for planes.
    bool convex = false;                      ///< Support map exact: undeformed superquadric, ε ≤ 2.
    bool deformed = false;                    ///< Taper or bend: queries go through the inverse map.
    double thickness = 0.0;                   ///< Smallest extent (2 × smallest radius) [m], for tunnelling.
    Aabb local_box{};                         ///< Box of the shape in the body frame [m].
    /// Sampling gap the spacing was chosen to keep under [m] (auto bodies, contact/sample_density.h);
    /// 0: the spacing came from ContactDef::sample_spacing (or its default).
    double sampling_tolerance = 0.0;
    SampleDensityChoice sampling{}; ///< What that choice measured (sampling_tolerance > 0 only).
};

/// Spacing used when ContactDef::sample_spacing is 0: a quarter of the smallest radius [m].
[[nodiscard]] double default_sample_spacing(const ShapeDef& shape);

/// Builds the collider of a shape with its centre of mass at com_shape.
[[nodiscard]] Collider make_collider(const ShapeDef& shape, const Vec3& com_shape, double spacing,
                                     int max_samples);

/// Calls fn(const SurfaceSample&) for each sample in a bucket whose box passes keep(const Aabb&).
template <class Keep, class Fn> void for_samples_where(const SampleSet& set, Keep&& keep, Fn&& fn)
{
    for (size_t b = 0; b + 1 < set.start.size(); ++b) {
        if (!keep(set.bucket_box[b]))
            continue;
        for (uint32_t i = set.start[b]; i < set.start[b + 1]; ++i)
            fn(set.samples[i]);
    }
}

} // namespace supermodal
