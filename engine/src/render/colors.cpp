// SPDX-License-Identifier: MIT
// A scene's look for the renderer: body colours (scene_body_colors) and render meshes.
#include "supermodal/render.h"

namespace supermodal
{

void apply_scene_looks(Renderer& renderer, const Scene& scene, const World& world)
{
    const std::vector<Vec3> colors = scene_body_colors(scene);
    const std::vector<Entity> bodies = world_bodies(world);
    for (size_t i = 0; i < bodies.size() && i < colors.size(); ++i) {
        renderer.set_body_color(bodies[i], colors[i]);
        if (scene.bodies[i].render_mesh)
            renderer.set_body_mesh(bodies[i], scene.bodies[i].render_mesh);
    }
}

} // namespace supermodal
