// SPDX-License-Identifier: MIT
// The built-in TaskSystem: a small persistent pool. Part p of a run goes to thread p mod thread_count
// (thread 0 is the caller), so a run of at most thread_count parts uses each thread once.
#pragma once

#include "supermodal/tasks.h"

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

    std::vector<std::thread> m_workers;
    std::mutex m_mutex;
    std::condition_variable m_start, m_done;
    // The current run, read by workers after they see a new generation.
    uint64_t m_generation = 0;
    int m_parts = 0, m_pending = 0;
    TaskFn m_task = nullptr;
    void* m_context = nullptr;
    bool m_stop = false;
};

} // namespace supermodal
