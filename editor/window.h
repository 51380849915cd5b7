// SPDX-License-Identifier: MIT
// The windowed editor: a GLFW window with an OpenGL ES 3 context (through EGL), the 3-D view drawn by the
// offscreen renderer and shown behind the ImGui windows, the mouse picking and dragging bodies.
#pragma once

#include "session.h"
#include "ui.h"

#include <ostream>
#include <string>

namespace supermodal::editor
{

/// Why run_window() did not run: the host falls back to --headless with this message.
struct WindowUnavailable {
    std::string message;
};

/// True when a display is there to open a window on ($DISPLAY or $WAYLAND_DISPLAY set).
[[nodiscard]] bool display_available();

/// What to do in the window besides letting the user work.
struct WindowRun {
    std::string script;          ///< Actions run in the window first, their events through its callbacks.
    std::string screenshot;      ///< After the script: the window's framebuffer as a PNG, then close.
    std::ostream* log = nullptr; ///< The script's per-action lines.
};

/// Opens a window of the UI's size, runs `run`, and then (without a screenshot) runs until it is closed.
/// The exit status: 0, 1 when a script's check failed, 2 for a bad script or screenshot; or 2 with
/// `why` filled in when no window could be opened (no display, no GLFW, no GL ES 3 context).
int run_window(EditorSession& session, EditorUi& ui, const WindowRun& run, WindowUnavailable& why);

} // namespace supermodal::editor
