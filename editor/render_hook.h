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
#include <vector>

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
/// GL textures of the Parts panel's thumbnails in the current GL context, for ImGui's draw commands.
class ThumbnailTextures
{
  public:
    /// Uploads the library's thumbnails when they changed (a new scan, newly drawn ones).
    void update(const PartsLibrary& library);
    /// Points each draw command that shows a thumbnail at its texture (ImGui's OpenGL backend takes
    /// ImTextureID as a GL name); with a `font`, every other command at the font atlas.
    void bind(void* draw_data, void* font) const;
    /// Deletes the textures (their context current).
    void release();

  private:
    std::vector<unsigned> m_textures; ///< GL names, 0 for a part without a thumbnail.
    uint64_t m_generation = 0;
    size_t m_uploaded = 0; ///< Thumbnails with pixels when last uploaded.
};

/// The screenshot's pixels (see render_screenshot).
[[nodiscard]] Result<Image> render_editor_image(const EditorSession& session, EditorUi& ui, int width,
                                                int height);
#endif

} // namespace supermodal::editor
