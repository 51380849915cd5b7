// SPDX-License-Identifier: MIT
// The built-in TaskSystem: a small persistent pool. Part p of a run goes to thread p mod thread_count
// (thread 0 is the caller), so a run of at most thread_count parts uses each thread once.
//
// A step hands the pool a hundred or more short runs, a few hundred microseconds apart, so waking a
// sleeping thread (a futex round trip through the kernel, tens of microseconds on a virtual machine)
// would cost a large share of each run. Threads therefore spin a short while for the next run, or for
// the run's end, before they sleep; they only spin when the pool has no more threads than the machine
// has cores, so an oversubscribed pool never steals time from the thread it waits for.
#pragma once

#include "supermodal/tasks.h"

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace supermodal
{

class ThreadPool final : public TaskSystem
{
  public:
    /// A pool running on thread_count threads [-], ≥ 1: the caller plus thread_count − 1 workers.
    explicit ThreadPool(int thread_count);
    ~ThreadPool() override;
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    [[nodiscard]] int concurrency() const override { return static_cast<int>(m_workers.size()) + 1; }
    void run(int part_count, TaskFn task, void* context) override;

  private:
    void worker_main(int thread);
    void run_parts_of(int thread);
    /// Waits until a run other than `seen` starts or the pool stops; returns the run's word.
    uint64_t wait_for_run(uint64_t seen);
    void wait_until_done();

    std::vector<std::thread> m_workers;
    std::mutex m_mutex;
    std::condition_variable m_start, m_done;
    // The current run: written before m_run changes, read only by the workers it makes busy (the caller
    // waits for each of them before the next run).
    int m_parts = 0;
    TaskFn m_task = nullptr;
    void* m_context = nullptr;
    /// The run's word: its number above the low byte, the highest busy worker in the low byte (a
    /// worker not busy in it reads nothing else, so it never races the next run's set-up).
    std::atomic<uint64_t> m_run{0};
    std::atomic<int> m_pending{0};  ///< Workers still running parts of the current run.
    std::atomic<int> m_sleeping{0}; ///< Workers asleep on m_start.
    std::atomic<bool> m_caller_asleep{false};
    std::atomic<bool> m_stop{false};
    bool m_spin = false; ///< Whether threads spin before they sleep (not oversubscribed).
};

} // namespace supermodal
