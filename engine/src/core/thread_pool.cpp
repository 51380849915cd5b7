// SPDX-License-Identifier: MIT
#include "core/thread_pool.h"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
#include <immintrin.h>
#define SM_CPU_RELAX() _mm_pause()
#else
#define SM_CPU_RELAX() ((void)0)
#endif

namespace supermodal
{
namespace
{

// How long a thread spins before it sleeps [s]: longer than the gaps between a step's runs (the
// stepping thread's serial work between them is mostly under 0.2 ms), short enough that an idle pool
// goes to sleep at once on a human scale.
constexpr std::chrono::microseconds k_spin_time{200};

// Spins until done() or until the spin time is over; true when done() held.
template <class Done> bool spin_until(Done&& done)
{
    const auto until = std::chrono::steady_clock::now() + k_spin_time;
    for (;;) {
        for (int i = 0; i < 64; ++i) {
            if (done())
                return true;
            SM_CPU_RELAX();
        }
        if (std::chrono::steady_clock::now() >= until)
            return done();
    }
}

} // namespace

std::shared_ptr<TaskSystem> make_thread_pool(int thread_count)
{
    return std::make_shared<ThreadPool>(std::clamp(thread_count, 1, 64));
}

ThreadPool::ThreadPool(int thread_count)
{
    const int workers = std::max(thread_count, 1) - 1;
    const unsigned cores = std::thread::hardware_concurrency();
    m_spin = cores != 0 && static_cast<unsigned>(workers + 1) <= cores;
    m_workers.reserve(static_cast<size_t>(workers));
    for (int i = 0; i < workers; ++i)
        m_workers.emplace_back([this, i] { worker_main(i + 1); });
}

ThreadPool::~ThreadPool()
{
    {
        std::lock_guard lock(m_mutex);
        m_stop.store(true);
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
    m_parts = part_count;
    m_task = task;
    m_context = context;
    m_pending.store(busy_workers);
    // Sequentially consistent with the workers' "asleep, then check": either a worker sees the new
    // run before it sleeps, or this sees it asleep and wakes it under the mutex.
    const uint64_t number = (m_run.load(std::memory_order_relaxed) >> 8) + 1;
    m_run.store(number << 8 | static_cast<uint64_t>(busy_workers));
    if (m_sleeping.load() > 0) {
        {
            std::lock_guard lock(m_mutex);
        }
        m_start.notify_all();
    }
    run_parts_of(0);
    wait_until_done();
}

void ThreadPool::wait_until_done()
{
    if (m_spin && spin_until([this] { return m_pending.load(std::memory_order_acquire) == 0; }))
        return;
    std::unique_lock lock(m_mutex);
    m_caller_asleep.store(true);
    m_done.wait(lock, [this] { return m_pending.load() == 0; });
    m_caller_asleep.store(false);
}

// The parts of the current run that belong to `thread` (its fields are stable until every part is done).
void ThreadPool::run_parts_of(int thread)
{
    for (int p = thread; p < m_parts; p += concurrency())
        m_task(m_context, p);
}

uint64_t ThreadPool::wait_for_run(uint64_t seen)
{
    auto started = [&] { return m_stop.load() || m_run.load(std::memory_order_acquire) != seen; };
    if (m_spin && spin_until(started))
        return m_run.load();
    std::unique_lock lock(m_mutex);
    m_sleeping.fetch_add(1);
    m_start.wait(lock, started);
    m_sleeping.fetch_sub(1);
    return m_run.load();
}

void ThreadPool::worker_main(int thread)
{
    uint64_t seen = 0;
    for (;;) {
        seen = wait_for_run(seen);
        if (m_stop.load())
            return;
        // A worker without a part this time (parts < threads) just waits for the next run.
        if (static_cast<uint64_t>(thread) > (seen & 0xff))
            continue;
        run_parts_of(thread);
        // The last worker out wakes the caller if it went to sleep; the caller checks m_pending under
        // the mutex after it says it sleeps, so taking the mutex here closes the gap.
        if (m_pending.fetch_sub(1) == 1 && m_caller_asleep.load()) {
            {
                std::lock_guard lock(m_mutex);
            }
            m_done.notify_one();
        }
    }
}

} // namespace supermodal
