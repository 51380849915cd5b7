// SPDX-License-Identifier: MIT
// Broadphase: sort-and-sweep over world AABBs. Pairs come out sorted by (min index, max index), so the
// narrowphase sees them in the same order whatever the sort's history (STYLE.md 2.9).
#pragma once

#include "supermodal/entity.h"
#include "supermodal/geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace supermodal
{

/// One body's box for the broadphase.
struct BroadphaseProxy {
    Entity entity{};
    Aabb box{};             ///< World frame [m], already grown by any contact margin.
    bool is_static = false; ///< Static and kinematic bodies never pair with each other.
};

/// A candidate pair; a.index < b.index.
struct BodyPair {
    Entity a{};
    Entity b{};

    [[nodiscard]] uint64_t key() const { return (uint64_t{a.index} << 32) | b.index; }
    friend constexpr bool operator==(const BodyPair&, const BodyPair&) = default;
};

/// Scratch kept between calls so a warmed-up broadphase does not allocate.
struct BroadphaseScratch {
    std::vector<uint32_t> order;
};

/// All pairs whose boxes overlap (touching counts), except static–static, sorted by key().
void find_overlapping_pairs(std::span<const BroadphaseProxy> proxies, BroadphaseScratch& io_scratch,
                            std::vector<BodyPair>& out_pairs);

/// True if the two boxes overlap or touch.
[[nodiscard]] bool overlaps(const Aabb& a, const Aabb& b);

} // namespace supermodal
