// Tests for engine/src/dynamics/integrate.cpp.
#include "supermodal/body.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
using sm::test::ellipsoid_def;
using sm::test::run_steps;

namespace
{
sm::WorldDef world_def(double dt, sm::Vec3 gravity = {0, -9.81, 0})
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.gravity = gravity;
    return def;
}
} // namespace

TEST(Integrate, ProjectileMatchesSemiImplicitEuler)
{
    // Semi-implicit Euler: v_n = v0 + g n h, x_n = x0 + v0 n h + g h² n(n+1)/2, exactly; only round-off
    // differs (1000 additions of numbers ~10 → ~1e-12).
    constexpr double k_round_off = 1e-10;
    constexpr double h = 0.001;
    constexpr int n = 1000;
    const sm::Vec3 g{0, -9.81, 0}, v0{3, 4, -1}, x0{0, 10, 0};
    sm::World world(world_def(h, g));
    sm::BodyDef b = ellipsoid_def({0.1, 0.1, 0.1}, x0);
    b.linear_velocity = v0;
    const sm::Entity e = sm::create_body(world, b);
    run_steps(world, n);
    const sm::Vec3 expected = x0 + v0 * (n * h) + g * (h * h * n * (n + 1) / 2.0);
    const sm::Vec3 p = sm::body_position(world, e);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(p[i], expected[i], k_round_off);
    // And the continuous parabola to first order in h: |x_n − x(t)| = g h t / 2.
    const double t = n * h;
    EXPECT_NEAR(p.y, x0.y + v0.y * t - 0.5 * 9.81 * t * t, 0.5 * 9.81 * h * t + k_round_off);
}

TEST(Integrate, ForcesTorquesAndImpulses)
{
    sm::World world(world_def(0.01, {}));
    const sm::Entity e = sm::create_body(world, ellipsoid_def({1, 1, 1}, {}, 3.0 / (4.0 * M_PI))); // 1 kg
    const sm::MassProperties& mp = sm::body_mass_properties(world, e);
    ASSERT_NEAR(mp.mass, 1.0, 1e-12);
    sm::apply_force_at_center(world, e, {2, 0, 0});
    world.step();
    EXPECT_NEAR(sm::body_linear_velocity(world, e).x, 0.02, 1e-15);
    world.step(); // forces were cleared after the first step
    EXPECT_NEAR(sm::body_linear_velocity(world, e).x, 0.02, 1e-15);
    sm::apply_linear_impulse(world, e, {0, 1, 0}, sm::body_position(world, e) + sm::Vec3{1, 0, 0});
    EXPECT_NEAR(sm::body_linear_velocity(world, e).y, 1.0, 1e-15);
    // Impulse (0,1,0) at r = (1,0,0): angular impulse (0,0,1) on I = 2/5 m r² = 0.4.
    EXPECT_NEAR(sm::body_angular_velocity(world, e).z, 2.5, 1e-12);
    sm::apply_torque(world, e, {0, 0, 0.4});
    world.step();
    EXPECT_NEAR(sm::body_angular_velocity(world, e).z, 2.51, 1e-12);
}

TEST(Integrate, StaticAndKinematicBodiesIgnoreForces)
{
    sm::World world(world_def(0.01));
    sm::BodyDef s = ellipsoid_def({1, 1, 1}, {0, 0, 0});
    s.motion = sm::MotionType::Static;
    sm::BodyDef k = ellipsoid_def({1, 1, 1}, {5, 0, 0});
    k.motion = sm::MotionType::Kinematic;
    k.linear_velocity = {1, 0, 0};
    k.angular_velocity = {0, 2, 0};
    const sm::Entity se = sm::create_body(world, s), ke = sm::create_body(world, k);
    sm::apply_force_at_center(world, ke, {100, 100, 100});
    run_steps(world, 100);
    EXPECT_EQ(sm::body_position(world, se), (sm::Vec3{}));
    EXPECT_NEAR(sm::body_position(world, ke).x, 6.0, 1e-12);
    EXPECT_NEAR(sm::body_position(world, ke).y, 0.0, 1e-15);
    // Rotated by 2 rad about y.
    const sm::Vec3 x_axis = sm::rotate(sm::body_orientation(world, ke), {1, 0, 0});
    EXPECT_NEAR(x_axis.x, std::cos(2.0), 1e-12);
    EXPECT_NEAR(x_axis.z, -std::sin(2.0), 1e-12);
}
