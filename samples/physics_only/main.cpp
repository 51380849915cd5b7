// SPDX-License-Identifier: MIT
// A physics-only host: a ground plane and a ball made in code, two simulated seconds, then the ball's
// pose and the world's state hash. Only the engine's headers, only supermodal::engine on the link line.
#include <cstdio>
#include <supermodal/body.h>
#include <supermodal/shape.h>
#include <supermodal/world.h>

int main()
{
    namespace sm = supermodal;
    sm::World world(sm::default_world_def()); // dt = 2 ms, gravity along -Y

    sm::BodyDef ground = sm::default_body_def();
    ground.name = "ground";
    ground.motion = sm::MotionType::Static;
    ground.shape.type = sm::ShapeType::Plane;  // y <= 0: normal +Y, offset 0
    sm::BodyDef ball = sm::default_body_def(); // a water-density sphere of radius 0.5 m
    ball.name = "ball";
    ball.position = {0.0, 1.0, 0.0};
    if (sm::create_body(world, ground).is_null() || sm::create_body(world, ball).is_null()) {
        std::fprintf(stderr, "physics_only: a body was refused\n");
        return 1;
    }

    for (int i = 0; i < 1000; ++i) // 1000 steps of 2 ms: the ball drops 0.5 m, bounces, settles
        world.step();
    const sm::Entity b = sm::find_body(world, "ball");
    const sm::Vec3 p = sm::body_position(world, b);
    std::printf("ball position %.6f %.6f %.6f\n", p.x, p.y, p.z);
    std::printf("steps %llu hash %016llx\n", static_cast<unsigned long long>(world.step_count()),
                static_cast<unsigned long long>(world.state_hash()));
    return 0;
}
