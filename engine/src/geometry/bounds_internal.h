// SPDX-License-Identifier: MIT
// Internals of world_aabb (bounds.cpp) that tests and benchmarks reach: the uncached path and the
// cache of local vertex sets for shapes without a closed-form support map.
#pragma once

#include "supermodal/geometry.h"

#include <cstddef>

namespace supermodal
{

/// world_aabb recomputing the local vertex set instead of looking it up; same result, bit for bit.
[[nodiscard]] Aabb world_aabb_uncached(const ShapeDef& shape, const Vec3& position, const Quat& orientation);

/// Number of shapes whose vertex sets are cached now.
[[nodiscard]] size_t bounds_cache_size();
/// Empties the cache (vertex sets already handed out stay valid).
void clear_bounds_cache();

/// The cache holds at most this many shapes (~70 KB each, ~18 MB in all); adding one more evicts one.
inline constexpr size_t k_bounds_cache_capacity = 256;

} // namespace supermodal
