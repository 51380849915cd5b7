// Tests for engine/src/world/faults.cpp and the per-stage non-finite guards in world.cpp.
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/fault.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <gtest/gtest.h>
#include <vector>

namespace sm = supermodal;
using sm::test::ellipsoid_def;
using sm::test::run_steps;

namespace
{

sm::World weightless_world(int substeps = 1)
{
    sm::WorldDef def = sm::default_world_def();
    def.gravity = {};
    def.substep_count = substeps;
    return sm::World(def);
}

void collect(const sm::FaultEvent& e, void* user)
{
    static_cast<std::vector<sm::FaultEvent>*>(user)->push_back(e);
}

} // namespace

TEST(Fault, OverflowingForceIsReportedWithBodyStageAndStep)
{
    sm::World world = weightless_world(3);
    const sm::Entity bad = sm::create_body(world, ellipsoid_def({1e-3, 1e-3, 1e-3}));
    std::vector<sm::FaultEvent> seen;
    sm::world_set_fault_callback(world, &collect, &seen);
    run_steps(world, 2);
    EXPECT_TRUE(seen.empty());
    // 1e308 N on a 4 mg body overflows its velocity to infinity in the first substep.
    sm::apply_force_at_center(world, bad, {1e308, 0, 0});
    world.step();
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].kind, sm::FaultKind::BodyNonFinite);
    EXPECT_EQ(seen[0].body, bad);
    EXPECT_EQ(seen[0].stage, sm::Stage::IntegrateForces);
    EXPECT_EQ(seen[0].step, 2u);
    EXPECT_EQ(seen[0].substep, 0);
    ASSERT_EQ(sm::world_fault_events(world).size(), 1u);
    EXPECT_EQ(sm::body_motion(world, bad), sm::MotionType::Kinematic);
    world.step();
    EXPECT_TRUE(sm::world_fault_events(world).empty()); // reported once, not every step after
    EXPECT_EQ(seen.size(), 1u);
    EXPECT_STREQ(sm::fault_kind_name(seen[0].kind), "body_non_finite");
}

// The faulty body touches a neighbour. Its infinite velocity would reach the neighbour through the
// contact damper in the same substep if the guard ran only at the end of the step.
TEST(Fault, DoesNotSpreadThroughAContactInTheSameStep)
{
    sm::World world = weightless_world();
    const sm::Entity bad = sm::create_body(world, ellipsoid_def({0.1, 0.1, 0.1}, {0, 0.1, 0}));
    const sm::Entity good = sm::create_body(world, ellipsoid_def({0.1, 0.1, 0.1}, {0, 0.295, 0}));
    world.step();
    ASSERT_GT(sm::world_contacts(world).size(), 0u) << "the bodies must overlap for this test";
    sm::apply_force_at_center(world, bad, {0, 1e308, 0});
    sm::apply_force_at_center(world, bad, {0, 1e308, 0});
    world.step();
    EXPECT_EQ(world.warnings().non_finite_bodies, 1u);
    EXPECT_EQ(world.warnings().last_non_finite, bad);
    EXPECT_EQ(sm::body_motion(world, good), sm::MotionType::Dynamic);
    // The neighbour only feels the 5 mm overlap's spring and damper: well under 1 m/s after one step.
    EXPECT_LT(sm::length(sm::body_linear_velocity(world, good)), 1.0);
    run_steps(world, 50);
    EXPECT_TRUE(sm::is_finite(sm::body_position(world, good)));
    EXPECT_EQ(world.warnings().non_finite_bodies, 1u);
}

TEST(Fault, ModalOverflowIsReportedAndTheShapeGoesBackToRest)
{
    sm::World world = weightless_world();
    sm::BodyDef def = ellipsoid_def({0.5, 0.1, 0.1});
    def.modal.enabled = true;
    def.modal.mode_count = 4;
    def.young = 1e6;
    def.motion = sm::MotionType::Dynamic;
    const sm::Entity body = sm::create_body(world, def);
    ASSERT_FALSE(body.is_null());
    std::vector<sm::FaultEvent> seen;
    sm::world_set_fault_callback(world, &collect, &seen);
    // Two opposite 1e308 N loads at the tips: no net force, but the modal load overflows to inf.
    sm::apply_force(world, body, {0, 1e308, 0}, {0.5, 0, 0});
    sm::apply_force(world, body, {0, 1e308, 0}, {0.5, 0, 0});
    sm::apply_force(world, body, {0, -1e308, 0}, {-0.5, 0, 0});
    world.step();
    bool modal_seen = false;
    for (const sm::FaultEvent& e : seen)
        modal_seen |= e.kind == sm::FaultKind::ModalNonFinite && e.body == body;
    EXPECT_TRUE(modal_seen);
    EXPECT_GE(world.warnings().modal_non_finite, 1u);
    for (double q : sm::body_modal_state(world, body).amplitudes)
        EXPECT_EQ(q, 0.0);
}

TEST(Fault, CallbackCanBeRemoved)
{
    sm::World world = weightless_world();
    const sm::Entity bad = sm::create_body(world, ellipsoid_def({1e-3, 1e-3, 1e-3}));
    std::vector<sm::FaultEvent> seen;
    sm::world_set_fault_callback(world, &collect, &seen);
    sm::world_set_fault_callback(world, nullptr, nullptr);
    sm::apply_force_at_center(world, bad, {1e308, 0, 0});
    world.step();
    EXPECT_TRUE(seen.empty());
    EXPECT_EQ(sm::world_fault_events(world).size(), 1u);
}

class FaultOnContact : public ::testing::TestWithParam<sm::ContactSolver>
{
};

TEST_P(FaultOnContact, BodyBlownUpInAContactIsFrozenAndReportedOnce)
{
    // A ball resting on a plane, thrown into it at 1e308 m/s, turns non-finite in the contact solve. On
    // the soft solver the rows' relax passes then pushed the frozen ball again, so it was reported twice.
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = GetParam();
    sm::World world(def);
    (void)sm::test::add_ground(world);
    sm::BodyDef ball = sm::default_body_def();
    ball.position = {0, ball.shape.radii.y, 0};
    const sm::Entity b = sm::create_body(world, ball);
    sm::set_body_linear_velocity(world, b, {0, -1e308, 0});
    std::vector<sm::FaultEvent> seen;
    sm::world_set_fault_callback(world, &collect, &seen);
    run_steps(world, 3);
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].body, b);
    EXPECT_EQ(world.warnings().non_finite_bodies, 1u);
    EXPECT_EQ(sm::body_motion(world, b), sm::MotionType::Kinematic);
}

INSTANTIATE_TEST_SUITE_P(Solvers, FaultOnContact,
                         ::testing::Values(sm::ContactSolver::Penalty, sm::ContactSolver::Soft),
                         [](const auto& info) {
                             return std::string(info.param == sm::ContactSolver::Soft ? "soft" : "penalty");
                         });
