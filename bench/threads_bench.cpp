// SPDX-License-Identifier: MIT
// Threads: one scene stepped with 1 and 2 threads of the built-in pool. Per run, the scene is loaded,
// settled for k_settle steps, then k_timed steps are timed: wall time per step (what a host sees on
// free cores), CPU time of the whole process per step, and each stage's ms per step (ms_broadphase...,
// World::profile()); the speed-up against 1 thread comes from two rows. Written against the public API
// only, so the same file measures older builds.
// Usage: threads_bench [benchmark flags] SCENE.json [SCENE.json ...]
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <array>
#include <benchmark/benchmark.h>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

namespace sm = supermodal;

namespace
{

constexpr int k_settle = 240; // 1 s at 1/240 s: bodies are falling into and onto each other
constexpr int k_timed = 120;
constexpr int k_block = 10; // steps per timed block of BM_Paired: ~0.2-0.5 s, well under the drift

double process_cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The scene at `path`, or the benchmark skipped with the loader's message.
sm::Result<sm::Scene> load_or_skip(benchmark::State& st, const std::string& path)
{
    sm::Result<sm::Scene> scene = sm::load_scene(path);
    if (!scene)
        st.SkipWithError(scene.error().message().c_str());
    return scene;
}

void BM_Threads(benchmark::State& st, const std::string& path)
{
    const int threads = static_cast<int>(st.range(0));
    sm::Result<sm::Scene> scene = load_or_skip(st, path);
    if (!scene)
        return;
    scene->world.thread_count = threads;
    double ms = 0.0, cpu_ms = 0.0;
    uint64_t hash = 0;
    std::array<double, static_cast<size_t>(sm::Stage::Count)> stages{}; // ms per timed step, by stage
    for (auto _ : st) {
        sm::Result<sm::World> world = sm::build_world(*scene);
        if (!world) {
            st.SkipWithError(world.error().message().c_str());
            return;
        }
        for (int i = 0; i < k_settle; ++i)
            world->step();
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = process_cpu_seconds();
        stages.fill(0.0);
        for (int i = 0; i < k_timed; ++i) {
            world->step();
            for (size_t s = 0; s < stages.size(); ++s)
                stages[s] += world->profile().stage_ms[s] / k_timed;
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        st.SetIterationTime(seconds);
        ms = 1e3 * seconds / k_timed;
        cpu_ms = 1e3 * (process_cpu_seconds() - cpu_start) / k_timed;
        hash = world->state_hash();
    }
    st.counters["ms_per_step"] = ms;
    st.counters["cpu_ms_per_step"] = cpu_ms;
    st.counters["bodies"] = static_cast<double>(scene->bodies.size());
    // Where the step goes, for comparing thread counts stage by stage (World::profile()).
    for (size_t s = 0; s < stages.size(); ++s)
        st.counters["ms_" + std::string(sm::stage_name(static_cast<sm::Stage>(s)))] = stages[s];
    // The low 32 bits of the hash: equal across thread counts (a determinism check in the table).
    st.counters["hash_low"] = static_cast<double>(hash & 0xffffffffu);
}

// Steps `world` n times; returns the wall time [s].
double timed_steps(sm::World& world, int n)
{
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i)
        world.step();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Two 1-thread worlds stepped side by side on two threads of their own, each k_block steps, against
// each alone: what the machine gives two independent runs at this moment (2 = two free cores).
double copies_speedup(sm::World& a, sm::World& b)
{
    const double alone = timed_steps(a, k_block) + timed_steps(b, k_block);
    const auto start = std::chrono::steady_clock::now();
    std::thread other([&] { timed_steps(b, k_block); });
    timed_steps(a, k_block);
    other.join();
    return alone / std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_Paired(benchmark::State& st, const std::string& path)
{
    const int threads = static_cast<int>(st.range(0));
    sm::Result<sm::Scene> scene = load_or_skip(st, path);
    if (!scene)
        return;
    double one_ms = 0.0, many_ms = 0.0, worst = 0.0, best = 0.0, copies_mean = 0.0;
    bool same = false;
    for (auto _ : st) {
        // one and many step in lockstep (the timed pair); the two copies measure the machine.
        std::vector<sm::Result<sm::World>> worlds;
        for (int count : {1, threads, 1, 1}) {
            scene->world.thread_count = count;
            worlds.push_back(sm::build_world(*scene));
            if (!worlds.back()) {
                st.SkipWithError(worlds.back().error().message().c_str());
                return;
            }
        }
        sm::World &one = *worlds[0], &many = *worlds[1];
        for (int i = 0; i < k_settle; ++i)
            for (sm::Result<sm::World>& w : worlds)
                (*w).step();
        double t_one = 0.0, t_many = 0.0, copies = 0.0;
        worst = 1e300;
        best = 0.0;
        const int rounds = k_timed / (2 * k_block);
        for (int r = 0; r < rounds; ++r) {
            // A B B A: one thread, two blocks of the threaded world, one thread; a linear drift cancels.
            const double a = timed_steps(one, k_block);
            const double b = timed_steps(many, 2 * k_block);
            const double c = timed_steps(one, k_block);
            t_one += a + c;
            t_many += b;
            worst = std::min(worst, (a + c) / b);
            best = std::max(best, (a + c) / b);
            copies += copies_speedup(*worlds[2], *worlds[3]);
        }
        st.SetIterationTime(t_one + t_many);
        one_ms = 1e3 * t_one / k_timed;
        many_ms = 1e3 * t_many / k_timed;
        copies_mean = copies / rounds;
        same = one.state_hash() == many.state_hash();
    }
    st.counters["ms_one_thread"] = one_ms;
    st.counters["ms_per_step"] = many_ms;
    st.counters["speedup"] = one_ms / many_ms;
    st.counters["speedup_worst_block"] = worst;
    st.counters["speedup_best_block"] = best;
    st.counters["copies_speedup"] = copies_mean; // a gauge of the machine, not a bound
    st.counters["bodies"] = static_cast<double>(scene->bodies.size());
    st.counters["same_hash"] = same ? 1.0 : 0.0; // 1 thread and `threads` step the same bits
}

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (argc < 2) {
        std::fprintf(stderr, "usage: threads_bench [benchmark flags] SCENE.json [SCENE.json ...]\n");
        return 2;
    }
    for (int i = 1; i < argc; ++i) {
        const std::string path = argv[i];
        const std::string name = "BM_Threads/" + path.substr(path.find_last_of('/') + 1);
        benchmark::RegisterBenchmark(name.c_str(), BM_Threads, path)
            ->Arg(1)
            ->Arg(2)
            ->Iterations(1)
            ->Repetitions(3)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_Paired/" + name.substr(name.find('/') + 1)).c_str(), BM_Paired,
                                     path)
            ->Arg(2)
            ->Iterations(1)
            ->Repetitions(3)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
