// SPDX-License-Identifier: MIT
// The step's parallel loops: a static partition of [0, count) handed to the host's TaskSystem as parts.
// Part p of P gets the contiguous range [p·n/P, (p+1)·n/P), or with a block size the blocks p, p + P,
// p + 2P, ... (which evens out costs that cluster along the range). The partition depends only on the
// count and the task system's concurrency, and callers write per-item or per-part slots that are reduced
// serially afterwards, so results do not depend on threads or scheduling (determinism rule 4).
#pragma once

#include "supermodal/tasks.h"

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace supermodal
{

/// Bytes kept between data that different threads write [B]: a cache line on x86 and most ARM cores is
/// 64 B, on Apple's cores 128 B, and x86's adjacent-line prefetcher fetches lines in pairs.
inline constexpr size_t k_thread_stride = 128;

/// A list that one part of a parallel loop fills, on cache lines of its own. A std::vector's end pointer
/// moves with every push_back: two parts' lists side by side in one array would have their threads
/// write the same cache line for every item, each write taking the line from the other core.
template <class T> struct alignas(k_thread_stride) PartList : std::vector<T> {
};

class Parallel
{
  public:
    /// Loops through `tasks`, or on the calling thread alone when it is null.
    explicit Parallel(TaskSystem* tasks = nullptr) : m_tasks(tasks) {}

    /// The most parts a loop is split into [-]: scratch arrays indexed by part need this many slots.
    [[nodiscard]] size_t part_capacity() const
    {
        return m_tasks != nullptr ? static_cast<size_t>(std::max(m_tasks->concurrency(), 1)) : 1;
    }

    /// Parts for `count` items of at least `min_chunk` each [-], in [1, part_capacity()].
    [[nodiscard]] size_t part_count(size_t count, size_t min_chunk) const
    {
        return std::clamp<size_t>(count / std::max<size_t>(min_chunk, 1), 1, part_capacity());
    }

    /// Start of part `part` when [0, count) is split into `parts` ranges.
    [[nodiscard]] static size_t part_begin(size_t count, size_t parts, size_t part)
    {
        return count * part / parts;
    }

    /// Calls fn(part, begin, end) over the partition of [0, count); with block > 0, once per block.
    /// Returns when every part is done.
    template <class Fn> void for_parts(size_t count, size_t min_chunk, Fn&& fn, size_t block = 0) const
    {
        const size_t parts = part_count(count, min_chunk);
        if (parts <= 1 || m_tasks == nullptr) {
            if (count > 0)
                fn(size_t{0}, size_t{0}, count);
            return;
        }
        using F = std::remove_reference_t<Fn>;
        Job<F> job{&fn, count, parts, block};
        m_tasks->run(static_cast<int>(parts), &Job<F>::run_part, &job);
    }

    /// An ordered gather in two passes over one partition of [0, count) (contiguous ranges): tally(begin,
    /// end) gives each part's T; the parts' running sums in part order give each its start; size(total)
    /// makes room for the sum of all; then fill(start, begin, end) writes each part's share from its
    /// start. T is a value type with += (a count, or the counts of several lists); io_starts is scratch.
    template <class T, class Tally, class Size, class Fill>
    void gather(size_t count, size_t min_chunk, std::vector<T>& io_starts, Tally&& tally, Size&& size,
                Fill&& fill) const
    {
        const size_t parts = part_count(count, min_chunk);
        io_starts.assign(parts + 1, T{});
        for_parts(count, min_chunk,
                  [&](size_t part, size_t begin, size_t end) { io_starts[part + 1] = tally(begin, end); });
        for (size_t p = 0; p < parts; ++p)
            io_starts[p + 1] += io_starts[p];
        size(static_cast<const T&>(io_starts[parts]));
        for_parts(count, min_chunk, [&](size_t part, size_t begin, size_t end) {
            fill(static_cast<const T&>(io_starts[part]), begin, end);
        });
    }

  private:
    template <class F> struct Job {
        F* fn;
        size_t count, parts, block;

        static void run_part(void* context, int part_index)
        {
            const auto& job = *static_cast<const Job*>(context);
            const auto part = static_cast<size_t>(part_index);
            if (job.block == 0) {
                (*job.fn)(part, part_begin(job.count, job.parts, part),
                          part_begin(job.count, job.parts, part + 1));
                return;
            }
            for (size_t begin = part * job.block; begin < job.count; begin += job.parts * job.block)
                (*job.fn)(part, begin, std::min(begin + job.block, job.count));
        }
    };

    TaskSystem* m_tasks = nullptr;
};

} // namespace supermodal
