// SPDX-License-Identifier: MIT
// A small persistent pool for the step's per-pair loops. The partition is static: part w of T gets the
// contiguous range [w·n/T, (w+1)·n/T), whatever the timing, and callers write per-item slots that are
// reduced serially afterwards, so results do not depend on the thread count (STYLE.md 2.9).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace supermodal
{

class ThreadPool
{
  public:
    /// A pool running loops on thread_count threads [-], ≥ 1: the caller plus thread_count − 1 workers.
    explicit ThreadPool(int thread_count);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    [[nodiscard]] int thread_count() const { return static_cast<int>(m_workers.size()) + 1; }

    /// Thread CPU time of the parallel loops since the pool was made [s]: summed over all parts, and
    /// summed over loops of the busiest part. (Sum − busiest) is what the other threads took off the
    /// caller; on a machine with free cores the loops' wall time is about the busiest-part sum.
    struct CpuStats {
        double parts_s = 0.0;
        double busiest_s = 0.0;
    };
    [[nodiscard]] CpuStats cpu_stats() const { return m_stats; }

    /// Calls fn(part, begin, end) over a static partition of [0, count) into at most thread_count
    /// parts of at least min_chunk items; part 0 runs on the caller. With block = 0 each part is one
    /// contiguous range (part_begin()); with block > 0 the blocks [k·block, (k+1)·block) are dealt
    /// round-robin (block k to part k mod parts), one call per block, which evens out costs that
    /// cluster along the range. Returns when all parts are done. Not re-entrant.
    template <class Fn> void parallel_for(size_t count, size_t min_chunk, Fn&& fn, size_t block = 0)
    {
        const size_t parts = part_count(count, min_chunk);
        if (parts <= 1) {
            if (count > 0)
                fn(size_t{0}, size_t{0}, count);
            return;
        }
        using F = std::remove_reference_t<Fn>;
        run(
            count, parts, block,
            [](void* ctx, size_t part, size_t begin, size_t end) {
                (*static_cast<F*>(ctx))(part, begin, end);
            },
            const_cast<void*>(static_cast<const void*>(&fn)));
    }

    /// Start of part `part` when [0, count) is split into `parts` ranges.
    [[nodiscard]] static size_t part_begin(size_t count, size_t parts, size_t part)
    {
        return count * part / parts;
    }

  private:
    using Call = void (*)(void* ctx, size_t part, size_t begin, size_t end);

    [[nodiscard]] size_t part_count(size_t count, size_t min_chunk) const;
    void run(size_t count, size_t parts, size_t block, Call call, void* ctx);
    void worker_main(size_t worker);
    void run_part(size_t part);

    std::vector<std::thread> m_workers;
    std::mutex m_mutex;
    std::condition_variable m_start, m_done;
    // The current job, read by workers after they see a new generation.
    uint64_t m_generation = 0;
    size_t m_count = 0, m_parts = 0, m_block = 0, m_pending = 0;
    Call m_call = nullptr;
    void* m_ctx = nullptr;
    bool m_stop = false;
    std::vector<double> m_part_cpu; // Thread CPU time of each part of the current job [s].
    CpuStats m_stats;
};

} // namespace supermodal
