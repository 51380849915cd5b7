// Tests for the support-map path (engine/src/contact/mpr.cpp, manifold.cpp) through the world's step:
// resting, stacking, determinism, and the path setting (ContactDef::path, scene settings.contact.path).
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"
#include "world/world_impl.h"

#include <cmath>
#include <numbers>
#include <gtest/gtest.h>

namespace sm = supermodal;
using sm::test::run_steps;

namespace
{

sm::World make_world(sm::ContactPath path, double dt = 0.002)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.contact.path = path;
    def.sleep.enabled = false; // the resting contact itself is measured: a sleeping body has none
    return sm::World(def);
}

void add_floor(sm::World& w)
{
    sm::BodyDef d = sm::default_body_def();
    d.motion = sm::MotionType::Static;
    d.shape.type = sm::ShapeType::Plane;
    d.shape.plane_normal = {0, 1, 0};
    (void)sm::create_body(w, d);
}

sm::Entity add_box(sm::World& w, double half, double eps, sm::Vec3 pos)
{
    sm::BodyDef d = sm::default_body_def();
    d.shape.radii = {half, half, half};
    d.shape.epsilon1 = d.shape.epsilon2 = eps;
    d.position = pos;
    return sm::create_body(w, d);
}

// Resting height of a rounded box (half 0.1 m, ε = 0.3) dropped from 1 mm, after 10 s.
double resting_height(sm::ContactPath path)
{
    sm::World w = make_world(path);
    add_floor(w);
    const sm::Entity b = add_box(w, 0.1, 0.3, {0, 0.101, 0});
    run_steps(w, 5000);
    return sm::body_position(w, b).y;
}

} // namespace

TEST(SupportMap, RoundedBoxRestsOnPlane)
{
    // The resting criteria (docs/contact.md) on the forced support-map path: penetration ≤ 1% of the smallest
    // radius, drift ≤ 1e-4 m, speed ≤ 1e-3 m/s after 10 s.
    sm::World w = make_world(sm::ContactPath::SupportMap);
    add_floor(w);
    const sm::Entity b = add_box(w, 0.1, 0.3, {0.3, 0.101, -0.2});
    run_steps(w, 5000);
    const sm::Vec3 p = sm::body_position(w, b);
    EXPECT_LE(0.1 - p.y, 1e-3);
    EXPECT_LE(std::hypot(p.x - 0.3, p.z + 0.2), 1e-4);
    EXPECT_LE(sm::length(sm::body_linear_velocity(w, b)), 1e-3);
    EXPECT_LE(sm::world_max_penetration(w), 1e-3);
    ASSERT_FALSE(sm::world_contacts(w).empty());
    EXPECT_EQ(sm::world_contacts(w)[0].point_count, 4); // the patch's outline, not one point
}

TEST(SupportMap, ForcedPathsGiveSimilarRestingHeights)
{
    // Both paths hold the box with a weighted mean depth of g/ω² ≈ 0.1 mm (ω = 2π·50 Hz). The
    // manifold keeps only points at least half as deep as the deepest, so its face sinks between
    // g/ω² and 2 g/ω²; sampling's points spread over the patch the same way. So both heights lie
    // within 2 g/ω² below the half-size, and so does their difference (measured: 0.067 mm and
    // 0.19 mm sinks). The support map must actually change something (not the same bits).
    const double sampled = resting_height(sm::ContactPath::Sampling);
    const double mapped = resting_height(sm::ContactPath::SupportMap);
    const double sink = 9.81 / std::pow(2.0 * 3.141592653589793 * 50.0, 2);
    for (double height : {sampled, mapped}) {
        EXPECT_LE(height, 0.1);
        EXPECT_GE(height, 0.1 - 2.0 * sink);
    }
    EXPECT_NEAR(sampled, mapped, 2.0 * sink);
    EXPECT_NE(sampled, mapped);
    EXPECT_EQ(resting_height(sm::ContactPath::Auto), mapped);
}

TEST(SupportMap, StackOfTenRoundedBoxesStandsTenSeconds)
{
    // Ten rounded boxes (half 0.1 m, ε = 0.3) stacked face on face stand for 10 s, started
    // with up to 1 mm of sideways jitter and a small twist so that any sway can grow. Standing: every
    // box stays over the one below (horizontal drift ≤ 1 mm, a hundredth of the half-size; a falling
    // box moves by its half-size), no box more than 5 mm below its stacked height (the penalty sinks
    // add up to about 2.5 mm at 100 Hz), every box slower than 1 cm/s at the end.
    // dt = 2 ms in two substeps: the penalty frequency is capped at 1/(10 h), and a penalty column is
    // a chain of rotational springs k·ρ² (ρ the rms lateral offset of an interface's points) under
    // gravity; a Cholesky test of that chain says ten such boxes need ρ ≥ 0.71·a at 50 Hz (h = 2 ms)
    // but only ρ ≥ 0.36·a at 100 Hz. A rounded box's patch has ρ ≈ 0.4–0.5·a, so at h = 2 ms the
    // column buckles whatever the narrowphase (measured: it falls after ~3 s) — see docs/contact.md.
    // The penalty solver's column (the analysis above); the soft solver's columns: contact_solve_test.cpp.
    sm::WorldDef def = sm::default_world_def();
    def.contact.solver = sm::ContactSolver::Penalty;
    def.dt = 0.002;
    def.substep_count = 2;
    sm::World w(def);
    add_floor(w);
    std::vector<sm::Entity> boxes;
    std::vector<sm::Vec3> start;
    for (int i = 0; i < 10; ++i) {
        sm::BodyDef d = sm::default_body_def();
        d.shape.radii = {0.1, 0.1, 0.1};
        d.shape.epsilon1 = d.shape.epsilon2 = 0.3;
        d.position = {0.001 * ((i * 7) % 3 - 1), 0.1 + 0.2 * i, 0.0005 * ((i * 5) % 3 - 1)};
        d.orientation = {std::cos(0.01 * i), 0, std::sin(0.01 * i), 0};
        boxes.push_back(sm::create_body(w, d));
        start.push_back(d.position);
    }
    run_steps(w, 5000);
    for (int i = 0; i < 10; ++i) {
        const sm::Vec3 p = sm::body_position(w, boxes[i]);
        EXPECT_LE(std::hypot(p.x - start[i].x, p.z - start[i].z), 1e-3) << "box " << i;
        EXPECT_NEAR(p.y, start[i].y, 5e-3) << "box " << i;
        EXPECT_LE(sm::length(sm::body_linear_velocity(w, boxes[i])), 1e-2) << "box " << i;
    }
}

TEST(SupportMap, SameSceneSameHashAndRestoreContinuesBitIdentically)
{
    auto build = [] {
        sm::World w = make_world(sm::ContactPath::SupportMap);
        add_floor(w);
        for (int i = 0; i < 4; ++i)
            (void)add_box(w, 0.1, 0.2 + 0.2 * i, {0.02 * i, 0.12 + 0.21 * i, -0.01 * i});
        return w;
    };
    sm::World a = build(), b = build();
    run_steps(a, 300);
    run_steps(b, 300);
    EXPECT_EQ(a.state_hash(), b.state_hash());
    const sm::Snapshot snap = a.snapshot();
    ASSERT_FALSE(sm::impl_of(a).contact.manifolds.empty());
    run_steps(a, 300);
    const uint64_t straight = a.state_hash();
    ASSERT_TRUE(a.restore(snap).ok());
    run_steps(a, 300);
    EXPECT_EQ(a.state_hash(), straight);
    // The manifold is state: restoring and then dropping it must change the continuation.
    ASSERT_TRUE(a.restore(snap).ok());
    sm::impl_of(a).contact.manifolds.clear();
    run_steps(a, 300);
    EXPECT_NE(a.state_hash(), straight);
}

TEST(SupportMap, RestoreDropsTheProofsOfBeingApart)
{
    // Two rounded boxes on the floor, one turned 45° and placed diagonally so that its face is about 5 mm
    // from the other's corner while their boxes overlap: the pair is queried and proven apart. The proof is a cache the snapshot does not carry; a restore (here into
    // a world that stepped on) drops every proof, and the continuation is the same bit for bit.
    sm::World w = make_world(sm::ContactPath::SupportMap);
    add_floor(w);
    (void)add_box(w, 0.1, 0.3, {0, 0.1, 0});
    const sm::Entity turned = add_box(w, 0.1, 0.3, {0.164, 0.1, 0.164});
    sm::set_body_orientation(w, turned, {std::cos(std::numbers::pi / 8), 0, std::sin(std::numbers::pi / 8), 0});
    auto proofs = [&] {
        int n = 0;
        for (const sm::PairManifold& m : sm::impl_of(w).contact.manifolds)
            n += m.apart.a != nullptr ? 1 : 0;
        return n;
    };
    run_steps(w, 20);
    ASSERT_EQ(proofs(), 1);
    const sm::Snapshot snap = w.snapshot();
    run_steps(w, 50);
    const uint64_t straight = w.state_hash();
    ASSERT_TRUE(w.restore(snap).ok());
    EXPECT_EQ(proofs(), 0);
    run_steps(w, 50);
    EXPECT_EQ(proofs(), 1);
    EXPECT_EQ(w.state_hash(), straight);
}

TEST(SupportMap, DamagedSnapshotIsRefusedAndChangesNothing)
{
    // Each byte of a snapshot holding a manifold flipped in turn: restore either refuses and leaves the
    // world as it was, or accepts bytes that still read as a state (a flipped value) whose manifold
    // counts are in range (4 points at most, or the narrowphase would read past its array).
    sm::World w = make_world(sm::ContactPath::SupportMap);
    add_floor(w);
    (void)add_box(w, 0.1, 0.3, {0, 0.099, 0});
    w.step();
    const sm::Snapshot good = w.snapshot();
    ASSERT_FALSE(sm::impl_of(w).contact.manifolds.empty());
    const uint64_t before = w.state_hash();
    std::vector<std::byte> bytes(good.bytes().begin(), good.bytes().end());
    int refused = 0;
    for (size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] ^= std::byte{0xff};
        const sm::Status s = w.restore(sm::Snapshot::from_bytes(bytes));
        bytes[i] ^= std::byte{0xff};
        if (!s.ok()) {
            ++refused;
            EXPECT_EQ(w.state_hash(), before) << "byte " << i << ": " << s.error().message();
        }
        for (const sm::PairManifold& m : sm::impl_of(w).contact.manifolds)
            ASSERT_LE(m.count, sm::PairManifold::k_capacity) << "byte " << i;
        ASSERT_TRUE(w.restore(good).ok());
    }
    EXPECT_GT(refused, 0);
    // Truncated: refused, unchanged.
    const sm::Status cut = w.restore(sm::Snapshot::from_bytes(good.bytes().first(good.bytes().size() - 8)));
    ASSERT_FALSE(cut.ok());
    EXPECT_NE(cut.error().what.find("ends early"), std::string::npos) << cut.error().what;
    EXPECT_EQ(w.state_hash(), before);
}

TEST(SupportMap, SceneSettingChoosesThePath)
{
    const auto path_of = [](const char* json) {
        const sm::Result<sm::Scene> scene = sm::parse_scene(json, "test.json");
        EXPECT_TRUE(scene.has_value());
        return scene.has_value() ? scene.value().world.contact.path : sm::ContactPath::Auto;
    };
    EXPECT_EQ(path_of(R"({"settings": {"contact": {"path": "sampling"}}})"), sm::ContactPath::Sampling);
    EXPECT_EQ(path_of(R"({"settings": {"contact": {"path": "support_map"}}})"), sm::ContactPath::SupportMap);
    EXPECT_EQ(path_of(R"({"settings": {"contact": {"path": "auto"}}})"), sm::ContactPath::Auto);
    const sm::Result<sm::Scene> bad =
        sm::parse_scene(R"({"settings": {"contact": {"path": "mpr"}}})", "test.json");
    ASSERT_FALSE(bad.has_value());
    EXPECT_EQ(bad.error().where, "/settings/contact/path");
}

TEST(SupportMap, SceneStiffnessSettingIsReadAndChecked)
{
    const sm::Result<sm::Scene> material =
        sm::parse_scene(R"({"settings": {"contact": {"stiffness": "material"}}})", "test.json");
    ASSERT_TRUE(material.has_value());
    EXPECT_EQ(material->world.contact.stiffness, sm::ContactStiffness::Material);
    const sm::Result<sm::Scene> bad =
        sm::parse_scene(R"({"settings": {"contact": {"stiffness": "hertz"}}})", "test.json");
    ASSERT_FALSE(bad.has_value());
    EXPECT_EQ(bad.error().where, "/settings/contact/stiffness");
}
