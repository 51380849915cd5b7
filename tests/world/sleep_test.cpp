// Tests for sleeping (engine/src/world/sleep.h): bodies at rest fall asleep and stay put, and wake
// when something reaches them, pulls them or the host edits them.
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

constexpr double k_dt = 0.004; // [s]

sm::WorldDef sleepy_world_def()
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = k_dt;
    def.substep_count = 4;
    return def;
}

// A rounded box 0.2 × 0.1 × 0.2 m (half extents), resting on its face when it lands.
sm::BodyDef box_def(sm::Vec3 position)
{
    sm::BodyDef def = sm::test::ellipsoid_def({0.2, 0.1, 0.2}, position);
    def.shape.epsilon1 = def.shape.epsilon2 = 0.3;
    return def;
}

// Steps until `body` sleeps or `seconds` pass; returns the time it took [s], or -1.
double steps_until_asleep(sm::World& w, sm::Entity body, double seconds)
{
    for (int i = 0; i < static_cast<int>(seconds / k_dt); ++i) {
        w.step();
        if (!sm::body_is_awake(w, body))
            return w.time();
    }
    return -1.0;
}

TEST(Sleep, DroppedBoxFallsAsleepAndStaysPut)
{
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    const sm::Entity box = sm::create_body(w, box_def({0, 0.4, 0}));
    EXPECT_TRUE(sm::body_is_awake(w, box));
    const double t = steps_until_asleep(w, box, 4.0);
    // It lands at ~0.25 s and settles; sleep_time (0.5 s) after it is slow, it sleeps.
    ASSERT_GT(t, 0.5);
    EXPECT_LT(t, 2.0);
    EXPECT_EQ(sm::world_sleeping_count(w), 1u);
    EXPECT_EQ(w.profile().sleeping_count, 1u);
    EXPECT_EQ(sm::body_linear_velocity(w, box), sm::Vec3{});
    const sm::Vec3 at = sm::body_position(w, box);
    EXPECT_NEAR(at.y, 0.1, 0.01);
    sm::test::run_steps(w, 250);
    EXPECT_FALSE(sm::body_is_awake(w, box));
    EXPECT_EQ(sm::body_position(w, box), at); // not integrated: bit for bit where it slept
    EXPECT_EQ(w.profile().pair_count, 0u);    // nor collided
}

TEST(Sleep, HostEditsWakeTheBody)
{
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    const sm::Entity box = sm::create_body(w, box_def({0, 0.1, 0}));
    ASSERT_GT(steps_until_asleep(w, box, 4.0), 0.0);
    sm::set_body_linear_velocity(w, box, {1, 0, 0});
    EXPECT_TRUE(sm::body_is_awake(w, box));
    w.step();
    EXPECT_GT(sm::body_position(w, box).x, 0.0);

    ASSERT_GT(steps_until_asleep(w, box, 6.0), 0.0);
    sm::apply_force_at_center(w, box, {0, 200, 0});
    EXPECT_TRUE(sm::body_is_awake(w, box));
    const double y = sm::body_position(w, box).y;
    w.step();
    EXPECT_GT(sm::body_position(w, box).y, y);

    ASSERT_GT(steps_until_asleep(w, box, 6.0), 0.0);
    sm::wake_body(w, box);
    EXPECT_TRUE(sm::body_is_awake(w, box));
    ASSERT_GT(steps_until_asleep(w, box, 6.0), 0.0);
    sm::WorldDef def = w.settings();
    def.gravity = {0, 9.81, 0};
    ASSERT_TRUE(w.set_settings(def).ok());
    EXPECT_TRUE(sm::body_is_awake(w, box));
}

TEST(Sleep, AllowSleepFalseAndDisabledNeverSleep)
{
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    sm::BodyDef def = box_def({0, 0.1, 0});
    def.allow_sleep = false;
    const sm::Entity restless = sm::create_body(w, def);
    const sm::Entity neighbour = sm::create_body(w, box_def({1, 0.1, 0}));
    EXPECT_LT(steps_until_asleep(w, restless, 3.0), 0.0);
    EXPECT_FALSE(sm::body_is_awake(w, neighbour)); // not touching: an island of its own

    sm::WorldDef off = sleepy_world_def();
    off.sleep.enabled = false;
    sm::World w2(off);
    sm::test::add_ground(w2);
    const sm::Entity box = sm::create_body(w2, box_def({0, 0.1, 0}));
    EXPECT_LT(steps_until_asleep(w2, box, 3.0), 0.0);
}

TEST(Sleep, RestlessBodyKeepsWhatItTouchesAwake)
{
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    sm::BodyDef top = box_def({0, 0.3, 0});
    top.allow_sleep = false;
    const sm::Entity bottom = sm::create_body(w, box_def({0, 0.1, 0}));
    (void)sm::create_body(w, top);
    EXPECT_LT(steps_until_asleep(w, bottom, 3.0), 0.0);
}

TEST(Sleep, SwingingPendulumStaysAwake)
{
    sm::World w(sleepy_world_def());
    const sm::Entity bob = sm::create_body(w, sm::test::ellipsoid_def({0.05, 0.05, 0.05}, {0.5, 1, 0}));
    sm::ConstraintDef c = sm::default_constraint_def();
    c.type = sm::ConstraintType::Distance;
    c.a = bob;
    c.anchor_b.point = {0, 1, 0};
    (void)sm::create_constraint(w, c);
    EXPECT_LT(steps_until_asleep(w, bob, 4.0), 0.0);
}

TEST(Sleep, BallRolledIntoSleepingStackWakesIt)
{
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    std::vector<sm::Entity> stack;
    for (int i = 0; i < 3; ++i)
        stack.push_back(sm::create_body(w, box_def({0, 0.1 + 0.2 * i, 0})));
    ASSERT_GT(steps_until_asleep(w, stack.back(), 4.0), 0.0);
    for (sm::Entity e : stack)
        EXPECT_FALSE(sm::body_is_awake(w, e));
    sm::BodyDef ball = sm::test::ellipsoid_def({0.1, 0.1, 0.1}, {-1.5, 0.1, 0});
    ball.linear_velocity = {4, 0, 0};
    ball.density = 5000.0;
    (void)sm::create_body(w, ball);
    const sm::Vec3 bottom_at = sm::body_position(w, stack[0]);
    bool woke = false;
    for (int i = 0; i < 250 && !woke; ++i) {
        w.step();
        woke = sm::body_is_awake(w, stack[2]); // the top wakes with the bottom one, as an island
    }
    EXPECT_TRUE(woke);
    EXPECT_TRUE(sm::body_is_awake(w, stack[0]));
    sm::test::run_steps(w, 50);
    EXPECT_GT(sm::body_position(w, stack[0]).x - bottom_at.x, 0.01);
}

TEST(Sleep, SnapshotMidSleepRestoresTheSameHash)
{
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    std::vector<sm::Entity> stack;
    for (int i = 0; i < 3; ++i)
        stack.push_back(sm::create_body(w, box_def({0.02 * i, 0.1 + 0.21 * i, 0})));
    ASSERT_GT(steps_until_asleep(w, stack[0], 6.0), 0.0);
    ASSERT_EQ(sm::world_sleeping_count(w), 3u);
    const sm::Snapshot snap = w.snapshot();
    // A ball that wakes the stack later, so the restored world must wake it with the same contacts.
    auto run = [&] {
        sm::test::run_steps(w, 100);
        sm::apply_linear_impulse(w, stack[2], {0.5, 0, 0}, sm::body_center_of_mass(w, stack[2]));
        sm::test::run_steps(w, 100);
        return w.state_hash();
    };
    const uint64_t ahead = run();
    ASSERT_TRUE(w.restore(snap).ok());
    EXPECT_EQ(sm::world_sleeping_count(w), 3u);
    EXPECT_EQ(run(), ahead);
}

} // namespace

TEST(Sleep, SleepersPairWithNothingUntilAMovingBodyWakesThemInTheSameStep)
{
    // Two boxes 0.2 mm apart (apart, so two islands; their swept boxes overlap by the gravity sag): once
    // asleep the broadphase pairs neither with the ground nor with each other. A kinematic plate moving
    // into the first wakes it, and the first, awake, reaches the second in the same step.
    sm::World w(sleepy_world_def());
    sm::test::add_ground(w);
    const sm::Entity first = sm::create_body(w, box_def({0, 0.1, 0}));
    const sm::Entity second = sm::create_body(w, box_def({0.4002, 0.1, 0}));
    ASSERT_GT(steps_until_asleep(w, first, 4.0), 0.0);
    sm::test::run_steps(w, 1);
    ASSERT_FALSE(sm::body_is_awake(w, second));
    EXPECT_EQ(w.profile().pair_count, 0u);
    EXPECT_EQ(sm::world_sleeping_count(w), 2u);

    sm::BodyDef plate = sm::test::ellipsoid_def({0.05, 0.1, 0.2}, {-0.4, 0.1, 0});
    plate.motion = sm::MotionType::Kinematic;
    plate.linear_velocity = {1, 0, 0};
    (void)sm::create_body(w, plate);
    bool first_awake = false;
    for (int i = 0; i < 100 && !first_awake; ++i) {
        w.step();
        first_awake = sm::body_is_awake(w, first);
    }
    ASSERT_TRUE(first_awake);
    EXPECT_TRUE(sm::body_is_awake(w, second));
}
