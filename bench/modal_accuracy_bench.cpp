// SPDX-License-Identifier: MIT
// Cost of the accuracy report, the stress check and plastic relief (docs/modal.md "Accuracy report",
// "Stress and plasticity"): the 2x4 board (8×1×1, 312 dofs) and the soft sphere (4³, 1179 dofs).
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <benchmark/benchmark.h>
#include <limits>
#include <utility>
#include <vector>

namespace sm = supermodal;

namespace
{

// Arg: 0 board, 1 sphere.
sm::BodyDef body(int which, int modes, double yield = std::numeric_limits<double>::infinity())
{
    sm::BodyDef def = sm::default_body_def();
    if (which == 0) {
        def.shape.radii = {0.5, 0.019, 0.0445};
        def.shape.epsilon1 = def.shape.epsilon2 = 0.05;
        def.density = 450.0;
        def.young = 11e9;
    } else {
        def.shape.radii = {0.5, 0.5, 0.5};
        def.density = 1000.0;
        def.young = 1e7;
    }
    def.modal.enabled = true;
    def.modal.mode_count = modes;
    def.modal.damping_ratio = 0.05;
    def.modal.yield_stress = yield;
    return def;
}

sm::World loaded_world(int which, int modes, sm::Entity& out_body,
                       double yield = std::numeric_limits<double>::infinity())
{
    sm::WorldDef wd = sm::default_world_def();
    wd.dt = 1e-3;
    wd.gravity = {};
    sm::World world(wd);
    out_body = sm::create_body(world, body(which, modes, yield));
    sm::apply_force(world, out_body, {0, -100, 0}, {0.1, which == 0 ? 0.019 : 0.5, 0});
    world.step();
    return world;
}

// body_modal_accuracy once the lattice is factored. Args: body, modes.
void BM_ModalAccuracy_Query(benchmark::State& st)
{
    sm::Entity b;
    sm::World world = loaded_world(static_cast<int>(st.range(0)), static_cast<int>(st.range(1)), b);
    (void)sm::body_modal_accuracy(world, b); // assemble and factor once
    for (auto _ : st)
        benchmark::DoNotOptimize(sm::body_modal_accuracy(world, b));
}
BENCHMARK(BM_ModalAccuracy_Query)
    ->Args({0, 12})
    ->Args({0, 48})
    ->Args({1, 12})
    ->Args({1, 48})
    ->Unit(benchmark::kMicrosecond);

// The first query of a basis: lattice assembly, M and pinned-K factorisations, plus one query.
void BM_ModalAccuracy_FirstQuery(benchmark::State& st)
{
    sm::Entity b;
    sm::World world = loaded_world(static_cast<int>(st.range(0)), 12, b);
    for (auto _ : st) {
        st.PauseTiming();
        sm::World fresh = loaded_world(static_cast<int>(st.range(0)), 12, b); // new surface: new cache
        st.ResumeTiming();
        benchmark::DoNotOptimize(sm::body_modal_accuracy(fresh, b));
    }
}
BENCHMARK(BM_ModalAccuracy_FirstQuery)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// body_max_stress: 6r multiply-adds per stress point. Args: body, modes.
void BM_ModalStress_Max(benchmark::State& st)
{
    sm::Entity b;
    sm::World world = loaded_world(static_cast<int>(st.range(0)), static_cast<int>(st.range(1)), b);
    for (auto _ : st)
        benchmark::DoNotOptimize(sm::body_max_stress(world, b));
}
BENCHMARK(BM_ModalStress_Max)
    ->Args({0, 12})
    ->Args({0, 48})
    ->Args({1, 12})
    ->Args({1, 48})
    ->Unit(benchmark::kMicrosecond);

// A free vibrating body's step, elastic against plastic (the stress check runs every substep; the yield
// is set high enough never to be reached). Args: body, plastic.
void BM_ModalStress_StepWithPlasticity(benchmark::State& st)
{
    sm::Entity b;
    sm::World world = loaded_world(static_cast<int>(st.range(0)), 12, b,
                                   st.range(1) ? 1e12 : std::numeric_limits<double>::infinity());
    for (auto _ : st)
        world.step();
}
BENCHMARK(BM_ModalStress_StepWithPlasticity)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMicrosecond);

// A soft ball (r = 0.3 m, E = 200 kPa, ζ = 0.5, 12 modes) resting on the ground under its weight, stepped
// after 1.5 s of settling: elastic, or plastic with the yield at `permille`/1000 of the settled peak
// stress (above 1000 it stays elastic while resting, yet every substep checks). Args: permille (0:
// elastic).
void BM_ModalStress_RestingBall(benchmark::State& st)
{
    auto make = [](double yield) {
        sm::World world(sm::default_world_def());
        (void)sm::test::add_ground(world);
        sm::BodyDef def = sm::test::soft_ball_def({0, 0.3, 0}, 0.5);
        def.modal.mode_count = 12;
        def.modal.yield_stress = yield;
        const sm::Entity ball = sm::create_body(world, def);
        for (int i = 0; i < 750; ++i)
            world.step();
        return std::pair{std::move(world), ball};
    };
    double yield = std::numeric_limits<double>::infinity();
    if (st.range(0) > 0) {
        auto [probe, ball] = make(yield);
        yield = 1e-3 * static_cast<double>(st.range(0)) * sm::body_max_stress(probe, ball).max_von_mises;
    }
    auto [world, ball] = make(yield);
    for (auto _ : st)
        world.step();
    st.counters["plastic_strain"] = sm::body_plastic_state(world, ball).plastic_strain;
}
BENCHMARK(BM_ModalStress_RestingBall)->Arg(0)->Arg(1250)->Arg(2000)->Unit(benchmark::kMicrosecond);

// body_point_test on a deformed body (Newton on the deformation field) against the rigid rest test, for
// points just inside the top of the body. Args: body, modal (0: the same shape, rigid).
void BM_ModalInverseMap_PointTest(benchmark::State& st)
{
    const int which = static_cast<int>(st.range(0));
    sm::WorldDef wd = sm::default_world_def();
    wd.gravity = {};
    sm::World world(wd);
    sm::BodyDef def = body(which, 12);
    def.modal.enabled = st.range(1) != 0;
    const sm::Entity b = sm::create_body(world, def);
    if (def.modal.enabled) {
        std::vector<double> q(12, 1e-4), v(12, 0.0);
        (void)sm::set_body_modal_state(world, b, q, v);
    }
    const double top = which == 0 ? 0.019 : 0.5;
    int i = 0;
    for (auto _ : st) {
        const double x = -0.4 + 0.8 * ((i++ % 97) / 97.0);
        benchmark::DoNotOptimize(sm::body_point_test(world, b, {x, top * 0.9, 0.0}));
    }
}
BENCHMARK(BM_ModalInverseMap_PointTest)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kNanosecond);

} // namespace
