// SPDX-License-Identifier: MIT
#include "render/gl_context.h"

#include <EGL/eglext.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <mutex>

namespace supermodal::render
{
namespace
{

std::string egl_error_text(const char* step)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04x)", step,
                  static_cast<unsigned>(eglGetError()));
    return buf;
}

bool has_extension(const char* list, const char* name)
{
    if (list == nullptr)
        return false;
    const size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

Error render_error(std::string what)
{
    return Error{"", "render", std::move(what)};
}

} // namespace

// The surfaceless display is one per process (eglGetPlatformDisplay returns the same handle every
// time) and eglTerminate is not reference-counted: terminate only when the last context goes.
std::mutex g_display_mutex;
int g_display_users = 0;

GlContext::~GlContext()
{
    if (m_display == EGL_NO_DISPLAY)
        return;
    eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (m_context != EGL_NO_CONTEXT)
        eglDestroyContext(m_display, m_context);
    const std::lock_guard lock(g_display_mutex);
    if (--g_display_users == 0)
        eglTerminate(m_display);
}

namespace
{

// A display on the surfaceless platform (Mesa: llvmpipe with no GPU and no display), else on the first
// EGL device (EGL_EXT_platform_device: NVIDIA's driver, which has no surfaceless platform).
EGLDisplay open_display(std::string& out_why)
{
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) {
        out_why = "eglGetPlatformDisplayEXT is missing";
        return EGL_NO_DISPLAY;
    }
    if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY)
            return d;
    }
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (has_extension(client, "EGL_EXT_platform_device") && query_devices != nullptr) {
        EGLDeviceEXT devices[4];
        EGLint count = 0;
        if (query_devices(4, devices, &count) && count > 0) {
            EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
            if (d != EGL_NO_DISPLAY)
                return d;
        }
    }
    out_why = "the EGL library has neither EGL_MESA_platform_surfaceless nor a usable EGL device (install "
              "libegl1 and libegl-mesa0; client extensions: " +
              std::string(client ? client : "none") + ")";
    return EGL_NO_DISPLAY;
}

} // namespace

Status GlContext::open()
{
    std::string why;
    m_display = open_display(why);
    if (m_display == EGL_NO_DISPLAY)
        return render_error("no EGL display: " + why);
    EGLint major = 0, minor = 0;
    {
        const std::lock_guard lock(g_display_mutex);
        if (!eglInitialize(m_display, &major, &minor)) {
            m_display = EGL_NO_DISPLAY;
            return render_error("no EGL display: " + egl_error_text("eglInitialize") +
                                " (Mesa's drivers: install libgl1-mesa-dri)");
        }
        ++g_display_users;
    }
    const char* display_ext = eglQueryString(m_display, EGL_EXTENSIONS);
    if (!has_extension(display_ext, "EGL_KHR_surfaceless_context") ||
        !has_extension(display_ext, "EGL_KHR_no_config_context"))
        return render_error("EGL display lacks EGL_KHR_surfaceless_context or EGL_KHR_no_config_context");
    if (!eglBindAPI(EGL_OPENGL_ES_API))
        return render_error("no OpenGL ES: " + egl_error_text("eglBindAPI"));
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    m_context = eglCreateContext(m_display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (m_context == EGL_NO_CONTEXT)
        return render_error("no OpenGL ES 3.0 context: " + egl_error_text("eglCreateContext"));
    if (Status s = make_current(); !s)
        return s;
    const auto text = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "?");
    };
    m_device = text(GL_VERSION) + " / " + text(GL_RENDERER);
    return {};
}

Status GlContext::make_current()
{
    if (!eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_context))
        return render_error(egl_error_text("eglMakeCurrent"));
    return {};
}

Framebuffer::~Framebuffer()
{
    release();
}

void Framebuffer::release()
{
    for (GLuint f : {m_fbo, m_ms_fbo, m_layer_fbo, m_saved_fbo})
        if (f != 0)
            glDeleteFramebuffers(1, &f);
    for (GLuint b : {m_color, m_depth, m_ms_color, m_ms_depth, m_saved_color, m_saved_depth})
        if (b != 0)
            glDeleteRenderbuffers(1, &b);
    if (m_layer_texture != 0)
        glDeleteTextures(1, &m_layer_texture);
    m_fbo = m_color = m_depth = m_ms_fbo = m_ms_color = m_ms_depth = m_layer_fbo = m_layer_texture = 0;
    m_saved_fbo = m_saved_color = m_saved_depth = 0;
}

namespace
{

// A renderbuffer of the given size attached to the bound framebuffer.
void attach_renderbuffer(GLuint& out, GLenum attachment, GLenum format, GLsizei samples, int width,
                         int height)
{
    glGenRenderbuffers(1, &out);
    glBindRenderbuffer(GL_RENDERBUFFER, out);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, out);
}

constexpr GLenum k_color_format = GL_RGBA8, k_depth_format = GL_DEPTH_COMPONENT24;

// A framebuffer with colour and depth renderbuffers of the given size and samples (0: one), left
// bound; false when it is incomplete.
bool make_target(GLuint& fbo, GLuint& color, GLuint& depth, GLsizei samples, int width, int height)
{
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    attach_renderbuffer(color, GL_COLOR_ATTACHMENT0, k_color_format, samples, width, height);
    attach_renderbuffer(depth, GL_DEPTH_ATTACHMENT, k_depth_format, samples, width, height);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

constexpr int k_tile = 64; ///< The multisampled target grows and shrinks by whole tiles of pixels.

int whole_tiles(int pixels, int limit)
{
    return std::min(limit, std::max(k_tile, (pixels + k_tile - 1) / k_tile * k_tile));
}

} // namespace

Status Framebuffer::create(int width, int height, int samples)
{
    release();
    m_width = width;
    m_height = height;
    GLint max_samples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    m_samples = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));
    const auto incomplete = [&](const char* which) {
        return render_error(std::string(which) + " framebuffer incomplete (" + std::to_string(width) + "x" +
                            std::to_string(height) + ", " + std::to_string(m_samples) + " samples)");
    };
    if (!make_target(m_fbo, m_color, m_depth, 0, width, height))
        return incomplete("image");
    if (m_samples > 1) {
        m_layer_width = whole_tiles(0, width);
        m_layer_height = whole_tiles(0, height);
        if (!make_target(m_ms_fbo, m_ms_color, m_ms_depth, m_samples, m_layer_width, m_layer_height))
            return incomplete("multisampled");
        glGenTextures(1, &m_layer_texture);
        glBindTexture(GL_TEXTURE_2D, m_layer_texture);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, width, height);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindTexture(GL_TEXTURE_2D, 0);
        glGenFramebuffers(1, &m_layer_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, m_layer_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, m_layer_texture, 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return incomplete("layer");
        if (!make_target(m_saved_fbo, m_saved_color, m_saved_depth, 0, width, height))
            return incomplete("background copy");
    }
    if (std::string e = gl_errors(); !e.empty())
        return render_error("framebuffer: " + e);
    return {};
}

void Framebuffer::bind() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, m_fbo);
    glViewport(0, 0, m_width, m_height);
}

void Framebuffer::begin_layer(int width, int height)
{
    const int w = whole_tiles(width, m_width), h = whole_tiles(height, m_height);
    if (w != m_layer_width || h != m_layer_height) {
        m_layer_width = w;
        m_layer_height = h;
        for (auto [buffer, format] : {std::pair{m_ms_color, k_color_format}, {m_ms_depth, k_depth_format}}) {
            glBindRenderbuffer(GL_RENDERBUFFER, buffer);
            glRenderbufferStorageMultisample(GL_RENDERBUFFER, m_samples, format, w, h);
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, m_ms_fbo);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void Framebuffer::resolve(int width, int height) const
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_ms_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m_layer_fbo);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

namespace
{

void copy_all(GLuint from, GLuint to, int width, int height)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT,
                      GL_NEAREST);
}

} // namespace

void Framebuffer::save_background() const
{
    copy_all(m_fbo, m_saved_fbo, m_width, m_height);
}

void Framebuffer::restore_background() const
{
    copy_all(m_saved_fbo, m_fbo, m_width, m_height);
}

void Framebuffer::read(std::vector<uint8_t>& rgba) const
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_fbo);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    const size_t row = static_cast<size_t>(m_width) * 4;
    rgba.resize(row * static_cast<size_t>(m_height));
    glReadPixels(0, 0, m_width, m_height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    // GL's first row is the bottom one; images here start at the top.
    std::vector<uint8_t> tmp(row);
    for (int y = 0; y < m_height / 2; ++y) {
        uint8_t* a = rgba.data() + static_cast<size_t>(y) * row;
        uint8_t* b = rgba.data() + static_cast<size_t>(m_height - 1 - y) * row;
        std::memcpy(tmp.data(), a, row);
        std::memcpy(a, b, row);
        std::memcpy(b, tmp.data(), row);
    }
}

std::string gl_errors()
{
    std::string out;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%sGL error 0x%04x", out.empty() ? "" : ", ", e);
        out += buf;
    }
    return out;
}

} // namespace supermodal::render
