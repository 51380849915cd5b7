// SPDX-License-Identifier: MIT
#include "frame_capture.h"

#include "supermodal/body.h"
#include "supermodal/render.h"
#include "supermodal/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace supermodal::cli
{
#if SM_HAVE_RENDER
namespace
{

using Clock = std::chrono::steady_clock;

Error bad(const std::string& option, const std::string& what)
{
    return Error{"", option, what};
}

// "1280x720" → (1280, 720); false unless both are integers in [16, 8192].
bool parse_size(const std::string& text, int& w, int& h)
{
    unsigned a = 0, b = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X'))
        return false;
    if (a < 16 || a > 8192 || b < 16 || b > 8192)
        return false;
    w = static_cast<int>(a);
    h = static_cast<int>(b);
    return true;
}

// The PNGs are encoded off the render loop. On two cores one thread gained nothing measurable and two
// cost more CPU (docs/rendering.md); one per four cores leaves llvmpipe its rasterising threads.
PngWriterDef png_writer_def()
{
    PngWriterDef def;
    def.threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()) / 4, 1, 4);
    def.queue = 2;
    return def;
}

// Single-quoted for /bin/sh.
std::string shell_quote(const std::string& s)
{
    std::string out = "'";
    for (char c : s)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

} // namespace

#endif

bool on_path(const std::string& name)
{
    const char* path = std::getenv("PATH");
    if (path == nullptr)
        return false;
    std::string dirs = path;
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::string dir = dirs.substr(start, end - start);
        const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
        if (::access(candidate.c_str(), X_OK) == 0)
            return true;
        start = end + 1;
    }
    return false;
}

#if SM_HAVE_RENDER
struct FrameCapture::Impl {
    CaptureOptions options;
    std::unique_ptr<Renderer> renderer;
    std::unique_ptr<PngWriter> png; ///< Encodes frame N while frame N + 1 renders.
    CameraDef camera;
    FILE* ffmpeg = nullptr;
    Image image;
    long long frames = 0;
    double render_s = 0.0, encode_s = 0.0;
    int width = 1280, height = 720;

    ~Impl()
    {
        if (ffmpeg != nullptr)
            ::pclose(ffmpeg);
    }
};

FrameCapture::FrameCapture(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
FrameCapture::~FrameCapture() = default;

Result<std::unique_ptr<FrameCapture>> FrameCapture::open(const CaptureOptions& o, const Scene& scene,
                                                         const World& world)
{
    auto impl = std::make_unique<Impl>();
    impl->options = o;
    if (!o.enabled() && (o.size_given || o.every_given))
        return bad("--every/--size", "give --frames DIR or --video OUT.mp4 too");
    if (!o.size.empty() && !parse_size(o.size, impl->width, impl->height))
        return bad("--size",
                   "expected WxH with each in [16, 8192] px (e.g. 1280x720), found \"" + o.size + "\"");
    if (o.every < 1)
        return bad("--every", "expected an integer >= 1");
    if (o.msaa < 1 || o.msaa > 16)
        return bad("--msaa", "expected 1 to 16 samples per pixel");
    if (!o.frames_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.frames_dir, ec);
        if (!std::filesystem::is_directory(o.frames_dir) || ::access(o.frames_dir.c_str(), W_OK) != 0)
            return bad("--frames", o.frames_dir + ": cannot make or write this directory");
    }
    if (!o.video.empty()) {
        if (!on_path("ffmpeg"))
            return bad("--video", "needs ffmpeg on PATH (apt-get install ffmpeg), or leave --video out and "
                                  "use --frames DIR");
        const std::filesystem::path dir = std::filesystem::path(o.video).parent_path();
        if (!dir.empty() && !std::filesystem::is_directory(dir))
            return bad("--video", o.video + ": directory " + dir.string() + " does not exist");
    }
    if (!o.frames_dir.empty()) {
        Result<std::unique_ptr<PngWriter>> png = PngWriter::create(png_writer_def());
        if (!png)
            return Error{"", "--frames", "cannot start the PNG writer: " + png.error().message()};
        impl->png = std::move(*png);
    }
    RenderDef def = default_render_def();
    def.width = impl->width;
    def.height = impl->height;
    def.samples = o.msaa;
    Result<Renderer> renderer = Renderer::create(def);
    if (!renderer)
        return Error{"", "render", "cannot render offscreen: " + renderer.error().message()};
    impl->renderer = std::make_unique<Renderer>(std::move(*renderer));
    apply_scene_looks(*impl->renderer, scene, world);
    // Frame the bodies once, at the start, so the camera does not swim as they move.
    impl->camera = frame_bodies(world, scene.camera, static_cast<double>(impl->width) / impl->height);
    if (!o.video.empty()) {
        // Real-time playback: one frame per `every` steps of dt; yuv420p (what players expect) needs
        // even sizes, so odd ones are padded.
        const double fps = 1.0 / (o.every * world.settings().dt);
        char rate[64];
        std::snprintf(rate, sizeof rate, "%.6g", std::clamp(fps, 1.0, 240.0));
        const std::string cmd = "ffmpeg -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgba -s " +
                                std::to_string(impl->width) + "x" + std::to_string(impl->height) + " -r " +
                                rate + " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -pix_fmt yuv420p " +
                                shell_quote(o.video);
        impl->ffmpeg = ::popen(cmd.c_str(), "w");
        if (impl->ffmpeg == nullptr)
            return Error{"", "--video", "cannot start ffmpeg"};
    }
    return std::unique_ptr<FrameCapture>(new FrameCapture(std::move(impl)));
}

Status FrameCapture::maybe_capture(const World& world, long long step)
{
    Impl& m = *m_impl;
    if (step % m.options.every != 0)
        return {};
    const auto t0 = Clock::now();
    if (Status s = m.renderer->render(world, m.camera, m.image); !s)
        return s;
    const auto t1 = Clock::now();
    if (m.ffmpeg != nullptr &&
        std::fwrite(m.image.rgba.data(), 1, m.image.rgba.size(), m.ffmpeg) != m.image.rgba.size())
        return Error{"", "--video", "ffmpeg stopped reading frames"};
    if (m.png) {
        char name[64];
        std::snprintf(name, sizeof name, "/frame_%06lld.png", m.frames);
        // The writer takes the pixels; the next render() fills a fresh buffer.
        if (Status s = m.png->submit(m.options.frames_dir + name, std::move(m.image)); !s)
            return s;
    }
    m.render_s += std::chrono::duration<double>(t1 - t0).count();
    m.encode_s += std::chrono::duration<double>(Clock::now() - t1).count();
    ++m.frames;
    return {};
}

Status FrameCapture::finish()
{
    Impl& m = *m_impl;
    if (m.png)
        if (Status s = m.png->finish(); !s)
            return s;
    if (m.ffmpeg == nullptr)
        return {};
    const int raw = ::pclose(m.ffmpeg);
    m.ffmpeg = nullptr;
    if (!(WIFEXITED(raw) && WEXITSTATUS(raw) == 0))
        return Error{"", "--video", "ffmpeg failed writing " + m.options.video};
    return {};
}

nlohmann::json FrameCapture::summary() const
{
    const Impl& m = *m_impl;
    const double n = static_cast<double>(std::max(1LL, m.frames));
    return {{"frames", m.frames},
            {"every", m.options.every},
            {"size", {m.width, m.height}},
            {"msaa", m.options.msaa},
            {"frames_dir", m.options.frames_dir},
            {"video", m.options.video},
            {"device", m.renderer->device_name()},
            {"png_threads", m.png ? png_writer_def().threads : 0},
            {"render_ms_mean", 1e3 * m.render_s / n},
            {"write_ms_mean", 1e3 * m.encode_s / n}};
}

#else // built with -DSUPERMODAL_RENDER=OFF: no renderer to capture with

struct FrameCapture::Impl {
};
FrameCapture::FrameCapture(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
FrameCapture::~FrameCapture() = default;
Result<std::unique_ptr<FrameCapture>> FrameCapture::open(const CaptureOptions&, const Scene&, const World&)
{
    return Error{"", "--frames", "this supermodal was built with -DSUPERMODAL_RENDER=OFF: no frame capture"};
}
Status FrameCapture::maybe_capture(const World&, long long)
{
    return {};
}
Status FrameCapture::finish()
{
    return {};
}
nlohmann::json FrameCapture::summary() const
{
    return {};
}
#endif

} // namespace supermodal::cli
