// Tests for engine/src/world/world.cpp, state.cpp and body.cpp.
#include "supermodal/body.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace sm = supermodal;
using sm::test::ellipsoid_def;
using sm::test::run_steps;

namespace
{

// A few spinning, falling bodies: enough state for hashes to notice any difference.
sm::World make_busy_world(sm::WorldDef def = sm::default_world_def())
{
    sm::World world(def);
    for (int i = 0; i < 4; ++i) {
        sm::BodyDef b = ellipsoid_def({0.1 + 0.05 * i, 0.2, 0.3}, {double(i), 5.0, 0.0});
        b.linear_velocity = {1.0, 2.0 * i, -0.5};
        b.angular_velocity = {3.0, 0.1 * i, 7.0};
        (void)sm::create_body(world, b);
    }
    return world;
}

} // namespace

TEST(World, AdvanceRunsWholeStepsAndKeepsTheRemainder)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.01;
    sm::World world(def);
    EXPECT_EQ(world.advance(0.025), 2);
    EXPECT_NEAR(world.interpolation_alpha(), 0.5, 1e-9);
    EXPECT_EQ(world.advance(0.006), 1); // 0.005 + 0.006 = 0.011
    EXPECT_NEAR(world.interpolation_alpha(), 0.1, 1e-9);
    EXPECT_EQ(world.step_count(), 3u);
    EXPECT_DOUBLE_EQ(world.time(), 0.03);
}

TEST(World, AdvanceCapsTheBacklog)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.01;
    def.max_steps_per_advance = 5;
    sm::World world(def);
    EXPECT_EQ(world.advance(1.0), 5);
    EXPECT_LT(world.interpolation_alpha(), 1.0);
    EXPECT_EQ(world.advance(0.0), 0);
}

TEST(World, InterpolatedPoseBlendsTheLastTwoSteps)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.01;
    def.gravity = {};
    sm::World world(def);
    sm::BodyDef b = ellipsoid_def({0.1, 0.1, 0.1});
    b.linear_velocity = {1, 0, 0};
    const sm::Entity e = sm::create_body(world, b);
    world.advance(0.0175);
    EXPECT_NEAR(sm::body_position(world, e).x, 0.01, 1e-12);
    // One whole step ran; alpha = 0.75. Rendering blends the previous and current step, so it lags the
    // simulation by one step but never extrapolates: 0 + 0.75 · (0.01 − 0).
    EXPECT_NEAR(world.interpolation_alpha(), 0.75, 1e-12);
    EXPECT_NEAR(sm::body_interpolated_position(world, e).x, 0.0075, 1e-12);
}

TEST(World, SameSceneGivesTheSameHash)
{
    sm::World a = make_busy_world(), b = make_busy_world();
    run_steps(a, 500);
    run_steps(b, 500);
    EXPECT_EQ(a.state_hash(), b.state_hash());
    b.step();
    EXPECT_NE(a.state_hash(), b.state_hash());
}

TEST(World, SnapshotRestoreContinuesBitIdentically)
{
    sm::World world = make_busy_world();
    run_steps(world, 100);
    const sm::Snapshot snap = world.snapshot();
    run_steps(world, 300);
    const uint64_t straight = world.state_hash();
    ASSERT_TRUE(world.restore(snap).ok());
    EXPECT_EQ(world.step_count(), 100u);
    run_steps(world, 300);
    EXPECT_EQ(world.state_hash(), straight);
}

TEST(World, RestoreRefusesAChangedBodySet)
{
    sm::World world = make_busy_world();
    const sm::Snapshot snap = world.snapshot();
    (void)sm::create_body(world, ellipsoid_def({1, 1, 1}));
    const sm::Status s = world.restore(snap);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.error().what.find("created or destroyed"), std::string::npos);
}

TEST(World, SnapshotBytesRoundTripAndForeignLayoutsAreRefused)
{
    sm::World world = make_busy_world();
    run_steps(world, 50);
    const sm::Snapshot snap = world.snapshot();
    EXPECT_GT(snap.layout_version(), 0u);
    run_steps(world, 100);
    const uint64_t straight = world.state_hash();
    // Through bytes (as a host keeps them in a file): the same continuation.
    const std::vector<std::byte> kept(snap.bytes().begin(), snap.bytes().end());
    ASSERT_TRUE(world.restore(sm::Snapshot::from_bytes(kept)).ok());
    run_steps(world, 100);
    EXPECT_EQ(world.state_hash(), straight);
    // Another layout version: refused with both versions named, the world unchanged.
    std::vector<std::byte> other = kept;
    other[4] = static_cast<std::byte>(static_cast<unsigned>(other[4]) + 1);
    const sm::Status s = world.restore(sm::Snapshot::from_bytes(other));
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().what.find("layout version " + std::to_string(snap.layout_version() + 1)),
              std::string::npos)
        << s.error().what;
    EXPECT_EQ(world.state_hash(), straight);
    EXPECT_FALSE(world.restore(sm::Snapshot{}).ok());
    EXPECT_EQ(world.state_hash(), straight);
}

TEST(World, StepListenerRunsBeforeEveryStepAndItsForcesAct)
{
    // A listener pushing up with exactly the body's weight holds it still: it runs before every step
    // (step() and each step of advance()) and its force lasts that step.
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.01;
    sm::World world(def);
    const sm::Entity body = sm::create_body(world, ellipsoid_def({0.1, 0.1, 0.1}));
    struct Hold {
        sm::Entity body;
        int calls = 0;
    } hold{body};
    sm::world_set_step_listener(
        world,
        [](sm::World& w, void* user) {
            auto& h = *static_cast<Hold*>(user);
            ++h.calls;
            const double weight = sm::body_mass_properties(w, h.body).mass * 9.81;
            sm::apply_force(w, h.body, {0, weight, 0}, sm::body_center_of_mass(w, h.body));
        },
        &hold);
    world.step();
    EXPECT_EQ(world.advance(0.035), 3);
    EXPECT_EQ(hold.calls, 4);
    // Gravity and the push cancel to round-off: h·(g − m g / m) per step.
    EXPECT_NEAR(sm::body_linear_velocity(world, body).y, 0.0, 1e-12);
    sm::world_set_step_listener(world, nullptr, nullptr);
    world.step();
    EXPECT_EQ(hold.calls, 4);
    EXPECT_NEAR(sm::body_linear_velocity(world, body).y, -9.81 * 0.01, 1e-12);
}

TEST(World, SetSettingsChangesWhatMayChangeAndRefusesTheRest)
{
    sm::World world = make_busy_world();
    sm::WorldDef def = world.settings();
    def.gravity = {0, -1.62, 0};
    def.substep_count = 3;
    ASSERT_TRUE(world.set_settings(def).ok());
    EXPECT_EQ(world.settings().substep_count, 3);
    EXPECT_EQ(world.settings().gravity.y, -1.62);
    world.step();
    sm::WorldDef bad = world.settings();
    bad.dt = 0.5 * bad.dt;
    const sm::Status dt = world.set_settings(bad);
    ASSERT_FALSE(dt.ok());
    EXPECT_EQ(dt.error().where, "dt");
    bad = world.settings();
    bad.thread_count = 2;
    EXPECT_EQ(world.set_settings(bad).error().where, "thread_count");
    bad = world.settings();
    bad.substep_count = 0;
    EXPECT_EQ(world.set_settings(bad).error().where, "substep_count");
    EXPECT_EQ(world.settings().substep_count, 3); // unchanged by the refusals
}

TEST(World, TwoWorldsSideBySideDoNotInteract)
{
    sm::World a = make_busy_world();
    sm::World reference = make_busy_world();
    sm::WorldDef other = sm::default_world_def();
    other.gravity = {0, 0, 3};
    sm::World b = make_busy_world(other);
    for (int i = 0; i < 200; ++i) {
        a.step();
        b.step();
        reference.step();
    }
    EXPECT_EQ(a.state_hash(), reference.state_hash());
    EXPECT_NE(a.state_hash(), b.state_hash());
}

TEST(World, SubstepsSplitTheStep)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.01;
    def.substep_count = 4;
    sm::World world(def);
    const sm::Entity e = sm::create_body(world, ellipsoid_def({0.1, 0.1, 0.1}));
    world.step();
    // Semi-implicit Euler over 4 substeps of h: y = −g h² (1+2+3+4).
    const double h = 0.0025;
    EXPECT_NEAR(sm::body_position(world, e).y, -9.81 * h * h * 10, 1e-15);
    EXPECT_DOUBLE_EQ(world.time(), 0.01);
}

TEST(World, StaleHandleIsDetectedAndNeverAliased)
{
    sm::World world;
    const sm::Entity a = sm::create_body(world, ellipsoid_def({1, 1, 1}, {1, 2, 3}));
    sm::destroy_body(world, a);
    EXPECT_FALSE(sm::world_valid(world, a));
    const sm::Entity b = sm::create_body(world, ellipsoid_def({1, 1, 1}, {7, 8, 9}));
    EXPECT_EQ(a.index, b.index);
    EXPECT_TRUE(sm::world_valid(world, b));
    EXPECT_FALSE(sm::world_valid(world, a));
    sm::test::AssertCounter asserts;
    const sm::Vec3 p = sm::body_position(world, a); // refused: reports, returns zeros
    EXPECT_EQ(p, (sm::Vec3{}));
    sm::set_body_position(world, a, {0, 0, 0});
    EXPECT_EQ(sm::body_position(world, b), (sm::Vec3{7, 8, 9}));
    if (sm::asserts_enabled()) {
        EXPECT_EQ(asserts.count(), 2);
    }
}

TEST(World, InvalidDefIsRefused)
{
    sm::World world;
    sm::BodyDef bad = ellipsoid_def({1, 1, 1});
    bad.density = -1;
    EXPECT_FALSE(sm::validate(bad).ok());
    sm::test::AssertCounter asserts;
    EXPECT_TRUE(sm::create_body(world, bad).is_null());
    EXPECT_TRUE(sm::world_bodies(world).empty());
}

TEST(World, FindBodyByName)
{
    sm::World world;
    sm::BodyDef b = ellipsoid_def({1, 1, 1});
    b.name = "ball";
    const sm::Entity e = sm::create_body(world, b);
    EXPECT_EQ(sm::find_body(world, "ball"), e);
    EXPECT_TRUE(sm::find_body(world, "nope").is_null());
    EXPECT_EQ(sm::body_name(world, e), "ball");
}

TEST(World, NonFiniteBodyIsFrozenAndDoesNotSpread)
{
    sm::World world;
    const sm::Entity bad = sm::create_body(world, ellipsoid_def({1e-3, 1e-3, 1e-3}, {0, 1, 0}));
    const sm::Entity good = sm::create_body(world, ellipsoid_def({1, 1, 1}, {5, 1, 0}));
    world.step();
    const sm::Vec3 last = sm::body_position(world, bad);
    // 1e308 N on a 4 mg body overflows the velocity to infinity in one step.
    sm::apply_force_at_center(world, bad, {1e308, 0, 0});
    world.step();
    EXPECT_EQ(world.warnings().non_finite_bodies, 1u);
    EXPECT_EQ(world.warnings().last_non_finite, bad);
    EXPECT_EQ(sm::body_position(world, bad), last);
    EXPECT_EQ(sm::body_motion(world, bad), sm::MotionType::Kinematic);
    run_steps(world, 10);
    EXPECT_TRUE(sm::is_finite(sm::body_position(world, good)));
    EXPECT_EQ(world.warnings().non_finite_bodies, 1u);
}
