// Penalty constraints against analytic values: static sag g/ω², pendulum period, limits, breaking.
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/world.h"
#include "support/shapes.h"
#include "support/world_fixture.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
using sm::test::ellipsoid_def;
using sm::test::run_steps;

namespace
{

sm::World make_world(double dt = 1e-3)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.contact.enabled = false; // these tests are about the springs alone
    return sm::World(def);
}

sm::ConstraintDef hang_from_world(sm::Entity body, sm::Vec3 world_point, sm::Vec3 local_anchor)
{
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = body;
    c.anchor_a.point = local_anchor;
    c.anchor_b.point = world_point;
    return c;
}

// A static 5 cm base at (0, 2, 0) and, below it, a limb of `radii` whose top end (0.2 m above its
// centre) sits at the base, spinning rigidly about that end at `omega` [rad/s] (v = ω × r).
sm::Entity add_limb(sm::World& w, sm::Vec3 radii, sm::Vec3 omega)
{
    sm::BodyDef base_def = ellipsoid_def({0.05, 0.05, 0.05}, {0, 2, 0});
    base_def.motion = sm::MotionType::Static;
    (void)sm::create_body(w, base_def);
    sm::BodyDef limb_def = ellipsoid_def(radii, {0, 1.8, 0});
    limb_def.angular_velocity = omega;
    limb_def.linear_velocity = sm::cross(omega, sm::Vec3{0, -0.2, 0});
    return sm::create_body(w, limb_def);
}

// The ball joint from add_limb's base (the first body) to the limb's top end, limit axis down.
sm::ConstraintDef limb_joint(const sm::World& w, sm::Entity limb)
{
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = sm::world_bodies(w).front();
    c.b = limb;
    c.anchor_b.point = {0, 0.2, 0};
    c.axis_a = {0, -1, 0};
    return c;
}

} // namespace

// A ball hanging from a world point sags by m·g/k = g/ω² (k = m·ω² for a point mass): with f = 30 Hz,
// 0.276 mm. The lever arm is zero, so the effective mass is exactly m. 1% covers the settling residue
// left after 3 s at ζ = 0.7 (e^(−ζω·3 s) is far below that).
TEST(ConstraintSolve, HangingBallSagsByGravityOverOmegaSquared)
{
    sm::World w = make_world();
    const sm::Entity ball = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0, 1, 0}));
    const sm::Constraint c = sm::create_constraint(w, hang_from_world(ball, {0, 1, 0}, {}));
    ASSERT_FALSE(c.is_null());
    run_steps(w, 3000);
    const double omega = 2.0 * M_PI * 30.0;
    const double expected = 9.81 / (omega * omega);
    EXPECT_NEAR(1.0 - sm::body_position(w, ball).y, expected, 0.01 * expected);
    EXPECT_NEAR(sm::constraint_error(w, c).linear, expected, 0.01 * expected);
    EXPECT_NEAR(sm::constraint_force(w, c).y, sm::body_mass_properties(w, ball).mass * 9.81,
                0.01 * sm::body_mass_properties(w, ball).mass * 9.81);
}

// Physical pendulum: a ball on a 1 m lever, small swing (0.05 rad). Period 2π·√(I_pivot/(m·g·L)) with
// I_pivot = I_cm + m·L². Corrections: finite amplitude θ²/16 = 1.6e-4, spring stretch g/(ω²L) = 2.8e-4
// (relative), step error O(h²); 0.2% bounds them with margin and fails for a wrong lever or inertia.
TEST(ConstraintSolve, PendulumPeriodMatchesPhysicalPendulum)
{
    sm::World w = make_world();
    const double length = 1.0, theta0 = 0.05, r = 0.1;
    const sm::Vec3 pivot{0, 2, 0};
    const sm::Vec3 start = pivot + sm::Vec3{length * std::sin(theta0), -length * std::cos(theta0), 0};
    const sm::Entity ball = sm::create_body(w, ellipsoid_def({r, r, r}, start));
    sm::ConstraintDef c = hang_from_world(ball, pivot, {0, 0, 0});
    c.anchor_a.point = pivot - start; // the pivot in the ball's frame (identity orientation)
    c.damping_ratio = 0.0;
    ASSERT_FALSE(sm::create_constraint(w, c).is_null());
    // Zero crossings of x − pivot.x going the same way mark whole periods.
    std::vector<double> crossings;
    double prev = sm::body_position(w, ball).x - pivot.x;
    for (int i = 0; i < 8000; ++i) {
        w.step();
        const double x = sm::body_position(w, ball).x - pivot.x;
        if (prev > 0.0 && x <= 0.0)
            crossings.push_back(w.time() - w.settings().dt * x / (x - prev));
        prev = x;
    }
    ASSERT_GE(crossings.size(), 3u);
    const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    // The ball rotates with the lever (the anchor is fixed in it), so its own inertia counts.
    const double m = sm::body_mass_properties(w, ball).mass;
    const double i_pivot = 0.4 * m * r * r + m * length * length;
    const double expected = 2.0 * M_PI * std::sqrt(i_pivot / (m * 9.81 * length));
    EXPECT_NEAR(period, expected, 2e-3 * expected);
}

// Any mass ratio: a 1 kg ball hanging under a 1000 kg ball hanging from the world. Each spring acts
// through its own pair's effective mass, so both settle to their own sag g/ω²·(load/m_eff) quickly.
TEST(ConstraintSolve, LightUnderHeavyChainSettlesTight)
{
    sm::World w = make_world();
    const double unit = 1.0 / (4.0 / 3.0 * M_PI * 1e-3); // density of 1 kg in a 0.1 m ball [kg/m³]
    const sm::Entity heavy = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0, 2, 0}, 1000.0 * unit));
    const sm::Entity light = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0, 1, 0}, unit));
    const sm::Constraint top = sm::create_constraint(w, hang_from_world(heavy, {0, 2.1, 0}, {0, 0.1, 0}));
    sm::ConstraintDef link = sm::default_constraint_def();
    link.a = heavy;
    link.b = light;
    link.anchor_a.point = {0, -0.4, 0};
    link.anchor_b.point = {0, 0.6, 0};
    const sm::Constraint bottom = sm::create_constraint(w, link);
    run_steps(w, 5000);
    for (sm::Entity e : {light, heavy})
        EXPECT_LT(sm::length(sm::body_linear_velocity(w, e)), 1e-4);
    // Top: load 1001 kg·g on m_eff = 1000 kg: 0.277 mm. Bottom: 1 kg·g on m_eff = 0.999 kg: 0.276 mm.
    const double omega = 2.0 * M_PI * 30.0, sag = 9.81 / (omega * omega);
    EXPECT_NEAR(sm::constraint_error(w, top).linear, 1.001 * sag, 0.02 * sag);
    EXPECT_NEAR(sm::constraint_error(w, bottom).linear, sag / 0.999, 0.02 * sag);
}

// The other way round, a 1000 kg ball under a 1 kg link: the link spring's stiffness is set by the
// 1 kg pair mass, so it carries 1001 kg·g with a large stretch, 1001·g/ω² = 0.28 m. That is the
// model (a frequency per pair), not an instability: the motion stays finite and, released from zero
// stretch, peaks below twice the static value (the undamped bound) per spring.
TEST(ConstraintSolve, HeavyUnderLightChainStaysBounded)
{
    sm::World w = make_world();
    const double unit = 1.0 / (4.0 / 3.0 * M_PI * 1e-3);
    const sm::Entity light = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0, 2, 0}, unit));
    const sm::Entity heavy = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0, 1, 0}, 1000.0 * unit));
    const sm::Constraint top = sm::create_constraint(w, hang_from_world(light, {0, 2.1, 0}, {0, 0.1, 0}));
    sm::ConstraintDef link = sm::default_constraint_def();
    link.a = light;
    link.b = heavy;
    link.anchor_a.point = {0, -0.4, 0};
    link.anchor_b.point = {0, 0.6, 0};
    const sm::Constraint bottom = sm::create_constraint(w, link);
    const double omega = 2.0 * M_PI * 30.0, stretch = 1001.0 * 9.81 / (omega * omega);
    double worst = 0.0;
    for (int i = 0; i < 5000; ++i) {
        w.step();
        worst =
            std::max({worst, sm::constraint_error(w, top).linear, sm::constraint_error(w, bottom).linear});
        ASSERT_TRUE(sm::is_finite(sm::body_position(w, heavy)));
    }
    EXPECT_LT(worst, 2.0 * stretch);
    EXPECT_GT(worst, 0.5 * stretch);
}

// The springs are integrated implicitly: a 1 MHz spring at a 10 ms step (ω·h = 6e4) holds like a rigid
// link instead of exploding, as an explicit penalty spring would.
TEST(ConstraintSolve, VeryStiffSpringAtLargeStepStaysStable)
{
    sm::World w = make_world(1e-2);
    const sm::Entity ball = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0.3, 1, 0}));
    sm::ConstraintDef c = hang_from_world(ball, {0, 1, 0}, {});
    c.frequency_hz = 1e6;
    ASSERT_FALSE(sm::create_constraint(w, c).is_null());
    run_steps(w, 500);
    EXPECT_TRUE(sm::is_finite(sm::body_position(w, ball)));
    EXPECT_LT(sm::length(sm::body_position(w, ball) - sm::Vec3{0, 1, 0}), 1e-3);
}

// Distance: a ball whirled on a 1 m rod keeps its radius; the rod's spring takes the centripetal
// load m·v²/L with stretch v²/(L·ω²) = 4/(1·(2π·30)²) = 0.113 mm.
TEST(ConstraintSolve, DistanceHoldsWhirlingBall)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1e-3;
    def.gravity = {};
    def.contact.enabled = false;
    sm::World w(def);
    sm::BodyDef bd = ellipsoid_def({0.05, 0.05, 0.05}, {1, 0, 0});
    bd.linear_velocity = {0, 0, 2};
    const sm::Entity ball = sm::create_body(w, bd);
    sm::ConstraintDef c = hang_from_world(ball, {0, 0, 0}, {});
    c.type = sm::ConstraintType::Distance;
    const sm::Constraint rod = sm::create_constraint(w, c);
    double worst = 0.0;
    for (int i = 0; i < 4000; ++i) {
        w.step();
        worst = std::max(worst, std::abs(sm::length(sm::body_position(w, ball)) - 1.0));
    }
    EXPECT_NEAR(sm::length(sm::body_linear_velocity(w, ball)), 2.0, 0.02);
    // Steady stretch v²/(L·ω²) = 0.113 mm, plus the overshoot of starting unstretched (4.6% at
    // ζ = 0.7) and the chord error of a 2 mm step on a 1 m circle (2e-6 m): within [0.9, 1.5]×.
    const double omega = 2.0 * M_PI * 30.0, stretch = 4.0 / (omega * omega);
    EXPECT_LT(worst, 1.5 * stretch);
    EXPECT_GT(worst, 0.9 * stretch); // the spring does stretch: the load is real
    EXPECT_NEAR(sm::constraint_error(w, rod).linear, stretch, 0.2 * stretch);
}

// Weld: a 1 m beam welded at one end to the world droops by the angle τ/(I_eff·ω²) only.
TEST(ConstraintSolve, WeldHoldsCantileverOrientation)
{
    sm::World w = make_world();
    const sm::Entity beam = sm::create_body(w, ellipsoid_def({0.5, 0.05, 0.05}, {0.5, 1, 0}));
    sm::ConstraintDef c = hang_from_world(beam, {0, 1, 0}, {-0.5, 0, 0});
    c.type = sm::ConstraintType::Weld;
    c.frequency_hz = 20.0;
    const sm::Constraint weld = sm::create_constraint(w, c);
    run_steps(w, 4000);
    const sm::ConstraintError e = sm::constraint_error(w, weld);
    // Angular: τ = m·g·0.5 m about the anchor, I_eff = I_cm (the world is immovable): for a
    // 0.5×0.05×0.05 ellipsoid I_cm,z = m(0.5² + 0.05²)/5, so θ ≈ g·0.5/((0.2525/5)·ω²) = 6.2e-3 rad.
    // The point spring carries the lever too, which shifts this; 30% bounds the coupling.
    const double omega = 2.0 * M_PI * 20.0;
    const double theta = 9.81 * 0.5 / ((0.2525 / 5.0) * omega * omega);
    EXPECT_NEAR(e.angular, theta, 0.3 * theta);
    EXPECT_LT(sm::length(sm::body_angular_velocity(w, beam)), 1e-3);
}

// An upper-arm-like limb (0.4 m ellipsoid) hanging from a ball joint, kicked hard enough to swing
// about 0.9 rad freely, stops near its 0.3 rad swing limit.
TEST(ConstraintSolve, SwingLimitStopsLimb)
{
    sm::World w = make_world();
    const sm::Entity limb = add_limb(w, {0.05, 0.2, 0.05}, {0, 0, 8.0});
    sm::ConstraintDef c = limb_joint(w, limb);
    c.swing_limit = 0.3;
    c.frequency_hz = 30.0;
    c.damping_ratio = 1.0;
    ASSERT_FALSE(sm::create_constraint(w, c).is_null());
    double max_angle = 0.0;
    for (int i = 0; i < 2000; ++i) {
        w.step();
        const sm::Vec3 d = sm::body_position(w, limb) - sm::Vec3{0, 2, 0};
        max_angle = std::max(max_angle, std::atan2(std::abs(d.x), -d.y));
    }
    // Free swing: ½·I_pivot·ω² = m·g·L·(1 − cos θ) with I_pivot = m(0.2² + 0.05²)/5 + m·0.2² gives
    // θ ≈ 0.95 rad. The penalty limit overshoots by the spring's give; 0.1 rad over the limit is far
    // below what a missing limit gives.
    EXPECT_GT(max_angle, 0.29);
    EXPECT_LT(max_angle, 0.4);
}

// A weld whose break force is below the load breaks on the first step, stays broken, and is hashed.
TEST(ConstraintSolve, BreakForceBreaksAndIsState)
{
    sm::World w = make_world();
    const sm::Entity ball = sm::create_body(w, ellipsoid_def({0.1, 0.1, 0.1}, {0, 0.9, 0}));
    sm::ConstraintDef c = hang_from_world(ball, {0, 1, 0}, {});
    c.break_force = 1.0; // N; the 4.2 kg ball pulls ~41 N on a 0.1 m stretch at once
    const sm::Constraint weak = sm::create_constraint(w, c);
    const sm::Snapshot before = w.snapshot();
    const uint64_t hash_before = w.state_hash();
    w.step();
    EXPECT_TRUE(sm::constraint_broken(w, weak));
    EXPECT_EQ(sm::world_broken_constraints(w), 1u);
    run_steps(w, 200);
    EXPECT_LT(sm::body_position(w, ball).y, 0.8); // falling freely
    ASSERT_TRUE(w.restore(before).ok());
    EXPECT_FALSE(sm::constraint_broken(w, weak));
    EXPECT_EQ(w.state_hash(), hash_before);
}

// A twist-limited ball joint swung through large angles must not gain energy. The twist is measured
// about the axis as both bodies carry it (their bisector), and not at all near a half-turn swing;
// with a's axis alone, or a twist that jumps at the singular swing, this limb gained energy without
// bound (a dummy with twist limits only reached 50 m/s).
TEST(ConstraintSolve, TwistLimitedJointDoesNotGainEnergy)
{
    sm::World w = make_world();
    // Swing about x and z, twist about y.
    const sm::Entity limb = add_limb(w, {0.05, 0.2, 0.03}, {6.0, 3.0, 9.0});
    sm::ConstraintDef c = limb_joint(w, limb);
    c.twist_limit = 0.1;
    c.frequency_hz = 60.0;
    c.damping_ratio = 1.0;
    ASSERT_FALSE(sm::create_constraint(w, c).is_null());
    const double e0 = sm::body_kinetic_energy(w, limb) + sm::body_potential_energy(w, limb);
    double worst = -1e300;
    for (int i = 0; i < 3000; ++i) {
        w.step();
        const double e = sm::body_kinetic_energy(w, limb) + sm::body_potential_energy(w, limb);
        worst = std::max(worst, e - e0);
    }
    // The springs and the limit only dissipate; allow the joint spring's stored energy (its stretch
    // under the swing's centripetal load is ~1e-4 m, so well under 1e-3 of e0).
    EXPECT_LT(worst, 1e-3 * e0);
}
