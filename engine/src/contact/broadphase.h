// SPDX-License-Identifier: MIT
// Broadphase: a uniform grid over world AABBs (cell size from the median box), with unbounded or very
// large boxes (planes, a huge static body) tested against all. Expected O(n) for bodies of similar
// size, where the sort-and-sweep it replaces grew as n^(5/3) for bodies filling a volume (measured:
// 0.64 s for 10^5 boxes). Pairs come out sorted by (min index, max index), so the narrowphase sees
// them in the same order whatever the input order (determinism).
#pragma once

#include "core/parallel.h"
#include "supermodal/entity.h"
#include "supermodal/geometry.h"

#include <array>
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
    bool asleep = false; ///< A sleeping dynamic body: pairs only with awake ones and moving kinematic ones.
    bool moving = false; ///< A kinematic body with a velocity: may wake a sleeping one.
};

/// A candidate pair; a.index < b.index.
struct BodyPair {
    Entity a{};
    Entity b{};

    [[nodiscard]] uint64_t key() const { return (uint64_t{a.index} << 32) | b.index; }
    friend constexpr bool operator==(const BodyPair&, const BodyPair&) = default;
};

/// The entity indices a pair key packs (BodyPair::key): a's, then b's.
[[nodiscard]] constexpr std::array<uint32_t, 2> pair_key_indices(uint64_t key)
{
    return {static_cast<uint32_t>(key >> 32), static_cast<uint32_t>(key & 0xffffffffu)};
}

/// Scratch kept between calls so a warmed-up broadphase does not allocate.
struct BroadphaseScratch {
    struct Entry {
        uint64_t key;   ///< Packed cell coordinates.
        uint32_t proxy; ///< Index into the proxies.
    };
    struct Cell {
        uint32_t x, y, z; ///< Cell coordinates, offset as in Entry::key.
    };
    std::vector<Entry> entries;                       ///< One per (box, cell it covers).
    std::vector<Cell> low_cells;                      ///< Per binned box: the cell of its lower corner.
    std::vector<Entry> sorted_entries;                ///< The sort's other buffer.
    std::vector<BodyPair> sorted_pairs;               ///< The pairs' sort's other buffer.
    std::vector<uint32_t> big;                        ///< Boxes tested against all, ascending.
    std::vector<double> extents;                      ///< For the median box size.
    std::vector<PartList<Entry>> part_entries;        ///< Per thread part: its boxes' entries.
    std::vector<PartList<Entry>> part_other_entries;  ///< Per thread part: its sort's other buffer.
    std::vector<PartList<uint32_t>> part_big;         ///< Per thread part: its boxes too big to bin.
    std::vector<PartList<BodyPair>> part_pairs;       ///< Per thread part: its cells' and big boxes' pairs.
    std::vector<PartList<BodyPair>> part_other_pairs; ///< Per thread part: its sort's other buffer.
    PartBalance pairs_balance; ///< Where find_pairs' parts split (a pile's cells are denser low down).
};

/// All pairs whose boxes overlap (touching counts), except static–static, sorted by key(); the boxes
/// and cells split over `par`'s threads (the same pairs on any count).
void find_overlapping_pairs(std::span<const BroadphaseProxy> proxies, BroadphaseScratch& io_scratch,
                            std::vector<BodyPair>& out_pairs, const Parallel& par = Parallel{});

/// True if the two boxes overlap or touch, or come within `margin` [m] of each other.
[[nodiscard]] inline bool overlaps(const Aabb& a, const Aabb& b, double margin = 0.0)
{
    return a.min.x <= b.max.x + margin && b.min.x <= a.max.x + margin && a.min.y <= b.max.y + margin &&
           b.min.y <= a.max.y + margin && a.min.z <= b.max.z + margin && b.min.z <= a.max.z + margin;
}

} // namespace supermodal
