// SPDX-License-Identifier: MIT
// The ImGui context of the editor, frames without a graphics backend, and pressing widgets by label.
#include "ui.h"

#include <algorithm>
#include <cfloat>
#include <imgui.h>
#include <imgui_internal.h>

namespace supermodal::editor
{
namespace
{

/// ImGui wants a positive frame time even when the simulation should not move (widget presses) [s].
constexpr double k_min_ui_delta = 1e-3;

std::string visible_part(const std::string& label)
{
    const size_t hash = label.find("##");
    return hash == std::string::npos ? label : label.substr(0, hash);
}

} // namespace

EditorUi::EditorUi(EditorSession& session, int width, int height) : m_session(session)
{
    IMGUI_CHECKVERSION();
    m_width = std::max(width, 1);
    m_height = std::max(height, 1);
    ImGuiContext* previous = ImGui::GetCurrentContext();
    m_context = ImGui::CreateContext();
    ImGui::SetCurrentContext(m_context);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // window layout is not saved next to whatever the working folder is
    io.LogFilename = nullptr;
    io.DisplaySize = ImVec2(static_cast<float>(m_width), static_cast<float>(m_height));
    const PanelLayout docked = panel_layout(io.DisplaySize.x, io.DisplaySize.y);
    m_viewport = {docked.scene.x1, 0, docked.body.x0, io.DisplaySize.y}; // until a frame says otherwise
    // NewFrame needs a built atlas; a renderer uploads these pixels later, headless runs never do.
    unsigned char* pixels = nullptr;
    int atlas_w = 0, atlas_h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &atlas_w, &atlas_h);
    ImGui::StyleColorsDark();
    m_mouse_x = m_mouse_y = -FLT_MAX;
    headless_input();
    if (previous != nullptr)
        ImGui::SetCurrentContext(previous);
}

EditorUi::~EditorUi()
{
    ImGui::DestroyContext(m_context);
}

void EditorUi::resize(int width, int height)
{
    m_width = std::max(width, 1);
    m_height = std::max(height, 1);
    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(m_context);
    ImGui::GetIO().DisplaySize = ImVec2(static_cast<float>(m_width), static_cast<float>(m_height));
    ImGui::SetCurrentContext(previous);
}

void EditorUi::set_scale(float scale)
{
    m_scale = std::clamp(scale, 0.5f, 4.0f);
    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(m_context);
    // From the unscaled style each time, so that scales do not compound.
    ImGuiStyle style;
    ImGui::StyleColorsDark(&style);
    style.ScaleAllSizes(m_scale);
    ImGui::GetStyle() = style;
    // The atlas's 13 px font drawn larger: a little soft, with no atlas to rebuild and re-upload.
    ImGui::GetIO().FontGlobalScale = m_scale;
    ImGui::SetCurrentContext(previous);
}

void EditorUi::set_mouse(float x, float y, bool left_down)
{
    m_mouse_x = x;
    m_mouse_y = y;
    m_mouse_down = left_down;
}

void EditorUi::headless_input()
{
    input.cursor = [this](double x, double y) { on_cursor(x, y); };
    input.button = [this](MouseButton b, bool down, uint8_t mods) { on_button(b, down, mods); };
    input.scroll = [this](double notches) {
        ImGui::SetCurrentContext(m_context);
        ImGui::GetIO().MouseWheel += static_cast<float>(notches); // a window's ImGui backend does this
        on_scroll(notches);
    };
    input.key = [this](EditorKey k, bool down, uint8_t mods) { on_key(k, down, mods); };
    input.resize = [this](int w, int h) { resize(w, h); };
    input.frame = [this](double seconds) {
        frame(seconds);
        ImGui::SetCurrentContext(m_context);
        view_input.act(m_session, *this, ImGui::GetIO().WantCaptureMouse);
    };
}

void EditorUi::on_cursor(double x, double y)
{
    set_mouse(static_cast<float>(x), static_cast<float>(y), m_mouse_down);
    view_input.cursor(x, y);
}

void EditorUi::on_button(MouseButton b, bool down, uint8_t mods)
{
    if (b == MouseButton::Left)
        m_mouse_down = down;
    else if (b == MouseButton::Right)
        m_mouse_right = down;
    view_input.button(b, down, mods);
}

void EditorUi::on_scroll(double notches)
{
    view_input.scroll(notches);
}

void EditorUi::on_key(EditorKey k, bool down, uint8_t mods)
{
    if (down)
        view_input.key(k, *this, mods);
}

void EditorUi::host_frame(double real_seconds)
{
    if (input.frame)
        input.frame(real_seconds);
    else
        frame(real_seconds);
}

void EditorUi::frame(double real_seconds)
{
    ImGui::SetCurrentContext(m_context);
    ImGuiIO& io = ImGui::GetIO();
    if (parts.render_in_frame && parts_library.pending())
        parts_library.render_pending(); // before the frame: a renderer of its own, once per part
    ImGui::SetCurrentContext(m_context);
    if (before_frame)
        before_frame();
    io.DeltaTime = static_cast<float>(std::max(real_seconds, k_min_ui_delta));
    if (synthetic_mouse) {
        io.MousePos = ImVec2(m_mouse_x, m_mouse_y);
        io.MouseDown[0] = m_mouse_down;
        io.MouseDown[1] = m_mouse_right;
    }
    m_widgets.clear();
    ImGui::NewFrame();
    speed_accuracy = SpeedAccuracyReadout{};
    if (show_windows) {
        draw_scene_tree(*this);
        draw_parts(*this);
        draw_body_window(*this);
        draw_controls(*this);
        draw_speed_accuracy(*this);
    }
    update_viewport();
    draw_gizmo(*this);
    help_lines.clear();
    if (show_help)
        draw_help(*this); // over the view, after the view's rectangle is known
    ImGui::Render();
    if (after_render)
        after_render();
    m_session.frame(real_seconds);
}

void EditorUi::track(const char* label)
{
    const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
    m_widgets.push_back({label, min.x, min.y, max.x, max.y, ImGui::IsItemVisible()});
}

Status EditorUi::press(const std::string& label)
{
    if (m_widgets.empty())
        frame(0.0);
    const auto find = [&](bool exact) {
        std::vector<const WidgetRect*> found;
        for (const WidgetRect& w : m_widgets)
            if (w.visible && (exact ? w.label == label : visible_part(w.label) == label))
                found.push_back(&w);
        return found;
    };
    std::vector<const WidgetRect*> found = find(true);
    if (found.empty())
        found = find(false);
    if (found.size() != 1) {
        std::string labels;
        for (const WidgetRect& w : m_widgets)
            if (w.visible)
                labels += (labels.empty() ? "" : ", ") + w.label;
        return Error{"", "",
                     (found.empty() ? "no visible widget labelled \"" : "more than one widget labelled \"") +
                         label + "\"; widgets are: " + labels};
    }
    const float x = 0.5f * (found[0]->min_x + found[0]->max_x),
                y = 0.5f * (found[0]->min_y + found[0]->max_y);
    // Hover, press, release through the host's events (a window's GLFW callbacks): ImGui buttons fire
    // on the release over the item they were pressed on. Zero seconds per frame, so a running
    // simulation does not move while the mouse works.
    const bool was_synthetic = synthetic_mouse;
    synthetic_mouse = true;
    input.cursor(x, y);
    host_frame(0.0);
    input.button(MouseButton::Left, true, k_mod_none);
    host_frame(0.0);
    input.button(MouseButton::Left, false, k_mod_none);
    host_frame(0.0);
    input.cursor(-FLT_MAX, -FLT_MAX);
    synthetic_mouse = was_synthetic;
    return {};
}

void EditorUi::report(const Status& status)
{
    m_last_error = status ? std::string() : status.error().message();
}

void EditorUi::apply(const std::string& path, const Json& value)
{
    report(m_session.set(path, value));
}

} // namespace supermodal::editor

namespace supermodal::editor
{

PanelLayout panel_layout(float w, float h, float scale)
{
    // Columns a sixth and a fifth of the width, within what their widgets need: 211 + 269 px at 1280,
    // which leaves the view 800 px of 1280 (62.5%). Run is as tall as its widgets.
    const float s = std::clamp(scale, 0.5f, 4.0f);
    const float left = std::clamp(0.165f * w, 180.0f * s, 300.0f * s);
    const float right = std::clamp(0.21f * w, 240.0f * s, 420.0f * s);
    const float run = std::min(150.0f * s, 0.4f * h);
    const float body = 0.55f * h;
    PanelLayout l;
    // Parts between Scene and Run: a third of what the column has left, two rows of thumbnails at most.
    const float parts = std::min(230.0f * s, (h - run) / 3.0f);
    l.scene = {0, 0, left, h - run - parts};
    l.parts = {0, h - run - parts, left, h - run};
    l.run = {0, h - run, left, h};
    l.body = {w - right, 0, w, body};
    l.speed = {w - right, body, w, h};
    return l;
}

float hidpi_ui_scale(float content_scale, int window_width, int framebuffer_width)
{
    if (window_width <= 0 || framebuffer_width <= 0 || !(content_scale > 0.0f))
        return 1.0f;
    const float applied = static_cast<float>(framebuffer_width) / static_cast<float>(window_width);
    return std::clamp(content_scale / applied, 0.5f, 4.0f);
}

void dock_next_window(const ScreenRect& r)
{
    ImGui::SetNextWindowPos(ImVec2(r.x0, r.y0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(r.width(), r.height()), ImGuiCond_Always);
}

void EditorUi::update_viewport()
{
    const float w = static_cast<float>(m_width), h = static_cast<float>(m_height);
    m_viewport = {0, 0, w, h};
    if (!show_windows)
        return;
    // Each expanded panel closes the view in from its side; a collapsed one is a title bar over it.
    for (const char* name : {"Scene", "Parts", "Run", "Body", "Speed / accuracy"}) {
        const ImGuiWindow* win = ImGui::FindWindowByName(name);
        if (win == nullptr || !win->Active || win->Collapsed)
            continue;
        if (win->Pos.x + 0.5f * win->Size.x < 0.5f * w)
            m_viewport.x0 = std::max(m_viewport.x0, std::min(win->Pos.x + win->Size.x, w));
        else
            m_viewport.x1 = std::min(m_viewport.x1, std::max(win->Pos.x, 0.0f));
    }
    m_viewport.x1 = std::max(m_viewport.x1, m_viewport.x0);
}

} // namespace supermodal::editor
