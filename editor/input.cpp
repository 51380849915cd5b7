// SPDX-License-Identifier: MIT
#include "input.h"

#include "render_hook.h"
#include "ui.h"

#include <array>
#include <imgui.h>
#include <utility>

namespace supermodal::editor
{
namespace
{

// Moulding depth of a right click [m] and its duration [steps].
constexpr double k_mould_depth = 0.005;
constexpr int k_mould_steps = 200;

constexpr std::array<std::pair<const char*, EditorKey>, 9> k_key_names = {{
    {"tab", EditorKey::Tab},
    {"space", EditorKey::Space},
    {"escape", EditorKey::Escape},
    {"enter", EditorKey::Enter},
    {"backspace", EditorKey::Backspace},
    {"left", EditorKey::Left},
    {"right", EditorKey::Right},
    {"up", EditorKey::Up},
    {"down", EditorKey::Down},
}};

} // namespace

std::optional<EditorKey> key_from_name(const std::string& name)
{
    for (const auto& [n, k] : k_key_names)
        if (name == n)
            return k;
    return std::nullopt;
}

std::string key_names()
{
    std::string out;
    for (const auto& [n, k] : k_key_names)
        out += (out.empty() ? "" : ", ") + std::string(n);
    return out;
}

void ViewInput::cursor(double x, double y)
{
    m_x = x;
    m_y = y;
}

void ViewInput::button(MouseButton b, bool down)
{
    if (b == MouseButton::Left) {
        m_left = down;
    } else {
        m_right_pressed = m_right_pressed || (down && !m_right); // one finger per press
        m_right = down;
    }
}

void ViewInput::key(EditorKey k, EditorUi& ui)
{
    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(ui.context());
    const bool typing = ImGui::GetIO().WantTextInput;
    ImGui::SetCurrentContext(previous);
    if (typing)
        return;
    EditorSession& session = ui.session();
    switch (k) {
    case EditorKey::Tab:
        ui.show_windows = !ui.show_windows;
        break;
    case EditorKey::Space:
        if (session.playing())
            session.pause();
        else
            session.play();
        break;
    case EditorKey::Escape:
        if (m_dragging) {
            session.drag_end();
            m_dragging = false;
        }
        break;
    default:
        break;
    }
}

void ViewInput::act(EditorSession& session, EditorUi& ui, bool imgui_wants_mouse)
{
    const bool mould = std::exchange(m_right_pressed, false);
    if (!session.has_world())
        return;
    Result<Ray> ray = screen_ray(session, ui, m_x, m_y);
    if (!ray)
        return;
    if (m_dragging) {
        if (!m_left) {
            session.drag_end();
            m_dragging = false;
            return;
        }
        // The grabbed point follows the mouse in the plane through it that faces the camera.
        const DragSpring& d = *session.drag();
        const Vec3 n = normalized(ray->direction);
        const double t = dot(d.target - ray->origin, n);
        session.drag_to(ray->origin + t * n);
        return;
    }
    if (imgui_wants_mouse)
        return;
    if (m_left) {
        if (const std::optional<PickHit> hit = session.pick(*ray)) {
            ui.select_body(hit->name);
            m_dragging = session.drag_begin(*ray).ok();
        }
    } else if (mould) {
        ui.report(session.mould(*ray, k_mould_depth, k_mould_steps));
    }
}

} // namespace supermodal::editor
