// SPDX-License-Identifier: MIT
// The ImGui context of the editor, frames without a graphics backend, and pressing widgets by label.
#include "ui.h"

#include <algorithm>
#include <cfloat>
#include <imgui.h>

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
    // NewFrame needs a built atlas; a renderer uploads these pixels later, headless runs never do.
    unsigned char* pixels = nullptr;
    int atlas_w = 0, atlas_h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &atlas_w, &atlas_h);
    ImGui::StyleColorsDark();
    m_mouse_x = m_mouse_y = -FLT_MAX;
    if (previous != nullptr)
        ImGui::SetCurrentContext(previous);
}

EditorUi::~EditorUi()
{
    ImGui::DestroyContext(m_context);
}

void EditorUi::set_mouse(float x, float y, bool left_down)
{
    m_mouse_x = x;
    m_mouse_y = y;
    m_mouse_down = left_down;
}

void EditorUi::frame(double real_seconds)
{
    ImGui::SetCurrentContext(m_context);
    ImGuiIO& io = ImGui::GetIO();
    if (before_frame)
        before_frame();
    io.DeltaTime = static_cast<float>(std::max(real_seconds, k_min_ui_delta));
    if (synthetic_mouse) {
        io.MousePos = ImVec2(m_mouse_x, m_mouse_y);
        io.MouseDown[0] = m_mouse_down;
    }
    m_widgets.clear();
    ImGui::NewFrame();
    speed_accuracy = SpeedAccuracyReadout{};
    if (show_windows) {
        draw_scene_tree(*this);
        draw_body_window(*this);
        draw_controls(*this);
        draw_speed_accuracy(*this);
    }
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
    const bool was_synthetic = synthetic_mouse;
    synthetic_mouse = true;
    // Hover, press, release: ImGui buttons fire on the release over the item they were pressed on.
    // Zero seconds per frame, so a running simulation does not move while the mouse works.
    set_mouse(x, y, false);
    frame(0.0);
    set_mouse(x, y, true);
    frame(0.0);
    set_mouse(x, y, false);
    frame(0.0);
    set_mouse(-FLT_MAX, -FLT_MAX, false);
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
