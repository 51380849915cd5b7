// Tests for the support-map evaluation count of the step profile (StepProfile::support_calls,
// touching_pairs; engine/src/world/contact_system.cpp): what it counts, per pair and substep.
#include "contact/manifold.h"
#include "supermodal/hierarchy.h"
#include "support/shapes.h"
#include "support/world_fixture.h"

#include <gtest/gtest.h>

namespace sm = supermodal;

TEST(SupportCount, ManifoldQueriesReportTheirEvaluations)
{
    // One rounded box 1 mm into another: a touching pair, so the query evaluated both support maps.
    const sm::Collider box =
        sm::make_collider(sm::test::superquadric({0.05, 0.05, 0.05}, 0.3, 0.3), {}, 0.0, 4000);
    const sm::BodyView lower{&box, {0, 0, 0}, {}, {{-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}}};
    const sm::BodyView upper{&box, {0, 0.099, 0}, {}, {{-0.05, 0.049, -0.05}, {0.05, 0.149, 0.05}}};
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    sm::QueryCost cost;
    ASSERT_GT(sm::collide_manifold(upper, lower, m, pts, false, &cost), 0);
    EXPECT_GE(cost.support_calls, 2);
    // Added to, not overwritten.
    const int first = cost.support_calls;
    pts.clear();
    sm::collide_manifold(upper, lower, m, pts, false, &cost);
    EXPECT_GT(cost.support_calls, first);
}

namespace
{

// A rounded box (half-size 5 cm, ε 0.3) placed 0.1 mm into the ground.
sm::BodyDef box_resting_on_ground()
{
    sm::BodyDef d = sm::default_body_def();
    d.shape.radii = {0.05, 0.05, 0.05};
    d.shape.epsilon1 = d.shape.epsilon2 = 0.3;
    d.position = {0, 0.0499, 0};
    return d;
}

} // namespace

TEST(SupportCount, StepProfileCountsTouchingPairsPerSubstep)
{
    // A rounded box resting on the ground in two substeps: one touching pair in each, and the
    // support-map evaluations of both substeps' queries (k_manifold_steady_queries: none once steady).
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.002;
    def.substep_count = 2;
    sm::World w(def);
    (void)sm::test::add_ground(w);
    sm::BodyDef d = box_resting_on_ground();
    (void)sm::create_body(w, d);
    sm::test::run_steps(w, 4); // fewer substeps than a pair needs to be steady (no reuse yet)
    EXPECT_EQ(w.profile().touching_pairs, 2u);
    EXPECT_GE(w.profile().support_calls, 2u);
    // At rest, once steady, the pair measures its stored points again: touching, no evaluations.
    sm::test::run_steps(w, 100);
    EXPECT_EQ(w.profile().touching_pairs, 2u);
    EXPECT_EQ(w.profile().support_calls, 0u);
    // A world without contact counts nothing.
    sm::World empty(def);
    empty.step();
    EXPECT_EQ(empty.profile().support_calls, 0u);
    EXPECT_EQ(empty.profile().touching_pairs, 0u);
}

TEST(SupportCount, AReshapedBodyQueriesItsPairsAfresh)
{
    // A rounded box at rest reuses its manifold with the ground (no evaluations); reshaped in place,
    // its stored points lay on the old surface, so the next step queries again.
    sm::WorldDef def = sm::default_world_def();
    def.dt = 0.002;
    sm::World w(def);
    (void)sm::test::add_ground(w);
    sm::BodyDef d = box_resting_on_ground();
    d.allow_sleep = false;
    const sm::Entity box = sm::create_body(w, d);
    sm::test::run_steps(w, 100);
    ASSERT_EQ(w.profile().touching_pairs, 1u);
    ASSERT_EQ(w.profile().support_calls, 0u);
    sm::ShapeDef wider = d.shape;
    wider.radii.x = 0.06;
    ASSERT_TRUE(sm::set_body_shape(w, box, wider));
    w.step();
    EXPECT_EQ(w.profile().touching_pairs, 1u);
    EXPECT_GT(w.profile().support_calls, 0u);
}
