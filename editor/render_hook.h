// SPDX-License-Identifier: MIT
// The one place where the editor meets the renderer (engine/src/render): screenshots of the 3-D view with
// the ImGui windows drawn over it, and rays through screen pixels for the mouse.
#pragma once

#include "camera.h"
#include "session.h"
#include "ui.h"

#include <array>
#include <optional>
#include <string>

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
#include "supermodal/render.h"
#endif

namespace supermodal::editor
{

/// Draws the session's world (interpolated poses, deformed modal surfaces) and the UI's last frame
/// (ImGui::GetDrawData() of ui.context(), scaled from the UI's display to the image) offscreen at
/// width × height pixels and writes a PNG. Call ui.frame() first.
[[nodiscard]] Status render_screenshot(const EditorSession& session, EditorUi& ui,
                                       const std::string& png_path, int width, int height);

/// The world ray through pixel (x, y) of the UI's display (top-left origin, y down) [px], seen by the
/// camera of the 3-D view (ui.viewport()) as the screenshot draws it. Fails without the renderer or a
/// loaded scene.
[[nodiscard]] Result<Ray> screen_ray(const EditorSession& session, EditorUi& ui, double x, double y);

/// Where a world point [m] lands on the UI's display [px] (inverse of screen_ray); nothing behind the eye
/// or without the renderer.
[[nodiscard]] std::optional<std::array<double, 2>> screen_pixel(const EditorSession& session, EditorUi& ui,
                                                                const Vec3& point);

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
/// The 3-D view's rectangle in an image of width × height showing the UI's display (scaled).
[[nodiscard]] PixelRect view_rect(const EditorUi& ui, int width, int height);
/// The screenshot's pixels (see render_screenshot).
[[nodiscard]] Result<Image> render_editor_image(const EditorSession& session, EditorUi& ui, int width,
                                                int height);
#endif

} // namespace supermodal::editor
