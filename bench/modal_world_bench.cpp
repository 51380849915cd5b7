// SPDX-License-Identifier: MIT
// Cost of modal bodies in a world step (docs/modal.md "Modal bodies in a world"): a free 2x4 board
// vibrating (ModalUpdate only: no pair, so no surface update) for r modes and both integrators, the board
// resting on the ground (its samples deformed every substep), and the same board rigid as the baseline.
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <benchmark/benchmark.h>
#include <vector>

namespace sm = supermodal;

namespace
{

sm::BodyDef board(int modes, sm::ModalIntegrator integrator)
{
    sm::BodyDef def = sm::default_body_def();
    def.shape.radii = {0.5, 0.019, 0.0445};
    def.shape.epsilon1 = def.shape.epsilon2 = 0.05;
    def.density = 450.0;
    def.modal.enabled = modes > 0;
    def.modal.mode_count = modes > 0 ? modes : 1;
    def.young = 11e9;
    def.modal.integrator = integrator;
    def.modal.damping_ratio = 0.0;
    return def;
}

// Arg 0: modes (0 = rigid); arg 1: 0 exact, 1 central difference. dt = 0.1 ms.
void BM_ModalWorld_BoardStep(benchmark::State& st)
{
    const int modes = static_cast<int>(st.range(0));
    sm::WorldDef wd = sm::default_world_def();
    wd.dt = 1e-4;
    wd.gravity = {};
    sm::World world(wd);
    const sm::Entity b =
        sm::create_body(world, board(modes, st.range(1) ? sm::ModalIntegrator::CentralDifference
                                                        : sm::ModalIntegrator::Exact));
    if (modes > 0) {
        std::vector<double> q(modes, 1e-5), v(modes, 0.0);
        (void)sm::set_body_modal_state(world, b, q, v);
    }
    double modal_ms = 0.0, surface_ms = 0.0;
    for (auto _ : st) {
        world.step();
        modal_ms += world.profile().stage_ms[static_cast<size_t>(sm::Stage::ModalUpdate)];
        surface_ms += world.profile().stage_ms[static_cast<size_t>(sm::Stage::UpdateSurfaces)];
    }
    st.counters["modal_update_us"] = 1e3 * modal_ms / static_cast<double>(st.iterations());
    st.counters["update_surfaces_us"] = 1e3 * surface_ms / static_cast<double>(st.iterations());
}
BENCHMARK(BM_ModalWorld_BoardStep)
    ->Args({0, 0})
    ->Args({6, 0})
    ->Args({12, 0})
    ->Args({24, 0})
    ->Args({12, 1})
    ->Unit(benchmark::kMicrosecond);

// The board resting on the ground (dt 2 ms, gravity): now in a pair, its samples are deformed every
// substep. Arg: modes (0 = rigid).
void BM_ModalWorld_BoardOnGround(benchmark::State& st)
{
    const int modes = static_cast<int>(st.range(0));
    sm::World world(sm::default_world_def());
    (void)sm::test::add_ground(world);
    sm::BodyDef def = board(modes, sm::ModalIntegrator::Exact);
    def.modal.damping_ratio = 0.05;
    def.position = {0, 0.019, 0};
    (void)sm::create_body(world, def);
    for (int i = 0; i < 200; ++i) // settle
        world.step();
    double surface_ms = 0.0, narrow_ms = 0.0, penalty_ms = 0.0, modal_ms = 0.0;
    for (auto _ : st) {
        world.step();
        const sm::StepProfile& p = world.profile();
        surface_ms += p.stage_ms[static_cast<size_t>(sm::Stage::UpdateSurfaces)];
        narrow_ms += p.stage_ms[static_cast<size_t>(sm::Stage::Narrowphase)];
        penalty_ms += p.stage_ms[static_cast<size_t>(sm::Stage::PenaltyForces)];
        modal_ms += p.stage_ms[static_cast<size_t>(sm::Stage::ModalUpdate)];
    }
    const double n = static_cast<double>(st.iterations());
    st.counters["update_surfaces_us"] = 1e3 * surface_ms / n;
    st.counters["narrowphase_us"] = 1e3 * narrow_ms / n;
    st.counters["penalty_us"] = 1e3 * penalty_ms / n;
    st.counters["modal_update_us"] = 1e3 * modal_ms / n;
    st.counters["contact_points"] =
        static_cast<double>(sm::world_contacts(world).empty() ? 0 : sm::world_contacts(world)[0].point_count);
}
BENCHMARK(BM_ModalWorld_BoardOnGround)->Arg(0)->Arg(6)->Arg(12)->Arg(24)->Unit(benchmark::kMicrosecond);

} // namespace
