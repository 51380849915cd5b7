// SPDX-License-Identifier: MIT
// A host that draws: load a scene, step it half a second, render one frame offscreen, write a PNG.
#include <cstdio>
#include <supermodal/render.h>
#include <supermodal/scene.h>
#include <supermodal/world.h>

int main(int argc, char** argv)
{
    namespace sm = supermodal;
    if (argc != 3) {
        std::fprintf(stderr, "usage: render_minimal SCENE.json OUT.png\n");
        return 2;
    }
    sm::Result<sm::Scene> scene = sm::load_scene(argv[1]);
    if (!scene) {
        std::fprintf(stderr, "%s\n", scene.error().message().c_str());
        return 2;
    }
    sm::Result<sm::World> world = sm::build_world(*scene);
    if (!world) {
        std::fprintf(stderr, "%s\n", world.error().message().c_str());
        return 2;
    }
    for (int frame = 0; frame < 30; ++frame)
        world->advance(1.0 / 60.0);

    sm::RenderDef def = sm::default_render_def();
    def.width = 160;
    def.height = 120;
    sm::Result<sm::Renderer> renderer = sm::Renderer::create(def);
    if (!renderer) {
        std::fprintf(stderr, "%s\n", renderer.error().message().c_str());
        return 1;
    }
    sm::apply_scene_looks(*renderer, *scene, *world); // the scene's colours and meshes
    sm::Image image;
    if (sm::Status s = renderer->render(*world, scene->camera, image); !s) {
        std::fprintf(stderr, "%s\n", s.error().message().c_str());
        return 1;
    }
    if (sm::Status s = sm::write_png(argv[2], image); !s) {
        std::fprintf(stderr, "%s\n", s.error().message().c_str());
        return 1;
    }
    std::printf("wrote %s: %dx%d on %s\n", argv[2], image.width, image.height,
                renderer->device_name().c_str());
    return 0;
}
