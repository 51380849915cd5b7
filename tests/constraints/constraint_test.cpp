// Constraint handles, anchors on surfaces, contact filtering, determinism and snapshots.
#include "constraints/constraint_world.h"
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/contact.h"
#include "supermodal/geometry.h"
#include "supermodal/world.h"
#include "support/shapes.h"
#include "support/world_fixture.h"
#include "world/world_impl.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;
using sm::test::ellipsoid_def;
using sm::test::run_steps;

namespace
{

// Two overlapping boxes joined by a ball joint, plus a ground plane: a tiny assembly.
struct Assembly {
    sm::World world;
    sm::Entity top, bottom;
    sm::Constraint joint;
};

Assembly make_assembly(bool collide_connected)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = 1e-3;
    Assembly out{sm::World(def), {}, {}, {}};
    sm::BodyDef ground = sm::default_body_def();
    ground.shape.type = sm::ShapeType::Plane;
    ground.motion = sm::MotionType::Static;
    (void)sm::create_body(out.world, ground);
    sm::BodyDef box = ellipsoid_def({0.1, 0.1, 0.1}, {0, 0.1, 0});
    box.shape = sm::test::superquadric({0.1, 0.1, 0.1}, 0.3, 0.3);
    out.bottom = sm::create_body(out.world, box);
    box.position = {0.02, 0.28, 0}; // overlaps the bottom box by 2 cm
    out.top = sm::create_body(out.world, box);
    sm::ConstraintDef c = sm::default_constraint_def();
    c.a = out.bottom;
    c.b = out.top;
    c.anchor_a.point = {0, 0.09, 0};
    c.anchor_b.point = {-0.02, -0.09, 0};
    c.collide_connected = collide_connected;
    c.frequency_hz = 60.0;
    out.joint = sm::create_constraint(out.world, c);
    return out;
}

bool touching(const sm::World& w, sm::Entity a, sm::Entity b)
{
    for (const sm::ContactInfo& c : sm::world_contacts(w))
        if ((c.a == a && c.b == b) || (c.a == b && c.b == a))
            return true;
    return false;
}

} // namespace

TEST(Constraint, JoinedBodiesDoNotCollideUnlessAsked)
{
    Assembly off = make_assembly(false);
    Assembly on = make_assembly(true);
    off.world.step();
    on.world.step();
    EXPECT_FALSE(touching(off.world, off.top, off.bottom));
    EXPECT_TRUE(touching(on.world, on.top, on.bottom));
}

TEST(Constraint, AssemblyIsDeterministicAndSnapshotsBitExactly)
{
    Assembly a = make_assembly(false);
    Assembly b = make_assembly(false);
    sm::set_body_angular_velocity(a.world, a.top, {0, 0, 3});
    sm::set_body_angular_velocity(b.world, b.top, {0, 0, 3});
    run_steps(a.world, 300);
    run_steps(b.world, 300);
    ASSERT_EQ(a.world.state_hash(), b.world.state_hash());
    const sm::Snapshot snap = a.world.snapshot();
    run_steps(a.world, 300);
    const uint64_t straight = a.world.state_hash();
    ASSERT_TRUE(a.world.restore(snap).ok());
    run_steps(a.world, 300);
    EXPECT_EQ(a.world.state_hash(), straight);
    // The warm-start impulses are state: changing them changes the hash.
    impl_of(a.world).constraints.reg.get<sm::ConstraintState>(sm::to_entity(a.joint)).impulse.x += 1e-9;
    EXPECT_NE(a.world.state_hash(), straight);
}

TEST(Constraint, AssemblySettlesOnTheGround)
{
    // The pair rocks on its rounded faces and settles slowly (measured 2026-11-26, top box: 1.0 cm/s
    // at 3 s, 0.42 cm/s at 4 s, 0.32 at 5 s, 0.11 at 6 s; rounding-level changes in the support map
    // move the 3 s value across 1 cm/s), so the bound is checked at 5 s.
    Assembly a = make_assembly(false);
    run_steps(a.world, 5000);
    EXPECT_LT(sm::length(sm::body_linear_velocity(a.world, a.top)), 1e-2);
    // The joint holds to within the top box's weight over its spring: m·g/(m_eff·ω²) ≈ 0.14 mm.
    EXPECT_LT(sm::constraint_error(a.world, a.joint).linear, 1e-3);
}

TEST(Constraint, DestroyingABodyDropsItsConstraints)
{
    Assembly a = make_assembly(false);
    ASSERT_TRUE(sm::world_valid(a.world, a.joint));
    sm::destroy_body(a.world, a.top);
    EXPECT_FALSE(sm::world_valid(a.world, a.joint));
    EXPECT_TRUE(sm::world_constraints(a.world).empty());
    a.world.step(); // nothing left pulling at a stale body
}

TEST(Constraint, InvalidDefsAreRefused)
{
    sm::test::AssertCounter asserts;
    Assembly a = make_assembly(false);
    sm::ConstraintDef c = sm::default_constraint_def();
    EXPECT_FALSE(sm::validate(c).ok()); // no body a
    c.a = a.top;
    c.b = a.top;
    EXPECT_FALSE(sm::validate(c).ok());
    c.b = a.bottom;
    c.frequency_hz = -1.0;
    EXPECT_FALSE(sm::validate(c).ok());
    c.frequency_hz = 30.0;
    c.anchor_a.point = {NAN, 0, 0};
    EXPECT_FALSE(sm::validate(c).ok());
    EXPECT_TRUE(sm::create_constraint(a.world, c).is_null());
    c.anchor_a.point = {};
    EXPECT_TRUE(sm::validate(c).ok());
    sm::destroy_body(a.world, a.bottom);
    EXPECT_TRUE(sm::create_constraint(a.world, c).is_null()); // stale body
    EXPECT_GE(asserts.count(), 2);
}

// Direction and surface anchors land on the surface (F = 1), for plain, tapered and bent shapes.
TEST(Constraint, SurfaceAnchorsLieOnTheSurface)
{
    sm::ShapeDef plain = sm::test::superquadric({0.3, 0.2, 0.5}, 0.4, 1.5);
    sm::ShapeDef deformed = plain;
    deformed.taper = {0.3, -0.2};
    deformed.bend.curvature = 0.5;
    for (const sm::ShapeDef& shape : {plain, deformed}) {
        for (const sm::Vec3& d : {sm::Vec3{1, 0, 0}, sm::Vec3{1, 1, 0}, sm::Vec3{-0.3, 0.5, -1}}) {
            sm::AnchorDef anchor;
            anchor.kind = sm::AnchorKind::Direction;
            anchor.direction = d;
            const sm::Vec3 p = sm::resolve_anchor(shape, anchor);
            // shape_measure is the scaled F^(ε1/2) − 1 through the inverse deformation: 0 on the surface.
            EXPECT_NEAR(sm::shape_measure(shape, p), 0.0, 1e-9);
        }
        sm::AnchorDef uv;
        uv.kind = sm::AnchorKind::Surface;
        uv.eta = 0.4;
        uv.omega = 2.0;
        EXPECT_NEAR(sm::shape_measure(shape, sm::resolve_anchor(shape, uv)), 0.0, 1e-9);
    }
}
