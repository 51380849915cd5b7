// SPDX-License-Identifier: MIT
// Cost of animation export (docs/pipeline.md) on the ball-on-board scene (modal board, steel ball, two
// supports): recording 1 s at 30 samples per second against the bare run, building the GLB in memory
// (counter: bytes), writing it (temp file + fsync + rename) and writing the OBJ sequence. Arguments:
// the board's mode count and the tessellation.
#include "supermodal/export.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <benchmark/benchmark.h>
#include <filesystem>
#include <string>

namespace sm = supermodal;

namespace
{

// samples/ball_on_board.json with the board's mode count as a parameter.
std::string scene_json(int64_t modes)
{
    return R"({
  "settings": { "dt": 0.0005, "substeps": 1, "gravity": [0, -9.81, 0], "duration": 1.0 },
  "materials": {
    "wood":  { "density": 450, "young": 11e9, "poisson": 0.3, "friction": 0.5, "restitution": 0.3,
               "rolling_resistance": 0.0002, "damping_ratio": 0.02 },
    "steel": { "density": 7850, "young": 200e9, "poisson": 0.29, "friction": 0.4, "restitution": 0.6 }
  },
  "bodies": [
    { "name": "floor", "shape": { "type": "plane", "normal": [0, 1, 0], "offset": 0 }, "motion": "static" },
    { "name": "support_left", "material": "wood", "motion": "static",
      "shape": { "type": "superquadric", "radii": [0.04, 0.05, 0.1], "exponents": [0.2, 0.2] },
      "position": [-0.4, 0.05, 0] },
    { "name": "support_right", "material": "wood", "motion": "static",
      "shape": { "type": "superquadric", "radii": [0.04, 0.05, 0.1], "exponents": [0.2, 0.2] },
      "position": [0.4, 0.05, 0] },
    { "name": "board", "material": "wood",
      "shape": { "type": "superquadric", "radii": [0.5, 0.019, 0.0445], "exponents": [0.1, 0.1] },
      "position": [0, 0.119, 0],
      "dynamics": { "type": "modal", "modes": )" +
           std::to_string(modes) + R"(, "lattice": [16, 1, 2] } },
    { "name": "ball", "material": "steel",
      "shape": { "type": "superquadric", "radii": [0.025, 0.025, 0.025], "exponents": [1, 1] },
      "position": [0.1, 0.4, 0], "velocity": [0, -3, 0] }
  ]
})";
}

sm::World make_world(int64_t modes)
{
    sm::Result<sm::Scene> scene = sm::parse_scene(scene_json(modes));
    if (!scene)
        throw std::runtime_error(scene.error().message());
    sm::Result<sm::World> world = sm::build_world(*scene);
    if (!world)
        throw std::runtime_error(world.error().message());
    return std::move(*world);
}

sm::ExportDef bench_def(int64_t tessellation)
{
    sm::ExportDef def = sm::default_export_def();
    def.seconds = 1.0;
    def.fps = 30.0;
    def.tessellation = static_cast<int>(tessellation);
    return def;
}

sm::ExportRecording recording(int64_t modes, int64_t tessellation)
{
    sm::World world = make_world(modes);
    sm::Result<sm::ExportRecording> rec = sm::record_animation(world, bench_def(tessellation));
    if (!rec)
        throw std::runtime_error(rec.error().message());
    return std::move(*rec);
}

// The run alone: 2000 steps (the basis build is outside the timing, in make_world).
void BM_RunOnly(benchmark::State& state)
{
    for (auto _ : state) {
        state.PauseTiming();
        sm::World world = make_world(state.range(0));
        state.ResumeTiming();
        for (int i = 0; i < 2000; ++i)
            world.step();
        benchmark::DoNotOptimize(world.time());
    }
}
BENCHMARK(BM_RunOnly)->Arg(8)->Arg(32)->Unit(benchmark::kMillisecond);

// The same run with sampling and the meshes' morph targets.
void BM_ExportRecord(benchmark::State& state)
{
    for (auto _ : state) {
        state.PauseTiming();
        sm::World world = make_world(state.range(0));
        state.ResumeTiming();
        sm::Result<sm::ExportRecording> rec = sm::record_animation(world, bench_def(state.range(1)));
        benchmark::DoNotOptimize(rec);
    }
}
BENCHMARK(BM_ExportRecord)->Args({8, 32})->Args({32, 32})->Args({8, 128})->Unit(benchmark::kMillisecond);

void BM_ExportGlbBytes(benchmark::State& state)
{
    const sm::ExportRecording rec = recording(state.range(0), state.range(1));
    size_t bytes = 0;
    for (auto _ : state) {
        sm::Result<std::vector<uint8_t>> glb = sm::glb_from_recording(rec);
        bytes = glb->size();
        benchmark::DoNotOptimize(glb);
    }
    state.counters["bytes"] = static_cast<double>(bytes);
    state.counters["frames"] = static_cast<double>(rec.times.size());
}
BENCHMARK(BM_ExportGlbBytes)->Args({8, 32})->Args({32, 32})->Args({8, 128})->Unit(benchmark::kMillisecond);

void BM_ExportWriteGlb(benchmark::State& state)
{
    const sm::ExportRecording rec = recording(state.range(0), state.range(1));
    const std::string path =
        (std::filesystem::temp_directory_path() / "supermodal_export_bench.glb").string();
    for (auto _ : state)
        if (!sm::write_glb(rec, path))
            state.SkipWithError("write failed");
    state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
    std::filesystem::remove(path);
}
BENCHMARK(BM_ExportWriteGlb)->Args({8, 32})->Unit(benchmark::kMillisecond);

void BM_ExportObjSequence(benchmark::State& state)
{
    const sm::ExportRecording rec = recording(state.range(0), state.range(1));
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "supermodal_export_bench_obj";
    for (auto _ : state)
        if (!sm::write_obj_sequence(rec, dir.string()))
            state.SkipWithError("write failed");
    uintmax_t bytes = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        bytes += e.file_size();
    state.counters["bytes"] = static_cast<double>(bytes);
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_ExportObjSequence)->Args({8, 32})->Unit(benchmark::kMillisecond);

} // namespace
