// Tests for the constraint stage's islands on threads (engine/src/world/constraint_solve.cpp through
// engine/src/world/islands.h): a scene of independent pendulum chains and a few joined ones (through a
// dynamic bar, a soft modal ball, a kinematic beam they only read, a chain that breaks) gives the same
// state hash for any thread count and for a host scheduler that runs the parts backwards; so does a
// block of spheres whose one large island is split into slabs (WorldDef::split_islands).
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "supermodal/tasks.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"

#include <gtest/gtest.h>
#include <memory>
#include <vector>

namespace sm = supermodal;

namespace
{

constexpr int k_chains = 16;
constexpr int k_links = 6;
constexpr double k_link = 0.1; // link length [m]

// A link whose top end is at `top` [m].
sm::Entity add_link(sm::World& w, sm::Vec3 top)
{
    return sm::create_body(
        w, sm::test::ellipsoid_def({0.02, 0.5 * k_link, 0.02}, top - sm::Vec3{0, 0.5 * k_link, 0}));
}

// A ball joint from a's point `pa` to b's point `pb` (shape frames); b null = the world.
sm::ConstraintDef joint(sm::Entity a, sm::Vec3 pa, sm::Entity b, sm::Vec3 pb)
{
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = a;
    c.b = b;
    c.anchor_a.point = pa;
    c.anchor_b.point = pb;
    return c;
}

// k_chains chains of k_links links, pushed so they swing, hung from the world (even chains) or from a
// moving kinematic beam (odd chains: they only read its velocity, so they stay separate islands).
// Constraints are created round-robin over the chains, so the islands' rows interleave in index order.
// Each ball joint has swing and twist limits and joint friction; chain 3 hangs by a weld, chain 4 by a
// distance constraint, and chain 7's third joint breaks at once.
std::vector<sm::ConstraintDef> add_chains(sm::World& w, sm::Entity beam)
{
    std::vector<std::vector<sm::ConstraintDef>> per_chain(k_chains);
    const sm::Vec3 top_half{0, 0.5 * k_link, 0}, bottom_half{0, -0.5 * k_link, 0};
    for (int c = 0; c < k_chains; ++c) {
        const sm::Vec3 top{0.15 * c - 1.2, 2.0, 0.0};
        const sm::Vec3 on_beam = top - sm::body_position(w, beam);
        sm::Entity above{};
        for (int i = 0; i < k_links; ++i) {
            const sm::Entity link = add_link(w, top - sm::Vec3{0, k_link * i, 0});
            sm::ConstraintDef d = i > 0        ? joint(above, bottom_half, link, top_half)
                                  : c % 2 == 0 ? joint(link, top_half, {}, top)
                                               : joint(link, top_half, beam, on_beam);
            if (c == 3 && i == 0) {
                d.type = sm::ConstraintType::Weld;
            } else if (c == 4 && i == 0) {
                d.type = sm::ConstraintType::Distance;
                d.anchor_b.point = top + sm::Vec3{0, 0.05, 0};
            } else {
                d.swing_limit = 0.6;
                d.twist_limit = 0.3;
                d.angular_damping = 2.0;
            }
            if (c == 7 && i == 2)
                d.break_force = 1.0;
            per_chain[static_cast<size_t>(c)].push_back(d);
            sm::set_body_linear_velocity(w, link, {0.2 * (c % 3) - 0.2, 0, 0.1 * (c % 4)});
            above = link;
        }
    }
    std::vector<sm::ConstraintDef> out;
    for (int i = 0; i < k_links; ++i)
        for (int c = 0; c < k_chains; ++c)
            out.push_back(per_chain[static_cast<size_t>(c)][static_cast<size_t>(i)]);
    return out;
}

// Joined chains: a dynamic bar hung from the world holding two links, and a soft modal ball hanging
// from two links (a ball joint and a weld).
void add_joined(sm::World& w)
{
    const sm::Entity bar = sm::create_body(w, sm::test::ellipsoid_def({0.3, 0.02, 0.02}, {0, 1.0, 1.0}));
    (void)sm::create_constraint(w, joint(bar, {0, 0, 0}, {}, {0, 1.0, 1.0}));
    sm::BodyDef ball_def = sm::test::soft_ball_def({0, 0.5, -1.0}, 0.05);
    ball_def.shape.radii = {0.1, 0.1, 0.1};
    const sm::Entity ball = sm::create_body(w, ball_def);
    const sm::Vec3 top_half{0, 0.5 * k_link, 0}, bottom_half{0, -0.5 * k_link, 0};
    for (double x : {-0.25, 0.25}) {
        const sm::Entity under_bar = add_link(w, {x, 1.0, 1.0});
        (void)sm::create_constraint(w, joint(under_bar, top_half, bar, {x, 0, 0}));
        sm::set_body_linear_velocity(w, under_bar, {0, 0, x});
    }
    for (double x : {-0.05, 0.05}) {
        const sm::Entity link = add_link(w, {x, 0.55 + k_link, -1.0});
        (void)sm::create_constraint(w, joint(link, top_half, {}, {x, 0.55 + k_link, -1.0}));
        sm::ConstraintDef to_ball = joint(link, bottom_half, ball, {x, 0.05, 0});
        if (x > 0.0)
            to_ball.type = sm::ConstraintType::Weld; // the modes' rotation at the anchor too
        (void)sm::create_constraint(w, to_ball);
    }
}

// Soft contact: the floor, and small piles of boxes beside the chains, so contact rows join the islands
// (the joined modal ball rests on the floor through its joints).
void add_floor_and_piles(sm::World& w)
{
    (void)sm::test::add_ground(w);
    for (int i = 0; i < 36; ++i) {
        sm::BodyDef box = sm::test::ellipsoid_def(
            {0.04, 0.04, 0.04}, {0.5 + 0.1 * (i % 3), 0.05 + 0.09 * (i / 9), -0.5 + 0.1 * ((i / 3) % 3)});
        box.shape.epsilon1 = box.shape.epsilon2 = i % 2 == 0 ? 0.3 : 1.0;
        (void)sm::create_body(w, box);
    }
}

uint64_t run(int threads, const std::shared_ptr<sm::ModalBasisCache>& cache,
             std::shared_ptr<sm::TaskSystem> tasks = {}, bool soft = false)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1.0 / 240.0;
    if (soft)
        def.contact.solver = sm::ContactSolver::Soft;
    def.thread_count = threads;
    def.task_system = std::move(tasks);
    def.modal_basis_cache = cache;
    sm::World w(def);
    sm::BodyDef beam_def = sm::test::ellipsoid_def({1.5, 0.02, 0.02}, {0, 2.0, 0.1});
    beam_def.motion = sm::MotionType::Kinematic;
    beam_def.linear_velocity = {0, 0, 0.3};
    const sm::Entity beam = sm::create_body(w, beam_def);
    for (const sm::ConstraintDef& d : add_chains(w, beam))
        EXPECT_FALSE(sm::create_constraint(w, d).is_null());
    add_joined(w);
    if (soft)
        add_floor_and_piles(w);
    sm::test::run_steps(w, 120);
    EXPECT_EQ(sm::world_broken_constraints(w), 1u); // chain 7's weak joint, on any thread
    if (soft) {
        EXPECT_GT(sm::world_contacts(w).size(), 20u); // the piles touch, or the test proves nothing
    }
    return w.state_hash();
}

// A host scheduler that runs the parts on the calling thread, last part first.
class ReverseOrderTasks final : public sm::TaskSystem
{
  public:
    [[nodiscard]] int concurrency() const override { return 4; }
    void run(int part_count, sm::TaskFn task, void* context) override
    {
        for (int p = part_count - 1; p >= 0; --p)
            task(context, p);
    }
};

} // namespace

TEST(IslandThreads, SameHashForAnyThreadCountAndScheduler)
{
    const auto cache = std::make_shared<sm::ModalBasisCache>();
    const uint64_t one = run(1, cache);
    for (int threads : {2, 3, 8})
        EXPECT_EQ(run(threads, cache), one) << threads << " threads";
    EXPECT_EQ(run(1, cache, std::make_shared<ReverseOrderTasks>()), one);
}

TEST(IslandThreads, SoftContactRowsJoinTheIslandsWithTheSameHash)
{
    const auto cache = std::make_shared<sm::ModalBasisCache>();
    const uint64_t one = run(1, cache, {}, true);
    for (int threads : {2, 3, 8})
        EXPECT_EQ(run(threads, cache, {}, true), one) << threads << " threads";
    EXPECT_EQ(run(1, cache, std::make_shared<ReverseOrderTasks>(), true), one);
}

namespace
{

constexpr int k_block_side = 10; // spheres along x and z
constexpr int k_block_layers = 6;

// A block of 600 spheres (radius 5 cm) packed on a cubic grid in a box of planes, each touching its
// neighbours, with distance joints between some neighbours: one island of about 1,900 rows (contacts
// and joints), which the split cuts into three slabs. Returns the top layer's mean height after 60
// steps at 1/240 s and the state hash.
std::pair<double, uint64_t> run_block(int threads, bool split, std::shared_ptr<sm::TaskSystem> tasks = {})
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1.0 / 240.0;
    def.thread_count = threads;
    def.task_system = std::move(tasks);
    def.split_islands = split;
    sm::World w(def);
    constexpr double r = 0.05, pitch = 0.0995; // 0.5 mm overlaps: touching from the first step
    // The floor and four walls 0.5 mm into the outer spheres, which hold the block together.
    (void)sm::test::add_ground(w);
    const double far = pitch * (k_block_side - 1) + r - 5e-4;
    (void)sm::test::add_plane(w, {1, 0, 0}, -r + 5e-4);
    (void)sm::test::add_plane(w, {-1, 0, 0}, -far);
    (void)sm::test::add_plane(w, {0, 0, 1}, -r + 5e-4);
    (void)sm::test::add_plane(w, {0, 0, -1}, -far);
    std::vector<sm::Entity> spheres;
    for (int y = 0; y < k_block_layers; ++y)
        for (int z = 0; z < k_block_side; ++z)
            for (int x = 0; x < k_block_side; ++x)
                spheres.push_back(sm::create_body(
                    w, sm::test::ellipsoid_def({r, r, r}, {pitch * x, r - 5e-4 + pitch * y, pitch * z})));
    for (size_t i = 0; i + 1 < spheres.size(); i += 7) {
        sm::ConstraintDef d = joint(spheres[i], {0.5 * pitch, 0, 0}, spheres[i + 1], {-0.5 * pitch, 0, 0});
        d.type = sm::ConstraintType::Distance;
        EXPECT_FALSE(sm::create_constraint(w, d).is_null());
    }
    sm::test::run_steps(w, 60);
    EXPECT_GT(sm::world_contacts(w).size(), 1500u); // one island of more than 1024 rows, or no split
    double top = 0.0;
    for (size_t i = spheres.size() - k_block_side * k_block_side; i < spheres.size(); ++i)
        top += sm::body_position(w, spheres[i]).y / (k_block_side * k_block_side);
    return {top, w.state_hash()};
}

} // namespace

TEST(IslandThreads, ASplitIslandGivesTheSameHashForAnyThreadCountAndScheduler)
{
    const auto [top, one] = run_block(1, true);
    for (int threads : {2, 3, 8})
        EXPECT_EQ(run_block(threads, true).second, one) << threads << " threads";
    EXPECT_EQ(run_block(1, true, std::make_shared<ReverseOrderTasks>()).second, one);
    // The split solved the island in another order (else this test proves nothing), to the same
    // physics: the top layer stands within 0.1 mm of where it stands unsplit, and within 2 mm of the
    // packing's height (the walls' and neighbours' 0.5 mm overlaps push the layers up as they open).
    // The orders differ only in rounding and in what the passes leave unconverged, yet that moves the
    // top by tens of um: the warm start alone taken in another order (forward, backward, by slab) put
    // the split top 9, 5 and 32 um from the unsplit one (measured), a fortieth of the 1.3 mm it rises.
    const auto [top_whole, whole] = run_block(1, false);
    EXPECT_NE(whole, one);
    EXPECT_NEAR(top, top_whole, 1e-4);
    EXPECT_NEAR(top, 0.05 + 5 * 0.0995, 2e-3);
}
