// SPDX-License-Identifier: MIT
// The step's parallel loops: a static partition of [0, count) handed to the host's TaskSystem as parts.
// Part p of P gets the contiguous range [p·n/P, (p+1)·n/P), or with a block size the blocks p, p + P,
// p + 2P, ... (which evens out costs that cluster along the range), or with a PartBalance ranges that
// the loop's measured times have evened out. Callers write per-item or per-part slots that are reduced
// serially afterwards, so results do not depend on threads, scheduling or where the parts split
// (determinism rule 4).
#pragma once

#include "supermodal/tasks.h"

#include <algorithm>
#include <chrono>
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

/// Where one loop's contiguous parts split, learnt from how long each part took the last time the loop
/// ran: the next split gives every part the same share of the time measured, taken as spread evenly
/// over each part's old range, and moves a quarter of the way there (a thread that the machine paused
/// once should not swing the split). For loops whose items cost unlike amounts in runs along the range
/// (a floor's cheap pairs first in key order) and whose results do not depend on the split.
class PartBalance
{
  public:
    /// Starts of `parts` ranges over [0, count), then count; uniform until a split of as many parts
    /// has been measured.
    [[nodiscard]] const std::vector<size_t>& split(size_t count, size_t parts);
    /// Called by part `part` of the running loop with its time [s].
    void note(size_t part, double seconds) { m_seconds[part].value = seconds; }
    /// Moves the split toward equal times after a run of the split() parts.
    void learn();
    /// The starts split() last gave, if that split was of `count` items into `parts`; else null.
    [[nodiscard]] const size_t* last_split(size_t count, size_t parts) const
    {
        return m_starts.size() == parts + 1 && m_starts.back() == count ? m_starts.data() : nullptr;
    }

  private:
    struct alignas(k_thread_stride) Slot {
        double value = 0.0;
    };
    std::vector<double> m_bounds; ///< parts + 1 fractions of the count where parts start [-].
    std::vector<Slot> m_seconds;  ///< Per part, its last time [s].
    std::vector<size_t> m_starts; ///< The last split's starts.
    std::vector<double> m_target; ///< learn()'s scratch: the bounds of equal times [-].
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
        if (!on_this_thread(count, parts, fn))
            run(count, parts, block, nullptr, fn);
    }

    /// Calls fn(part, begin, end) once per part over contiguous ranges that `balance` chose and then
    /// learns from (the same as the plain loop when there is one part).
    template <class Fn> void for_parts(size_t count, size_t min_chunk, PartBalance& balance, Fn&& fn) const
    {
        const size_t parts = part_count(count, min_chunk);
        if (on_this_thread(count, parts, fn))
            return;
        const std::vector<size_t>& starts = balance.split(count, parts);
        auto timed = [&](size_t part, size_t begin, size_t end) {
            const auto start = std::chrono::steady_clock::now();
            fn(part, begin, end);
            balance.note(part,
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        };
        run(count, parts, 0, starts.data(), timed);
        balance.learn();
    }

    /// An ordered gather in two passes over one partition of [0, count) (contiguous ranges): tally(begin,
    /// end) gives each part's T; the parts' running sums in part order give each its start; size(total)
    /// makes room for the sum of all; then fill(start, begin, end) writes each part's share from its
    /// start. T is a value type with += (a count, or the counts of several lists); io_starts is scratch.
    /// With `follow`, the parts are the ranges its loop last ran over the same count (so each thread
    /// gathers what it wrote), else the even split.
    template <class T, class Tally, class Size, class Fill>
    void gather(size_t count, size_t min_chunk, std::vector<T>& io_starts, Tally&& tally, Size&& size,
                Fill&& fill, const PartBalance* follow = nullptr) const
    {
        const size_t parts = part_count(count, min_chunk);
        const size_t* starts = follow != nullptr ? follow->last_split(count, parts) : nullptr;
        auto each_part = [&](auto&& fn) {
            if (!on_this_thread(count, parts, fn))
                run(count, parts, 0, starts, fn);
        };
        io_starts.assign(parts + 1, T{});
        each_part([&](size_t part, size_t begin, size_t end) { io_starts[part + 1] = tally(begin, end); });
        for (size_t p = 0; p < parts; ++p)
            io_starts[p + 1] += io_starts[p];
        size(static_cast<const T&>(io_starts[parts]));
        each_part([&](size_t part, size_t begin, size_t end) {
            fill(static_cast<const T&>(io_starts[part]), begin, end);
        });
    }

  private:
    // With one part or no task system: fn(0, 0, count) on the calling thread (nothing for no items) and
    // true; else false.
    template <class Fn> bool on_this_thread(size_t count, size_t parts, Fn& fn) const
    {
        if (parts > 1 && m_tasks != nullptr)
            return false;
        if (count > 0)
            fn(size_t{0}, size_t{0}, count);
        return true;
    }

    // fn(part, begin, end) on `parts` > 1 parts of [0, count) through the task system: the even split,
    // its blocks, or the ranges at `starts` (parts + 1 of them).
    template <class Fn> void run(size_t count, size_t parts, size_t block, const size_t* starts, Fn& fn) const
    {
        using F = std::remove_reference_t<Fn>;
        Job<F> job{&fn, count, parts, block, starts};
        m_tasks->run(static_cast<int>(parts), &Job<F>::run_part, &job);
    }

    template <class F> struct Job {
        F* fn;
        size_t count, parts, block;
        const size_t* starts = nullptr; ///< parts + 1 starts, or null for the even split.

        static void run_part(void* context, int part_index)
        {
            const auto& job = *static_cast<const Job*>(context);
            const auto part = static_cast<size_t>(part_index);
            if (job.starts != nullptr) {
                (*job.fn)(part, job.starts[part], job.starts[part + 1]);
                return;
            }
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
