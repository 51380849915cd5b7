// SPDX-License-Identifier: MIT
// The one place where the editor meets the renderer (issue #8 item 1, engine/src/render). Until the
// renderer is linked, render_screenshot() says so and fails; the lead replaces render_hook.cpp.
#pragma once

#include "session.h"
#include "ui.h"

#include <string>

namespace supermodal::editor
{

/// Draws the session's world (interpolated poses, deformed modal surfaces) and the UI's last frame
/// (ImGui::GetDrawData() of ui.context()) offscreen at width × height pixels and writes a PNG.
[[nodiscard]] Status render_screenshot(const EditorSession& session, EditorUi& ui,
                                       const std::string& png_path, int width, int height);

} // namespace supermodal::editor
