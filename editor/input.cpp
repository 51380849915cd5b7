// SPDX-License-Identifier: MIT
#include "input.h"

#include "render_hook.h"
#include "supermodal/body.h"
#include "ui.h"

#include <array>
#include <cmath>
#include <imgui.h>
#include <utility>

namespace supermodal::editor
{
namespace
{

// Moulding depth of a right click [m] and its duration [steps].
constexpr double k_mould_depth = 0.005;
constexpr int k_mould_steps = 200;

constexpr std::array<std::pair<const char*, EditorKey>, 26> k_key_names = {{
    {"tab", EditorKey::Tab},
    {"space", EditorKey::Space},
    {"escape", EditorKey::Escape},
    {"enter", EditorKey::Enter},
    {"backspace", EditorKey::Backspace},
    {"left", EditorKey::Left},
    {"right", EditorKey::Right},
    {"up", EditorKey::Up},
    {"down", EditorKey::Down},
    {"f", EditorKey::F},
    {"home", EditorKey::Home},
    {"plus", EditorKey::Plus},
    {"minus", EditorKey::Minus},
    {"w", EditorKey::W},
    {"a", EditorKey::A},
    {"s", EditorKey::S},
    {"d", EditorKey::D},
    {"h", EditorKey::H},
    {"f1", EditorKey::F1},
    {"z", EditorKey::Z},
    {"y", EditorKey::Y},
    {"g", EditorKey::G},
    {"r", EditorKey::R},
    {"e", EditorKey::E},
    {"q", EditorKey::Q},
    {"n", EditorKey::N},
}};

constexpr Shortcut k_shortcuts[] = {
    {"Left drag on a body", "selects it and pulls it with a spring"},
    {"Right click on a modal body", "moulds it 5 mm deep"},
    {"Middle drag, Alt + left drag", "orbits the camera about its target"},
    {"Shift + middle drag", "pans"},
    {"Wheel", "zooms towards the point under the cursor"},
    {"Arrows", "orbit 15 degrees"},
    {"+ / -", "zoom in / out"},
    {"W A S D", "pan up, left, down, right"},
    {"F", "frames the selected body (all without one)"},
    {"Home", "frames everything"},
    {"Space", "plays or pauses"},
    {"Tab", "hides or shows the panels"},
    {"Escape", "lets go of a dragged body; cancels a part to drop and Attach"},
    {"Ctrl + Z", "undoes the last edit"},
    {"Ctrl + Shift + Z, Ctrl + Y", "redoes it"},
    {"G / R / E", "gizmo: move / rotate / scale the selected body"},
    {"Q", "hides the gizmo (the left button pulls bodies again)"},
    {"Left drag on a gizmo handle", "moves along, turns about or scales one axis"},
    {"N", "snapping on or off (0.05 m, 15 degrees, 0.1 scale)"},
    {"Left drag from the Parts panel", "sets the part on the surface under the pointer"},
    {"H, F1", "shows or hides this list"},
};

/// The camera after a user's move: kept from now on, not re-framed when the view changes shape.
void set_camera(EditorUi& ui, const CameraDef& camera)
{
    ui.view_camera = camera;
    ui.view_moved = true;
}

double view_aspect(const EditorUi& ui)
{
    return static_cast<double>(ui.viewport().width()) / std::max(ui.viewport().height(), 1.0f);
}

/// Frames the selected body, or every body when none is selected (or it has no bounds: a plane).
CameraDef frame_selection(EditorSession& session, EditorUi& ui, const CameraDef& camera,
                          const CameraControlDef& control, bool everything)
{
    const World& world = session.world();
    std::optional<Aabb> box;
    if (!everything && !ui.selected_body().empty())
        box = body_box(world, find_body(world, ui.selected_body()));
    if (box)
        return frame_boxes(camera, std::span<const Aabb>(&*box, 1), view_aspect(ui), control.frame_margin);
    return frame_boxes(camera, body_boxes(world), view_aspect(ui), control.frame_margin);
}

/// The camera moved by a camera key; nothing for other keys.
std::optional<CameraDef> camera_key(EditorKey k, EditorSession& session, EditorUi& ui,
                                    const CameraControlDef& c)
{
    const CameraDef cam = editor_camera(session, ui);
    const double pan = c.pan_key_fraction * ui.viewport().height();
    const double h = ui.viewport().height();
    switch (k) {
    case EditorKey::Left:
        return orbit(cam, -c.orbit_key_deg, 0.0);
    case EditorKey::Right:
        return orbit(cam, c.orbit_key_deg, 0.0);
    case EditorKey::Up:
        return orbit(cam, 0.0, c.orbit_key_deg);
    case EditorKey::Down:
        return orbit(cam, 0.0, -c.orbit_key_deg);
    case EditorKey::Plus:
        return zoom_towards(cam, cam.target.value_or(Vec3{}), c.zoom_per_notch, c);
    case EditorKey::Minus:
        return zoom_towards(cam, cam.target.value_or(Vec3{}), 1.0 / c.zoom_per_notch, c);
    case EditorKey::W: // the view moves up: the scene down, as if the cursor had dragged it down
        return pan_pixels(cam, 0.0, pan, h);
    case EditorKey::S:
        return pan_pixels(cam, 0.0, -pan, h);
    case EditorKey::A:
        return pan_pixels(cam, pan, 0.0, h);
    case EditorKey::D:
        return pan_pixels(cam, -pan, 0.0, h);
    case EditorKey::F:
    case EditorKey::Home:
        return frame_selection(session, ui, cam, c, k == EditorKey::Home);
    default:
        return std::nullopt;
    }
}

} // namespace

std::span<const Shortcut> shortcuts()
{
    return k_shortcuts;
}

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

void ViewInput::button(MouseButton b, bool down, uint8_t mods)
{
    if (down) { // a gesture starting on this press moves the camera from here
        m_last_x = m_x;
        m_last_y = m_y;
    }
    switch (b) {
    case MouseButton::Left:
        m_left_pressed = m_left_pressed || (down && !m_left);
        m_left_mods = down ? mods : m_left_mods;
        m_left = down;
        break;
    case MouseButton::Right:
        m_right_pressed = m_right_pressed || (down && !m_right); // one finger per press
        m_right = down;
        break;
    case MouseButton::Middle:
        m_middle_pressed = m_middle_pressed || (down && !m_middle);
        m_middle_mods = down ? mods : m_middle_mods;
        m_middle = down;
        break;
    }
}

void ViewInput::scroll(double notches)
{
    if (std::isfinite(notches))
        m_wheel += notches;
}

void ViewInput::key(EditorKey k, EditorUi& ui, uint8_t mods)
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
    case EditorKey::G:
    case EditorKey::R:
    case EditorKey::E:
    case EditorKey::Q:
        ui.gizmo.mode = k == EditorKey::G   ? GizmoMode::Move
                        : k == EditorKey::R ? GizmoMode::Rotate
                        : k == EditorKey::E ? GizmoMode::Scale
                                            : GizmoMode::Off;
        ui.gizmo_drag.reset();
        break;
    case EditorKey::N:
        ui.gizmo.snap = !ui.gizmo.snap;
        break;
    case EditorKey::Escape:
        ui.gizmo_drag.reset();     // a gizmo drag is dropped: nothing applied
        ui.parts.carrying.clear(); // so is a part carried or armed, and Attach
        ui.parts.armed.clear();
        ui.parts.attach_armed = false;
        if (m_dragging) {
            session.drag_end();
            m_dragging = false;
        }
        break;
    case EditorKey::H:
    case EditorKey::F1:
        ui.show_help = !ui.show_help;
        break;
    case EditorKey::Z:
    case EditorKey::Y:
        if ((mods & k_mod_ctrl) != 0 && session.has_world()) {
            const bool redo = k == EditorKey::Y || (mods & k_mod_shift) != 0;
            ui.report(redo ? session.redo() : session.undo());
        }
        break;
    default:
        if (session.has_world())
            if (const std::optional<CameraDef> moved = camera_key(k, session, ui, control))
                set_camera(ui, *moved);
        break;
    }
}

void ViewInput::camera_gesture(EditorSession& session, EditorUi& ui)
{
    const bool held = m_gesture_button == MouseButton::Left ? m_left : m_middle;
    const double dx = m_x - m_last_x, dy = m_y - m_last_y;
    if (dx != 0.0 || dy != 0.0) {
        const CameraDef cam = editor_camera(session, ui);
        // Orbit as if the scene were grabbed: dragging right turns it right (the eye goes left),
        // dragging down tips its top towards the user (the eye goes up).
        set_camera(ui, m_gesture == Gesture::Orbit
                           ? orbit(cam, -control.orbit_deg_per_px * dx, control.orbit_deg_per_px * dy)
                           : pan_pixels(cam, dx, dy, ui.viewport().height()));
        m_last_x = m_x;
        m_last_y = m_y;
    }
    if (!held)
        m_gesture = Gesture::None;
}

void ViewInput::zoom_at_cursor(EditorSession& session, EditorUi& ui, double notches)
{
    const Result<Ray> ray = screen_ray(session, ui, m_x, m_y);
    if (!ray)
        return;
    const CameraDef cam = editor_camera(session, ui);
    const Vec3 dir = normalized(ray->direction);
    // The point under the cursor: the surface hit, else where the ray crosses the plane through the
    // target facing the camera; any point of the ray stays under the cursor, the cap only keeps a far
    // hit (the floor near the horizon) from flinging the eye.
    double t = control.zoom_depth_cap * cam.distance;
    if (const std::optional<PickHit> hit = session.pick(*ray))
        t = std::min(t, hit->distance);
    else if (const double facing = dot(dir, -camera_axes(cam).back); facing > 0.0)
        t = std::min(t, cam.distance / facing);
    set_camera(ui,
               zoom_towards(cam, ray->origin + t * dir, std::pow(control.zoom_per_notch, notches), control));
}

void ViewInput::act(EditorSession& session, EditorUi& ui, bool imgui_wants_mouse)
{
    const bool mould = std::exchange(m_right_pressed, false);
    const bool left_pressed = std::exchange(m_left_pressed, false);
    const bool middle_pressed = std::exchange(m_middle_pressed, false);
    const double wheel = std::exchange(m_wheel, 0.0);
    if (!session.has_world())
        return;
    if (m_gesture != Gesture::None) {
        camera_gesture(session, ui);
        return;
    }
    Result<Ray> ray = screen_ray(session, ui, m_x, m_y);
    if (!ray)
        return;
    if (parts_view_action(session, ui, *ray, left_pressed, m_left))
        return;
    if (ui.gizmo_drag) {
        gizmo_follow(session, ui, *ui.gizmo_drag, m_x, m_y);
        if (!m_left) { // released: the previewed transform becomes one undoable edit
            const GizmoDrag drag = *std::exchange(ui.gizmo_drag, std::nullopt);
            ui.report(session.transform(drag.body, drag.pending, ui.gizmo.steps));
        }
        return;
    }
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
    if (wheel != 0.0)
        zoom_at_cursor(session, ui, wheel);
    const bool alt_left = m_left && (m_left_mods & k_mod_alt) != 0;
    if ((middle_pressed && m_middle) || (left_pressed && alt_left)) {
        m_gesture_button = middle_pressed && m_middle ? MouseButton::Middle : MouseButton::Left;
        const bool shift = m_gesture_button == MouseButton::Middle && (m_middle_mods & k_mod_shift) != 0;
        m_gesture = shift ? Gesture::Pan : Gesture::Orbit;
        camera_gesture(session, ui);
        return;
    }
    if (left_pressed && m_left && !alt_left)
        if (std::optional<GizmoDrag> grabbed = gizmo_grab(session, ui, m_x, m_y)) {
            ui.gizmo_drag = std::move(grabbed);
            return;
        }
    if (m_left && !alt_left) {
        if (const std::optional<PickHit> hit = session.pick(*ray)) {
            ui.select_body(hit->name);
            m_dragging = session.drag_begin(*ray).ok();
        }
    } else if (mould) {
        ui.report(session.mould(*ray, k_mould_depth, k_mould_steps));
    }
}

} // namespace supermodal::editor
