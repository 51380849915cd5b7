// SPDX-License-Identifier: MIT
// EGL display + OpenGL ES 3.0 context on Mesa's surfaceless platform, and the framebuffer a frame is
// drawn into (multisampled, resolved into a single-sample one for read-back). Internal to render/.
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

/// Colour + depth render target of a fixed size; `samples` > 1 adds a resolve target.
class Framebuffer
{
  public:
    Framebuffer() = default;
    ~Framebuffer();
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    /// Needs a current context. samples is clamped to what the driver allows.
    Status create(int width, int height, int samples);
    /// Binds the framebuffer to draw into, with the viewport set.
    void bind() const;
    /// Resolves (if multisampled) and reads RGBA8, rows top to bottom.
    void read(std::vector<uint8_t>& rgba) const;
    [[nodiscard]] int samples() const { return m_samples; }

  private:
    void release();
    int m_width = 0, m_height = 0, m_samples = 1;
    GLuint m_fbo = 0, m_color = 0, m_depth = 0;
    GLuint m_resolve_fbo = 0, m_resolve_color = 0;
};

/// The GL error flags as text, or empty when none is set (clears them).
[[nodiscard]] std::string gl_errors();

} // namespace supermodal::render
