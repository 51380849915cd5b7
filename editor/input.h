// SPDX-License-Identifier: MIT
// Mouse and keyboard of the editor: what the 3-D view does with them (pick and drag with the left
// button, mould with the right, orbit, pan and zoom the camera, shortcut keys), and the events a host
// delivers. A window feeds GLFW's
// callbacks into these; a script feeds the same events, headless or through the window's callbacks.
#pragma once

#include "camera.h"
#include "session.h"

#include <functional>
#include <optional>
#include <span>
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
    Left, ///< Orbits left (arrows: orbit).
    Right,
    Up,
    Down,
    F,     ///< Frames the selected body (everything when none is selected).
    Home,  ///< Frames everything.
    Plus,  ///< Zooms in towards the view's centre.
    Minus, ///< Zooms out.
    W,     ///< Pans: the view moves up.
    A,     ///< Left.
    S,     ///< Down.
    D,     ///< Right.
    H,     ///< Shows or hides the shortcut list.
    F1,    ///< As H.
    Z,     ///< With Ctrl: undoes the last edit; with Ctrl + Shift: redoes it.
    Y,     ///< With Ctrl: redoes.
    G,     ///< The gizmo moves the selected body.
    R,     ///< The gizmo rotates it.
    E,     ///< The gizmo scales it.
    Q,     ///< No gizmo.
    N,     ///< Snapping on or off.
};
/// "tab", "space", ... (the enum's names in lower case); nothing for an unknown name.
[[nodiscard]] std::optional<EditorKey> key_from_name(const std::string& name);
/// The names key_from_name() knows, comma separated (for error messages).
[[nodiscard]] std::string key_names();

enum class MouseButton : uint8_t { Left, Right, Middle };

/// Modifier keys held with a button or key, a bit set.
enum KeyMods : uint8_t {
    k_mod_none = 0,
    k_mod_shift = 1,
    k_mod_ctrl = 2,
    k_mod_alt = 4,
};

/// One line of the shortcut list (the help overlay and docs/editor.md show the same).
struct Shortcut {
    const char* input; ///< "Middle drag", "Shift + middle drag", "F".
    const char* does;  ///< "orbits the camera about its target".
};
/// Every mouse and key action of the editor, in the order the help overlay lists them.
[[nodiscard]] std::span<const Shortcut> shortcuts();

/// What the 3-D view does with the pointer and the keys. The host reports events as they come
/// (window pixels, top-left origin); act() runs once per frame, after the UI frame decided whether
/// ImGui wants the mouse.
class ViewInput
{
  public:
    void cursor(double x, double y);
    void button(MouseButton b, bool down, uint8_t mods = k_mod_none);
    /// Wheel notches (positive: away from the user, zooming in), acted on in the next act().
    void scroll(double notches);
    /// A key press (not its release): shortcuts act at once unless ImGui is typing.
    void key(EditorKey k, EditorUi& ui, uint8_t mods = k_mod_none);
    /// How far gestures and keys move the camera.
    CameraControlDef control;
    /// Picks, drags or moulds from the pointer's state. `imgui_wants_mouse`: the pointer is over a
    /// panel, so a press there is ImGui's.
    void act(EditorSession& session, EditorUi& ui, bool imgui_wants_mouse);

    [[nodiscard]] double x() const { return m_x; }
    [[nodiscard]] double y() const { return m_y; }
    [[nodiscard]] bool left() const { return m_left; }
    [[nodiscard]] bool dragging() const { return m_dragging; }
    /// What a held button is doing to the camera.
    enum class Gesture : uint8_t { None, Orbit, Pan };
    [[nodiscard]] Gesture gesture() const { return m_gesture; }

  private:
    void camera_gesture(EditorSession& session, EditorUi& ui);
    void zoom_at_cursor(EditorSession& session, EditorUi& ui, double notches);

    double m_x = -1.0, m_y = -1.0;
    bool m_left = false, m_right = false, m_middle = false, m_right_pressed = false;
    bool m_dragging = false;
    uint8_t m_left_mods = k_mod_none, m_middle_mods = k_mod_none; ///< Held when the button went down.
    bool m_left_pressed = false, m_middle_pressed = false;        ///< Went down since the last act().
    double m_wheel = 0.0;                                         ///< Notches since the last act().
    Gesture m_gesture = Gesture::None;
    MouseButton m_gesture_button = MouseButton::Middle;
    double m_last_x = 0.0, m_last_y = 0.0; ///< Cursor when the gesture last moved the camera [px].
};

/// The events of a host, as a script sends them: a window routes them through its GLFW callbacks,
/// a headless run straight to the UI and its ViewInput. Empty functions are skipped.
struct InputEvents {
    std::function<void(double x, double y)> cursor; ///< The pointer moved [window px].
    std::function<void(MouseButton, bool down, uint8_t mods)> button;
    std::function<void(double notches)> scroll; ///< The wheel turned (positive: away from the user).
    std::function<void(EditorKey, bool down, uint8_t mods)> key;
    std::function<void(int width, int height)> resize; ///< The display's new size [px] (a window resized).
    std::function<void(double seconds)> frame;         ///< One frame of the host: the UI, the view, input.
};

} // namespace supermodal::editor
