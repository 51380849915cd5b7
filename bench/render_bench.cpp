// SPDX-License-Identifier: MIT
// Headless capture speed (docs/rendering.md): frames per second of the chair scene at 1280x720 on
// whatever EGL offers (llvmpipe on a machine without a GPU), with and without PNG encoding.
#include "supermodal/body.h"
#include "supermodal/render.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <benchmark/benchmark.h>
#include <cstdio>
#include <ctime>
#include <string>

namespace sm = supermodal;

namespace
{

struct Setup {
    sm::Scene scene;
    sm::World world;
};

// The demo scene, stepped 0.2 s so the dummy has settled onto the seat.
Setup chair()
{
    sm::Result<sm::Scene> scene =
        sm::load_scene(std::string(SM_SOURCE_DIR) + "/samples/chair_with_dummy.json");
    if (!scene)
        std::abort();
    sm::Result<sm::World> world = sm::build_world(*scene);
    if (!world)
        std::abort();
    for (int i = 0; i < 200; ++i)
        world->step();
    return {std::move(*scene), std::move(*world)};
}

double process_cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Args: MSAA samples, 1 = also write a PNG, tessellation segments, 1 = ground grid.
void BM_CaptureChair(benchmark::State& st)
{
    Setup s = chair();
    sm::RenderDef def = sm::default_render_def();
    def.width = 1280;
    def.height = 720;
    def.samples = static_cast<int>(st.range(0));
    def.tessellation = static_cast<int>(st.range(2));
    def.grid = st.range(3) != 0;
    sm::Result<sm::Renderer> r = sm::Renderer::create(def);
    if (!r) {
        st.SkipWithError(r.error().message().c_str());
        return;
    }
    const std::vector<sm::Vec3> colors = sm::scene_body_colors(s.scene);
    const std::vector<sm::Entity> bodies = sm::world_bodies(s.world);
    for (size_t i = 0; i < bodies.size(); ++i)
        r->set_body_color(bodies[i], colors[i]);
    const sm::CameraDef camera = sm::frame_bodies(s.world, s.scene.camera, 1280.0 / 720.0);
    const std::string path = "/tmp/supermodal_render_bench.png";
    sm::Image image;
    const double cpu0 = process_cpu_seconds();
    for (auto _ : st) {
        if (!r->render(s.world, camera, image))
            st.SkipWithError("render failed");
        if (st.range(1) != 0 && !sm::write_png(path, image))
            st.SkipWithError("png failed");
        benchmark::DoNotOptimize(image.rgba.data());
    }
    std::remove(path.c_str());
    // CPU time of every thread (llvmpipe rasterises on its own threads) per frame: on a loaded machine
    // wall time mostly measures the other loads, this the renderer's own work.
    st.counters["cpu_ms_per_frame"] =
        1e3 * (process_cpu_seconds() - cpu0) / static_cast<double>(st.iterations());
    st.counters["fps"] =
        benchmark::Counter(static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
    st.SetLabel(r->device_name());
}
BENCHMARK(BM_CaptureChair)
    ->ArgNames({"samples", "png", "segments", "grid"})
    ->Args({1, 0, 48, 1})
    ->Args({4, 0, 48, 1})
    ->Args({4, 1, 48, 1})
    ->Args({1, 1, 48, 1})
    ->Args({1, 0, 32, 1})
    ->Args({4, 0, 32, 1})
    ->Args({4, 1, 32, 1})
    ->Args({1, 1, 32, 1})
    ->Args({1, 0, 48, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

} // namespace
