// SPDX-License-Identifier: MIT
// A host that makes its world in code: a ground plane, a rope of five links hung from a world point by
// point constraints, and a rounded box dropped beside it. Its frame loop runs at an uneven frame rate,
// as a game's does: advance() runs the whole fixed steps each frame's time holds, and the "renderer"
// draws each body between its last two steps by interpolation_alpha(). At the end it checks what it
// drew and prints "ok" (exit 0), or what went wrong (exit 1).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <supermodal/body.h>
#include <supermodal/constraint.h>
#include <supermodal/world.h>
#include <vector>

namespace sm = supermodal;

namespace
{

constexpr int k_links = 5;              // rope links [-]
constexpr double k_link_half = 0.1;     // half length of a link along y [m]
constexpr sm::Vec3 k_hook{0.0, 2.0, 0}; // where the rope hangs from [m]

sm::Entity add_link(sm::World& world, int i)
{
    sm::BodyDef link = sm::default_body_def();
    link.shape.radii = {0.03, k_link_half, 0.03}; // an ellipsoid along y
    link.position = {0.0, k_hook.y - k_link_half * (2 * i + 1), 0.0};
    link.linear_velocity = {i == k_links - 1 ? 1.0 : 0.0, 0.0, 0.0}; // the bottom link is pushed aside
    return sm::create_body(world, link);
}

// A point joint between the bottom of `upper` and the top of `lower`; `upper` null: the world hook.
sm::Constraint join(sm::World& world, sm::Entity upper, sm::Entity lower)
{
    sm::ConstraintDef joint = sm::default_constraint_def();
    joint.type = sm::ConstraintType::Point;
    joint.a = lower;
    joint.anchor_a.point = {0.0, k_link_half, 0.0};
    joint.b = upper; // null: anchor_b is a world point
    joint.anchor_b.point = upper.is_null() ? k_hook : sm::Vec3{0.0, -k_link_half, 0.0};
    return sm::create_constraint(world, joint);
}

double distance(sm::Vec3 p, sm::Vec3 q)
{
    return std::sqrt(sm::dot(p - q, p - q));
}

} // namespace

int main()
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1.0 / 120.0; // the fixed step [s]
    sm::World world(def);

    sm::BodyDef ground = sm::default_body_def();
    ground.motion = sm::MotionType::Static;
    ground.shape.type = sm::ShapeType::Plane; // y <= 0
    sm::BodyDef box = sm::default_body_def();
    box.shape.radii = {0.15, 0.15, 0.15};
    box.shape.epsilon1 = box.shape.epsilon2 = 0.3; // a rounded box
    box.position = {1.0, 0.6, 0.0};
    const bool ground_made = !sm::create_body(world, ground).is_null();
    const sm::Entity dropped = sm::create_body(world, box);
    std::vector<sm::Entity> links;
    std::vector<sm::Constraint> joints;
    bool joints_made = true;
    for (int i = 0; i < k_links; ++i) {
        links.push_back(add_link(world, i));
        joints.push_back(join(world, i == 0 ? sm::Entity{} : links[i - 1], links.back()));
        joints_made = joints_made && !links.back().is_null() && !joints.back().is_null();
    }
    if (!ground_made || dropped.is_null() || !joints_made) {
        std::fprintf(stderr, "embed_in_code: a body or joint was refused\n");
        return 1;
    }

    // Frames of 12, 17 and 21 ms in turn (about 60 fps, uneven), three simulated seconds.
    const double frames[] = {0.012, 0.017, 0.021};
    double bad_alpha = 0.0, off_segment = 0.0;
    for (int frame = 0; frame < 180; ++frame) {
        const sm::Vec3 last = sm::body_position(world, links.back()); // after the last step
        const int steps = world.advance(frames[frame % 3]);
        const double alpha = world.interpolation_alpha();
        if (!(alpha >= 0.0 && alpha < 1.0))
            bad_alpha = alpha;
        // What a renderer draws: the pose blended between the previous and the current step by alpha.
        const sm::Vec3 drawn = sm::body_interpolated_position(world, links.back());
        if (steps == 1) { // then the previous step's pose is `last`
            const sm::Vec3 now = sm::body_position(world, links.back());
            off_segment = std::max(off_segment, distance(drawn, last + alpha * (now - last)));
        }
        if (frame % 60 == 0)
            std::printf("frame %3d: %d steps, alpha %.3f, bottom link drawn at %.4f %.4f %.4f\n", frame,
                        steps, alpha, drawn.x, drawn.y, drawn.z);
    }

    double joint_error = 0.0;
    for (sm::Constraint j : joints)
        joint_error = std::max(joint_error, sm::constraint_error(world, j).linear);
    const double box_height = sm::body_position(world, dropped).y;
    std::printf("after %llu steps: largest joint error %.2e m, box at height %.4f m, hash %016llx\n",
                static_cast<unsigned long long>(world.step_count()), joint_error, box_height,
                static_cast<unsigned long long>(world.state_hash()));
    // The rope holds together (joint springs at 30 Hz: a few millimetres under the links' swing), the
    // box rests on its face (0.15 m half size), alpha stays in [0, 1), and the drawn pose lies between
    // the two steps' poses.
    const bool ok =
        joint_error < 0.01 && std::abs(box_height - 0.15) < 0.005 && bad_alpha == 0.0 && off_segment < 1e-9;
    std::printf("%s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
