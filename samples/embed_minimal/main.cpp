// SPDX-License-Identifier: MIT
// The smallest host: load a scene, step it one simulated second, print each body's pose.
#include <cstdio>
#include <supermodal/supermodal.hpp>

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: embed_minimal SCENE.json\n");
        return 2;
    }
    supermodal::Result<supermodal::Scene> scene = supermodal::load_scene(argv[1]);
    if (!scene) {
        std::fprintf(stderr, "%s\n", scene.error().message().c_str());
        return 2;
    }
    supermodal::Result<supermodal::World> world = supermodal::build_world(*scene);
    if (!world) {
        std::fprintf(stderr, "%s\n", world.error().message().c_str());
        return 2;
    }
    // A host's frame loop: 60 frames of 1/60 s; the world runs whole fixed steps from its accumulator.
    for (int frame = 0; frame < 60; ++frame)
        world->advance(1.0 / 60.0);
    for (supermodal::Entity body : supermodal::world_bodies(*world)) {
        const supermodal::Vec3 p = supermodal::body_position(*world, body);
        const supermodal::Quat q = supermodal::body_orientation(*world, body);
        std::printf("%s position %.6f %.6f %.6f orientation %.6f %.6f %.6f %.6f\n",
                    supermodal::body_name(*world, body).c_str(), p.x, p.y, p.z, q.w, q.x, q.y, q.z);
    }
    std::printf("steps %llu hash %016llx\n", static_cast<unsigned long long>(world->step_count()),
                static_cast<unsigned long long>(world->state_hash()));
    return 0;
}
