// Tests for engine/src/world/contact_solve.cpp: the soft contact solver through the world's step, at a
// game's step (1/60 s, one substep) and against analytic results.
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "supermodal/tasks.h"
#include "supermodal/world.h"
#include "support/stack_checks.h"
#include "support/world_fixture.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace sm = supermodal;
using sm::test::run_steps;

namespace
{

constexpr double k_g = 9.81;
constexpr double k_game_dt = 1.0 / 60.0;

sm::WorldDef soft_def(double dt, sm::ContactPath path = sm::ContactPath::Auto)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.contact.solver = sm::ContactSolver::Soft;
    def.contact.path = path;
    def.contact.soft.substeps = 1; // one narrowphase and one solve per step, unless a test says otherwise
    def.sleep.enabled = false;     // these tests measure the contact at rest, not a body put to sleep
    return def;
}

using sm::test::about_z;
using sm::test::add_plane;

sm::Entity add_body(sm::World& w, sm::Vec3 radii, double eps, sm::Vec3 pos, sm::Quat q = {},
                    double friction = 0.5, double restitution = 0.0, double density = 1000.0)
{
    return sm::test::add_superquadric(w, radii, eps, pos, q, friction, restitution, density);
}

// A ball (r = 5 cm, restitution e) dropped `drop` onto a plane at 1 ms: the height of its first
// bounce's apex [m].
double bounce_apex(int solver_substeps, double e, double drop)
{
    const double r = 0.05;
    sm::WorldDef def = soft_def(0.001, sm::ContactPath::SupportMap);
    def.contact.soft.substeps = solver_substeps;
    sm::World w(def);
    add_plane(w, {0, 1, 0});
    const sm::Entity b = add_body(w, {r, r, r}, 1.0, {0, r + drop, 0}, {}, 0.0, e);
    double apex = 0.0;
    bool bounced = false;
    for (int i = 0; i < 3000; ++i) {
        w.step();
        const double y = sm::body_position(w, b).y - r;
        const double vy = sm::body_linear_velocity(w, b).y;
        bounced = bounced || (y > 0.01 && vy > 0.0);
        if (bounced)
            apex = std::max(apex, y);
        if (bounced && vy < 0.0)
            break;
    }
    return apex;
}

struct RestCase {
    const char* name;
    sm::Vec3 radii;
    double eps;
    sm::ContactPath path;
};

} // namespace

class SoftRest : public ::testing::TestWithParam<RestCase>
{
};

TEST_P(SoftRest, BodyRestsOnPlaneAtSixtyHertzWithOneSubstep)
{
    // The static spring runs at twice the automatic 1/(2h) = 30 Hz, so a body sinks g/ω² ≈ 0.07 mm:
    // within 1% of the smallest radius. At rest it neither drifts nor moves.
    const RestCase c = GetParam();
    sm::World w(soft_def(k_game_dt, c.path));
    add_plane(w, {0, 1, 0});
    const sm::Entity b = add_body(w, c.radii, c.eps, {0.3, c.radii.y + 1e-3, -0.2});
    run_steps(w, 600);
    const double smallest = std::min({c.radii.x, c.radii.y, c.radii.z});
    const sm::Vec3 p = sm::body_position(w, b);
    EXPECT_LE(c.radii.y - p.y, 0.01 * smallest);
    EXPECT_LE(std::hypot(p.x - 0.3, p.z + 0.2), 1e-4);
    EXPECT_LE(sm::length(sm::body_linear_velocity(w, b)), 1e-3);
    EXPECT_LE(sm::world_max_penetration(w), 0.01 * smallest);
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, SoftRest,
    ::testing::Values(RestCase{"sphere", {0.1, 0.1, 0.1}, 1.0, sm::ContactPath::Sampling},
                      RestCase{"ellipsoid", {0.2, 0.1, 0.15}, 1.0, sm::ContactPath::Sampling},
                      RestCase{"rounded_box", {0.1, 0.1, 0.1}, 0.3, sm::ContactPath::Sampling},
                      RestCase{"sphere_mpr", {0.1, 0.1, 0.1}, 1.0, sm::ContactPath::SupportMap},
                      RestCase{"ellipsoid_mpr", {0.2, 0.1, 0.15}, 1.0, sm::ContactPath::SupportMap},
                      RestCase{"rounded_box_mpr", {0.1, 0.1, 0.1}, 0.3, sm::ContactPath::SupportMap}),
    [](const ::testing::TestParamInfo<RestCase>& info) { return std::string(info.param.name); });

TEST(SoftContact, StiffSpringAtLongStepStaysStable)
{
    // ω·h = 2π·1000/60 ≈ 105, far past any explicit method's limit (2): the implicit spring tends to a
    // rigid contact instead of blowing up. The ball lands from 5 cm and rests (g/ω² = 0.06 µm).
    sm::WorldDef def = soft_def(k_game_dt, sm::ContactPath::SupportMap);
    def.contact.soft.frequency_hz = 1000.0;
    sm::World w(def);
    add_plane(w, {0, 1, 0});
    const sm::Entity b = add_body(w, {0.1, 0.1, 0.1}, 1.0, {0, 0.15, 0});
    double highest = 0.0;
    for (int i = 0; i < 300; ++i) {
        w.step();
        if (i > 30)
            highest = std::max(highest, sm::body_position(w, b).y);
    }
    EXPECT_LT(highest, 0.1 + 1e-3); // no bounce off a stiff spring
    EXPECT_NEAR(sm::body_position(w, b).y, 0.1, 1e-3);
    EXPECT_LT(sm::length(sm::body_linear_velocity(w, b)), 1e-3);
}

TEST(SoftContact, BlockOnInclineBelowFrictionAngleStaysPut)
{
    // tan θ = 0.4 < μ = 0.5: static friction holds. Friction is a velocity constraint, so nothing
    // stretches: after settling the block moves less than 1 mm over 2 s at 1/60 s.
    const double theta = std::atan(0.4);
    sm::World w(soft_def(k_game_dt));
    const sm::Vec3 up{-std::sin(theta), std::cos(theta), 0};
    add_plane(w, up, 0.0, 0.5);
    const sm::Entity b = add_body(w, {0.1, 0.05, 0.1}, 0.1, 0.0501 * up, about_z(theta), 0.5);
    run_steps(w, 30);
    const sm::Vec3 p0 = sm::body_position(w, b);
    run_steps(w, 120);
    EXPECT_LT(sm::length(sm::body_position(w, b) - p0), 1e-3);
}

TEST(SoftContact, BlockOnInclineAboveFrictionAngleSlidesAtCoulombRate)
{
    // tan θ = 0.7 > μ = 0.3: a = g (sin θ − μ cos θ) along the slope, within 2%.
    const double theta = std::atan(0.7), mu = 0.3;
    sm::World w(soft_def(k_game_dt));
    const sm::Vec3 up{-std::sin(theta), std::cos(theta), 0};
    const sm::Vec3 down{-std::cos(theta), -std::sin(theta), 0};
    add_plane(w, up, 0.0, mu);
    const sm::Entity b = add_body(w, {0.1, 0.05, 0.1}, 0.1, 0.0501 * up, about_z(theta), mu);
    run_steps(w, 30);
    const double v0 = sm::dot(sm::body_linear_velocity(w, b), down);
    run_steps(w, 60);
    const double v1 = sm::dot(sm::body_linear_velocity(w, b), down);
    const double expected = k_g * (std::sin(theta) - mu * std::cos(theta));
    EXPECT_NEAR((v1 - v0) / (60 * k_game_dt), expected, 0.02 * expected);
}

TEST(SoftContact, BounceLeavesAtRestitutionTimesImpactSpeed)
{
    // Restitution is a velocity target: a ball hitting at v leaves at e·v, so it rises to e²·h, within
    // 5%. The rest is the landing: the contact is found once the ball overlaps, up to v·dt deep, and
    // it leaves from there (at 1/240 s, 13 mm: the apex measured 7% low; at 1 ms, 3 mm).
    const double e = 0.5, drop = 0.5;
    EXPECT_NEAR(bounce_apex(1, e, drop), e * e * drop, 0.05 * e * e * drop);
}

TEST(SoftContact, LightBoxOnHeavyBoxRestsAtGameStep)
{
    // Mass ratio 1000 at 1/60 s, the light box on top: both rest where they were put, within the
    // springs' sink (g/ω², 0.07 mm under the automatic 60 Hz static spring, 0.28 mm at 30 Hz between
    // the boxes) and the 1 mm the narrowphase's manifold may misplace on the rounded faces.
    sm::World w(soft_def(k_game_dt, sm::ContactPath::SupportMap));
    add_plane(w, {0, 1, 0});
    const sm::Entity low = add_body(w, {0.1, 0.1, 0.1}, 0.3, {0, 0.1, 0}, {}, 0.5, 0.0, 1e6);
    const sm::Entity high = add_body(w, {0.1, 0.1, 0.1}, 0.3, {0, 0.3, 0}, {}, 0.5, 0.0, 1000.0);
    run_steps(w, 300);
    EXPECT_NEAR(sm::body_position(w, high).y, 0.3, 1.5e-3);
    EXPECT_NEAR(sm::body_position(w, low).y, 0.1, 1e-3);
    EXPECT_LT(sm::length(sm::body_linear_velocity(w, high)), 1e-3);
}

struct HeavyCase {
    const char* name;
    double mass_ratio;
    double dt;
};

class SoftHeavyOnLight : public ::testing::TestWithParam<HeavyCase>
{
};

TEST_P(SoftHeavyOnLight, HeavyBoxDroppedOnLightBoxStands)
{
    // A rounded box 1000 (10^6) times heavier dropped 5 cm onto a light one resting on the ground: it
    // must stop on it and both stand. Unscaled, the passes moved the heavy box by the light one's
    // effective mass and shot the light box out (measured: 2.2 m away after the 3 s). Bounds: each contact
    // sinks by g/ω² under its load (the springs are tuned to it), 0.07 mm at the automatic 60 Hz
    // between the boxes and 0.02 mm at the doubled 120 Hz on the ground; 0.5 mm leaves room for the
    // landing's leftover overlap on the rounded faces (measured 0.08 mm between the boxes at 1/240 s,
    // 0.14 mm at 1 ms). The landing may shift the heavy box sideways (measured 3.4 mm), not the light one.
    const HeavyCase c = GetParam();
    sm::World w(soft_def(c.dt, sm::ContactPath::SupportMap));
    add_plane(w, {0, 1, 0});
    const double half = 0.1, drop = 0.05, sink = 5e-4;
    const sm::Entity low = add_body(w, {half, half, half}, 0.5, {0, half, 0}, {}, 0.5, 0.5);
    run_steps(w, static_cast<int>(1.0 / c.dt));
    const sm::Vec3 settled = sm::body_position(w, low);
    const sm::Entity high = add_body(w, {half, half, half}, 0.5, {0, settled.y + 2.0 * half + drop, 0}, {},
                                     0.5, 0.5, 1000.0 * c.mass_ratio);
    run_steps(w, static_cast<int>(3.0 / c.dt));
    sm::test::expect_box_stands_on_box(w, low, high, settled, half, sink);
}

INSTANTIATE_TEST_SUITE_P(MassRatioAndStep, SoftHeavyOnLight,
                         ::testing::Values(HeavyCase{"ratio_1e3_240hz", 1e3, 1.0 / 240.0},
                                           HeavyCase{"ratio_1e3_1ms", 1e3, 1e-3},
                                           HeavyCase{"ratio_1e6_240hz", 1e6, 1.0 / 240.0}),
                         [](const ::testing::TestParamInfo<HeavyCase>& info) {
                             return std::string(info.param.name);
                         });

TEST(SoftContact, SameHashOnOneAndTwoThreads)
{
    // `heavy`: every third body 1000 times denser, so heavy-on-light pairs take the scaled lower mass.
    auto run = [](int threads, int solver_substeps, bool heavy) {
        sm::WorldDef def = soft_def(1.0 / 240.0);
        def.thread_count = threads;
        def.contact.soft.substeps = solver_substeps;
        sm::World w(def);
        add_plane(w, {0, 1, 0});
        for (int i = 0; i < 60; ++i)
            add_body(w, {0.05, 0.04, 0.03}, i % 2 == 0 ? 1.0 : 0.3,
                     {0.09 * (i % 5), 0.1 + 0.09 * (i / 5), 0.09 * ((i / 5) % 3)}, {}, 0.5, 0.0,
                     heavy && i % 3 == 0 ? 1e6 : 1000.0);
        run_steps(w, 240);
        return w.state_hash();
    };
    for (const bool heavy : {false, true})
        for (const int solver_substeps : {1, 3})
            EXPECT_EQ(run(1, solver_substeps, heavy), run(2, solver_substeps, heavy))
                << solver_substeps << " solver substeps, heavy " << heavy;
}

class SoftModalBounce : public ::testing::TestWithParam<int>
{
};

TEST_P(SoftModalBounce, BouncingModalBallDoesNotGainEnergy)
{
    // A soft modal ball (r = 0.1 m, E = 2 MPa, 8 modes, restitution 0.5) dropped 0.05 m at 1 ms: between
    // contacts its total energy (rigid, potential, modal) never exceeds the start by more than 1% of the
    // drop's. The modes bounce it; a restitution target on the ringing surface's speed pumped it to
    // 3.3× the drop energy before such points were left out of the bounce.
    // With solver substeps (the parameter) the modal sides are made anew every substep.
    sm::WorldDef wd = soft_def(0.001, sm::ContactPath::Sampling);
    wd.contact.soft.substeps = GetParam();
    sm::World w(wd);
    add_plane(w, {0, 1, 0});
    sm::BodyDef def = sm::default_body_def();
    def.shape.radii = {0.1, 0.1, 0.1};
    def.restitution = 0.5;
    def.modal.enabled = true;
    def.modal.mode_count = 8;
    def.young = 2e6;
    def.position = {0, 0.15, 0};
    const sm::Entity ball = sm::create_body(w, def);
    ASSERT_FALSE(ball.is_null());
    auto energy = [&] {
        return sm::body_kinetic_energy(w, ball) + sm::body_potential_energy(w, ball) +
               sm::body_modal_energy(w, ball);
    };
    const double e_ref = sm::body_mass_properties(w, ball).mass * k_g * 0.05;
    const double e0 = energy();
    double gain = -1.0;
    bool touched = false;
    for (int i = 0; i < 1000; ++i) {
        w.step();
        touched = touched || !sm::world_contacts(w).empty();
        if (touched && sm::world_contacts(w).empty())
            gain = std::max(gain, (energy() - e0) / e_ref);
    }
    EXPECT_TRUE(touched);
    EXPECT_LE(gain, 0.01);
}

INSTANTIATE_TEST_SUITE_P(SolverSubsteps, SoftModalBounce, ::testing::Values(1, 4));

TEST(SoftContact, BoxesPlacedTouchingHoldFromTheFirstStep)
{
    // Three rounded boxes placed exactly touching each other and the floor, at 1/60 s: faces apart by
    // less than the speculative gap are rows already, so no box falls in the first step. Without them
    // each pair acted only once it overlapped, and the boxes fell freely (g·dt = 0.16 m/s) one after
    // another up the column. Bound: 1 cm/s, well under one step of free fall.
    sm::World w(soft_def(k_game_dt, sm::ContactPath::SupportMap));
    add_plane(w, {0, 1, 0});
    std::vector<sm::Entity> boxes;
    for (int i = 0; i < 3; ++i)
        boxes.push_back(add_body(w, {0.1, 0.1, 0.1}, 0.3, {0, 0.1 + 0.2 * i, 0}));
    for (int step = 0; step < 3; ++step) {
        w.step();
        for (const sm::Entity b : boxes)
            EXPECT_LT(sm::length(sm::body_linear_velocity(w, b)), 0.01) << "step " << step;
    }
}

TEST(SoftContact, BoxAcrossTwoPlacedTouchingHoldsFromTheFirstStep)
{
    // A rounded box placed on two others 1 cm apart (a pyramid's two rows), faces level: the faces side
    // by side drop towards their edges and meet, 0.4 mm apart, in the middle of where they overlap, so
    // they are rows from the first step. Without that pair they had no points until they overlapped by
    // about a centimetre: at 1/60 s the top box fell 1.7 mm in the first step, and a 10-row pyramid fell
    // 11 cm at the top before it held. Bounds: after the first step it moves at under 1 cm/s (free
    // fall: g·dt = 16 cm/s), having closed the gap and sunk by less than 0.6 mm.
    sm::World w(soft_def(k_game_dt, sm::ContactPath::SupportMap));
    add_plane(w, {0, 1, 0});
    add_body(w, {0.1, 0.1, 0.1}, 0.3, {-0.105, 0.1, 0});
    add_body(w, {0.1, 0.1, 0.1}, 0.3, {0.105, 0.1, 0});
    const sm::Entity top = add_body(w, {0.1, 0.1, 0.1}, 0.3, {0, 0.3, 0});
    w.step();
    EXPECT_EQ(sm::world_contacts(w).size(), 4u); // each lower box on the floor and under the top box
    EXPECT_LT(sm::length(sm::body_linear_velocity(w, top)), 0.01);
    EXPECT_GT(sm::body_position(w, top).y, 0.3 - 0.6e-3);
    for (int step = 0; step < 120; ++step)
        w.step();
    EXPECT_LT(sm::length(sm::body_linear_velocity(w, top)), 1e-3);
}

class SoftRestingBox : public ::testing::TestWithParam<double>
{
};

TEST_P(SoftRestingBox, RoundedBoxOnTheFloorIsStill)
{
    // A rounded box (ε 0.3) at rest on the floor, sleep off. Its face is nearly flat only near the pole:
    // on the stiff spring of short steps it sinks tens of micrometres, and its patch corners, set where
    // the face has dropped 0.1 mm, were rows above the floor. It stood on its pole and rocked from one
    // side of it to the other every step (3 mm/s at 1/240 s, measured). With the corners touching it is
    // still to rounding: bound 1e-6 m/s, a thousandth of that.
    sm::World w(soft_def(GetParam(), sm::ContactPath::SupportMap));
    add_plane(w, {0, 1, 0});
    const sm::Entity b = add_body(w, {0.1, 0.1, 0.1}, 0.3, {0.3, 0.101, -0.2});
    double fastest = 0.0;
    const int settle = static_cast<int>(std::lround(2.0 / GetParam()));
    for (int step = 0; step < settle + 100; ++step) {
        w.step();
        if (step >= settle)
            fastest = std::max(fastest, sm::length(sm::body_linear_velocity(w, b)) +
                                            0.1 * sm::length(sm::body_angular_velocity(w, b)));
    }
    EXPECT_LT(fastest, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(StepSizes, SoftRestingBox, ::testing::Values(1.0 / 60.0, 1.0 / 240.0, 1.0 / 1000.0));

namespace
{

// A column of `count` rounded boxes (half 0.1 m, ε 0.3, μ 0.5) at 1/60 s with ±1 mm and ±1° jitter, as
// bench/stack_bench builds it; returns the top box's drift [m] and the largest speed after 2 s [m/s].
// `solver_substeps` 0: the default (automatic).
std::pair<double, double> column_at_game_step(int solver_substeps, int count = 20, int relax_iterations = 0)
{
    sm::WorldDef def = soft_def(k_game_dt, sm::ContactPath::SupportMap);
    def.contact.soft.substeps = solver_substeps;
    def.contact.soft.relax_iterations = relax_iterations;
    def.sleep.enabled = true; // the default, as in the benchmark
    sm::World w(def);
    add_plane(w, {0, 1, 0});
    std::vector<sm::Entity> boxes;
    for (int i = 0; i < count; ++i) {
        const double jitter = 1e-3 * ((i * 7) % 5 - 2) / 2.0; // ±1 mm, fixed pattern
        const double yaw = (std::numbers::pi / 180.0) * ((i * 3) % 5 - 2) / 2.0;
        boxes.push_back(add_body(w, {0.1, 0.1, 0.1}, 0.3, {jitter, 0.1 + 0.2 * i, -jitter}, about_z(0.0)));
        sm::set_body_orientation(w, boxes.back(), sm::quat_from_rotation_vector({0, yaw, 0}));
    }
    const sm::Vec3 start = sm::body_position(w, boxes.back());
    double speed_after = 0.0;
    for (int step = 1; step <= 600; ++step) {
        w.step();
        if (step >= 120)
            for (const sm::Entity b : boxes)
                speed_after = std::max(speed_after, sm::length(sm::body_linear_velocity(w, b)));
    }
    return {sm::length(sm::body_position(w, boxes.back()) - start), speed_after};
}

} // namespace

TEST(SoftContact, TwentyBoxColumnStandsAtGameStepWithFourSolverSubsteps)
{
    // The stacking benchmark's bar: top drift ≤ 1 cm over 10 s and every speed < 1 cm/s after 2 s,
    // default settings (sleeping on). Four solver substeps on one narrowphase per step settle it until
    // it sleeps; with one, the ten passes do not carry the load up the column each step and it falls
    // (measured). Kept awake, it sways and falls within the 10 s on every setting tried (1-4 solver or
    // world substeps, 10-20 passes, 30-60 Hz): the passes leave a residual the column's sway grows on.
    const auto [drift, speed] = column_at_game_step(4);
    EXPECT_LE(drift, 0.01);
    EXPECT_LT(speed, 0.01);
}

TEST(SoftContact, TwentyBoxColumnStandsAtGameStepWithDefaultSettings)
{
    // The same bar with every contact setting at its default: the solver substeps are chosen to keep
    // each at or under 1/240 s, four at 1/60 s.
    const auto [drift, speed] = column_at_game_step(0);
    EXPECT_LE(drift, 0.01);
    EXPECT_LT(speed, 0.01);
}

TEST(SoftContact, TwentyBoxColumnStandsAtGameStepWithOneRelaxPass)
{
    // The cheapest relax (one pass per substep, Box2D's count) leaves some of the push-out's speed in
    // the velocities; the column still meets the bar.
    const auto [drift, speed] = column_at_game_step(0, 20, 1);
    EXPECT_LE(drift, 0.01);
    EXPECT_LT(speed, 0.01);
}

TEST(SoftContact, RelaxPassesOutOfRangeAreRefused)
{
    sm::WorldDef def = soft_def(k_game_dt);
    def.contact.soft.relax_iterations = -1;
    EXPECT_EQ(sm::validate(def).error().where, "contact.soft.relax_iterations");
    def.contact.soft.relax_iterations = 101;
    EXPECT_EQ(sm::validate(def).error().where, "contact.soft.relax_iterations");
    def.contact.soft.relax_iterations = 100;
    EXPECT_TRUE(sm::validate(def).ok());
}

TEST(SoftContact, TallColumnStandsWithTheLoadTunedSpringBounded)
{
    // 25 boxes at 1/60 s in four solver substeps. The bottom contacts' load-tuned springs would reach
    // ω·h ≈ 7 (a rigid row), which the passes leave unconverged down the column; its sway grew on that
    // and it fell (measured in bench/stack_bench: 25 and 30 boxes). Bounded at ω·h = π it stands.
    const auto [drift, speed] = column_at_game_step(4, 25);
    EXPECT_LE(drift, 0.01);
    EXPECT_LT(speed, 0.01);
}

TEST(SoftContact, AutomaticSolverSubstepsKeepEachAtMostA240thOfASecond)
{
    const sm::SoftContactDef automatic{};
    EXPECT_EQ(automatic.substeps, 0);
    EXPECT_EQ(sm::soft_solver_substeps(automatic, 1.0 / 60.0), 4);
    EXPECT_EQ(sm::soft_solver_substeps(automatic, 1.0 / 100.0), 3); // 1/300 s each
    EXPECT_EQ(sm::soft_solver_substeps(automatic, 1.0 / 240.0), 1); // rounding does not add one
    EXPECT_EQ(sm::soft_solver_substeps(automatic, 1.0 / 1000.0), 1);
    EXPECT_EQ(sm::soft_solver_substeps(automatic, 10.0), 64);            // the setting's own bound
    EXPECT_EQ(sm::soft_solver_substeps({.substeps = 2}, 1.0 / 60.0), 2); // a set count is kept
}

TEST(SoftContact, SolverSubstepsFallFreelyLikeWorldSubsteps)
{
    // Without contact, k solver substeps are k substeps of h = dt/k: the same free fall as
    // WorldDef::substep_count = k, to the last bit (same arithmetic, same order).
    auto fall = [](int world_substeps, int solver_substeps) {
        sm::WorldDef def = soft_def(k_game_dt);
        def.substep_count = world_substeps;
        def.contact.soft.substeps = solver_substeps;
        sm::World w(def);
        const sm::Entity b = add_body(w, {0.1, 0.1, 0.1}, 0.5, {0, 10, 0});
        sm::set_body_angular_velocity(w, b, {1, 2, 3});
        run_steps(w, 60);
        return std::pair{sm::body_position(w, b), sm::body_orientation(w, b)};
    };
    const auto [p1, q1] = fall(4, 1);
    const auto [p2, q2] = fall(1, 4);
    EXPECT_EQ(p1.y, p2.y);
    EXPECT_EQ(q1.w, q2.w);
    EXPECT_NEAR(p2.y, 10.0 - 0.5 * k_g * (1.0 + 1.0 / 240.0), 1e-9); // semi-implicit Euler over 240 steps
}

TEST(SoftContact, SolverSubstepsBounceOnceAtRestitutionTimesImpactSpeed)
{
    // The bounce target acts on the last solver substep only, from the approach speed the narrowphase
    // saw: the apex is e²·h within 5% as with one substep (BounceLeavesAtRestitutionTimesImpactSpeed).
    const double e = 0.5, drop = 0.5;
    EXPECT_NEAR(bounce_apex(4, e, drop), e * e * drop, 0.05 * e * e * drop);
}
