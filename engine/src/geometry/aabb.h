// SPDX-License-Identifier: MIT
// Growing axis-aligned boxes point by point: the samples' buckets, a collider's local box, a mesh's bounds.
#pragma once

#include "supermodal/geometry.h"

#include <algorithm>
#include <limits>
#include <span>

namespace supermodal
{

/// The box that holds nothing: its first grow() makes it that point's.
[[nodiscard]] inline Aabb empty_box()
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

/// Grows the box to hold p [m].
inline void grow(Aabb& box, const Vec3& p)
{
    for (int i = 0; i < 3; ++i) {
        box.min[i] = std::min(box.min[i], p[i]);
        box.max[i] = std::max(box.max[i], p[i]);
    }
}

/// Grows the box to hold `other`.
inline void grow(Aabb& box, const Aabb& other)
{
    grow(box, other.min);
    grow(box, other.max);
}

/// The smallest box holding the points (a zero box at the origin when there are none).
[[nodiscard]] inline Aabb bounds_of(std::span<const Vec3> points)
{
    if (points.empty())
        return {};
    Aabb box = empty_box();
    for (const Vec3& p : points)
        grow(box, p);
    return box;
}

} // namespace supermodal
