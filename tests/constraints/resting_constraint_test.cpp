// A body held by a constraint while it rests on the ground in static friction stays put: the friction
// anchors follow the motion the body makes after the constraint impulses (engine/src/world/world.cpp,
// update_contact_anchors), not the velocity from before them.
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/world.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;

// A 0.2 m box-like block rests on the floor and a soft point
// constraint pulls it sideways towards a world point 5 cm away with a force well under μ·m·g. Static
// friction holds it: it may shift by the friction spring's stretch (sub-millimetre), not creep. With the
// anchors fed the pre-constraint velocity, the spring grew every substep by the constraint's share of the
// motion and the block crept towards the constraint point (measured: 1.46 mm in 3 s, steadily).
class RestingConstraint : public ::testing::TestWithParam<sm::ContactSolver>
{
};

TEST_P(RestingConstraint, PulledBlockInStaticFrictionDoesNotCreep)
{
    // On the penalty solver its friction anchors (update_contact_anchors) are what this checks; on the
    // soft solver the friction rows' stick spring, which a rocking face's unloaded corner reaching its
    // own Coulomb disc used to reset (measured: 0.81 mm in 3 s, 0.27 mm/s steadily; now 7 µm).
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = GetParam();
    def.dt = 1e-3;
    def.substep_count = 4;
    def.sleep.enabled = false; // creep must show, not stop when the block falls asleep
    sm::World w(def);
    sm::BodyDef floor = sm::default_body_def();
    floor.shape.type = sm::ShapeType::Plane;
    floor.motion = sm::MotionType::Static;
    (void)sm::create_body(w, floor);
    sm::BodyDef block = sm::default_body_def();
    block.shape.radii = {0.1, 0.1, 0.1};
    block.shape.epsilon1 = block.shape.epsilon2 = 0.2; // box-like: a flat face on the floor
    block.position = {0, 0.1, 0};
    block.friction = 0.8;
    const sm::Entity b = sm::create_body(w, block);
    for (int i = 0; i < 500; ++i) // settle onto the floor
        w.step();
    const sm::Vec3 start = sm::body_position(w, b);
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = b;
    c.anchor_b.point = start + sm::Vec3{0.05, 0, 0};
    c.frequency_hz = 1.0; // k = m ω² ≈ 39·m N/m: 2.0·m N at 5 cm, a third of μ·m·g (μ = √(0.8·0.5))
    c.damping_ratio = 1.0;
    const sm::Constraint pull = sm::create_constraint(w, c);
    for (int i = 0; i < 3000; ++i)
        w.step();
    const double moved = sm::length(sm::body_position(w, b) - start);
    // Measured: ≤ 9 µm over 3 s (and over 12 s); with the pre-constraint velocity: 1.46 mm in 3 s.
    EXPECT_LT(moved, 1e-4) << "moved " << moved << " m, force " << sm::length(sm::constraint_force(w, pull));
    // The block keeps a small rocking on its face (≤ 2.5 mm/s, 0.02 rad/s, bounded over 12 s, with either
    // anchor update): a penalty-contact limit cycle, not creep. Bound with margin.
    EXPECT_LT(sm::length(sm::body_linear_velocity(w, b)), 5e-3);
}

INSTANTIATE_TEST_SUITE_P(Solvers, RestingConstraint,
                         ::testing::Values(sm::ContactSolver::Penalty, sm::ContactSolver::Soft),
                         [](const auto& info) {
                             return info.param == sm::ContactSolver::Soft ? "Soft" : "Penalty";
                         });
