// SPDX-License-Identifier: MIT
// Offscreen rendering of a World (library supermodal_render; the engine itself never touches GL).
// Headless through EGL on Mesa's surfaceless platform into a framebuffer object, OpenGL ES 3.0:
// works with no GPU and no display (llvmpipe), as in CI. Bodies are tessellated once per distinct
// shape; modal bodies are deformed per vertex on the CPU through the public modal API. See
// docs/rendering.md. This header includes no GL or EGL header: the renderer is an opaque handle.
#pragma once

#include "supermodal/api.h"
#include "supermodal/entity.h"
#include "supermodal/geometry.h"
#include "supermodal/math.h"
#include "supermodal/result.h"
#include "supermodal/scene.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace supermodal
{

class World;

/// Deliberately broken renders, for tests that prove the golden-image comparison can fail.
enum class RenderFault : uint8_t {
    None,        ///< A correct render.
    FlatShading, ///< The fragment shader ignores the lights (a "broken shader").
    FlippedYaw,  ///< The camera looks from the opposite side (a "wrong camera").
};

/// How to make a renderer. Start from default_render_def() and change what differs.
struct RenderDef {
    int width = 1280;                      ///< Image width [px], in [16, 8192].
    int height = 720;                      ///< Image height [px], in [16, 8192].
    int samples = 4;                       ///< Multisample anti-aliasing samples per pixel, 1 (off) to 16.
    int tessellation = 32;                 ///< Mesh segments around a body's equator, in [8, 512]; with
                                           ///< gap_pixels > 0 the most a rigid superquadric gets.
    double gap_pixels = 0.25;              ///< Level of detail [px], 0 or in [0.01, 100]: a rigid
                                           ///< superquadric gets the fewest of 8, 12, 16, 20, 24, 32,
                                           ///< 48, ... (up to tessellation) segments whose mesh stays
                                           ///< within this of its surface on screen; 0: every body at
                                           ///< tessellation.
    bool grid = true;                      ///< Draw static planes (or, with none, y = 0) as a grid.
    Vec3 sky_top{0.58, 0.68, 0.80};        ///< Background at the top of the image, RGB in [0, 1].
    Vec3 sky_bottom{0.90, 0.91, 0.93};     ///< Background at the bottom, RGB in [0, 1].
    double deformation_scale = 1.0;        ///< Multiplies modal displacements for display [-], ≥ 0
                                           ///< (> 1 exaggerates millimetre bending to see it).
    RenderFault fault = RenderFault::None; ///< Test hook; leave None.
};
/// The documented starting point: 1280×720, 4× MSAA, up to 32 segments within a quarter pixel of the
/// surface, grid on, true deformation.
[[nodiscard]] SM_API RenderDef default_render_def();
/// Checks the ranges in the field comments.
[[nodiscard]] SM_API Status validate(const RenderDef& def);

/// An 8-bit RGBA image, rows top to bottom, 4 bytes per pixel.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;
};

/// Which poses a frame shows.
enum class PoseSource : uint8_t {
    Current,      ///< The state after the last step (frame capture between step() calls).
    Interpolated, ///< Blended between the last two steps by World::interpolation_alpha() (advance()).
};

/// A rectangle of an image [px]: left and top edges, counted from the top-left corner, and its size.
struct PixelRect {
    int x = 0, y = 0;
    int width = 0, height = 0; ///< 0 × 0: the whole image.
};

/// Unit axes of an orbit camera (yaw, pitch; the pitch held within [−89°, 89°]), world frame: `back`
/// points from the target to the eye, `right` and `up` are the screen's.
struct CameraAxes {
    Vec3 back{}, right{}, up{};
};
[[nodiscard]] SM_API CameraAxes camera_axes(const CameraDef& camera);

/// The distance [m] from `target` at which every corner of every box lies inside the view of
/// `camera`'s yaw, pitch and vertical fov (aspect = width / height), with no margin; at least 1 mm.
[[nodiscard]] SM_API double framing_distance(const CameraDef& camera, const Vec3& target,
                                             std::span<const Aabb> boxes, double aspect);

/// The camera a frame uses: `camera` with an absent target or a zero distance filled in so that every
/// non-plane body's world box fits in the view (a margin of 10%). Yaw, pitch and fov are kept.
[[nodiscard]] SM_API CameraDef frame_bodies(const World& world, const CameraDef& camera, double aspect);

/// An offscreen renderer with its own EGL display, context and framebuffer. One thread at a time.
class SM_API Renderer
{
  public:
    /// Opens EGL (surfaceless Mesa platform), makes an OpenGL ES 3.0 context and a framebuffer of
    /// def's size. Errors name what is missing (no EGL display, no ES 3 context, ...).
    [[nodiscard]] static Result<Renderer> create(const RenderDef& def = default_render_def());
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    [[nodiscard]] const RenderDef& settings() const;
    /// "OpenGL ES 3.2 Mesa 22.3.6 / llvmpipe (LLVM 15.0.6, 256 bits)": what the context runs on.
    [[nodiscard]] std::string device_name() const;

    /// Colour of a body, RGB in [0, 1]; bodies without one get a stable colour from their index.
    void set_body_color(Entity body, const Vec3& rgb);
    /// Draws `mesh` (shape frame [m], as SceneBody::render_mesh) for the body instead of its
    /// tessellation, deformed through the body's modes like the tessellation; null: the tessellation.
    void set_body_mesh(Entity body, std::shared_ptr<const TriangleMesh> mesh);
    /// Draws the world as seen by `camera` (absent parts framed by frame_bodies()) into `out`.
    Status render(const World& world, const CameraDef& camera, Image& out,
                  PoseSource poses = PoseSource::Current);
    /// As render(), then `overlay()` runs with this renderer's GL ES 3.0 context current and its
    /// framebuffer bound (viewport = the image), after the scene and before the read-back: a host draws
    /// its UI over the frame (the editor draws its ImGui windows through ImGui's OpenGL ES 3 backend).
    /// A non-empty `view` draws the scene into that rectangle only, framed for its aspect (the rest is
    /// RenderDef::sky_bottom): a host whose panels cover the image's sides keeps the scene between them.
    /// camera_ray() and project_to_pixel() with the rectangle's size give its pixels.
    Status render(const World& world, const CameraDef& camera, Image& out, PoseSource poses,
                  const std::function<void()>& overlay, const PixelRect& view = {});
    /// Distinct shapes tessellated so far (the mesh cache's size; a shape change adds one).
    [[nodiscard]] int cached_mesh_count() const;

    struct Impl;

  private:
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

// ---- Pixels and rays (camera_ray.cpp) ------------------------------------------------------------

/// A ray from the eye: origin [m] and unit direction, world frame.
struct CameraRay {
    Vec3 origin{};
    Vec3 direction{0, 0, -1};
};
/// The ray through pixel (x, y) of a width × height frame drawn by render() with `camera` (absent
/// parts framed as render() frames them). Pixels count from the top-left corner, x right, y down; the
/// centre of pixel (i, j) is (i + 0.5, j + 0.5) [px].
[[nodiscard]] SM_API CameraRay camera_ray(const World& world, const CameraDef& camera, int width, int height,
                                          double x, double y);
/// Where a world point [m] lands in that frame [px] (same pixel convention), through the matrix the
/// renderer draws with; nothing when the point is behind the eye.
[[nodiscard]] SM_API std::optional<std::array<double, 2>>
project_to_pixel(const World& world, const CameraDef& camera, int width, int height, const Vec3& point);

/// Gives the renderer the scene's look for the world built from it: scene_body_colors() (scene.h) and each
/// body's render mesh (SceneBody::render_mesh), matched in world_bodies() order.
SM_API void apply_scene_looks(Renderer& renderer, const Scene& scene, const World& world);

// ---- Images ---------------------------------------------------------------------------------------

/// The PNG file of an image, in memory (libspng; zlib level 1, the Sub filter on every row, 8-bit RGB
/// when every pixel is opaque, else RGBA). The same image always gives the same bytes.
[[nodiscard]] SM_API Result<std::vector<uint8_t>> encode_png(const Image& image);
/// Writes encode_png() to `path` through a temporary file next to it, renamed when complete: an error
/// leaves no file behind. Errors name the path.
SM_API Status write_png(const std::string& path, const Image& image);
/// Reads a PNG as RGBA.
[[nodiscard]] SM_API Result<Image> read_png(const std::string& path);

/// How a PngWriter works. Start from the defaults and change what differs.
struct PngWriterDef {
    int threads = 1; ///< Encoding threads, in [0, 64]; 0 encodes inside submit() (no thread).
    int queue = 2;   ///< Frames that may wait for a thread before submit() blocks, in [1, 64].
};

/// Writes PNG files on worker threads so that a host renders frame N + 1 while frame N is encoded.
/// Each file holds exactly what write_png() would write, and files appear complete and in submission
/// order (each is renamed into place only after every earlier one). After the first error nothing more
/// is written; submit() and finish() return that error.
class SM_API PngWriter
{
  public:
    /// Starts the threads. Errors when def is out of range.
    [[nodiscard]] static Result<std::unique_ptr<PngWriter>> create(const PngWriterDef& def = {});
    /// Waits for every submitted file (errors then are lost: call finish() to see them).
    ~PngWriter();
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;

    /// Queues `image` for `path`, taking its pixels; blocks while the queue is full. Returns the first
    /// error of an earlier file, if any (this image is then not written).
    Status submit(const std::string& path, Image&& image);
    /// Waits until every submitted file is written; the first error, if any.
    Status finish();
    /// Files written so far.
    [[nodiscard]] long long files_written() const;

    struct Impl;

  private:
    explicit PngWriter(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

/// Pixel-wise comparison of two images of the same size.
struct ImageDiff {
    int max_difference = 0;         ///< Largest per-channel difference [0, 255].
    long long differing_pixels = 0; ///< Pixels with some channel differing by more than the tolerance.
    double differing_fraction = 0.0;
    Image diff; ///< Differing pixels red over a faded copy of `expected`.
};
/// Compares; `tolerance` is the largest per-channel difference [0, 255] that still counts as equal.
/// Errors when the sizes differ.
[[nodiscard]] SM_API Result<ImageDiff> compare_images(const Image& actual, const Image& expected,
                                                      int tolerance);

} // namespace supermodal
