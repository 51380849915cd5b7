// SPDX-License-Identifier: MIT
// Screenshots through the offscreen EGL renderer (supermodal_render). The 3-D view only for now: the
// ImGui windows are not yet drawn into the image (that needs ImGui's GLES backend in the renderer's
// context, see docs/editor.md). Without the renderer, a clear error.
#include "render_hook.h"

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
#include "supermodal/body.h"
#include "supermodal/render.h"
#endif

namespace supermodal::editor
{

#ifdef SUPERMODAL_EDITOR_HAS_RENDER
Status render_screenshot(const EditorSession& session, EditorUi&, const std::string& png_path, int width,
                         int height)
{
    if (!session.has_world())
        return Error{png_path, "", "cannot write a screenshot: no scene is loaded"};
    RenderDef def = default_render_def();
    def.width = width;
    def.height = height;
    if (Status ok = validate(def); !ok.ok())
        return Error{png_path, "size", ok.error().what};
    Result<Renderer> renderer = Renderer::create(def);
    if (!renderer)
        return Error{png_path, "", "cannot write a screenshot: " + renderer.error().message()};
    const World& world = session.world();
    const std::vector<Vec3> colors = scene_body_colors(session.scene());
    const std::vector<Entity> bodies = world_bodies(world);
    for (size_t i = 0; i < bodies.size() && i < colors.size(); ++i)
        renderer->set_body_color(bodies[i], colors[i]);
    Image image;
    if (Status ok = renderer->render(world, session.scene().camera, image, PoseSource::Interpolated);
        !ok.ok())
        return Error{png_path, "", "cannot write a screenshot: " + ok.error().message()};
    return write_png(png_path, image);
}
#else
Status render_screenshot(const EditorSession&, EditorUi&, const std::string& png_path, int, int)
{
    return Error{
        png_path, "",
        "cannot write a screenshot: this build has no renderer (configure with SUPERMODAL_RENDER=ON)"};
}
#endif

} // namespace supermodal::editor
