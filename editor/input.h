// SPDX-License-Identifier: MIT
// Mouse and keyboard of the editor: what the 3-D view does with them (pick and drag with the left
// button, mould with the right, shortcut keys), and the events a host delivers. A window feeds GLFW's
// callbacks into these; a script feeds the same events, headless or through the window's callbacks.
#pragma once

#include "session.h"

#include <functional>
#include <optional>
#include <string>

namespace supermodal::editor
{

class EditorUi;

/// The keys the editor reacts to (or hands to ImGui), independent of the window library.
enum class EditorKey : uint8_t {
    Tab,    ///< Hides or shows the panels.
    Space,  ///< Plays or pauses.
    Escape, ///< Ends a drag.
    Enter,
    Backspace,
    Left,
    Right,
    Up,
    Down,
};
/// "tab", "space", ... (the enum's names in lower case); nothing for an unknown name.
[[nodiscard]] std::optional<EditorKey> key_from_name(const std::string& name);
/// The names key_from_name() knows, comma separated (for error messages).
[[nodiscard]] std::string key_names();

enum class MouseButton : uint8_t { Left, Right };

/// What the 3-D view does with the pointer and the keys. The host reports events as they come
/// (window pixels, top-left origin); act() runs once per frame, after the UI frame decided whether
/// ImGui wants the mouse.
class ViewInput
{
  public:
    void cursor(double x, double y);
    void button(MouseButton b, bool down);
    /// A key press (not its release): shortcuts act at once unless ImGui is typing.
    void key(EditorKey k, EditorUi& ui);
    /// Picks, drags or moulds from the pointer's state. `imgui_wants_mouse`: the pointer is over a
    /// panel, so a press there is ImGui's.
    void act(EditorSession& session, EditorUi& ui, bool imgui_wants_mouse);

    [[nodiscard]] double x() const { return m_x; }
    [[nodiscard]] double y() const { return m_y; }
    [[nodiscard]] bool left() const { return m_left; }
    [[nodiscard]] bool dragging() const { return m_dragging; }

  private:
    double m_x = -1.0, m_y = -1.0;
    bool m_left = false, m_right = false, m_right_pressed = false;
    bool m_dragging = false;
};

/// The events of a host, as a script sends them: a window routes them through its GLFW callbacks,
/// a headless run straight to the UI and its ViewInput. Empty functions are skipped.
struct InputEvents {
    std::function<void(double x, double y)> cursor; ///< The pointer moved [window px].
    std::function<void(MouseButton, bool down)> button;
    std::function<void(EditorKey, bool down)> key;
    std::function<void(double seconds)> frame; ///< One frame of the host: the UI, the view, input.
};

} // namespace supermodal::editor
