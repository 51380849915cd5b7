// Tests for the threaded contact stages (engine/src/contact/contact_system.cpp on
// engine/src/core/thread_pool.cpp): a pile gives the same state hash and the same events for any
// thread count and across runs; the pool's partition; thread_count validation in Defs and scenes.
#include "core/thread_pool.h"
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace sm = supermodal;

namespace
{

sm::Entity add_static_plane(sm::World& w, sm::Vec3 normal, double offset)
{
    sm::BodyDef d = sm::default_body_def();
    d.motion = sm::MotionType::Static;
    d.shape.type = sm::ShapeType::Plane;
    d.shape.plane_normal = normal;
    d.shape.plane_offset = offset;
    return sm::create_body(w, d);
}

// ~100 spheres, ellipsoids and rounded boxes on a jittered grid in a 0.5 m wide box of planes,
// low enough that they are piled up and touching well before 200 steps.
sm::World make_pile(int threads)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1.0 / 240.0;
    def.thread_count = threads;
    sm::World w(def);
    add_static_plane(w, {0, 1, 0}, 0.0);
    add_static_plane(w, {1, 0, 0}, -0.25);
    add_static_plane(w, {-1, 0, 0}, -0.25);
    add_static_plane(w, {0, 0, 1}, -0.25);
    add_static_plane(w, {0, 0, -1}, -0.25);
    uint32_t seed = 12345;
    auto jitter = [&seed] { // a fixed LCG: the same scene on every run
        seed = seed * 1664525u + 1013904223u;
        return (static_cast<double>(seed >> 8) / 16777216.0 - 0.5) * 0.02;
    };
    int i = 0;
    for (int layer = 0; layer < 4; ++layer)
        for (int x = 0; x < 5; ++x)
            for (int z = 0; z < 5; ++z, ++i) {
                sm::BodyDef d = sm::default_body_def();
                const int kind = i % 3;
                d.shape.radii = kind == 0   ? sm::Vec3{0.04, 0.04, 0.04}
                                : kind == 1 ? sm::Vec3{0.045, 0.03, 0.025}
                                            : sm::Vec3{0.035, 0.035, 0.035};
                d.shape.epsilon1 = d.shape.epsilon2 = kind == 2 ? 0.3 : 1.0;
                d.position = {-0.2 + 0.1 * x + jitter(), 0.05 + 0.1 * layer + jitter(),
                              -0.2 + 0.1 * z + jitter()};
                d.orientation = sm::Quat{std::cos(0.3 * i), std::sin(0.3 * i), 0, 0};
                (void)sm::create_body(w, d);
            }
    return w;
}

struct PileRun {
    uint64_t hash = 0;
    size_t contacts = 0;
    std::vector<sm::ContactEvent> events;
};

PileRun run_pile(int threads, int steps)
{
    sm::World w = make_pile(threads);
    PileRun out;
    for (int s = 0; s < steps; ++s) {
        w.step();
        for (const sm::ContactEvent& e : sm::world_contact_events(w))
            out.events.push_back(e);
    }
    out.hash = w.state_hash();
    out.contacts = sm::world_contacts(w).size();
    return out;
}

bool same_events(const std::vector<sm::ContactEvent>& x, const std::vector<sm::ContactEvent>& y)
{
    if (x.size() != y.size())
        return false;
    for (size_t i = 0; i < x.size(); ++i)
        if (x[i].kind != y[i].kind || x[i].a != y[i].a || x[i].b != y[i].b || x[i].point != y[i].point ||
            x[i].impulse_on_a != y[i].impulse_on_a || x[i].normal_impulse != y[i].normal_impulse)
            return false;
    return true;
}

} // namespace

TEST(ContactThreads, PileHashIsTheSameForAnyThreadCountAndRun)
{
    constexpr int k_steps = 200;
    const PileRun one = run_pile(1, k_steps);
    // The pile must be in contact, or equal hashes would prove nothing about the threaded stages.
    EXPECT_GT(one.contacts, 100u);
    EXPECT_GT(one.events.size(), 1000u);
    const PileRun again = run_pile(1, k_steps);
    EXPECT_EQ(again.hash, one.hash);
    for (int threads : {2, 3, 8}) {
        const PileRun many = run_pile(threads, k_steps);
        EXPECT_EQ(many.hash, one.hash) << threads << " threads";
        EXPECT_EQ(many.contacts, one.contacts) << threads << " threads";
        EXPECT_TRUE(same_events(many.events, one.events)) << threads << " threads";
    }
}

TEST(ContactThreads, SnapshotRestoreRerunGivesTheSameHashWithTwoThreads)
{
    sm::World w = make_pile(2);
    sm::test::run_steps(w, 100);
    const sm::Snapshot snap = w.snapshot();
    sm::test::run_steps(w, 50);
    const uint64_t first = w.state_hash();
    ASSERT_TRUE(w.restore(snap).ok());
    sm::test::run_steps(w, 50);
    EXPECT_EQ(w.state_hash(), first);
}

TEST(ThreadPool, StaticPartitionCoversEveryIndexOnce)
{
    for (int threads : {1, 2, 3, 8}) {
        sm::ThreadPool pool(threads);
        for (size_t count : {0u, 1u, 5u, 100u, 1001u}) {
            std::vector<std::atomic<int>> hits(count);
            std::vector<size_t> part_begin(static_cast<size_t>(threads), count + 1);
            pool.parallel_for(count, 4, [&](size_t part, size_t begin, size_t end) {
                part_begin[part] = begin;
                for (size_t i = begin; i < end; ++i)
                    ++hits[i];
            });
            for (size_t i = 0; i < count; ++i)
                EXPECT_EQ(hits[i].load(), 1) << threads << " threads, index " << i;
            // Parts are contiguous, in order, and as the documented formula says.
            const size_t parts = std::clamp<size_t>(count / 4, 1, static_cast<size_t>(threads));
            for (size_t p = 0; p < parts && count > 0; ++p)
                EXPECT_EQ(part_begin[p], sm::ThreadPool::part_begin(count, parts, p));
        }
    }
}

TEST(ThreadPool, RoundRobinBlocksCoverEveryIndexOnce)
{
    constexpr size_t k_block = 3;
    for (int threads : {2, 3}) {
        sm::ThreadPool pool(threads);
        constexpr size_t k_count = 100;
        std::vector<std::atomic<int>> hits(k_count);
        std::vector<std::atomic<int>> owner(k_count);
        pool.parallel_for(
            k_count, 4,
            [&](size_t part, size_t begin, size_t end) {
                EXPECT_LE(end - begin, k_block);
                for (size_t i = begin; i < end; ++i) {
                    ++hits[i];
                    owner[i] = static_cast<int>(part);
                }
            },
            k_block);
        for (size_t i = 0; i < k_count; ++i) {
            EXPECT_EQ(hits[i].load(), 1) << threads << " threads, index " << i;
            EXPECT_EQ(owner[i].load(), static_cast<int>((i / k_block) % static_cast<size_t>(threads)));
        }
    }
}

TEST(ContactThreads, ThreadCountIsValidated)
{
    sm::WorldDef def = sm::default_world_def();
    for (int bad : {0, -1, 65}) {
        def.thread_count = bad;
        const sm::Status s = sm::validate(def);
        ASSERT_FALSE(s.ok()) << bad;
        EXPECT_EQ(s.error().where, "thread_count");
    }
    def.thread_count = 64;
    EXPECT_TRUE(sm::validate(def).ok());
}

TEST(ContactThreads, SceneSettingThreads)
{
    const sm::Result<sm::Scene> ok = sm::parse_scene(R"({"settings": {"threads": 2}})");
    ASSERT_TRUE(ok) << ok.error().message();
    EXPECT_EQ(ok->world.thread_count, 2);
    const sm::Result<sm::Scene> zero = sm::parse_scene(R"({"settings": {"threads": 0}})");
    ASSERT_FALSE(zero);
    EXPECT_EQ(zero.error().where, "/settings/threads");
    const sm::Result<sm::Scene> many = sm::parse_scene(R"({"settings": {"threads": 65}})");
    ASSERT_FALSE(many);
    EXPECT_EQ(many.error().where, "/settings/threads");
    const sm::Result<sm::Scene> half = sm::parse_scene(R"({"settings": {"threads": 1.5}})");
    ASSERT_FALSE(half);
    EXPECT_EQ(half.error().where, "/settings/threads");
}
