// SPDX-License-Identifier: MIT
// A stable least-significant-byte radix sort on 64-bit keys, for the broadphase's per-step lists (its
// boxes' cells and its pairs): a few passes over the items instead of n·log n comparisons, and a byte
// that every key shares costs nothing (keys of entity indices under 65,536 take two or three passes).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace supermodal
{

/// Sorts `items` ascending by key(item), stably; `scratch` holds the passes (reused, so a warm call
/// allocates nothing). Sorting twice, first by a minor key then by a major one, sorts by both.
template <class T, class Key> void radix_sort(std::vector<T>& items, std::vector<T>& scratch, Key&& key)
{
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t any = 0, all = ~uint64_t{0};
    for (const T& t : items) {
        any |= key(t);
        all &= key(t);
    }
    const uint64_t varies = any ^ all;
    scratch.resize(items.size());
    for (int shift = 0; shift < 64; shift += 8) {
        if (((varies >> shift) & 0xffu) == 0)
            continue;
        std::array<size_t, 257> start{};
        for (const T& t : items)
            ++start[((key(t) >> shift) & 0xffu) + 1];
        for (size_t b = 0; b < 256; ++b)
            start[b + 1] += start[b];
        for (const T& t : items)
            scratch[start[(key(t) >> shift) & 0xffu]++] = t;
        items.swap(scratch);
    }
}

} // namespace supermodal
