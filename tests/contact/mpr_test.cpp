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

TEST(Mpr, AHugeBodyBesideASmallOneEndsWithinTheSupportBudget)
{
    // The fuzzer's hang: a 1e60 m long ellipsoid among 6 cm ones. libccd's portal refinement has no
    // iteration cap and rounding at that scale never meets its tolerance; the support budget ends the
    // query, reported as no overlap (the pair had to fail somehow: no double resolves 3 cm on 1e60 m).
    const sm::Collider huge = collider({0.06, 0.04, 1e60}, 1.0), small = collider({0.06, 0.04, 0.03}, 1.0);
    const sm::Quat qh{-0.30494454806978222, 0.80000904718307064, 0.14441348303304696, -0.49612407011353088};
    const sm::Quat qs{0.10150388499320943, 0.80334385994625668, 0.4340158139709645, -0.39492515397357969};
    const sm::MprResult r = sm::mpr_penetration(view(small, {-0.28578, 0.089238, 0.119869}, qs),
                                                view(huge, {-0.287476, 1.312823, 0.116257}, qh));
    EXPECT_TRUE(r.gave_up);
    EXPECT_FALSE(r.hit);
    EXPECT_LE(r.support_calls, sm::k_mpr_max_support_calls + 1);
}
