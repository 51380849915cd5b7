// Tests for remoulding (engine/src/world/remould.cpp): a plastic board bent past its yield gets modes
// rebuilt for its moulded shape, swapped in at a fixed step, deterministically.
#include "modal/modal_scenes.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

namespace sm = supermodal;
using sm::test::k_board_length;
using sm::test::k_board_thickness;
using sm::test::k_board_width;

namespace
{

constexpr int k_loaded_steps = 100; // 200 N at the centre for 0.1 s, then let go
constexpr int k_total_steps = 400;
constexpr double k_threshold = 1e-3; // 1 mm of rest-shape change on the 1 m board

// The plasticity test's board (8×1×1, 12 modes, ζ = 0.7), yielding at 2.5e5 Pa: 200 N bends it well past.
sm::BodyDef board(double threshold)
{
    sm::BodyDef def = sm::default_body_def();
    def.shape = sm::test::board_def({0, 0, 0}).shape;
    def.density = 450.0;
    def.young = 11e9;
    def.poisson = 0.3;
    def.modal.enabled = true;
    def.modal.mode_count = 12;
    def.modal.lattice = {8, 1, 1};
    def.modal.damping_ratio = 0.7;
    def.modal.yield_stress = 2.5e5;
    def.modal.remould_threshold = threshold;
    return def;
}

struct BoardRun {
    std::unique_ptr<sm::World> world;
    sm::Entity body;
};

BoardRun make_run(double threshold, int threads = 1, std::shared_ptr<sm::ModalBasisCache> cache = nullptr)
{
    sm::WorldDef wd = sm::default_world_def();
    wd.dt = 1e-3;
    wd.gravity = {};
    wd.thread_count = threads;
    wd.modal_basis_cache = std::move(cache);
    BoardRun r{std::make_unique<sm::World>(wd), {}};
    r.body = sm::create_body(*r.world, board(threshold));
    return r;
}

// One step of the load schedule (the load depends only on the step count, so restored runs repeat it).
void step(BoardRun& r)
{
    if (r.world->step_count() < k_loaded_steps) {
        const sm::Vec3 top{0.0, k_board_thickness / 2, 0.0};
        sm::apply_force(*r.world, r.body, {0, -200.0, 0},
                        sm::body_position(*r.world, r.body) +
                            sm::rotate(sm::body_orientation(*r.world, r.body), top));
    }
    r.world->step();
}

void step_to(BoardRun& r, uint64_t count)
{
    while (r.world->step_count() < count)
        step(r);
}

// Points on the board's surface (rest positions, shape frame): 11 along it on each of its four long edges.
std::vector<sm::Vec3> surface_points()
{
    std::vector<sm::Vec3> out;
    for (int i = 0; i <= 10; ++i)
        for (const double y : {-k_board_thickness / 2, k_board_thickness / 2})
            for (const double z : {-k_board_width / 2, k_board_width / 2})
                out.push_back({k_board_length * (i / 10.0 - 0.5), y, z});
    return out;
}

} // namespace

TEST(ModalRemould, RebuiltFrequenciesMatchAFreshBasisOfTheMouldedShape)
{
    BoardRun run = make_run(k_threshold);
    const std::vector<double> before = sm::body_modal_basis(*run.world, run.body)->frequencies_hz;
    step_to(run, k_total_steps);
    const sm::BodyRemould remould = sm::body_remould(*run.world, run.body);
    ASSERT_GE(remould.rebuilds, 1);
    EXPECT_FALSE(remould.failed);
    ASSERT_FALSE(remould.rest_offsets.empty());
    double largest_offset = 0.0;
    for (const sm::Vec3& u : remould.rest_offsets)
        largest_offset = std::max(largest_offset, sm::length(u));
    std::printf("rebuilds %d, largest node rest offset %.4g m, build %.3g s, waited %.3g s\n",
                remould.rebuilds, largest_offset, remould.build_seconds, remould.wait_seconds);
    EXPECT_GT(largest_offset, k_threshold * k_board_length);

    // A basis built directly for that rest shape, outside any world.
    sm::ModalBasisDef def = sm::test::board_def({8, 1, 1}, 12);
    def.density = 450.0;
    def.young = 11e9;
    def.poisson = 0.3;
    def.rest_offsets = remould.rest_offsets;
    const sm::Result<sm::ModalBasis> fresh = sm::build_modal_basis(def);
    ASSERT_TRUE(fresh) << fresh.error().what;
    const sm::ModalBasis& used = *sm::body_modal_basis(*run.world, run.body);
    ASSERT_EQ(used.frequencies_hz.size(), fresh->frequencies_hz.size());
    double moved = 0.0;
    for (size_t k = 0; k < used.frequencies_hz.size(); ++k) {
        // The same build on the same def: equal up to rounding (1e-12 leaves room for none in practice).
        EXPECT_NEAR(used.frequencies_hz[k], fresh->frequencies_hz[k], 1e-12 * fresh->frequencies_hz[k]) << k;
        moved = std::max(moved, std::abs(used.frequencies_hz[k] / before[k] - 1.0));
    }
    std::printf("largest relative frequency change from the unmoulded board %.3g\n", moved);
    EXPECT_GT(moved, 1e-9); // the modes did change: the test would catch a swap that kept the old ones
    EXPECT_EQ(used.mode_shapes, fresh->mode_shapes);
}

TEST(ModalRemould, SwapKeepsTheSurfaceAndAddsNoEnergy)
{
    // The same board twice, one never remoulded: the same until the first swap, which only projects the
    // state, so right after it the two differ only by the projection.
    BoardRun a = make_run(k_threshold), b = make_run(0.0);
    while (sm::body_remould(*a.world, a.body).rebuilds == 0 && a.world->step_count() < k_total_steps) {
        ASSERT_EQ(a.world->state_hash(), b.world->state_hash()) << a.world->step_count();
        step(a);
        step(b);
    }
    ASSERT_EQ(sm::body_remould(*a.world, a.body).rebuilds, 1);
    double gap = 0.0, deformation = 0.0;
    const sm::Vec3 origin = sm::body_position(*b.world, b.body);
    const sm::Quat turn = sm::body_orientation(*b.world, b.body);
    for (const sm::Vec3& p : surface_points()) {
        const sm::Vec3 pa = sm::body_deformed_point(*a.world, a.body, p);
        const sm::Vec3 pb = sm::body_deformed_point(*b.world, b.body, p);
        gap = std::max(gap, sm::length(pa - pb));
        deformation = std::max(deformation, sm::length(pb - (origin + sm::rotate(turn, p))));
    }
    const double ea = sm::body_modal_energy(*a.world, a.body);
    const double eb = sm::body_modal_energy(*b.world, b.body);
    std::printf("swap at step %llu: surface gap %.3g m of %.3g m deformation; modal energy %.6g J, "
                "unswapped %.6g J\n",
                static_cast<unsigned long long>(a.world->step_count()), gap, deformation, ea, eb);
    // The projection is a least-squares fit of the same field on the modes of a nearby shape: within 1%
    // of the deformation (measured: docs/modal.md "Remoulding: modes of the moulded shape").
    EXPECT_GT(deformation, 1e-3);
    EXPECT_LT(gap, 0.01 * deformation);
    // No jump up in energy at the swap: at most 1% above the unswapped body's.
    EXPECT_LE(ea, 1.01 * eb);
}

TEST(ModalRemould, SameHashOnOneAndTwoThreads)
{
    BoardRun one = make_run(k_threshold, 1), two = make_run(k_threshold, 2);
    step_to(one, k_total_steps);
    step_to(two, k_total_steps);
    EXPECT_GE(sm::body_remould(*one.world, one.body).rebuilds, 1);
    EXPECT_EQ(one.world->state_hash(), two.world->state_hash());
}

TEST(ModalRemould, ResultDoesNotDependOnHowLongTheBuildTakes)
{
    // The first run builds every rebuilt basis (milliseconds: its swaps wait); the second finds them all in
    // the cache the first filled, so its builds are done at once. The same swaps, the same bits.
    auto cache = std::make_shared<sm::ModalBasisCache>();
    BoardRun cold = make_run(k_threshold, 1, cache);
    step_to(cold, k_total_steps);
    const int built = cache->size();
    BoardRun warm = make_run(k_threshold, 1, cache);
    step_to(warm, k_total_steps);
    EXPECT_GE(sm::body_remould(*cold.world, cold.body).rebuilds, 1);
    EXPECT_EQ(cache->size(), built); // nothing new was built: every rebuild of the second run was found
    EXPECT_EQ(cold.world->state_hash(), warm.world->state_hash());
}

TEST(ModalRemould, SnapshotAcrossAPendingRebuildRestoresTheSameRun)
{
    BoardRun run = make_run(k_threshold);
    while (sm::body_remould(*run.world, run.body).pending_step == 0 &&
           run.world->step_count() < k_total_steps)
        step(run);
    ASSERT_NE(sm::body_remould(*run.world, run.body).pending_step, 0u);
    const sm::Snapshot pending = run.world->snapshot();
    const uint64_t at = run.world->step_count();
    step_to(run, k_total_steps);
    const uint64_t expected = run.world->state_hash();
    const sm::Snapshot after = run.world->snapshot();

    // Back in the same world (its modes already rebuilt): the pending rebuild is asked for again.
    ASSERT_TRUE(run.world->restore(pending));
    EXPECT_EQ(sm::body_remould(*run.world, run.body).rest_offsets.size(), 0u);
    step_to(run, k_total_steps);
    EXPECT_EQ(run.world->state_hash(), expected);

    // In a fresh world made alike, before the rebuild and after it (the moulded shape rebuilt on restore).
    BoardRun fresh = make_run(k_threshold);
    ASSERT_TRUE(fresh.world->restore(pending));
    ASSERT_EQ(fresh.world->step_count(), at);
    step_to(fresh, k_total_steps);
    EXPECT_EQ(fresh.world->state_hash(), expected);
    BoardRun later = make_run(k_threshold);
    ASSERT_TRUE(later.world->restore(after));
    EXPECT_EQ(later.world->state_hash(), expected);
    EXPECT_FALSE(sm::body_remould(*later.world, later.body).rest_offsets.empty());
    EXPECT_EQ(sm::body_modal_basis(*later.world, later.body)->frequencies_hz,
              sm::body_modal_basis(*run.world, run.body)->frequencies_hz);
}
