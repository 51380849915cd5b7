// Tests for engine/src/contact/manifold.cpp: which points a pair's manifold holds.
#include "contact/manifold.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

sm::Collider collider(sm::Vec3 radii, double eps)
{
    return sm::make_collider(sm::test::superquadric(radii, eps, eps), {}, 0.0, 4000);
}

sm::Collider plane_collider()
{
    sm::ShapeDef s = sm::default_shape_def();
    s.type = sm::ShapeType::Plane;
    s.plane_normal = {0, 1, 0};
    s.plane_offset = 0.0;
    return sm::make_collider(s, {}, 0.0, 4000);
}

double weight_sum(const std::vector<sm::ContactPoint>& pts)
{
    double w = 0.0;
    for (const sm::ContactPoint& p : pts)
        w += p.weight;
    return w;
}

} // namespace

TEST(Manifold, SharpBoxOnPlaneTouchesAtItsFourCorners)
{
    // A flat ε = 0.05 box 1 mm into the plane: the four bottom corners (|x|, |z| > 0.8 of the half
    // size), not the face's centre, each at most 1 mm deep and, by the manifold's rule for tilted
    // points, at least half of it (the corners round off above the face), weights summing to 1.
    const sm::Collider box = collider({0.1, 0.05, 0.1}, 0.05), plane = plane_collider();
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    const int n =
        sm::collide_manifold_plane({&box, {0, 0.049, 0}, {}, {}}, {&plane, {}, {}, {}}, true, m, pts);
    ASSERT_EQ(n, 4);
    EXPECT_EQ(m.count, 4);
    for (const sm::ContactPoint& p : pts) {
        EXPECT_GT(std::abs(p.point.x), 0.08);
        EXPECT_GT(std::abs(p.point.z), 0.08);
        EXPECT_LE(p.depth, 1e-3 + 1e-12);
        EXPECT_GE(p.depth, 0.5e-3);
        EXPECT_EQ(p.normal, (sm::Vec3{0, 1, 0}));
    }
    EXPECT_NEAR(weight_sum(pts), 1.0, 1e-12);
}

TEST(Manifold, SphereOnPlaneTouchesInOnePoint)
{
    const sm::Collider ball = collider({0.1, 0.1, 0.1}, 1.0), plane = plane_collider();
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    // The plane is B and the body A: normals point from the plane to the ball... and flip when the
    // plane is the pair's first body.
    ASSERT_EQ(sm::collide_manifold_plane({&ball, {0, 0.099, 0}, {}, {}}, {&plane, {}, {}, {}}, false, m, pts),
              1);
    EXPECT_NEAR(pts[0].depth, 1e-3, 1e-12);
    EXPECT_EQ(pts[0].normal, (sm::Vec3{0, -1, 0}));
    EXPECT_EQ(pts[0].weight, 1.0);
}

TEST(Manifold, OverhangingBoxTouchesOnlyOverTheOtherBox)
{
    // Two equal ε = 0.05 boxes 1 mm into each other, the upper shifted by 0.15 m along x: the overlap
    // spans x in [0.05, 0.1]; there are four points, all there (within 5 mm for the corner rounding),
    // between half the depth and the depth (the rule for tilted points), all along the face normal.
    const sm::Collider box = collider({0.1, 0.1, 0.1}, 0.05);
    const sm::BodyView lower{&box, {0, 0, 0}, {}, {{-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}}};
    const sm::BodyView upper{&box, {0.15, 0.199, 0}, {}, {{0.05, 0.099, -0.1}, {0.25, 0.299, 0.1}}};
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    ASSERT_EQ(sm::collide_manifold(upper, lower, m, pts), 4);
    for (const sm::ContactPoint& p : pts) {
        EXPECT_GT(p.point.x, 0.045);
        EXPECT_LT(p.point.x, 0.105);
        EXPECT_LE(p.depth, 1e-3 + 1e-5);
        EXPECT_GE(p.depth, 0.5e-3);
        EXPECT_NEAR(p.normal.y, 1.0, 1e-6);
    }
}

TEST(Manifold, PointsPersistAndSeparatedPairsEmpty)
{
    // A sharp box's manifold survives a small lateral move of the body (its points are material
    // points), and empties when the box lifts off the plane.
    const sm::Collider box = collider({0.1, 0.05, 0.1}, 0.05), plane = plane_collider();
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    sm::collide_manifold_plane({&box, {0, 0.049, 0}, {}, {}}, {&plane, {}, {}, {}}, true, m, pts);
    ASSERT_EQ(m.count, 4);
    const sm::PairManifold before = m;
    pts.clear();
    sm::collide_manifold_plane({&box, {0.001, 0.049, 0}, {}, {}}, {&plane, {}, {}, {}}, true, m, pts);
    EXPECT_EQ(m.count, 4);
    for (int i = 0; i < 4; ++i)
        EXPECT_LT(sm::length(m.points[i].local_a - before.points[i].local_a), 1e-9);
    pts.clear();
    EXPECT_EQ(sm::collide_manifold_plane({&box, {0, 0.051, 0}, {}, {}}, {&plane, {}, {}, {}}, true, m, pts),
              0);
    EXPECT_EQ(m.count, 0);
}

TEST(Manifold, ASmoothBodyRollingOnAPlaneKeepsOnlyItsSupportPoint)
{
    // A sphere rolled 15° between two substeps: its earlier deepest point is now a material point 26 mm
    // aside (beyond the 10 mm merge distance) and still 6.6 mm deep. A flat face would keep it (its corners
    // steady the face); a smooth body touches at its support point alone, whose spring ½k·depth² is
    // conservative. Carrying the old point made a thin ε 1.5 disc landing on its rim gain 21–63% of its drop
    // energy (docs/stability.md).
    const sm::Collider ball = collider({0.1, 0.1, 0.1}, 1.0), plane = plane_collider();
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    sm::collide_manifold_plane({&ball, {0, 0.09, 0}, {}, {}}, {&plane, {}, {}, {}}, true, m, pts);
    ASSERT_EQ(m.count, 1);
    const sm::Quat rolled = sm::quat_from_rotation_vector({0, 0, 0.2618});
    pts.clear();
    const int n =
        sm::collide_manifold_plane({&ball, {0, 0.09, 0}, rolled, {}}, {&plane, {}, {}, {}}, true, m, pts);
    EXPECT_EQ(n, 1);
    EXPECT_EQ(m.count, 1);
    ASSERT_EQ(pts.size(), 1u);
    EXPECT_NEAR(pts[0].depth, 0.01, 1e-9); // the support point's depth, not a mix with the old point's
    EXPECT_NEAR(pts[0].point.x, 0.0, 1e-9);
}
