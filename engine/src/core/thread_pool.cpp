// SPDX-License-Identifier: MIT
#include "core/thread_pool.h"

#include <algorithm>

namespace supermodal
{

ThreadPool::ThreadPool(int thread_count)
{
    const int workers = std::max(thread_count, 1) - 1;
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

void ThreadPool::run(size_t count, size_t parts, Call call, void* ctx)
{
    {
        std::lock_guard lock(m_mutex);
        m_count = count;
        m_parts = parts;
        m_call = call;
        m_ctx = ctx;
        m_pending = parts - 1;
        ++m_generation;
    }
    m_start.notify_all();
    call(ctx, 0, 0, part_begin(count, parts, 1));
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [this] { return m_pending == 0; });
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
        const size_t count = m_count, parts = m_parts;
        const Call call = m_call;
        void* const ctx = m_ctx;
        lock.unlock();
        // A worker without a part this time (parts < threads) just waits for the next job.
        if (worker < parts) {
            call(ctx, worker, part_begin(count, parts, worker), part_begin(count, parts, worker + 1));
            lock.lock();
            if (--m_pending == 0)
                m_done.notify_one();
        }
    }
}

} // namespace supermodal
