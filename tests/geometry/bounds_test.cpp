// Tests for engine/src/geometry/bounds.cpp.
#include "geometry/bounds_internal.h"
#include "supermodal/geometry.h"
#include "support/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

namespace sm = supermodal;

namespace
{

constexpr double k_pi = std::numbers::pi;

using supermodal::test::superquadric;

sm::Quat random_orientation(std::mt19937_64& rng)
{
    std::normal_distribution<double> g;
    return sm::normalized(sm::Quat{g(rng), g(rng), g(rng), g(rng)});
}

// Checks that box contains every point and that each face is within `slack` of the farthest point.
void expect_tight(const sm::Aabb& box, const std::vector<sm::Vec3>& points, double round_off, double slack)
{
    sm::Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const sm::Vec3& p : points)
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], p[i]);
            hi[i] = std::max(hi[i], p[i]);
        }
    for (int i = 0; i < 3; ++i) {
        EXPECT_LE(box.min[i], lo[i] + round_off) << "axis " << i;
        EXPECT_GE(box.max[i], hi[i] - round_off) << "axis " << i;
        EXPECT_LE(lo[i] - box.min[i], slack) << "axis " << i;
        EXPECT_LE(box.max[i] - hi[i], slack) << "axis " << i;
    }
}

std::vector<sm::Vec3> world_surface_grid(const sm::ShapeDef& s, const sm::Vec3& position, const sm::Quat& q,
                                         bool deformed)
{
    constexpr int k_eta = 64, k_omega = 128;
    std::vector<sm::Vec3> points;
    for (int i = 0; i <= k_eta; ++i)
        for (int j = 0; j < k_omega; ++j) {
            sm::Vec3 x = sm::surface_point(s, -k_pi / 2 + k_pi * i / k_eta, -k_pi + 2 * k_pi * j / k_omega);
            if (deformed)
                x = sm::deform_point(s, x);
            points.push_back(position + sm::rotate(q, x));
        }
    return points;
}

} // namespace

TEST(Bounds, SphereAndRotatedEllipsoidMatchClosedForm)
{
    constexpr double k_round_off = 1e-12;
    const sm::Aabb sphere = sm::world_aabb(superquadric({2, 2, 2}, 1, 1), {1, -2, 3}, sm::Quat::identity());
    EXPECT_NEAR(sphere.min.x, -1.0, k_round_off);
    EXPECT_NEAR(sphere.max.z, 5.0, k_round_off);
    // Ellipsoid: half extent along world axis i is sqrt(Σ_j R_ij² a_j²).
    const sm::Vec3 a{1, 2, 3};
    const sm::Quat q = sm::normalized(sm::Quat{0.9, 0.2, -0.3, 0.25});
    const sm::Mat3 r = sm::to_mat3(q);
    const sm::Aabb box = sm::world_aabb(superquadric(a, 1, 1), {0, 0, 0}, q);
    for (int i = 0; i < 3; ++i) {
        double h2 = 0;
        for (int j = 0; j < 3; ++j)
            h2 += r.m[i][j] * r.m[i][j] * a[j] * a[j];
        EXPECT_NEAR(box.max[i], std::sqrt(h2), k_round_off);
        EXPECT_NEAR(box.min[i], -std::sqrt(h2), k_round_off);
    }
    // A non-unit quaternion is normalised first.
    const sm::Aabb scaled = sm::world_aabb(superquadric(a, 1, 1), {0, 0, 0}, {1.8, 0.4, -0.6, 0.5});
    EXPECT_NEAR(scaled.max.x, box.max.x, k_round_off);
}

TEST(Bounds, TightForAnyPoseAndExponent)
{
    // Containment: the box's faces are support values, so grid points reach them up to round-off.
    // Tightness: a 64×128 (η, ω) grid comes within ~1e-3 of the largest radius of every support
    // value for these aspect ratios (the chord sagitta of ~2° steps), so the box may not exceed it
    // by more than 5e-3.
    constexpr double k_round_off_rel = 1e-12, k_grid_slack_rel = 5e-3;
    std::mt19937_64 rng(9);
    for (double e1 : {0.01, 0.5, 1.0, 2.0, 3.0, 4.0})
        for (double e2 : {0.01, 0.5, 1.0, 2.0, 4.0})
            for (const sm::Vec3& a : {sm::Vec3{1, 1, 1}, sm::Vec3{0.2, 1, 3}}) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                const double size = std::max({a.x, a.y, a.z});
                const sm::Quat q = random_orientation(rng);
                const sm::Vec3 position{0.5, -1.0, 2.0};
                const sm::Aabb box = sm::world_aabb(s, position, q);
                SCOPED_TRACE(testing::Message() << "e " << e1 << " " << e2);
                expect_tight(box, world_surface_grid(s, position, q, false), k_round_off_rel * size,
                             k_grid_slack_rel * size);
            }
}

TEST(Bounds, PlaneIsUnbounded)
{
    sm::ShapeDef plane = sm::default_shape_def();
    plane.type = sm::ShapeType::Plane;
    const sm::Aabb box = sm::world_aabb(plane, {1, 2, 3}, sm::Quat::identity());
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(box.min[i], -1e300);
        EXPECT_EQ(box.max[i], 1e300);
    }
}

TEST(Bounds, DeformedShapesContainTheirSurface)
{
    // The box bounds a 64-segment tessellation plus 2% of its largest half extent (bounds.cpp): it
    // must contain the exact deformed surface (a denser (η, ω) grid through deform_point, and a
    // 128-segment tessellation, which also covers the flat faces' middles that Barr's angles skip at
    // small ε) and stay within that margin plus the references' own sagitta of it.
    constexpr double k_round_off_rel = 1e-12, k_slack_rel = 2e-2 + 5e-3;
    std::mt19937_64 rng(13);
    for (double e : {0.1, 1.0, 2.0, 4.0}) {
        sm::ShapeDef tapered = superquadric({0.5, 0.3, 1.0}, e, e);
        tapered.taper = {0.6, -0.4};
        sm::ShapeDef bent = superquadric({0.3, 0.3, 1.5}, e, 1.0);
        bent.bend = {0.5, 0.7};
        for (const sm::ShapeDef& s : {tapered, bent}) {
            ASSERT_TRUE(sm::is_deformed(s));
            const sm::Quat q = random_orientation(rng);
            const sm::Aabb box = sm::world_aabb(s, {1, 2, 3}, q);
            const double size = std::max({s.radii.x, s.radii.y, s.radii.z});
            SCOPED_TRACE(testing::Message() << "e " << e);
            std::vector<sm::Vec3> points = world_surface_grid(s, {1, 2, 3}, q, true);
            for (const sm::Vec3& v : sm::tessellate(s, 128).positions)
                points.push_back(sm::Vec3{1, 2, 3} + sm::rotate(q, v));
            expect_tight(box, points, k_round_off_rel * size, k_slack_rel * size);
        }
    }
}

TEST(Bounds, HyperquadricContainsItsSurface)
{
    // Three slabs |2x|^8 + |2y|^8 + |2z|^8 ≤ 1: a rounded cube of half-width 0.5 whose surface a denser
    // tessellation samples; the same 2% margin as for deformed shapes, plus its sagitta.
    constexpr double k_round_off = 1e-12, k_slack = (2e-2 + 5e-3) * 0.5;
    sm::ShapeDef s = sm::default_shape_def();
    s.type = sm::ShapeType::Hyperquadric;
    s.terms = {{{2, 0, 0}, 0, 8}, {{0, 2, 0}, 0, 8}, {{0, 0, 2}, 0, 8}};
    std::mt19937_64 rng(17);
    const sm::Quat q = random_orientation(rng);
    const sm::Aabb box = sm::world_aabb(s, {0, 0, 1}, q);
    std::vector<sm::Vec3> points;
    for (const sm::Vec3& v : sm::tessellate(s, 256).positions)
        points.push_back(sm::Vec3{0, 0, 1} + sm::rotate(q, v));
    ASSERT_FALSE(points.empty());
    expect_tight(box, points, k_round_off, k_slack);
}

TEST(Bounds, CachedVertexSetsGiveTheUncachedBoxBitForBit)
{
    // Shapes that bound a tessellation keep its vertices in a cache keyed by their parameters; a cached
    // box must equal the recomputed one exactly (determinism must not depend on what was cached).
    sm::ShapeDef tapered = superquadric({0.5, 0.3, 1.0}, 0.3, 2.5);
    tapered.taper = {0.6, -0.4};
    sm::ShapeDef bent = superquadric({0.3, 0.3, 1.5}, 1.0, 0.1);
    bent.bend = {0.5, 0.7};
    sm::ShapeDef hyper = sm::default_shape_def();
    hyper.type = sm::ShapeType::Hyperquadric;
    hyper.terms = {{{2, 0, 0}, 0, 8}, {{0, 2, 0}, 0.1, 4}, {{0, 0, 2}, 0, 8}, {{1, 1, 1}, 0, 2}};
    sm::clear_bounds_cache();
    std::mt19937_64 rng(19);
    for (int round = 0; round < 3; ++round)
        for (const sm::ShapeDef& s : {tapered, bent, hyper}) {
            const sm::Quat q = random_orientation(rng);
            const sm::Vec3 at{0.1 * round, -2.0, 3.0};
            const sm::Aabb cached = sm::world_aabb(s, at, q), fresh = sm::world_aabb_uncached(s, at, q);
            for (int i = 0; i < 3; ++i) {
                EXPECT_EQ(cached.min[i], fresh.min[i]);
                EXPECT_EQ(cached.max[i], fresh.max[i]);
            }
        }
    EXPECT_EQ(sm::bounds_cache_size(), 3u); // one entry per distinct shape, however often asked

    // A changed parameter is a different shape, never a stale hit.
    sm::ShapeDef longer = bent;
    longer.radii.z = 3.0;
    const sm::Aabb a = sm::world_aabb(bent, {}, sm::Quat::identity());
    const sm::Aabb b = sm::world_aabb(longer, {}, sm::Quat::identity());
    EXPECT_GT(b.max.z - b.min.z, 1.5 * (a.max.z - a.min.z));
    EXPECT_EQ(sm::bounds_cache_size(), 4u);

    // Past its capacity the cache evicts instead of growing without bound, and still answers right.
    for (size_t i = 0; i <= sm::k_bounds_cache_capacity; ++i) {
        sm::ShapeDef s = tapered;
        s.taper.kx = -0.5 + 1e-3 * double(i);
        (void)sm::world_aabb(s, {}, sm::Quat::identity());
    }
    EXPECT_EQ(sm::bounds_cache_size(), sm::k_bounds_cache_capacity);
    const sm::Quat q = random_orientation(rng);
    const sm::Aabb again = sm::world_aabb(bent, {}, q), fresh = sm::world_aabb_uncached(bent, {}, q);
    EXPECT_EQ(again.min, fresh.min);
    EXPECT_EQ(again.max, fresh.max);
    sm::clear_bounds_cache();
    EXPECT_EQ(sm::bounds_cache_size(), 0u);
}
