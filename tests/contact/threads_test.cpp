// Tests for the threaded stages (engine/src/world/*.cpp through engine/src/core/parallel.h on
// engine/src/core/thread_pool.cpp or a host's TaskSystem): a pile of rigid bodies and one of modal
// bodies give the same state hash and the same events for any thread count, any scheduler and across
// runs; the partition; thread_count validation in Defs and scenes.
#include "core/parallel.h"
#include "core/thread_pool.h"
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/tasks.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <gtest/gtest.h>
#include <memory>
#include <thread>
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
sm::World make_pile(sm::ContactSolver solver, int threads, std::shared_ptr<sm::TaskSystem> tasks = {})
{
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = solver;
    def.dt = 1.0 / 240.0;
    def.thread_count = threads;
    def.task_system = std::move(tasks);
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
    uint64_t support_calls = 0; ///< StepProfile::support_calls summed over the run.
    std::vector<sm::ContactEvent> events;
};

PileRun run_pile(sm::ContactSolver solver, int threads, int steps, std::shared_ptr<sm::TaskSystem> tasks = {})
{
    sm::World w = make_pile(solver, threads, std::move(tasks));
    PileRun out;
    for (int s = 0; s < steps; ++s) {
        w.step();
        out.support_calls += w.profile().support_calls;
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

// A host scheduler that runs the parts on the calling thread, last part first.
class ReverseSerialTasks final : public sm::TaskSystem
{
  public:
    explicit ReverseSerialTasks(int concurrency) : m_concurrency(concurrency) {}
    [[nodiscard]] int concurrency() const override { return m_concurrency; }
    void run(int part_count, sm::TaskFn task, void* context) override
    {
        ++runs;
        for (int p = part_count - 1; p >= 0; --p)
            task(context, p);
    }
    int runs = 0;

  private:
    int m_concurrency;
};

// A host scheduler that starts one fresh thread per part (a stand-in for a game's job system).
class ThreadPerPartTasks final : public sm::TaskSystem
{
  public:
    [[nodiscard]] int concurrency() const override { return 4; }
    void run(int part_count, sm::TaskFn task, void* context) override
    {
        std::vector<std::thread> threads;
        for (int p = 0; p < part_count; ++p)
            threads.emplace_back([=] { task(context, p); });
        for (std::thread& t : threads)
            t.join();
    }
};

// Eight soft modal balls (supermodal tests' soft ball, scaled down) dropped on each other and the ground.
sm::World make_modal_pile(sm::ContactSolver solver, int threads,
                          const std::shared_ptr<sm::ModalBasisCache>& cache)
{
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = solver;
    def.dt = 1.0 / 240.0;
    def.thread_count = threads;
    def.modal_basis_cache = cache;
    sm::World w(def);
    sm::test::add_ground(w);
    for (int i = 0; i < 8; ++i) {
        sm::BodyDef d =
            sm::test::soft_ball_def({0.25 * (i % 2) - 0.12, 0.12 + 0.2 * i, 0.02 * (i % 3)}, 0.02);
        d.shape.radii = {0.1, 0.1, 0.1};
        d.modal.mode_count = 6;
        (void)sm::create_body(w, d);
    }
    return w;
}

} // namespace

// The determinism tests on both contact solvers (the parameter, named in the test).
class ContactThreadsBySolver : public ::testing::TestWithParam<sm::ContactSolver>
{
};

TEST_P(ContactThreadsBySolver, PileHashIsTheSameForAnyThreadCountAndRun)
{
    constexpr int k_steps = 200;
    const PileRun one = run_pile(GetParam(), 1, k_steps);
    // The pile must be in contact, or equal hashes would prove nothing about the threaded stages.
    EXPECT_GT(one.contacts, 100u);
    EXPECT_GT(one.events.size(), 1000u);
    const PileRun again = run_pile(GetParam(), 1, k_steps);
    EXPECT_EQ(again.hash, one.hash);
    for (int threads : {2, 3, 8}) {
        const PileRun many = run_pile(GetParam(), threads, k_steps);
        EXPECT_EQ(many.hash, one.hash) << threads << " threads";
        EXPECT_EQ(many.contacts, one.contacts) << threads << " threads";
        EXPECT_EQ(many.support_calls, one.support_calls) << threads << " threads";
        EXPECT_TRUE(same_events(many.events, one.events)) << threads << " threads";
    }
}

TEST_P(ContactThreadsBySolver, SnapshotRestoreRerunGivesTheSameHashWithTwoThreads)
{
    sm::World w = make_pile(GetParam(), 2);
    sm::test::run_steps(w, 100);
    const sm::Snapshot snap = w.snapshot();
    sm::test::run_steps(w, 50);
    const uint64_t first = w.state_hash();
    ASSERT_TRUE(w.restore(snap).ok());
    sm::test::run_steps(w, 50);
    EXPECT_EQ(w.state_hash(), first);
}

TEST_P(ContactThreadsBySolver, AnyHostSchedulerGivesTheSameHashAsOneThread)
{
    constexpr int k_steps = 120;
    const PileRun one = run_pile(GetParam(), 1, k_steps);
    auto reverse = std::make_shared<ReverseSerialTasks>(3);
    const PileRun reversed = run_pile(GetParam(), 1, k_steps, reverse);
    EXPECT_GT(reverse->runs, k_steps); // the world really handed its loops to the host's scheduler
    EXPECT_EQ(reversed.hash, one.hash);
    EXPECT_EQ(reversed.support_calls, one.support_calls);
    EXPECT_TRUE(same_events(reversed.events, one.events));
    const PileRun per_part = run_pile(GetParam(), 1, k_steps, std::make_shared<ThreadPerPartTasks>());
    EXPECT_EQ(per_part.hash, one.hash);
    EXPECT_TRUE(same_events(per_part.events, one.events));
}

TEST_P(ContactThreadsBySolver, ModalPileHashIsTheSameForAnyThreadCount)
{
    // Contact pairs with modal bodies, the modal update and the surfaces all run on the threads.
    constexpr int k_steps = 240;
    auto cache = std::make_shared<sm::ModalBasisCache>();
    sm::World one = make_modal_pile(GetParam(), 1, cache);
    size_t most_contacts = 0; // touching at some step, or the test would prove nothing
    for (int i = 0; i < k_steps; ++i) {
        one.step();
        most_contacts = std::max(most_contacts, sm::world_contacts(one).size());
    }
    ASSERT_GT(most_contacts, 4u);
    for (int threads : {2, 3}) {
        sm::World many = make_modal_pile(GetParam(), threads, cache);
        sm::test::run_steps(many, k_steps);
        EXPECT_EQ(many.state_hash(), one.state_hash()) << threads << " threads";
    }
}

INSTANTIATE_TEST_SUITE_P(Solvers, ContactThreadsBySolver,
                         ::testing::Values(sm::ContactSolver::Penalty, sm::ContactSolver::Soft),
                         [](const auto& info) {
                             return std::string(info.param == sm::ContactSolver::Soft ? "soft" : "penalty");
                         });

TEST(Parallel, StaticPartitionCoversEveryIndexOnce)
{
    for (int threads : {1, 2, 3, 8}) {
        sm::ThreadPool pool(threads);
        const sm::Parallel par(&pool);
        for (size_t count : {0u, 1u, 5u, 100u, 1001u}) {
            std::vector<std::atomic<int>> hits(count);
            std::vector<size_t> part_begin(static_cast<size_t>(threads), count + 1);
            par.for_parts(count, 4, [&](size_t part, size_t begin, size_t end) {
                part_begin[part] = begin;
                for (size_t i = begin; i < end; ++i)
                    ++hits[i];
            });
            for (size_t i = 0; i < count; ++i)
                EXPECT_EQ(hits[i].load(), 1) << threads << " threads, index " << i;
            // Parts are contiguous, in order, and as the documented formula says.
            const size_t parts = std::clamp<size_t>(count / 4, 1, static_cast<size_t>(threads));
            for (size_t p = 0; p < parts && count > 0; ++p)
                EXPECT_EQ(part_begin[p], sm::Parallel::part_begin(count, parts, p));
        }
    }
}

TEST(Parallel, RoundRobinBlocksCoverEveryIndexOnce)
{
    constexpr size_t k_block = 3;
    for (int threads : {2, 3}) {
        sm::ThreadPool pool(threads);
        const sm::Parallel par(&pool);
        constexpr size_t k_count = 100;
        std::vector<std::atomic<int>> hits(k_count);
        std::vector<std::atomic<int>> owner(k_count);
        par.for_parts(
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

// Items that cost unlike amounts in runs along the range (here the first fifth ten times the rest):
// fed the parts' times, the split moves until the parts' times agree, stays contiguous and covering,
// and keeps every part at least a quarter of an even one wide.
TEST(Parallel, BalancedSplitEvensOutMeasuredTimes)
{
    auto cost = [](size_t i, size_t count) { return i < count / 5 ? 10.0 : 1.0; };
    for (size_t parts : {2u, 3u, 8u}) {
        sm::PartBalance balance;
        const size_t count = 10000;
        double spread = 0.0;
        for (int run = 0; run < 60; ++run) {
            const std::vector<size_t>& starts = balance.split(count, parts);
            ASSERT_EQ(starts.size(), parts + 1);
            EXPECT_EQ(starts.front(), 0u);
            EXPECT_EQ(starts.back(), count);
            double lo = HUGE_VAL, hi = 0.0;
            for (size_t p = 0; p < parts; ++p) {
                ASSERT_LE(starts[p], starts[p + 1]);
                EXPECT_GE(starts[p + 1] - starts[p], count / (4 * parts) - 1)
                    << parts << " parts, run " << run;
                double t = 0.0;
                for (size_t i = starts[p]; i < starts[p + 1]; ++i)
                    t += cost(i, count);
                balance.note(p, t * 1e-6);
                lo = std::min(lo, t);
                hi = std::max(hi, t);
            }
            EXPECT_EQ(balance.last_split(count, parts), starts.data());
            EXPECT_EQ(balance.last_split(count + 1, parts), nullptr);
            balance.learn();
            spread = hi / lo;
        }
        // Even counts give two parts times of 4.6 : 1 (the first fifth costs 10 per item, the rest 1).
        EXPECT_LT(spread, 1.02) << parts << " parts";
    }
}

// The split a PartBalance chooses covers every index once and is what the loop's parts receive.
TEST(Parallel, BalancedPartsCoverEveryIndexOnce)
{
    for (int threads : {1, 2, 3}) {
        sm::ThreadPool pool(threads);
        const sm::Parallel par(&pool);
        sm::PartBalance balance;
        for (size_t count : {0u, 7u, 1000u, 999u}) {
            std::vector<std::atomic<int>> hits(count);
            par.for_parts(count, 4, balance, [&](size_t, size_t begin, size_t end) {
                for (size_t i = begin; i < end; ++i)
                    ++hits[i];
            });
            for (size_t i = 0; i < count; ++i)
                EXPECT_EQ(hits[i].load(), 1) << threads << " threads, index " << i;
        }
    }
}

TEST(ThreadPool, RunsEveryPartOnceEvenBeyondItsThreads)
{
    for (int threads : {1, 2, 3}) {
        sm::ThreadPool pool(threads);
        for (int parts : {0, 1, 2, 7}) {
            std::vector<std::atomic<int>> hits(static_cast<size_t>(parts));
            pool.run(
                parts,
                [](void* ctx, int part) { ++(*static_cast<std::vector<std::atomic<int>>*>(ctx))[part]; },
                &hits);
            for (int p = 0; p < parts; ++p)
                EXPECT_EQ(hits[static_cast<size_t>(p)].load(), 1) << threads << " threads, part " << p;
        }
    }
}

// Runs back to back, as a step issues them, with part counts above and below the thread count: a
// worker left out of one run must neither miss the next nor run a part of it twice, whether the
// threads spin between runs (no more threads than cores) or sleep (more).
TEST(ThreadPool, BackToBackRunsOfChangingSizeRunEachPartOnce)
{
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    for (int threads : {2, 3, cores, cores + 2}) {
        sm::ThreadPool pool(threads);
        std::vector<std::atomic<int>> hits(static_cast<size_t>(threads) + 2);
        long expected = 0;
        for (int run = 0; run < 3000; ++run) {
            const int parts = 1 + run % (threads + 2);
            pool.run(
                parts,
                [](void* ctx, int part) { ++(*static_cast<std::vector<std::atomic<int>>*>(ctx))[part]; },
                &hits);
            long total = 0;
            for (const std::atomic<int>& h : hits)
                total += h.load();
            expected += parts;
            ASSERT_EQ(total, expected) << threads << " threads, run " << run;
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
