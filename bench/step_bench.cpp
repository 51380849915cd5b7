// SPDX-License-Identifier: MIT
// Cost of one rigid step per body (no contact yet): free-flying, spinning ellipsoids.
#include "supermodal/body.h"
#include "supermodal/world.h"

#include <benchmark/benchmark.h>

namespace sm = supermodal;

static void BM_Step_RigidSpinning(benchmark::State& st)
{
    sm::World world;
    for (int64_t i = 0; i < st.range(0); ++i) {
        sm::BodyDef b = sm::default_body_def();
        b.shape.radii = {0.1, 0.2, 0.3};
        b.position = {double(i % 100), double(i / 100), 0.0};
        b.angular_velocity = {0.3, 5.0, 0.1 * double(i % 7)};
        (void)sm::create_body(world, b);
    }
    for (int i = 0; i < 10; ++i) // warm up into a typical state
        world.step();
    const sm::Snapshot start = world.snapshot();
    constexpr int k_steps = 10;
    for (auto _ : st) {
        st.PauseTiming();
        (void)world.restore(start);
        st.ResumeTiming();
        for (int i = 0; i < k_steps; ++i)
            world.step();
    }
    st.SetItemsProcessed(st.iterations() * k_steps * st.range(0)); // body-steps
    st.counters["gyroscopic_fallbacks"] = static_cast<double>(world.warnings().gyroscopic_fallbacks);
}
BENCHMARK(BM_Step_RigidSpinning)->RangeMultiplier(10)->Range(10, 100'000)->Unit(benchmark::kMicrosecond);

// A scene of static bodies only (a gallery, a scene held in the editor): N touching static spheres on a
// line. No pair can collide, so the step skips the broadphase and the narrowphase's boxes.
static void BM_Step_StaticOnly(benchmark::State& st)
{
    sm::World world;
    for (int64_t i = 0; i < st.range(0); ++i) {
        sm::BodyDef b = sm::default_body_def();
        b.motion = sm::MotionType::Static;
        b.shape.radii = {0.3, 0.3, 0.3};
        b.position = {0.5 * double(i), 0.0, 0.0};
        (void)sm::create_body(world, b);
    }
    for (auto _ : st)
        world.step();
    st.SetItemsProcessed(st.iterations() * st.range(0)); // body-steps
}
BENCHMARK(BM_Step_StaticOnly)->RangeMultiplier(10)->Range(10, 10'000)->Unit(benchmark::kMicrosecond);
