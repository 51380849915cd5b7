// SPDX-License-Identifier: MIT
// GLFW host of the editor. The 3-D view comes from the offscreen renderer (its own surfaceless EGL
// context) as an image, is uploaded into the window's context and blitted behind ImGui's windows. The
// mouse and keys go through the editor's GLFW callbacks (input.h says what they do); a script runs
// inside the window and sends its events through the same callbacks. Built only with GLFW and the
// renderer; tested under Xvfb (tests/editor/window_test.cpp).
#include "window.h"

#include <algorithm>
#include <cstdlib>
#include <memory>

#if defined(SUPERMODAL_EDITOR_HAS_WINDOW) && defined(SUPERMODAL_EDITOR_HAS_RENDER)
#include "render_hook.h"
#include "script.h"
#include "supermodal/render.h"

#include <GLES3/gl3.h>
#include <array>
#include <iostream>
#include <utility>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#endif

namespace supermodal::editor
{

bool display_available()
{
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x11 != nullptr && *x11 != '\0') || (wayland != nullptr && *wayland != '\0');
}

#if defined(SUPERMODAL_EDITOR_HAS_WINDOW) && defined(SUPERMODAL_EDITOR_HAS_RENDER)
namespace
{

/// The 3-D view as a texture of the window's context, blitted to the window's framebuffer.
struct ViewTexture {
    GLuint texture = 0, fbo = 0;
    int width = 0, height = 0;

    void upload(const Image& image)
    {
        if (texture == 0) {
            glGenTextures(1, &texture);
            glGenFramebuffers(1, &fbo);
        }
        glBindTexture(GL_TEXTURE_2D, texture);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     image.rgba.data());
        width = image.width;
        height = image.height;
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    }
    void blit(int window_w, int window_h) const
    {
        if (texture == 0)
            return;
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        // The image's first row is the top one, GL's the bottom one: flip while blitting.
        glBlitFramebuffer(0, 0, width, height, 0, window_h, window_w, 0, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    ~ViewTexture()
    {
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &texture);
    }
};

/// GLFW's keys for the editor's.
constexpr std::pair<int, EditorKey> k_glfw_keys[] = {
    {GLFW_KEY_TAB, EditorKey::Tab},
    {GLFW_KEY_SPACE, EditorKey::Space},
    {GLFW_KEY_ESCAPE, EditorKey::Escape},
    {GLFW_KEY_ENTER, EditorKey::Enter},
    {GLFW_KEY_BACKSPACE, EditorKey::Backspace},
    {GLFW_KEY_LEFT, EditorKey::Left},
    {GLFW_KEY_RIGHT, EditorKey::Right},
    {GLFW_KEY_UP, EditorKey::Up},
    {GLFW_KEY_DOWN, EditorKey::Down},
    {GLFW_KEY_F, EditorKey::F},
    {GLFW_KEY_HOME, EditorKey::Home},
    {GLFW_KEY_EQUAL, EditorKey::Plus}, // '+' is Shift + '=' on most layouts
    {GLFW_KEY_KP_ADD, EditorKey::Plus},
    {GLFW_KEY_MINUS, EditorKey::Minus},
    {GLFW_KEY_KP_SUBTRACT, EditorKey::Minus},
    {GLFW_KEY_W, EditorKey::W},
    {GLFW_KEY_A, EditorKey::A},
    {GLFW_KEY_S, EditorKey::S},
    {GLFW_KEY_D, EditorKey::D},
    {GLFW_KEY_H, EditorKey::H},
    {GLFW_KEY_F1, EditorKey::F1},
    {GLFW_KEY_Z, EditorKey::Z},
    {GLFW_KEY_Y, EditorKey::Y},
    {GLFW_KEY_G, EditorKey::G},
    {GLFW_KEY_R, EditorKey::R},
    {GLFW_KEY_E, EditorKey::E},
    {GLFW_KEY_Q, EditorKey::Q},
    {GLFW_KEY_N, EditorKey::N},
};

constexpr std::pair<int, MouseButton> k_glfw_buttons[] = {
    {GLFW_MOUSE_BUTTON_LEFT, MouseButton::Left},
    {GLFW_MOUSE_BUTTON_RIGHT, MouseButton::Right},
    {GLFW_MOUSE_BUTTON_MIDDLE, MouseButton::Middle},
};

uint8_t editor_mods(int glfw_mods)
{
    return static_cast<uint8_t>(((glfw_mods & GLFW_MOD_SHIFT) != 0 ? k_mod_shift : 0) |
                                ((glfw_mods & GLFW_MOD_CONTROL) != 0 ? k_mod_ctrl : 0) |
                                ((glfw_mods & GLFW_MOD_ALT) != 0 ? k_mod_alt : 0));
}

int glfw_mods(uint8_t mods)
{
    return ((mods & k_mod_shift) != 0 ? GLFW_MOD_SHIFT : 0) |
           ((mods & k_mod_ctrl) != 0 ? GLFW_MOD_CONTROL : 0) | ((mods & k_mod_alt) != 0 ? GLFW_MOD_ALT : 0);
}

/// The open window: its context, the view's texture, and one frame of its loop.
struct WindowHost {
    GLFWwindow* window = nullptr;
    Renderer renderer; ///< The 3-D view's, at the framebuffer's size (made again when it changes).
    EditorSession& session;
    EditorUi& ui;
    std::unique_ptr<ViewTexture> view = std::make_unique<ViewTexture>();
    Image image;
    ThumbnailTextures thumbnails; ///< The Parts panel's, in the window's context.

    [[nodiscard]] int image_width() const { return renderer.settings().width; }
    [[nodiscard]] int image_height() const { return renderer.settings().height; }

    /// Window coordinates [screen units] to the UI's pixels (they differ on HiDPI or after a resize).
    [[nodiscard]] std::array<double, 2> to_ui(double x, double y) const
    {
        int ww = 1, wh = 1;
        glfwGetWindowSize(window, &ww, &wh);
        return {x * ui.width() / std::max(ww, 1), y * ui.height() / std::max(wh, 1)};
    }
    [[nodiscard]] std::array<double, 2> from_ui(double x, double y) const
    {
        int ww = 1, wh = 1;
        glfwGetWindowSize(window, &ww, &wh);
        return {x * std::max(ww, 1) / ui.width(), y * std::max(wh, 1) / ui.height()};
    }

    /// Follows the window: the UI laid out for its size in screen units and scaled for its content
    /// scale, the 3-D view rendered at its framebuffer's size (its pixels: sharp on HiDPI). False while
    /// it is minimised (nothing to draw).
    bool follow_window_size()
    {
        int ww = 0, wh = 0, fw = 0, fh = 0;
        glfwGetWindowSize(window, &ww, &wh);
        glfwGetFramebufferSize(window, &fw, &fh);
        if (ww <= 0 || wh <= 0 || fw <= 0 || fh <= 0)
            return false;
        if (ww != ui.width() || wh != ui.height())
            ui.resize(ww, wh);
        float xs = 1.0f, ys = 1.0f;
        glfwGetWindowContentScale(window, &xs, &ys);
        if (const float s = hidpi_ui_scale(xs, ww, fw); s != ui.scale())
            ui.set_scale(s);
        if (fw != image_width() || fh != image_height()) {
            RenderDef def = renderer.settings();
            def.width = std::clamp(fw, 16, 8192);
            def.height = std::clamp(fh, 16, 8192);
            if (Result<Renderer> resized = Renderer::create(def))
                renderer = std::move(*resized);
            else
                ui.report(resized.error());
            glfwMakeContextCurrent(window); // the new renderer made its own context current
        }
        return true;
    }

    /// One frame: events, the 3-D view rendered offscreen and uploaded, the UI over it, the mouse's
    /// action in the view; `capture` gets the window's framebuffer before it is shown.
    void frame(double seconds, Image* capture = nullptr)
    {
        glfwPollEvents();
        if (!follow_window_size()) {
            glfwWaitEventsTimeout(0.1); // minimised: wait for it to come back
            return;
        }
        ui.parts_library
            .render_pending(); // renderers of their own: before the window's context is made current
        if (session.has_world()) {
            apply_scene_looks(renderer, session.scene(), session.world());
            // Only a failure is reported: a success would clear the error of a widget's action.
            if (Status drawn = renderer.render(session.world(), editor_camera(session, ui), image,
                                               PoseSource::Interpolated, {},
                                               view_rect(ui, image_width(), image_height()));
                !drawn)
                ui.report(drawn);
        }
        glfwMakeContextCurrent(window); // the renderer made its own context current
        if (!image.rgba.empty())
            view->upload(image);
        ui.frame(seconds);
        ImGui::SetCurrentContext(ui.context());
        ui.view_input.act(session, ui, ImGui::GetIO().WantCaptureMouse);
        if (capture != nullptr)
            read_window(*capture);
        glfwSwapBuffers(window);
    }

    void read_window(Image& out) const
    {
        int fw = 1, fh = 1;
        glfwGetFramebufferSize(window, &fw, &fh);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        out.width = fw;
        out.height = fh;
        out.rgba.resize(static_cast<size_t>(fw) * static_cast<size_t>(fh) * 4);
        glReadPixels(0, 0, fw, fh, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
        const size_t row = static_cast<size_t>(fw) * 4; // GL's first row is the bottom one
        for (int y = 0; y < fh / 2; ++y)
            std::swap_ranges(out.rgba.begin() + static_cast<long>(y * row),
                             out.rgba.begin() + static_cast<long>((y + 1) * row),
                             out.rgba.begin() + static_cast<long>((fh - 1 - y) * row));
        for (size_t i = 3; i < out.rgba.size(); i += 4)
            out.rgba[i] = 255; // the window is opaque whatever alpha its framebuffer kept
    }
};

WindowHost& host_of(GLFWwindow* window)
{
    return *static_cast<WindowHost*>(glfwGetWindowUserPointer(window));
}

// The editor's GLFW callbacks, installed before ImGui's: ImGui's button and key callbacks call these
// after their own work, and a script's events enter the same chain.
void on_cursor(GLFWwindow* window, double x, double y)
{
    WindowHost& h = host_of(window);
    const auto [ux, uy] = h.to_ui(x, y);
    h.ui.on_cursor(ux, uy);
}

void on_button(GLFWwindow* window, int button, int action, int mods)
{
    for (const auto& [glfw, b] : k_glfw_buttons)
        if (glfw == button)
            host_of(window).ui.on_button(b, action == GLFW_PRESS, editor_mods(mods));
}

void on_scroll(GLFWwindow* window, double /*x*/, double y)
{
    host_of(window).ui.on_scroll(y);
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods)
{
    for (const auto& [glfw, k] : k_glfw_keys) {
        // A held camera key repeats; a toggle (Tab, Space, H) does not flicker.
        const bool repeats = k == EditorKey::Left || k == EditorKey::Right || k == EditorKey::Up ||
                             k == EditorKey::Down || k == EditorKey::Plus || k == EditorKey::Minus ||
                             k == EditorKey::W || k == EditorKey::A || k == EditorKey::S || k == EditorKey::D;
        if (glfw == key && (action != GLFW_REPEAT || repeats))
            host_of(window).ui.on_key(k, action != GLFW_RELEASE, editor_mods(mods));
    }
}

/// A script's events, sent through the window's callback chain as GLFW would send them.
InputEvents window_events(WindowHost& h)
{
    InputEvents e;
    e.cursor = [&h](double x, double y) {
        const auto [wx, wy] = h.from_ui(x, y);
        ImGui_ImplGlfw_CursorEnterCallback(h.window, GLFW_TRUE); // the pointer is inside the window
        on_cursor(h.window, wx, wy);
    };
    e.button = [&h](MouseButton b, bool down, uint8_t mods) {
        for (const auto& [glfw, button] : k_glfw_buttons)
            if (button == b)
                ImGui_ImplGlfw_MouseButtonCallback(h.window, glfw, down ? GLFW_PRESS : GLFW_RELEASE,
                                                   glfw_mods(mods));
    };
    e.scroll = [&h](double notches) { ImGui_ImplGlfw_ScrollCallback(h.window, 0.0, notches); };
    e.key = [&h](EditorKey k, bool down, uint8_t mods) {
        for (const auto& [glfw, key] : k_glfw_keys)
            if (key == k) {
                ImGui_ImplGlfw_KeyCallback(h.window, glfw, 0, down ? GLFW_PRESS : GLFW_RELEASE,
                                           glfw_mods(mods));
                return; // the first GLFW key of the editor's (Plus: '=' rather than the keypad's)
            }
    };
    e.frame = [&h](double seconds) { h.frame(seconds); };
    e.resize = [&h](int width, int height) {
        glfwSetWindowSize(h.window, width, height);
        // The window system answers asynchronously: wait (at most 2 s) until it has the new size.
        for (int i = 0; i < 40; ++i) {
            int ww = 0, wh = 0;
            glfwGetWindowSize(h.window, &ww, &wh);
            if (ww == width && wh == height)
                break;
            glfwWaitEventsTimeout(0.05);
        }
    };
    return e;
}

// Starts GLFW and opens an OpenGL ES 3.0 window through EGL; null, with `why` filled in, when it cannot.
GLFWwindow* open_window(EditorUi& ui, WindowUnavailable& why)
{
    if (!display_available()) {
        why.message = "no display ($DISPLAY and $WAYLAND_DISPLAY are unset)";
        return nullptr;
    }
    if (!glfwInit()) {
        why.message = "GLFW could not start on this display";
        return nullptr;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API); // libGLESv2 dispatches EGL contexts
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE); // a 1280x720 window as large on a 200% screen
    GLFWwindow* window = glfwCreateWindow(ui.width(), ui.height(), "supermodal-editor", nullptr, nullptr);
    if (window == nullptr) {
        glfwTerminate();
        why.message = "no OpenGL ES 3.0 window could be created through EGL";
    }
    return window;
}

// The script (if any) through the window, the screenshot of its framebuffer (if asked), then the
// interactive loop until the window is closed (unless a screenshot was asked for). The exit status.
int window_session(WindowHost& h, const WindowRun& run)
{
    int status = 0;
    if (!run.script.empty()) {
        const ScriptOutcome outcome = run_script_file(run.script, h.session, h.ui, *run.log);
        if (outcome.failure != ScriptFailure::None) {
            std::cerr << outcome.error.message() << "\n";
            return outcome.failure == ScriptFailure::CheckFailed ? 1 : 2;
        }
    }
    if (!run.screenshot.empty()) {
        Image shot;
        h.frame(0.0, &shot);
        if (Status s = write_png(run.screenshot, shot); !s) {
            std::cerr << s.error().message() << "\n";
            status = 2;
        }
        return status;
    }
    double last = glfwGetTime();
    while (!glfwWindowShouldClose(h.window)) {
        const double now = glfwGetTime();
        h.frame(now - last);
        last = now;
    }
    return status;
}

// ImGui's GLFW and GL back ends, the editor's callbacks and the script's events live as long as this.
int window_loop(GLFWwindow* window, Renderer renderer, EditorSession& session, EditorUi& ui,
                const WindowRun& run)
{
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    WindowHost host{window, std::move(renderer), session, ui, std::make_unique<ViewTexture>(), Image{}, {}};
    glfwSetWindowUserPointer(window, &host);
    glfwSetCursorPosCallback(window, on_cursor);
    glfwSetMouseButtonCallback(window, on_button);
    glfwSetScrollCallback(window, on_scroll);
    glfwSetKeyCallback(window, on_key);
    ImGui::SetCurrentContext(ui.context());
    ImGui_ImplGlfw_InitForOpenGL(window, true); // chains to the callbacks above
    ImGui_ImplOpenGL3_Init("#version 300 es");
    ui.parts.render_in_frame = false; // drawn in frame(), before the window's context is current
    const InputEvents headless = ui.input;
    ui.input = window_events(host);
    ui.before_frame = [] {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
    };
    ui.after_render = [&] {
        int fw = 1, fh = 1;
        glfwGetFramebufferSize(window, &fw, &fh);
        glViewport(0, 0, fw, fh);
        host.view->blit(fw, fh);
        host.thumbnails.update(ui.parts_library);
        host.thumbnails.bind(ImGui::GetDrawData(), nullptr);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    };
    const int status = window_session(host, run);
    ui.before_frame = nullptr;
    ui.after_render = nullptr;
    ui.input = headless;
    ui.parts.render_in_frame = true;
    host.view.reset(); // its GL objects go before the context does
    host.thumbnails.release();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    glfwSetWindowUserPointer(window, nullptr);
    return status;
}

} // namespace

int run_window(EditorSession& session, EditorUi& ui, const WindowRun& run, WindowUnavailable& why)
{
    GLFWwindow* window = open_window(ui, why);
    if (window == nullptr)
        return 2;
    RenderDef def = default_render_def();
    def.width = ui.width();
    def.height = ui.height();
    Result<Renderer> renderer = Renderer::create(def);
    if (!renderer) {
        glfwDestroyWindow(window);
        glfwTerminate();
        why.message = renderer.error().message();
        return 2;
    }
    const int status = window_loop(window, std::move(*renderer), session, ui, run);
    glfwDestroyWindow(window);
    glfwTerminate();
    return status;
}
#else
int run_window(EditorSession&, EditorUi&, const WindowRun&, WindowUnavailable& why)
{
    why.message = display_available() ? "this build has no window support (GLFW and the renderer)"
                                      : "no display ($DISPLAY and $WAYLAND_DISPLAY are unset)";
    return 2;
}
#endif

} // namespace supermodal::editor
