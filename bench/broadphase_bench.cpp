// SPDX-License-Identifier: MIT
// Broadphase: N boxes of 0.1 m on a jittered 0.2 m grid (a falling pile's density, about one neighbour
// overlap per box), N = 10^3 … 10^5. "Warm": the boxes moved a little since the last call, as between
// steps (the scratch order is almost sorted); "cold": a fresh scratch. "Resting": a settled pile's
// density, boxes of 0.15 m (a turned 0.1 m cube's box) on a 0.1 m grid, each overlapping its 26
// neighbours' boxes.
#include "contact/broadphase.h"

#include <benchmark/benchmark.h>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sm = supermodal;

namespace
{

struct Lcg {
    uint32_t state = 7;
    double next() // uniform in [-1, 1)
    {
        state = state * 1664525u + 1013904223u;
        return static_cast<double>(state >> 8) / 8388608.0 - 1.0;
    }
};

std::vector<sm::BroadphaseProxy> make_proxies(int n, bool resting)
{
    const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
    const double pitch = resting ? 0.1 : 0.2, half = resting ? 0.075 : 0.05, jitter = resting ? 0.01 : 0.06;
    std::vector<sm::BroadphaseProxy> out(static_cast<size_t>(n));
    Lcg rng;
    for (int i = 0; i < n; ++i) {
        const sm::Vec3 c{pitch * (i % side) + jitter * rng.next(),
                         pitch * ((i / side) % side) + jitter * rng.next(),
                         pitch * (i / (side * side)) + jitter * rng.next()};
        out[static_cast<size_t>(i)].entity = sm::Entity{static_cast<uint32_t>(i + 1), 1};
        out[static_cast<size_t>(i)].box =
            sm::Aabb{{c.x - half, c.y - half, c.z - half}, {c.x + half, c.y + half, c.z + half}};
    }
    return out;
}

void BM_Broadphase(benchmark::State& st, bool warm, bool resting)
{
    std::vector<sm::BroadphaseProxy> proxies = make_proxies(static_cast<int>(st.range(0)), resting);
    sm::BroadphaseScratch scratch;
    std::vector<sm::BodyPair> pairs;
    sm::find_overlapping_pairs(proxies, scratch, pairs);
    Lcg rng;
    for (auto _ : st) {
        st.PauseTiming();
        // Move every box by up to 1 mm, as one step of a 0.24 m/s body at 1/240 s.
        for (sm::BroadphaseProxy& p : proxies) {
            const double d = 1e-3 * rng.next();
            p.box.min.x += d;
            p.box.max.x += d;
        }
        if (!warm)
            scratch = sm::BroadphaseScratch{};
        st.ResumeTiming();
        sm::find_overlapping_pairs(proxies, scratch, pairs);
        benchmark::DoNotOptimize(pairs.data());
    }
    st.counters["pairs"] = static_cast<double>(pairs.size());
    st.counters["seconds_per_body"] =
        benchmark::Counter(static_cast<double>(st.range(0)),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK_CAPTURE(BM_Broadphase, warm, true, false)
    ->RangeMultiplier(10)
    ->Range(1'000, 100'000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Broadphase, resting, true, true)
    ->RangeMultiplier(10)
    ->Range(1'000, 100'000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Broadphase, cold, false, false)
    ->RangeMultiplier(10)
    ->Range(1'000, 100'000)
    ->Unit(benchmark::kMicrosecond);
