// Tests for the rolling resistance of engine/src/contact/penalty.cpp against the rigid-ball results:
// a torque up to ℓ·F_n slows a rolling ball by a = (5/7)·g·ℓ/r and holds it on slopes with tan θ ≤ ℓ/r.
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"
#include "world/world_impl.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace sm = supermodal;
using sm::test::run_steps;

namespace
{

constexpr double k_g = 9.81;
constexpr double k_radius = 0.05; // [m]

sm::World make_world(sm::ContactSolver solver)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.002;
    def.contact.solver = solver;
    return sm::World(def);
}

void add_plane(sm::World& w, sm::Vec3 normal)
{
    sm::BodyDef d = sm::default_body_def();
    d.motion = sm::MotionType::Static;
    d.shape.type = sm::ShapeType::Plane;
    d.shape.plane_normal = normal;
    d.friction = 0.8;
    (void)sm::create_body(w, d);
}

sm::Entity add_ball(sm::World& w, sm::Vec3 position, double rolling_resistance)
{
    sm::BodyDef d = sm::default_body_def();
    d.shape.radii = {k_radius, k_radius, k_radius};
    d.position = position;
    d.friction = 0.8;
    d.rolling_resistance = rolling_resistance;
    return sm::create_body(w, d);
}

} // namespace

// Each test on both contact solvers (the parameter, named in the test).
class RollingResistance : public ::testing::TestWithParam<sm::ContactSolver>
{
};

TEST_P(RollingResistance, BallRollsToAStopAtFiveSeventhsGEllOverR)
{
    // v0 = 0.5 m/s, ℓ = 1 mm, r = 5 cm: a = (5/7)·9.81·0.02 = 0.140 m/s², stopping in 3.57 s after
    // v0²/(2a) = 0.892 m. Measured (2026-11-26) within 0.12% of each; asserted within 1% (the ball sits
    // on its penalty spring a fraction of a millimetre deep, so its lever differs from r by that share).
    sm::World w = make_world(GetParam());
    add_plane(w, {0, 1, 0});
    const double ell = 0.001, v0 = 0.5;
    const sm::Entity b = add_ball(w, {0, k_radius, 0}, ell);
    run_steps(w, 50); // settle onto the spring
    const sm::Vec3 start = sm::body_position(w, b);
    sm::set_body_linear_velocity(w, b, {v0, 0, 0});
    sm::set_body_angular_velocity(w, b, {0, 0, -v0 / k_radius});
    const double a = 5.0 / 7.0 * k_g * ell / k_radius;
    const double t_stop = v0 / a, distance = v0 * v0 / (2.0 * a);
    run_steps(w, static_cast<int>(std::lround(0.5 * t_stop / 0.002)));
    // Halfway in time the speed has halved and three quarters of the distance are covered.
    EXPECT_NEAR(sm::body_linear_velocity(w, b).x, 0.5 * v0, 0.01 * v0);
    EXPECT_NEAR(sm::body_position(w, b).x - start.x, 0.75 * distance, 0.01 * distance);
    run_steps(w, static_cast<int>(std::lround(t_stop / 0.002)));
    EXPECT_NEAR(sm::body_position(w, b).x - start.x, distance, 0.01 * distance);
    // Then it rests: the spring holds it, no creep.
    EXPECT_LT(sm::length(sm::body_linear_velocity(w, b)), 1e-4);
}

TEST_P(RollingResistance, HoldsOnASlopeBelowEllOverRAndRollsAbove)
{
    // Static rolling resistance holds a ball where tan θ ≤ ℓ/r = 0.05 (2.86°): at 2° it stays, at 4° it
    // rolls off at (5/7)·g·(sin θ − cos θ·ℓ/r) = 0.139 m/s² (measured within 0.02%; asserted within
    // 1%, as above). At 2° it moves 1.4 nm in 1 s (asserted under 0.1 mm).
    for (const double degrees : {2.0, 4.0}) {
        const double theta = degrees * std::numbers::pi / 180.0;
        const sm::Vec3 up{-std::sin(theta), std::cos(theta), 0};
        const sm::Vec3 down{-std::cos(theta), -std::sin(theta), 0};
        sm::World w = make_world(GetParam());
        add_plane(w, up);
        const sm::Entity b = add_ball(w, k_radius * up, 0.0025);
        run_steps(w, 250);
        const sm::Vec3 p0 = sm::body_position(w, b);
        const double v0 = sm::dot(sm::body_linear_velocity(w, b), down);
        run_steps(w, 500);
        const double s = sm::dot(sm::body_position(w, b) - p0, down);
        if (degrees < 3.0) {
            EXPECT_LT(std::abs(s), 1e-4) << degrees << " degrees";
        } else {
            const double a = 2.0 * (s - v0 * 1.0);
            const double expected = 5.0 / 7.0 * k_g * (std::sin(theta) - std::cos(theta) * 0.05);
            EXPECT_NEAR(a, expected, 0.01 * expected) << degrees << " degrees";
        }
    }
}

TEST_P(RollingResistance, ZeroKeepsTheBallRolling)
{
    // The default (ℓ = 0): no rolling torque, a rolling ball on the level keeps its speed to 0.1%.
    sm::World w = make_world(GetParam());
    add_plane(w, {0, 1, 0});
    const sm::Entity b = add_ball(w, {0, k_radius, 0}, 0.0);
    run_steps(w, 50);
    sm::set_body_linear_velocity(w, b, {0.5, 0, 0});
    sm::set_body_angular_velocity(w, b, {0, 0, -0.5 / k_radius});
    run_steps(w, 1000);
    EXPECT_NEAR(sm::body_linear_velocity(w, b).x, 0.5, 5e-4);
}

TEST_P(RollingResistance, AnchorIsStateSnapshotRestoreContinuesBitIdentical)
{
    sm::World w = make_world(GetParam());
    add_plane(w, {0, 1, 0});
    const sm::Entity b = add_ball(w, {0, k_radius, 0}, 0.001);
    run_steps(w, 50);
    sm::set_body_angular_velocity(w, b, {0, 0, -2.0});
    run_steps(w, 10);
    const sm::Snapshot snap = w.snapshot();
    ASSERT_FALSE(sm::impl_of(w).contact.anchors.empty());
    run_steps(w, 100);
    const uint64_t expected = w.state_hash();
    ASSERT_TRUE(w.restore(snap));
    run_steps(w, 100);
    EXPECT_EQ(w.state_hash(), expected);
}

INSTANTIATE_TEST_SUITE_P(Solvers, RollingResistance,
                         ::testing::Values(sm::ContactSolver::Penalty, sm::ContactSolver::Soft),
                         [](const auto& info) {
                             return std::string(info.param == sm::ContactSolver::Soft ? "soft" : "penalty");
                         });
