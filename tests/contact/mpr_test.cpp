// Tests for engine/src/contact/mpr.cpp: libccd MPR on the analytic support map against analytic
// depths and normals.
#include "contact/mpr.h"
#include "support/shapes.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

sm::Collider collider(sm::Vec3 radii, double eps)
{
    return sm::make_collider(sm::test::superquadric(radii, eps, eps), {}, 0.0, 4000);
}

sm::BodyView view(const sm::Collider& c, sm::Vec3 position, sm::Quat q = {})
{
    return {&c, position, q, {}};
}

double angle_between(sm::Vec3 a, sm::Vec3 b)
{
    return std::atan2(sm::length(sm::cross(a, b)), sm::dot(a, b));
}

} // namespace

TEST(Mpr, SphereSphereDepthAndNormalAreAnalytic)
{
    // Depth r1 + r2 − |d|, normal d/|d|. MPR stops when the portal is within its tolerance
    // t = 1e-4 × 0.05 m = 5e-6 m of the Minkowski sum's surface (a sphere of radius R = 0.15 m), so the
    // depth is within t; the portal triangle then spans at most √(2Rt) ≈ 1.2 mm of that sphere, which
    // tilts its closest point by at most √(2t/R) ≈ 8e-3 rad.
    const sm::Collider big = collider({0.1, 0.1, 0.1}, 1.0), small = collider({0.05, 0.05, 0.05}, 1.0);
    const sm::Vec3 pa{0.3, -0.2, 0.1}, d{0.11, 0.07, -0.05};
    const sm::MprResult r = sm::mpr_penetration(view(big, pa), view(small, pa - d));
    ASSERT_TRUE(r.hit);
    const double t = 1e-4 * 0.05, big_r = 0.15;
    EXPECT_NEAR(r.depth, big_r - sm::length(d), t);
    EXPECT_LT(angle_between(r.normal, d), std::sqrt(2.0 * t / big_r));
}

TEST(Mpr, BoxOnBoxDepthIsTheFaceOverlapAndNormalTheFaceNormal)
{
    // Two ε = 0.1 boxes, face on face, offset sideways, both turned by the same rotation: the depth is
    // the faces' overlap (0.1 + 0.1 − 0.195 = 5 mm) and the normal the lower box's face normal. The
    // faces are flat within (x/a)^20 of their radius away from the edges, so MPR meets a plane: depth
    // within its tolerance (1e-5 m), normal within tolerance / (portal size ~ 0.1 m) = 1e-4 rad, ×10
    // margin for the portal not being centred.
    const sm::Collider a = collider({0.1, 0.1, 0.1}, 0.1), b = collider({0.2, 0.1, 0.2}, 0.1);
    const sm::Quat q = sm::normalized(sm::Quat{0.9, 0.2, -0.3, 0.1});
    const sm::Vec3 offset = sm::rotate(q, {0.03, 0.195, 0.02}), origin{1.0, 2.0, -0.5};
    const sm::MprResult r = sm::mpr_penetration(view(a, origin + offset, q), view(b, origin, q));
    ASSERT_TRUE(r.hit);
    EXPECT_NEAR(r.depth, 0.005, 1e-5);
    EXPECT_LT(angle_between(r.normal, sm::rotate(q, {0, 1, 0})), 1e-3);
}

TEST(Mpr, SeparatedBodiesDoNotHit)
{
    const sm::Collider a = collider({0.1, 0.1, 0.1}, 0.3);
    EXPECT_FALSE(sm::mpr_penetration(view(a, {0, 0.2001, 0}), view(a, {})).hit);
    EXPECT_TRUE(sm::mpr_penetration(view(a, {0, 0.1999, 0}), view(a, {})).hit);
}

TEST(Mpr, NonFinitePoseHasNoContact)
{
    const sm::Collider a = collider({0.1, 0.1, 0.1}, 0.3);
    const double nan = std::nan("");
    EXPECT_FALSE(sm::mpr_penetration(view(a, {nan, 0, 0}), view(a, {})).hit);
    EXPECT_FALSE(sm::mpr_penetration(view(a, {}), view(a, {0, 0.1, 0}, {nan, 0, 0, 1})).hit);
}

TEST(Mpr, BodySupportIsTheShapeSupportMovedToTheBody)
{
    const sm::Collider a = collider({0.1, 0.2, 0.3}, 0.5);
    const sm::Quat q = sm::normalized(sm::Quat{0.8, 0.1, 0.5, -0.2});
    const sm::Vec3 dir{0.3, -1.0, 0.2};
    const sm::Vec3 expected =
        sm::Vec3{1, 2, 3} + sm::rotate(q, sm::support_point(a.shape, sm::inv_rotate(q, dir)));
    const sm::Vec3 got = sm::body_support(view(a, {1, 2, 3}, q), dir);
    EXPECT_LT(sm::length(got - expected), 1e-12);
}

TEST(Mpr, OrdinaryQueriesStayFarInsideTheSupportBudget)
{
    // Overlapping pairs over ε 0.1…2 and aspect up to 10 at random poses: smooth convex pairs converge
    // in tens of supports (the samples' maximum is 32), so a budget of 3 × 100 + 8 never cuts a real
    // query short. Bound: a fifth of the budget.
    int most = 0;
    unsigned seed = 12345;
    auto uniform = [&seed](double lo, double hi) {
        seed = seed * 1664525u + 1013904223u;
        return lo + (hi - lo) * (seed >> 8) / double(1u << 24);
    };
    for (int i = 0; i < 100; ++i) {
        const sm::Collider a =
            collider({uniform(0.05, 0.5), uniform(0.05, 0.5), uniform(0.05, 0.5)}, uniform(0.1, 2.0));
        const sm::Collider b =
            collider({uniform(0.05, 0.5), uniform(0.05, 0.5), uniform(0.05, 0.5)}, uniform(0.1, 2.0));
        const sm::Quat qa =
            sm::normalized(sm::Quat{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
        const sm::Quat qb =
            sm::normalized(sm::Quat{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)});
        const sm::Vec3 d{uniform(-0.1, 0.1), uniform(-0.1, 0.1), uniform(-0.1, 0.1)};
        const sm::MprResult r = sm::mpr_penetration(view(a, d, qa), view(b, {}, qb));
        EXPECT_TRUE(r.hit) << i; // the centres are at most 0.17 m apart, each body at least 0.05 m deep
        EXPECT_FALSE(r.gave_up) << i;
        most = std::max(most, r.support_calls);
    }
    EXPECT_LT(most, sm::k_mpr_max_support_calls / 5);
}

TEST(Mpr, AHugeBodyBesideASmallOneIsRefusedAtOnce)
{
    // A hang the scene fuzzer found: a 1e60 m long ellipsoid among 6 cm ones. libccd's portal refinement
    // has no iteration cap and rounding at that scale never meets its tolerance. First ended by the
    // support budget; now refused before libccd runs (no double resolves 3 cm on 1e60 m).
    const sm::Collider huge = collider({0.06, 0.04, 1e60}, 1.0), small = collider({0.06, 0.04, 0.03}, 1.0);
    const sm::Quat qh{-0.30494454806978222, 0.80000904718307064, 0.14441348303304696, -0.49612407011353088};
    const sm::Quat qs{0.10150388499320943, 0.80334385994625668, 0.4340158139709645, -0.39492515397357969};
    const sm::MprResult r = sm::mpr_penetration(view(small, {-0.28578, 0.089238, 0.119869}, qs),
                                                view(huge, {-0.287476, 1.312823, 0.116257}, qh));
    EXPECT_TRUE(r.gave_up);
    EXPECT_FALSE(r.hit);
    EXPECT_EQ(r.support_calls, 0);
}

TEST(Mpr, AHugeBodyFarFromTheOriginEndsAtOnce)
{
    // The fuzzer's second hang (the exploding pile): the 1e60 m ellipsoid flung to 1.2e41 m, against
    // a 6 cm one near the origin. Rounding at that scale kept one of libccd's portal loops turning
    // even on the budget's fallback supports (the shape's centre). A query whose coordinates double
    // cannot resolve to the MPR tolerance is now refused before libccd runs: no support is evaluated.
    const sm::Collider huge = collider({0.06, 0.04, 1e60}, 1.0), small = collider({0.06, 0.04, 0.03}, 1.0);
    const sm::Quat qh{-0.70547658588452178, -0.34495933349150898, 0.43088120836163413, 0.44457533589553866};
    const sm::Quat qs{0.11089045294428784, 0.16220212991850846, 0.67207443166234504, -0.7139395876413116};
    const sm::MprResult r = sm::mpr_penetration(
        view(huge, {1.2493412836166424e+41, 2.4986825672332787e+40, 1.8378931116193796e+25}, qh),
        view(small, {-0.084506999999999999, 1.3039942063137755, 0.100656}, qs));
    EXPECT_TRUE(r.gave_up);
    EXPECT_FALSE(r.hit);
    EXPECT_EQ(r.support_calls, 0);
}

TEST(Mpr, TwoSmallBodiesFarOutOverlapWhileDoublesResolveThemAndAreRefusedPastIt)
{
    // The rounding rule's edge for position: two 3 cm spheres 1 cm deep, shifted out along x. Up to
    // 1e8 m (spacing of doubles 1.5e-8 m) the depth is found; at 1e10 m (rounding bound 1.6e-5 m over
    // the 3e-6 m tolerance) the query is refused.
    const sm::Collider s = collider({0.03, 0.03, 0.03}, 1.0);
    for (const double far : {0.0, 1e3, 1e6, 1e8}) {
        const sm::MprResult r = sm::mpr_penetration(view(s, {far, 0, 0}), view(s, {far + 0.05, 0, 0}));
        EXPECT_TRUE(r.hit) << far;
        EXPECT_NEAR(r.depth, 0.01, 1e-5) << far; // MPR's tolerance 3e-6 m, plus rounding 1.5e-8 m
    }
    const sm::MprResult r = sm::mpr_penetration(view(s, {1e10, 0, 0}), view(s, {1e10 + 0.05, 0, 0}));
    EXPECT_TRUE(r.gave_up);
    EXPECT_FALSE(r.hit);
    EXPECT_EQ(r.support_calls, 0);
}

TEST(Mpr, PastTheBudgetEveryLoopEnds)
{
    // The budget's fallback (a point far behind each shape's centre) must end each of libccd's loops
    // wherever it stands: cut ordinary overlapping queries short at every budget from 1 to 40 supports
    // (they need up to ~30), so the cut lands in portal discovery, refinement and the depth search.
    // Each query ends within one Minkowski support past its budget, and a cut query reports no overlap.
    const sm::Collider a = collider({0.1, 0.07, 0.05}, 0.6), b = collider({0.08, 0.12, 0.06}, 1.4);
    const sm::Quat qa = sm::normalized(sm::Quat{0.8, 0.1, 0.5, -0.2});
    const sm::Quat qb = sm::normalized(sm::Quat{0.3, -0.6, 0.2, 0.7});
    int cut = 0;
    for (int budget = 1; budget <= 40; ++budget)
        for (const sm::Vec3 d :
             {sm::Vec3{0.05, 0.02, -0.01}, sm::Vec3{-0.02, 0.09, 0.03}, sm::Vec3{0.0, 0.0, 0.1}}) {
            const sm::MprResult r = sm::mpr_penetration(view(a, d, qa), view(b, {}, qb), budget);
            EXPECT_LE(r.support_calls, budget + 1) << budget;
            if (r.gave_up) {
                EXPECT_FALSE(r.hit) << budget;
                ++cut;
            }
        }
    EXPECT_GT(cut, 30); // the small budgets really cut
}
