// Tests for engine/src/contact/events.cpp through the world's step: begin/persist/end of a bouncing
// ball, the impulse of a resting contact, momentum bookkeeping, order, and the callback rules.
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <cmath>
#include <gtest/gtest.h>
#include <tuple>
#include <vector>

namespace sm = supermodal;
using sm::test::run_steps;

namespace
{

constexpr double k_g = 9.81;

sm::Entity add_plane(sm::World& w)
{
    sm::BodyDef d = sm::default_body_def();
    d.motion = sm::MotionType::Static;
    d.shape.type = sm::ShapeType::Plane;
    d.shape.plane_normal = {0, 1, 0};
    return sm::create_body(w, d);
}

sm::Entity add_ball(sm::World& w, double r, sm::Vec3 pos, double restitution)
{
    sm::BodyDef d = sm::default_body_def();
    d.shape.radii = {r, r, r};
    d.position = pos;
    d.restitution = restitution;
    return sm::create_body(w, d);
}

// Events as the callback received them, step by step.
struct Recorder {
    std::vector<sm::ContactEvent> events;
    static void on_event(const sm::ContactEvent& e, void* self)
    {
        static_cast<Recorder*>(self)->events.push_back(e);
    }
};

bool same_event(const sm::ContactEvent& x, const sm::ContactEvent& y)
{
    return x.kind == y.kind && x.a == y.a && x.b == y.b && x.point == y.point && x.normal == y.normal &&
           x.impulse_on_a == y.impulse_on_a && x.normal_impulse == y.normal_impulse && x.depth == y.depth;
}

} // namespace

TEST(ContactEvents, BouncingBallBeginsPersistsAndEnds)
{
    // A ball (e = 0.5) dropped 0.2 m onto a plane: one Begin, then Persist while the spring pushes,
    // then one End once it has left the plane going up; nothing before the Begin.
    sm::World w;
    const sm::Entity plane = add_plane(w);
    const sm::Entity ball = add_ball(w, 0.05, {0, 0.25, 0}, 0.5);
    Recorder rec;
    sm::world_set_contact_callback(w, &Recorder::on_event, &rec);
    std::vector<sm::ContactEventKind> kinds;
    double vy_at_end = 0.0;
    for (int i = 0; i < 1000 && (kinds.empty() || kinds.back() != sm::ContactEventKind::End); ++i) {
        const size_t before = rec.events.size();
        w.step();
        const std::span<const sm::ContactEvent> pulled = sm::world_contact_events(w);
        ASSERT_EQ(pulled.size(), rec.events.size() - before);
        for (size_t k = 0; k < pulled.size(); ++k)
            EXPECT_TRUE(same_event(pulled[k], rec.events[before + k]));
        for (const sm::ContactEvent& e : pulled) {
            EXPECT_EQ(e.a, plane);
            EXPECT_EQ(e.b, ball);
            kinds.push_back(e.kind);
        }
        vy_at_end = sm::body_linear_velocity(w, ball).y;
    }
    ASSERT_GE(kinds.size(), 3u);
    EXPECT_EQ(kinds.front(), sm::ContactEventKind::Begin);
    EXPECT_EQ(kinds.back(), sm::ContactEventKind::End);
    for (size_t k = 1; k + 1 < kinds.size(); ++k)
        EXPECT_EQ(kinds[k], sm::ContactEventKind::Persist) << "event " << k;
    EXPECT_GT(vy_at_end, 0.0); // it ended because the ball bounced off
    // The Begin's normal points from the ball (b) towards the plane (a): down.
    EXPECT_NEAR(rec.events.front().normal.y, -1.0, 1e-12);
}

// The momentum balances below, on both contact solvers (the parameter, named in the test).
class ContactEventsBalance : public ::testing::TestWithParam<sm::ContactSolver>
{
};

TEST_P(ContactEventsBalance, RestingImpulseIsWeightTimesStep)
{
    // A resting ball's contact carries its weight: the impulse over a step is m·g·dt exactly once the
    // ball is still, since the step's momentum balance is m·Δv = contact impulse − m·g·dt. After 2 s the
    // drop has died out (ζ ≈ 0.46 at e = 0.2, decay exp(−ζωt) with ω = 314 rad/s: e^-290) and the
    // discrete map sits at its fixed point (measured: equal to the last bit). 1e-6 relative leaves room
    // for a fixed point a few ulps off in another build, and still fails on any real imbalance.
    constexpr double k_rel_tol = 1e-6;
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = GetParam();
    def.sleep.enabled = false; // a sleeping pair reports no Persist events
    sm::World w(def);
    add_plane(w);
    const sm::Entity ball = add_ball(w, 0.05, {0, 0.0505, 0}, 0.2);
    run_steps(w, 1000);
    const double m = sm::body_mass_properties(w, ball).mass;
    const double dt = w.settings().dt;
    for (int i = 0; i < 10; ++i) {
        w.step();
        const std::span<const sm::ContactEvent> events = sm::world_contact_events(w);
        ASSERT_EQ(events.size(), 1u);
        EXPECT_EQ(events[0].kind, sm::ContactEventKind::Persist);
        // On the ball (b): minus the impulse on the plane (a).
        EXPECT_NEAR(-events[0].impulse_on_a.y, m * k_g * dt, k_rel_tol * m * k_g * dt);
        EXPECT_NEAR(events[0].normal_impulse, m * k_g * dt, k_rel_tol * m * k_g * dt);
    }
}

TEST_P(ContactEventsBalance, ImpulsesAddUpToTheMomentumChangeWithSubsteps)
{
    // Large steps with many substeps, so a bounce can begin and end inside one step. Whatever the
    // events, every step's contact impulse is reported exactly once, so over the run
    // Σ impulse on the ball = m·Δv − m·g·T. Round-off over ~10^3 substeps: 1e-9 of m·g·T.
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = GetParam();
    def.dt = 0.02;
    def.substep_count = 20;
    // A sleeping ball is neither pushed by its contact nor pulled by gravity, so the balance holds over
    // its awake steps only (on the soft solver it falls asleep within the 2 s).
    def.sleep.enabled = false;
    sm::World w(def);
    add_plane(w);
    const sm::Entity ball = add_ball(w, 0.05, {0, 0.3, 0}, 0.8);
    Recorder rec;
    sm::world_set_contact_callback(w, &Recorder::on_event, &rec);
    const double m = sm::body_mass_properties(w, ball).mass;
    const sm::Vec3 v0 = sm::body_linear_velocity(w, ball);
    constexpr int k_steps = 100;
    int same_step_begin_end = 0;
    size_t step_first = 0;
    for (int i = 0; i < k_steps; ++i) {
        step_first = rec.events.size();
        w.step();
        for (size_t k = step_first; k + 1 < rec.events.size(); ++k)
            if (rec.events[k].kind == sm::ContactEventKind::Begin &&
                rec.events[k + 1].kind == sm::ContactEventKind::End) {
                ++same_step_begin_end;
                EXPECT_EQ(rec.events[k + 1].normal_impulse, 0.0); // reported on the Begin already
            }
    }
    sm::Vec3 impulse_on_ball{};
    int begins = 0, ends = 0;
    for (const sm::ContactEvent& e : rec.events) {
        impulse_on_ball -= e.impulse_on_a;
        begins += e.kind == sm::ContactEventKind::Begin ? 1 : 0;
        ends += e.kind == sm::ContactEventKind::End ? 1 : 0;
    }
    const double T = k_steps * def.dt;
    const sm::Vec3 expected = m * (sm::body_linear_velocity(w, ball) - v0) - m * T * def.gravity;
    EXPECT_NEAR(impulse_on_ball.y, expected.y, 1e-9 * m * k_g * T);
    EXPECT_GE(begins, 2); // it bounced more than once
    EXPECT_GE(ends, begins - 1);
    EXPECT_LE(ends, begins);
    EXPECT_GE(same_step_begin_end, 1) << "the scene no longer exercises a bounce inside one step";
}

INSTANTIATE_TEST_SUITE_P(Solvers, ContactEventsBalance,
                         ::testing::Values(sm::ContactSolver::Penalty, sm::ContactSolver::Soft),
                         [](const auto& info) {
                             return std::string(info.param == sm::ContactSolver::Soft ? "soft" : "penalty");
                         });

TEST(ContactEvents, SortedByPairThenKind)
{
    // Three balls in a row on a plane, created out of order in space: events come by (a, b) index.
    sm::World w;
    add_plane(w);
    for (double x : {0.2, -0.2, 0.0})
        (void)add_ball(w, 0.05, {x, 0.0505, 0}, 0.2);
    run_steps(w, 20);
    const std::span<const sm::ContactEvent> events = sm::world_contact_events(w);
    ASSERT_EQ(events.size(), 3u);
    for (size_t k = 1; k < events.size(); ++k) {
        const auto key = [](const sm::ContactEvent& e) {
            return std::tuple(e.a.index, e.b.index, static_cast<int>(e.kind));
        };
        EXPECT_LT(key(events[k - 1]), key(events[k]));
    }
}

namespace
{
sm::World* g_world = nullptr;
void set_callback_inside(const sm::ContactEvent&, void*)
{
    sm::world_set_contact_callback(*g_world, nullptr, nullptr);
}
} // namespace

TEST(ContactEvents, CallbackMayNotChangeCallbacks)
{
    sm::World w;
    add_plane(w);
    (void)add_ball(w, 0.05, {0, 0.0495, 0}, 0.2);
    g_world = &w;
    sm::world_set_contact_callback(w, &set_callback_inside, nullptr);
    sm::test::AssertCounter asserts;
    w.step();
    EXPECT_EQ(asserts.count(), sm::asserts_enabled() ? 1 : 0);
    g_world = nullptr;
}

TEST(ContactEvents, RemovedCallbackIsNotCalled)
{
    sm::World w;
    add_plane(w);
    (void)add_ball(w, 0.05, {0, 0.0495, 0}, 0.2);
    Recorder rec;
    sm::world_set_contact_callback(w, &Recorder::on_event, &rec);
    w.step();
    const size_t seen = rec.events.size();
    EXPECT_EQ(seen, 1u);
    sm::world_set_contact_callback(w, nullptr, nullptr);
    w.step();
    EXPECT_EQ(rec.events.size(), seen);
    EXPECT_EQ(sm::world_contact_events(w).size(), 1u); // the pull-style list still fills
}
