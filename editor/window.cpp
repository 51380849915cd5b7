// SPDX-License-Identifier: MIT
// GLFW host of the editor. The 3-D view comes from the offscreen renderer (its own surfaceless EGL
// context) as an image, is uploaded into the window's context and blitted behind ImGui's windows. Left
// mouse on a body (outside the ImGui windows) selects it and drags it with the spring; right mouse
// moulds a modal body 5 mm deep. Built only with GLFW and the renderer; not testable without a display.
#include "window.h"

#include <algorithm>
#include <cstdlib>
#include <memory>

#if defined(SUPERMODAL_EDITOR_HAS_WINDOW) && defined(SUPERMODAL_EDITOR_HAS_RENDER)
#include "render_hook.h"
#include "supermodal/render.h"

#include <GLES3/gl3.h>
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

// Moulding depth of a right click [m] and its duration [steps].
constexpr double k_mould_depth = 0.005;
constexpr int k_mould_steps = 200;

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

void handle_mouse(GLFWwindow* window, EditorSession& session, EditorUi& ui, bool& dragging,
                  bool& right_was_down)
{
    const ImGuiIO& io = ImGui::GetIO();
    double cx = 0, cy = 0;
    glfwGetCursorPos(window, &cx, &cy);
    int ww = 1, wh = 1;
    glfwGetWindowSize(window, &ww, &wh);
    const double x = cx * ui.width() / std::max(ww, 1), y = cy * ui.height() / std::max(wh, 1);
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right_down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    const bool right = right_down && !right_was_down; // one finger per press, not one per frame
    right_was_down = right_down;
    Result<Ray> ray = screen_ray(session, ui, x, y);
    if (!ray)
        return;
    if (dragging) {
        if (!left) {
            session.drag_end();
            dragging = false;
            return;
        }
        // The grabbed point follows the mouse in the plane through it that faces the camera.
        const DragSpring& d = *session.drag();
        const Vec3 n = normalized(ray->direction);
        const double t = dot(d.target - ray->origin, n);
        session.drag_to(ray->origin + t * n);
        return;
    }
    if (io.WantCaptureMouse)
        return;
    if (left) {
        if (const std::optional<PickHit> hit = session.pick(*ray)) {
            ui.select_body(hit->name);
            dragging = session.drag_begin(*ray).ok();
        }
    } else if (right) {
        ui.report(session.mould(*ray, k_mould_depth, k_mould_steps));
    }
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
    GLFWwindow* window = glfwCreateWindow(ui.width(), ui.height(), "supermodal-editor", nullptr, nullptr);
    if (window == nullptr) {
        glfwTerminate();
        why.message = "no OpenGL ES 3.0 window could be created through EGL";
    }
    return window;
}

// The window's loop until it is closed: the scene rendered offscreen, shown behind ImGui's windows,
// and the mouse. ImGui's GLFW and GL back ends live as long as the loop.
void window_loop(GLFWwindow* window, Renderer& renderer, EditorSession& session, EditorUi& ui)
{
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    ImGui::SetCurrentContext(ui.context());
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 300 es");
    ui.synthetic_mouse = false;
    auto view = std::make_unique<ViewTexture>(); // its GL objects go before the context does
    Image image;
    bool dragging = false, right_was_down = false;
    ui.before_frame = [] {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
    };
    ui.after_render = [&] {
        int fw = 1, fh = 1;
        glfwGetFramebufferSize(window, &fw, &fh);
        glViewport(0, 0, fw, fh);
        view->blit(fw, fh);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    };
    double last = glfwGetTime();
    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        if (session.has_world()) {
            apply_scene_looks(renderer, session.scene(), session.world());
            ui.report(renderer.render(session.world(), editor_camera(session, ui), image,
                                      PoseSource::Interpolated));
        }
        glfwMakeContextCurrent(window); // the renderer made its own context current
        if (!image.rgba.empty())
            view->upload(image);
        handle_mouse(window, session, ui, dragging, right_was_down);
        const double now = glfwGetTime();
        ui.frame(now - last);
        last = now;
        glfwSwapBuffers(window);
    }
    ui.before_frame = nullptr;
    ui.after_render = nullptr;
    view.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
}

} // namespace

int run_window(EditorSession& session, EditorUi& ui, WindowUnavailable& why)
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
    window_loop(window, *renderer, session, ui);
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}
#else
int run_window(EditorSession&, EditorUi&, WindowUnavailable& why)
{
    why.message = display_available() ? "this build has no window support (GLFW and the renderer)"
                                      : "no display ($DISPLAY and $WAYLAND_DISPLAY are unset)";
    return 2;
}
#endif

} // namespace supermodal::editor
