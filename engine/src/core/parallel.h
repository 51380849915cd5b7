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

namespace supermodal
{

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
