// SPDX-License-Identifier: MIT
// Headless capture speed (docs/rendering.md): frames per second of the chair scene at 1280x720 on
// whatever EGL offers (llvmpipe on a machine without a GPU), with and without PNG files; and the PNG
// encoders and settings compared on one rendered frame.
#include "supermodal/body.h"
#include "supermodal/render.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <benchmark/benchmark.h>
#include <cstdio>
#include <ctime>
#include <memory>
#include <spng.h>
#include <stb_image_write.h>
#include <string>
#include <zlib.h>

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

// Writes PNG files of the captured frames as a host would: -1 none, 0 write_png() in the render loop,
// k >= 1 through a PngWriter with k threads.
struct PngSink {
    int mode = -1;
    std::unique_ptr<sm::PngWriter> writer;
    long long frame = 0;

    explicit PngSink(int m) : mode(m)
    {
        if (mode >= 1)
            writer = std::move(*sm::PngWriter::create({.threads = mode, .queue = 2}));
    }
    bool put(sm::Image& image)
    {
        if (mode < 0)
            return true;
        const std::string path = "/tmp/supermodal_render_bench_" + std::to_string(frame++ % 8) + ".png";
        if (mode == 0)
            return sm::write_png(path, image).ok();
        return writer->submit(path, std::move(image)).ok();
    }
    bool finish() { return !writer || writer->finish().ok(); }
    ~PngSink()
    {
        for (int i = 0; i < 8; ++i)
            std::remove(("/tmp/supermodal_render_bench_" + std::to_string(i) + ".png").c_str());
    }
};

// Args: MSAA samples, PNG files (PngSink's mode), tessellation segments (the most a body gets), 1 =
// ground grid, level of detail: the mesh's largest gap to the surface on screen [1/100 px] (0: every
// body at `segments`). With `orbit` the camera turns by a degree every frame (nothing of the last
// frame's view can be reused), otherwise it stands still.
void capture_chair(benchmark::State& st, bool orbit)
{
    Setup s = chair();
    sm::RenderDef def = sm::default_render_def();
    def.width = 1280;
    def.height = 720;
    def.samples = static_cast<int>(st.range(0));
    def.tessellation = static_cast<int>(st.range(2));
    def.grid = st.range(3) != 0;
    def.gap_pixels = 0.01 * static_cast<double>(st.range(4));
    sm::Result<sm::Renderer> r = sm::Renderer::create(def);
    if (!r) {
        st.SkipWithError(r.error().message().c_str());
        return;
    }
    const std::vector<sm::Vec3> colors = sm::scene_body_colors(s.scene);
    const std::vector<sm::Entity> bodies = sm::world_bodies(s.world);
    for (size_t i = 0; i < bodies.size(); ++i)
        r->set_body_color(bodies[i], colors[i]);
    sm::CameraDef camera = sm::frame_bodies(s.world, s.scene.camera, 1280.0 / 720.0);
    PngSink png(static_cast<int>(st.range(1)));
    sm::Image image;
    const double cpu0 = process_cpu_seconds();
    for (auto _ : st) {
        if (orbit)
            camera.yaw_deg += 1.0;
        if (!r->render(s.world, camera, image))
            st.SkipWithError("render failed");
        benchmark::DoNotOptimize(image.rgba.data());
        if (!png.put(image))
            st.SkipWithError("png failed");
    }
    if (!png.finish()) // the last frames' files count in the time
        st.SkipWithError("png failed");
    // CPU time of every thread (llvmpipe rasterises on its own threads) per frame: on a loaded machine
    // wall time mostly measures the other loads, this the renderer's own work.
    st.counters["cpu_ms_per_frame"] =
        1e3 * (process_cpu_seconds() - cpu0) / static_cast<double>(st.iterations());
    st.counters["fps"] =
        benchmark::Counter(static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
    st.SetLabel(r->device_name());
}
void BM_CaptureChair(benchmark::State& st)
{
    capture_chair(st, false);
}
void BM_CaptureChairOrbit(benchmark::State& st)
{
    capture_chair(st, true);
}
BENCHMARK(BM_CaptureChairOrbit)
    ->ArgNames({"samples", "png", "segments", "grid", "lod"})
    ->Args({4, -1, 32, 1, 25})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_CaptureChair)
    ->ArgNames({"samples", "png", "segments", "grid", "lod"})
    ->Args({1, -1, 32, 1, 25})
    ->Args({4, -1, 32, 1, 25})
    ->Args({4, -1, 32, 1, 0})
    ->Args({1, -1, 32, 1, 0})
    ->Args({1, 0, 32, 1, 25})
    ->Args({4, 0, 32, 1, 25})
    ->Args({1, 1, 32, 1, 25})
    ->Args({4, 1, 32, 1, 25})
    ->Args({1, 2, 32, 1, 25})
    ->Args({4, 2, 32, 1, 25})
    ->Args({1, -1, 48, 1, 25})
    ->Args({4, -1, 48, 1, 25})
    ->Args({1, -1, 48, 0, 25})
    ->Args({1, -1, 32, 0, 25})
    ->Args({4, -1, 32, 0, 25})
    ->Args({2, -1, 32, 1, 25})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A thousand ellipsoids (10 cm, a 10x10x10 block 2 m wide, turned at random) seen whole at 1280x720,
// 4x MSAA: many bodies small on screen. Args: level of detail [1/100 px] (0: all at 32 segments).
void BM_CapturePile(benchmark::State& st)
{
    sm::World world;
    sm::BodyDef ball = sm::default_body_def();
    ball.shape.radii = {0.05, 0.05, 0.05};
    ball.motion = sm::MotionType::Static;
    for (int i = 0; i < 1000; ++i) {
        ball.position = {0.2 * (i % 10) - 0.9, 0.2 * (i / 100) + 0.1, 0.2 * (i / 10 % 10) - 0.9};
        (void)sm::create_body(world, ball);
    }
    sm::RenderDef def = sm::default_render_def();
    def.gap_pixels = 0.01 * static_cast<double>(st.range(0));
    sm::Result<sm::Renderer> r = sm::Renderer::create(def);
    if (!r) {
        st.SkipWithError(r.error().message().c_str());
        return;
    }
    const sm::CameraDef camera =
        sm::frame_bodies(world, sm::CameraDef{.target = std::nullopt, .pitch_deg = 25}, 1280.0 / 720.0);
    sm::Image image;
    const double cpu0 = process_cpu_seconds();
    for (auto _ : st) {
        if (!r->render(world, camera, image))
            st.SkipWithError("render failed");
        benchmark::DoNotOptimize(image.rgba.data());
    }
    st.counters["cpu_ms_per_frame"] =
        1e3 * (process_cpu_seconds() - cpu0) / static_cast<double>(st.iterations());
    st.counters["fps"] =
        benchmark::Counter(static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
    st.SetLabel(r->device_name());
}
BENCHMARK(BM_CapturePile)->ArgName("lod")->Arg(25)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace

namespace
{

// One rendered frame of the chair scene (1280x720, 4x MSAA), the input of every encoder below.
const sm::Image& chair_frame()
{
    static const sm::Image frame = [] {
        Setup s = chair();
        sm::Result<sm::Renderer> r = sm::Renderer::create(sm::default_render_def());
        if (!r)
            std::abort();
        sm::apply_scene_looks(*r, s.scene, s.world);
        sm::Image image;
        if (!r->render(s.world, sm::frame_bodies(s.world, s.scene.camera, 1280.0 / 720.0), image))
            std::abort();
        return image;
    }();
    return frame;
}

// libspng with the given zlib level, zlib strategy and row filters, RGBA or RGB; the PNG's size.
size_t spng_size(const sm::Image& image, int level, int strategy, int filters, bool rgb)
{
    std::vector<uint8_t> packed;
    if (rgb)
        for (size_t i = 0; i < image.rgba.size(); i += 4)
            packed.insert(packed.end(), image.rgba.begin() + static_cast<long>(i),
                          image.rgba.begin() + static_cast<long>(i) + 3);
    const std::vector<uint8_t>& px = rgb ? packed : image.rgba;
    spng_ctx* ctx = spng_ctx_new(SPNG_CTX_ENCODER);
    spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
    spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, level);
    spng_set_option(ctx, SPNG_IMG_COMPRESSION_STRATEGY, strategy);
    spng_set_option(ctx, SPNG_FILTER_CHOICE, filters);
    spng_ihdr ihdr{};
    ihdr.width = static_cast<uint32_t>(image.width);
    ihdr.height = static_cast<uint32_t>(image.height);
    ihdr.bit_depth = 8;
    ihdr.color_type = rgb ? SPNG_COLOR_TYPE_TRUECOLOR : SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
    spng_set_ihdr(ctx, &ihdr);
    size_t size = 0;
    int error = spng_encode_image(ctx, px.data(), px.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    void* out = error == 0 ? spng_get_png_buffer(ctx, &size, &error) : nullptr;
    std::free(out);
    spng_ctx_free(ctx);
    return error == 0 ? size : 0;
}

// stb_image_write at a level with one filter for every row (-1: the best of five per row).
size_t stb_size(const sm::Image& image, int level, int filter)
{
    stbi_write_png_compression_level = level;
    stbi_write_force_png_filter = filter;
    size_t size = 0;
    const auto count = [](void* total, void*, int n) {
        *static_cast<size_t*>(total) += static_cast<size_t>(n);
    };
    if (stbi_write_png_to_func(count, &size, image.width, image.height, 4, image.rgba.data(),
                               image.width * 4) == 0)
        return 0;
    return size;
}

// Arg: which encoder (the list below); in memory, one thread.
void BM_EncodePng(benchmark::State& st)
{
    const sm::Image& image = chair_frame();
    size_t bytes = 0;
    for (auto _ : st) {
        switch (st.range(0)) {
        case 0:
            bytes = stb_size(image, 8, -1);
            break; // stb's defaults
        case 1:
            bytes = stb_size(image, 1, 1);
            break; // stb, level 1, Sub
        case 2:
            bytes = spng_size(image, 6, Z_FILTERED, SPNG_FILTER_CHOICE_ALL, false);
            break; // spng's defaults
        case 3:
            bytes = spng_size(image, 1, Z_DEFAULT_STRATEGY, SPNG_FILTER_CHOICE_ALL, false);
            break;
        case 4:
            bytes = spng_size(image, 1, Z_DEFAULT_STRATEGY, SPNG_FILTER_CHOICE_SUB, false);
            break;
        case 5:
            bytes = spng_size(image, 1, Z_RLE, SPNG_FILTER_CHOICE_SUB, false);
            break;
        case 6:
            bytes = spng_size(image, 1, Z_DEFAULT_STRATEGY, SPNG_FILTER_CHOICE_SUB, true);
            break;
        case 7:
            bytes = spng_size(image, 1, Z_RLE, SPNG_FILTER_CHOICE_SUB, true);
            break;
        default: { // what write_png() does
            sm::Result<std::vector<uint8_t>> png = sm::encode_png(image);
            bytes = png ? png->size() : 0;
        }
        }
        if (bytes == 0)
            st.SkipWithError("encoding failed");
    }
    st.counters["bytes"] = static_cast<double>(bytes);
    static const char* const names[] = {"stb level 8, best filter per row",
                                        "stb level 1, Sub",
                                        "spng level 6, best filter per row",
                                        "spng level 1, best filter per row",
                                        "spng level 1, Sub",
                                        "spng level 1 RLE, Sub",
                                        "spng level 1, Sub, RGB",
                                        "spng level 1 RLE, Sub, RGB",
                                        "encode_png()"};
    st.SetLabel(names[std::min<int64_t>(st.range(0), 8)]);
}
BENCHMARK(BM_EncodePng)->DenseRange(0, 8)->ArgName("encoder")->Unit(benchmark::kMillisecond);

} // namespace
