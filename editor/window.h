// SPDX-License-Identifier: MIT
// The windowed editor: a GLFW window with an OpenGL ES 3 context (through EGL), the 3-D view drawn by the
// offscreen renderer and shown behind the ImGui windows, the mouse picking and dragging bodies.
#pragma once

#include "session.h"
#include "ui.h"

namespace supermodal::editor
{

/// Why run_window() did not run: the host falls back to --headless with this message.
struct WindowUnavailable {
    std::string message;
};

/// True when a display is there to open a window on ($DISPLAY or $WAYLAND_DISPLAY set).
[[nodiscard]] bool display_available();

/// Opens a window of the UI's size and runs until it is closed; returns the exit status (0), or fills
/// `why` and returns 2 when no window could be opened (no display, no GLFW, no GL ES 3 context).
int run_window(EditorSession& session, EditorUi& ui, WindowUnavailable& why);

} // namespace supermodal::editor
