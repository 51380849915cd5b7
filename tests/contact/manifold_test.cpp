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

TEST(Manifold, ASteadyPairReusesItsPointsWithinTheStatedBound)
{
    // Two rounded boxes face on face, 1 mm deep, queried until steady. With the upper one then moved
    // and the lower one turned by just under the reuse tolerances, the pair evaluates no support map,
    // and each point's depth is the separation of the two true surfaces along the normal where its
    // point on A lies (found by bisection on B's inside-outside function) within manifold_reuse_bound.
    // Moved by twice the tolerance, it queries.
    const sm::Collider box = collider({0.05, 0.05, 0.05}, 0.3);
    const double r = 0.05, reach = std::sqrt(3.0) * 0.05;
    const double move = sm::k_manifold_reuse_move_rel * r, turn = sm::k_manifold_reuse_turn;
    const double bound = sm::manifold_reuse_bound(r, reach);
    auto view = [&box](sm::Vec3 p, sm::Quat q) {
        return sm::BodyView{&box, p, q, {p - sm::Vec3{0.09, 0.09, 0.09}, p + sm::Vec3{0.09, 0.09, 0.09}}};
    };
    // Where the line p + t·n leaves B's surface, t in [lo, hi] (B inside at lo, outside at hi).
    auto surface_along = [&box](const sm::BodyView& b, sm::Vec3 p, sm::Vec3 n, double lo, double hi) {
        auto inside = [&](double t) {
            return sm::shape_measure(box.shape, sm::inv_rotate(b.orientation, p + t * n - b.position)) < 0.0;
        };
        EXPECT_TRUE(inside(lo));
        EXPECT_FALSE(inside(hi));
        for (int i = 0; i < 60; ++i)
            (inside(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
        return 0.5 * (lo + hi);
    };
    uint32_t seed = 7;
    auto unit = [&seed] { // in [-1, 1]
        seed = seed * 1664525u + 1013904223u;
        return 2.0 * (seed >> 8) / double(1u << 24) - 1.0;
    };
    const sm::BodyView lower = view({0, 0, 0}, sm::Quat::identity());
    double worst = 0.0;
    int reused = 0;
    for (int trial = 0; trial < 50; ++trial) {
        const sm::BodyView upper = view({0.01 * unit(), 0.099, 0.01 * unit()}, sm::Quat::identity());
        sm::PairManifold m;
        std::vector<sm::ContactPoint> pts;
        for (int q = 0; q <= sm::k_manifold_steady_queries + 1; ++q) {
            pts.clear();
            ASSERT_GT(sm::collide_manifold(upper, lower, m, pts, true), 0);
        }
        ASSERT_GE(m.steady, sm::k_manifold_steady_queries);
        const sm::PairManifold steady = m;
        const sm::Vec3 dir = sm::normalized(sm::Vec3{unit(), unit(), unit()});
        const sm::Vec3 axis = sm::normalized(sm::Vec3{unit(), unit(), unit()});
        const sm::BodyView moved = view(upper.position + 0.99 * move * dir, sm::Quat::identity());
        const sm::BodyView turned = view({0, 0, 0}, sm::quat_from_rotation_vector(0.99 * turn * axis));
        sm::QueryCost cost;
        pts.clear();
        ASSERT_GT(sm::collide_manifold(moved, turned, m, pts, true, &cost), 0);
        EXPECT_EQ(cost.support_calls, 0) << "trial " << trial;
        ASSERT_EQ(static_cast<int>(pts.size()), m.count);
        for (int i = 0; i < m.count; ++i) {
            const sm::Vec3 pa =
                moved.position + sm::rotate(moved.orientation, m.points[static_cast<size_t>(i)].local_a);
            const sm::Vec3 n = pts[static_cast<size_t>(i)].normal;
            const double depth = pts[static_cast<size_t>(i)].depth;
            if (!(depth > 0.0))
                continue;
            worst = std::max(
                worst, std::abs(depth - surface_along(turned, pa, n, depth - 0.5 * r, depth + 0.5 * r)));
            ++reused;
        }
        sm::PairManifold again = steady;
        sm::QueryCost far_cost;
        pts.clear();
        (void)sm::collide_manifold(view(upper.position + 2.0 * move * dir, sm::Quat::identity()), lower,
                                   again, pts, true, &far_cost);
        EXPECT_GT(far_cost.support_calls, 0) << "trial " << trial;
    }
    EXPECT_GT(reused, 50);
    EXPECT_LE(worst, bound);
}
