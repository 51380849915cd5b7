// SPDX-License-Identifier: MIT
// `supermodal run --frames DIR --every K --size WxH [--video OUT.mp4]`: renders frames of a run
// offscreen (supermodal_render) into PNG files and/or an ffmpeg pipe. Reads the world, never writes it,
// so a captured run has the same state hash as one without frames.
#pragma once

#include "supermodal/result.h"
#include "supermodal/scene.h"

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace supermodal::cli
{

struct CaptureOptions {
    std::string frames_dir; ///< PNG frames go here (made if missing); empty: none.
    std::string video;      ///< An .mp4 written through ffmpeg; empty: none.
    int every = 1;          ///< A frame every K steps (and one before the first step).
    std::string size;       ///< "WxH" [px]; empty: 1280x720.
    int msaa = 4;           ///< Multisample anti-aliasing samples, 1 (off, fastest) to 16.
    bool size_given = false, every_given = false;

    [[nodiscard]] bool enabled() const { return !frames_dir.empty() || !video.empty(); }
};

/// An open capture: renderer, output folder, ffmpeg process.
class FrameCapture
{
  public:
    /// Checks the options, makes the folder, starts EGL and ffmpeg. Errors say what to fix; where is
    /// the option at fault, or "render" when the machine cannot render offscreen.
    [[nodiscard]] static Result<std::unique_ptr<FrameCapture>> open(const CaptureOptions& options,
                                                                    const Scene& scene, const World& world);
    ~FrameCapture();
    FrameCapture(const FrameCapture&) = delete;
    FrameCapture& operator=(const FrameCapture&) = delete;

    /// Renders and writes the frame of step `step` if it is one of the every-K steps.
    Status maybe_capture(const World& world, long long step);
    /// Waits for the PNG files still being encoded, closes the video pipe and checks that ffmpeg
    /// succeeded; the first error of either.
    Status finish();
    /// {"frames", "size", "every", "render_ms_mean", "write_ms_mean" (time the run waited for the PNG
    /// writer or ffmpeg), ...} for the run summary.
    [[nodiscard]] nlohmann::json summary() const;

    struct Impl;

  private:
    explicit FrameCapture(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

/// Whether an executable named `name` is on PATH.
[[nodiscard]] bool on_path(const std::string& name);

} // namespace supermodal::cli
