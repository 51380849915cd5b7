// SPDX-License-Identifier: MIT
// Cost of modal bodies in a world step (docs/modal.md "World integration"): a free 2x4 board vibrating
// (ModalUpdate + UpdateSurfaces, no contact) for r modes and both integrators, and the same board as a
// rigid body for the baseline.
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

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
    def.modal.young = 11e9;
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

} // namespace
