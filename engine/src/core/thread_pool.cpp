// SPDX-License-Identifier: MIT
#include "core/thread_pool.h"

#include <algorithm>
#include <ctime>

namespace supermodal
{
namespace
{

double thread_cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

} // namespace

ThreadPool::ThreadPool(int thread_count)
{
    const int workers = std::max(thread_count, 1) - 1;
    m_part_cpu.assign(static_cast<size_t>(workers) + 1, 0.0);
    m_workers.reserve(static_cast<size_t>(workers));
    for (int i = 0; i < workers; ++i)
        m_workers.emplace_back([this, i] { worker_main(static_cast<size_t>(i) + 1); });
}

ThreadPool::~ThreadPool()
{
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
    }
    m_start.notify_all();
    for (std::thread& t : m_workers)
        t.join();
}

size_t ThreadPool::part_count(size_t count, size_t min_chunk) const
{
    const size_t by_size = count / std::max<size_t>(min_chunk, 1);
    return std::clamp<size_t>(by_size, 1, static_cast<size_t>(thread_count()));
}

void ThreadPool::run(size_t count, size_t parts, size_t block, Call call, void* ctx)
{
    {
        std::lock_guard lock(m_mutex);
        m_count = count;
        m_parts = parts;
        m_block = block;
        m_call = call;
        m_ctx = ctx;
        m_pending = parts - 1;
        ++m_generation;
    }
    m_start.notify_all();
    run_part(0);
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [this] { return m_pending == 0; });
    double busiest = 0.0;
    for (size_t p = 0; p < parts; ++p) {
        m_stats.parts_s += m_part_cpu[p];
        busiest = std::max(busiest, m_part_cpu[p]);
    }
    m_stats.busiest_s += busiest;
}

// Runs one part of the current job (its fields are stable until every part is done).
void ThreadPool::run_part(size_t part)
{
    const double start = thread_cpu_seconds();
    if (m_block == 0)
        m_call(m_ctx, part, part_begin(m_count, m_parts, part), part_begin(m_count, m_parts, part + 1));
    else
        for (size_t begin = part * m_block; begin < m_count; begin += m_parts * m_block)
            m_call(m_ctx, part, begin, std::min(begin + m_block, m_count));
    m_part_cpu[part] = thread_cpu_seconds() - start;
}

void ThreadPool::worker_main(size_t worker)
{
    uint64_t seen = 0;
    for (;;) {
        std::unique_lock lock(m_mutex);
        m_start.wait(lock, [&] { return m_stop || m_generation != seen; });
        if (m_stop)
            return;
        seen = m_generation;
        const size_t parts = m_parts;
        lock.unlock();
        // A worker without a part this time (parts < threads) just waits for the next job.
        if (worker < parts) {
            run_part(worker);
            lock.lock();
            if (--m_pending == 0)
                m_done.notify_one();
        }
    }
}

} // namespace supermodal
