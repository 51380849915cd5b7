// SPDX-License-Identifier: MIT
// The host owns the threads: a world runs its parallel loops through a TaskSystem the host may supply
// (its game engine's or tool's job system), or through a small built-in pool.
//
// The world splits each loop into parts itself, by a fixed rule that depends only on the loop's length
// and concurrency(), and every part writes only its own slots; whatever is summed across parts is summed
// afterwards on the stepping thread in a fixed order. So the order in which parts run, and the threads
// they run on, cannot change a result: any task system gives the same bits as one thread.
#pragma once

#include "supermodal/api.h"

#include <memory>

namespace supermodal
{

/// One part of a parallel loop: task(context, part).
using TaskFn = void (*)(void* context, int part);

/// A scheduler the world hands its loops to. Implement it over the host's job system.
class SM_API TaskSystem
{
  public:
    virtual ~TaskSystem() = default;
    /// How many parts may usefully run at once [-], ≥ 1 (fixed for the task system's lifetime): the
    /// world splits a loop into at most this many parts.
    [[nodiscard]] virtual int concurrency() const = 0;
    /// Runs task(context, part) exactly once for every part in [0, part_count), in any order, on any
    /// threads (the calling one included), and returns when all have finished. Called only from the
    /// thread that steps the world, never re-entrantly for one world.
    virtual void run(int part_count, TaskFn task, void* context) = 0;
};

/// The built-in pool: the calling thread plus thread_count − 1 workers [-], thread_count in [1, 64];
/// part p runs on thread p mod thread_count.
[[nodiscard]] SM_API std::shared_ptr<TaskSystem> make_thread_pool(int thread_count);

} // namespace supermodal
