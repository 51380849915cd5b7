// SPDX-License-Identifier: MIT
// Screenshots through the offscreen EGL renderer (supermodal_render), with the ImGui windows drawn over
// the 3-D view by ImGui's OpenGL ES 3 backend (compiled from libimgui-dev's backend sources) in the
// renderer's own context. Without the renderer, a clear error.
#include "render_hook.h"

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
#include "supermodal/body.h"

#include <GLES3/gl3.h>
#include <algorithm>
#include <cmath>
#include <imgui.h>
#include <imgui_impl_opengl3.h>
#endif

namespace supermodal::editor
{

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
namespace
{

size_t thumbnails_drawn(const PartsLibrary& library)
{
    size_t n = 0;
    for (const PartEntry& e : library.entries())
        n += e.width > 0 ? 1 : 0;
    return n;
}

} // namespace

void ThumbnailTextures::update(const PartsLibrary& library)
{
    const size_t drawn = thumbnails_drawn(library);
    if (library.generation() == m_generation && drawn == m_uploaded && !m_textures.empty())
        return;
    release();
    for (const PartEntry& e : library.entries()) {
        GLuint t = 0;
        if (e.width > 0) {
            glGenTextures(1, &t);
            glBindTexture(GL_TEXTURE_2D, t);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, e.width, e.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                         e.rgba.data());
        }
        m_textures.push_back(t);
    }
    m_generation = library.generation();
    m_uploaded = drawn;
}

void ThumbnailTextures::bind(void* draw_data, void* font) const
{
    ImDrawData& data = *static_cast<ImDrawData*>(draw_data);
    for (int i = 0; i < data.CmdListsCount; ++i)
        for (ImDrawCmd& cmd : data.CmdLists[i]->CmdBuffer) {
            const int k = thumbnail_index(cmd.TextureId, m_textures.size());
            if (k >= 0)
                cmd.TextureId = reinterpret_cast<ImTextureID>(static_cast<intptr_t>(m_textures[k]));
            else if (font != nullptr)
                cmd.TextureId = font; // drawn headless (texture 0) or for an earlier screenshot's atlas
        }
}

void ThumbnailTextures::release()
{
    for (unsigned t : m_textures)
        if (t != 0)
            glDeleteTextures(1, &t);
    m_textures.clear();
    m_uploaded = 0;
}

PixelRect view_rect(const EditorUi& ui, int width, int height)
{
    const ScreenRect& v = ui.viewport();
    const double sx = static_cast<double>(width) / ui.width(), sy = static_cast<double>(height) / ui.height();
    PixelRect r;
    r.x = std::clamp(static_cast<int>(std::lround(v.x0 * sx)), 0, width - 1);
    r.y = std::clamp(static_cast<int>(std::lround(v.y0 * sy)), 0, height - 1);
    r.width = std::clamp(static_cast<int>(std::lround(v.x1 * sx)), r.x + 1, width) - r.x;
    r.height = std::clamp(static_cast<int>(std::lround(v.y1 * sy)), r.y + 1, height) - r.y;
    return r;
}

std::optional<std::array<double, 2>> screen_pixel(const EditorSession& session, EditorUi& ui,
                                                  const Vec3& point)
{
    const PixelRect r = view_rect(ui, ui.width(), ui.height());
    std::optional<std::array<double, 2>> p =
        project_to_pixel(session.world(), editor_camera(session, ui), r.width, r.height, point);
    if (p) {
        (*p)[0] += r.x;
        (*p)[1] += r.y;
    }
    return p;
}

Result<Image> render_editor_image(const EditorSession& session, EditorUi& ui, int width, int height)
{
    if (!session.has_world())
        return Error{"", "", "cannot draw the editor: no scene is loaded"};
    RenderDef def = default_render_def();
    def.width = width;
    def.height = height;
    if (Status ok = validate(def); !ok.ok())
        return Error{"", "size", ok.error().what};
    Result<Renderer> renderer = Renderer::create(def); // its context is current from here on
    if (!renderer)
        return Error{"", "", "cannot draw the editor: " + renderer.error().message()};
    const World& world = session.world();
    apply_scene_looks(*renderer, session.scene(), world);

    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGui::SetCurrentContext(ui.context());
    ImDrawData* data = ImGui::GetDrawData(); // the last frame's (ui.frame())
    bool backend = false;
    std::string backend_error;
    ThumbnailTextures thumbnails;
    const auto overlay = [&] {
        if (data == nullptr || !data->Valid)
            return;
        if (!ImGui_ImplOpenGL3_Init("#version 300 es")) {
            backend_error = "ImGui's OpenGL ES 3 backend did not start";
            return;
        }
        backend = true;
        ImGui_ImplOpenGL3_NewFrame(); // uploads the font atlas, sets io.Fonts->TexID
        thumbnails.update(ui.parts_library);
        thumbnails.bind(data, ImGui::GetIO().Fonts->TexID);
        // The UI was laid out for its display; scale it onto this image.
        data->FramebufferScale = ImVec2(static_cast<float>(width) / data->DisplaySize.x,
                                        static_cast<float>(height) / data->DisplaySize.y);
        ImGui_ImplOpenGL3_RenderDrawData(data);
        thumbnails.release();
    };
    Image image;
    Status drawn = renderer->render(world, editor_camera(session, ui), image, PoseSource::Interpolated,
                                    overlay, view_rect(ui, width, height));
    if (backend) {
        // Back to a headless atlas: draw commands of later frames get texture 0 again.
        ImGui_ImplOpenGL3_Shutdown();
        ImGui::GetIO().Fonts->SetTexID(ImTextureID{});
    }
    ImGui::SetCurrentContext(previous);
    if (!backend_error.empty())
        return Error{"", "", "cannot draw the editor: " + backend_error};
    if (!drawn)
        return Error{"", "", "cannot draw the editor: " + drawn.error().message()};
    return image;
}

Status render_screenshot(const EditorSession& session, EditorUi& ui, const std::string& png_path, int width,
                         int height)
{
    Result<Image> image = render_editor_image(session, ui, width, height);
    if (!image)
        return Error{png_path, image.error().where, "cannot write a screenshot: " + image.error().what};
    return write_png(png_path, *image);
}

Result<Ray> screen_ray(const EditorSession& session, EditorUi& ui, double x, double y)
{
    if (!session.has_world())
        return Error{"", "", "no scene is loaded"};
    const PixelRect v = view_rect(ui, ui.width(), ui.height());
    const CameraRay r =
        camera_ray(session.world(), editor_camera(session, ui), v.width, v.height, x - v.x, y - v.y);
    return Ray{r.origin, r.direction};
}
#else
Status render_screenshot(const EditorSession&, EditorUi&, const std::string& png_path, int, int)
{
    return Error{
        png_path, "",
        "cannot write a screenshot: this build has no renderer (configure with SUPERMODAL_RENDER=ON)"};
}

std::optional<std::array<double, 2>> screen_pixel(const EditorSession&, EditorUi&, const Vec3&)
{
    return std::nullopt;
}

Result<Ray> screen_ray(const EditorSession&, EditorUi&, double, double)
{
    return Error{"", "",
                 "rays through pixels need the renderer's camera (configure with SUPERMODAL_RENDER=ON)"};
}
#endif

} // namespace supermodal::editor
