// Sleeping on threads (engine/src/world/sleep.h): a pile that settles, falls asleep in islands and is
// woken by a thrown ball ends with the same state hash for any thread count.
#include "supermodal/body.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

struct PileRun {
    uint64_t hash = 0;
    size_t most_asleep = 0;
};

// 4 towers of 36 boxes in 3 layers (more bodies than a thread part holds), stepped until most of the
// pile sleeps, then a heavy ball thrown into one tower.
PileRun run_pile(int threads)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.004;
    def.substep_count = 4;
    def.thread_count = threads;
    sm::World w(def);
    sm::test::add_ground(w);
    for (int i = 0; i < 144; ++i) {
        const int tower = i / 36, in = i % 36;
        sm::BodyDef d =
            sm::test::ellipsoid_def({0.05, 0.05, 0.05}, {1.5 * tower + 0.11 * (in % 4),
                                                         0.05 + 0.11 * (in / 12), 0.11 * ((in / 4) % 3)});
        d.shape.epsilon1 = d.shape.epsilon2 = 0.3;
        (void)sm::create_body(w, d);
    }
    PileRun out;
    for (int i = 0; i < 500; ++i) {
        w.step();
        out.most_asleep = std::max(out.most_asleep, sm::world_sleeping_count(w));
    }
    sm::BodyDef ball = sm::test::ellipsoid_def({0.08, 0.08, 0.08}, {-1.0, 0.1, 0.1}, 4000.0);
    ball.linear_velocity = {5, 0, 0};
    (void)sm::create_body(w, ball);
    sm::test::run_steps(w, 150);
    out.hash = w.state_hash();
    return out;
}

TEST(SleepThreads, SameHashForAnyThreadCount)
{
    const PileRun one = run_pile(1);
    EXPECT_GT(one.most_asleep, 72u); // the test is about sleeping islands: most of the pile slept
    for (int threads : {2, 4}) {
        const PileRun many = run_pile(threads);
        EXPECT_EQ(many.hash, one.hash) << threads << " threads";
        EXPECT_EQ(many.most_asleep, one.most_asleep);
    }
}

} // namespace
