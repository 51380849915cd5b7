// SPDX-License-Identifier: MIT
#include "core/thread_pool.h"

#include <algorithm>

namespace supermodal
{

std::shared_ptr<TaskSystem> make_thread_pool(int thread_count)
{
    return std::make_shared<ThreadPool>(std::clamp(thread_count, 1, 64));
}

ThreadPool::ThreadPool(int thread_count)
{
    const int workers = std::max(thread_count, 1) - 1;
    m_workers.reserve(static_cast<size_t>(workers));
    for (int i = 0; i < workers; ++i)
        m_workers.emplace_back([this, i] { worker_main(i + 1); });
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

void ThreadPool::run(int part_count, TaskFn task, void* context)
{
    if (part_count <= 0)
        return;
    const int busy_workers = std::min(part_count, concurrency()) - 1;
    if (busy_workers == 0) {
        for (int p = 0; p < part_count; ++p)
            task(context, p);
        return;
    }
    {
        std::lock_guard lock(m_mutex);
        m_parts = part_count;
        m_task = task;
        m_context = context;
        m_pending = busy_workers;
        ++m_generation;
    }
    m_start.notify_all();
    run_parts_of(0);
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [this] { return m_pending == 0; });
}

// The parts of the current run that belong to `thread` (its fields are stable until every part is done).
void ThreadPool::run_parts_of(int thread)
{
    for (int p = thread; p < m_parts; p += concurrency())
        m_task(m_context, p);
}

void ThreadPool::worker_main(int thread)
{
    uint64_t seen = 0;
    for (;;) {
        std::unique_lock lock(m_mutex);
        m_start.wait(lock, [&] { return m_stop || m_generation != seen; });
        if (m_stop)
            return;
        seen = m_generation;
        const int parts = m_parts;
        lock.unlock();
        // A worker without a part this time (parts < threads) just waits for the next run.
        if (thread < parts) {
            run_parts_of(thread);
            lock.lock();
            if (--m_pending == 0)
                m_done.notify_one();
        }
    }
}

} // namespace supermodal
