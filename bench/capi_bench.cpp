// SPDX-License-Identifier: MIT
// The C API's costs (docs/c_api.md): call overhead on a step, and the deformed-mesh queries an
// animation host makes per frame (tessellation + modal field per vertex) on a modal board.
#include "supermodal/supermodal.h"
#include "supermodal/supermodal.hpp"

#include <benchmark/benchmark.h>
#include <vector>

namespace
{

// tests/tools/scenes/modal_board.json, inline so the benchmark needs no files: a free 2×4 board with
// 6 modes on an 8×1×1 lattice, and a ball.
constexpr const char* k_board = R"({
  "settings": { "dt": 0.0005, "gravity": [0, 0, 0] },
  "materials": { "wood": { "density": 450, "young": 11e9, "poisson": 0.3, "damping_ratio": 0.02 } },
  "bodies": [
    { "name": "board", "material": "wood",
      "shape": { "type": "superquadric", "radii": [0.5, 0.019, 0.0445], "exponents": [0.05, 0.05] },
      "dynamics": { "type": "modal", "modes": 6, "lattice": [8, 1, 1] } },
    { "name": "ball", "shape": { "type": "superquadric", "radii": [0.05, 0.05, 0.05] }, "position": [0, 1, 0] }
  ] })";

// A bent board: struck at the tip and stepped 10 ms, so the modal field is non-zero.
sm_world* bent_board(sm_body& board)
{
    sm_world* w = nullptr;
    if (sm_world_create_from_json(k_board, &w) != SM_OK || sm_world_find_body(w, "board", &board) != SM_OK)
        return nullptr;
    (void)sm_body_apply_impulse(w, board, sm_vec3{0, 2, 0}, sm_vec3{0.45, 0, 0});
    for (int i = 0; i < 20; ++i)
        (void)sm_world_step(w);
    return w;
}

void BM_Capi_Step_ModalBoard(benchmark::State& st)
{
    sm_body board{};
    sm_world* w = bent_board(board);
    for (auto _ : st)
        benchmark::DoNotOptimize(sm_world_step(w));
    sm_world_destroy(w);
}
BENCHMARK(BM_Capi_Step_ModalBoard)->Unit(benchmark::kMicrosecond);

// The same step through the C++ API: the difference is the C layer's per-call cost.
void BM_Cpp_Step_ModalBoard(benchmark::State& st)
{
    supermodal::Result<supermodal::Scene> scene = supermodal::parse_scene(k_board);
    supermodal::Result<supermodal::World> world = supermodal::build_world(*scene);
    const supermodal::Entity board = supermodal::find_body(*world, "board");
    supermodal::apply_linear_impulse(*world, board, {0, 2, 0}, {0.45, 0, 0});
    for (int i = 0; i < 20; ++i)
        world->step();
    for (auto _ : st)
        world->step();
}
BENCHMARK(BM_Cpp_Step_ModalBoard)->Unit(benchmark::kMicrosecond);

// One frame's deformed mesh at `resolution` segments, world frame, after the first call cached the rest
// mesh and its lattice weights.
void BM_Capi_Mesh_ModalBoard(benchmark::State& st)
{
    sm_body board{};
    sm_world* w = bent_board(board);
    const int resolution = static_cast<int>(st.range(0));
    size_t nv = 0, ni = 0;
    (void)sm_body_get_mesh(w, board, resolution, nullptr, 0, nullptr, 0, &nv, &ni);
    std::vector<sm_vec3> positions(nv);
    std::vector<uint32_t> indices(ni);
    for (auto _ : st)
        benchmark::DoNotOptimize(
            sm_body_get_mesh(w, board, resolution, positions.data(), nv, indices.data(), ni, &nv, &ni));
    st.counters["vertices"] = static_cast<double>(nv);
    st.SetItemsProcessed(st.iterations() * static_cast<int64_t>(nv));
    sm_world_destroy(w);
}
BENCHMARK(BM_Capi_Mesh_ModalBoard)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);

// The tessellation alone: what the first mesh query per body and resolution pays (then cached).
void BM_Cpp_Tessellate_Board(benchmark::State& st)
{
    supermodal::ShapeDef shape = supermodal::default_shape_def();
    shape.radii = {0.5, 0.019, 0.0445};
    shape.epsilon1 = shape.epsilon2 = 0.05;
    for (auto _ : st)
        benchmark::DoNotOptimize(supermodal::tessellate(shape, static_cast<int>(st.range(0))));
}
BENCHMARK(BM_Cpp_Tessellate_Board)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);

// A host's own mesh: 1000 rest points through the modal field.
void BM_Capi_DeformedPoints_ModalBoard(benchmark::State& st)
{
    sm_body board{};
    sm_world* w = bent_board(board);
    std::vector<sm_vec3> rest(1000), out(1000);
    for (size_t i = 0; i < rest.size(); ++i)
        rest[i] = sm_vec3{-0.5 + 0.001 * static_cast<double>(i), 0.01, 0.02};
    for (auto _ : st)
        benchmark::DoNotOptimize(sm_body_get_deformed_points(w, board, rest.data(), rest.size(), out.data()));
    st.SetItemsProcessed(st.iterations() * static_cast<int64_t>(rest.size()));
    sm_world_destroy(w);
}
BENCHMARK(BM_Capi_DeformedPoints_ModalBoard)->Unit(benchmark::kMicrosecond);

} // namespace
