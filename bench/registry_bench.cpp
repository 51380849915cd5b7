// SPDX-License-Identifier: MIT
// Entity registry: create and iterate 10^4..10^6 entities with two components.
#include "core/registry.h"

#include <benchmark/benchmark.h>

namespace sm = supermodal;

namespace
{
struct Position {
    double x = 0, y = 0, z = 0;
};
struct Velocity {
    double x = 1, y = 2, z = 3;
};
using Reg = sm::BasicRegistry<Position, Velocity>;

void fill(Reg& reg, int64_t n)
{
    for (int64_t i = 0; i < n; ++i) {
        const sm::Entity e = reg.create();
        reg.emplace(e, Position{});
        reg.emplace(e, Velocity{});
    }
}
} // namespace

static void BM_Registry_Create(benchmark::State& st)
{
    for (auto _ : st) {
        Reg reg;
        fill(reg, st.range(0));
        benchmark::DoNotOptimize(reg.pool().alive_count());
    }
    st.SetItemsProcessed(st.iterations() * st.range(0));
}
BENCHMARK(BM_Registry_Create)->RangeMultiplier(10)->Range(10'000, 1'000'000)->Unit(benchmark::kMillisecond);

static void BM_Registry_IterateTwoComponents(benchmark::State& st)
{
    Reg reg;
    fill(reg, st.range(0));
    for (auto _ : st) {
        reg.each<Position, Velocity>([](sm::Entity, Position& p, const Velocity& v) {
            p.x += 0.001 * v.x;
            p.y += 0.001 * v.y;
            p.z += 0.001 * v.z;
        });
        benchmark::ClobberMemory();
    }
    st.SetItemsProcessed(st.iterations() * st.range(0));
}
BENCHMARK(BM_Registry_IterateTwoComponents)
    ->RangeMultiplier(10)
    ->Range(10'000, 1'000'000)
    ->Unit(benchmark::kMillisecond);

static void BM_Registry_DestroyHalfAndReuse(benchmark::State& st)
{
    for (auto _ : st) {
        Reg reg;
        std::vector<sm::Entity> es;
        es.reserve(static_cast<size_t>(st.range(0)));
        for (int64_t i = 0; i < st.range(0); ++i) {
            es.push_back(reg.create());
            reg.emplace(es.back(), Position{});
        }
        for (size_t i = 0; i < es.size(); i += 2)
            reg.destroy(es[i]);
        for (size_t i = 0; i < es.size(); i += 2)
            reg.emplace(reg.create(), Position{});
        benchmark::DoNotOptimize(reg.pool().alive_count());
    }
    st.SetItemsProcessed(st.iterations() * st.range(0));
}
BENCHMARK(BM_Registry_DestroyHalfAndReuse)->Arg(1'000'000)->Unit(benchmark::kMillisecond);
