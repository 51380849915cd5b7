// SPDX-License-Identifier: MIT
// EGL display + OpenGL ES 3.0 context on Mesa's surfaceless platform, and the framebuffers a frame is
// drawn into (the single-sample image; under MSAA the bodies' multisampled layer). Internal to render/.
#pragma once

#include "supermodal/result.h"

#include <EGL/egl.h>
#include <GLES3/gl3.h>
#include <cstdint>
#include <string>
#include <vector>

namespace supermodal::render
{

/// Owns the EGL display connection and context; makes the context current on creation.
class GlContext
{
  public:
    GlContext() = default;
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Opens the surfaceless display and an ES 3.0 context; errors say which step failed and why.
    Status open();
    /// Makes this context current on the calling thread.
    Status make_current();
    [[nodiscard]] const std::string& device_name() const { return m_device; }

  private:
    EGLDisplay m_display = EGL_NO_DISPLAY;
    EGLContext m_context = EGL_NO_CONTEXT;
    std::string m_device;
};

/// The image a frame ends in (colour + depth, one sample) and, when `samples` > 1, a multisampled
/// colour + depth target for the bodies and a single-sample texture their samples resolve into, to be
/// composited over the image (only bodies have edges that need the samples: the ground and the sky
/// shade smoothly at one sample). The multisampled target is only as large as the bodies' rectangle
/// (in whole 64-pixel tiles): on llvmpipe clearing all of a small target is several times cheaper
/// than a scissored clear of part of a large one, which it draws as a rectangle.
class Framebuffer
{
  public:
    Framebuffer() = default;
    ~Framebuffer();
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    /// Needs a current context. samples is clamped to what the driver allows.
    Status create(int width, int height, int samples);
    /// Binds the single-sample image to draw into, with the viewport set to all of it.
    void bind() const;
    /// Binds the multisampled target (samples() > 1 only), sized to hold width x height pixels from
    /// its lower left corner, and clears all of it to transparent at the far plane.
    void begin_layer(int width, int height);
    /// Resolves the multisampled target's lower left width x height pixels into layer_texture(), same
    /// place.
    void resolve(int width, int height) const;
    [[nodiscard]] GLuint layer_texture() const { return m_layer_texture; }
    /// Copies the image's colour and depth aside (samples() > 1 only) ...
    void save_background() const;
    /// ... and back, all of it.
    void restore_background() const;
    /// Reads the image as RGBA8, rows top to bottom.
    void read(std::vector<uint8_t>& rgba) const;
    [[nodiscard]] int samples() const { return m_samples; }

  private:
    void release();
    int m_width = 0, m_height = 0, m_samples = 1;
    int m_layer_width = 0, m_layer_height = 0;  ///< The multisampled target's size.
    GLuint m_fbo = 0, m_color = 0, m_depth = 0; ///< The image.
    GLuint m_ms_fbo = 0, m_ms_color = 0, m_ms_depth = 0;
    GLuint m_layer_fbo = 0, m_layer_texture = 0;
    GLuint m_saved_fbo = 0, m_saved_color = 0, m_saved_depth = 0; ///< save_background()'s copy.
};

/// The GL error flags as text, or empty when none is set (clears them).
[[nodiscard]] std::string gl_errors();

} // namespace supermodal::render
