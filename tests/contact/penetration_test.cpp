// Tests for engine/src/contact/penetration.cpp: the Newton search of MPR's normal (where the ray from
// the shape centres leaves the Minkowski difference), warm-started from a nearby normal.
#include "contact/mpr.h"
#include "contact/penetration.h"
#include "support/shapes.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

struct Rng {
    uint32_t seed = 11;
    double next()
    {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<double>(seed >> 8) / 8388608.0 - 1.0;
    }
    sm::Quat quat() { return sm::normalized(sm::Quat{next(), next(), next(), next()}); }
    sm::Vec3 unit() { return sm::normalized(sm::Vec3{next(), next(), next()}); }
};

// B at the origin; A along `dir` from it, `overlap` [m] into it along the centre line (bisection on
// MPR's hit, then moved in).
sm::BodyView place(const sm::Collider& ca, const sm::Quat& qa, const sm::BodyView& b, const sm::Vec3& dir,
                   double overlap)
{
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (sm::mpr_penetration({&ca, mid * dir, qa, {}}, b).hit ? lo : hi) = mid;
    }
    return {&ca, (lo - overlap) * dir, qa, {}};
}

// The residual of the search's condition: how far B − A's support point along the normal lies off
// the ray through the shape centres [m].
double off_ray(const sm::BodyView& a, const sm::BodyView& b, const sm::Penetration& p)
{
    const sm::Vec3 u = sm::normalized(sm::body_shape_centre(a) - sm::body_shape_centre(b));
    const sm::Vec3 w = p.on_b - p.on_a;
    return sm::length(w - sm::dot(w, u) * u);
}

} // namespace

TEST(Penetration, WarmStartedSearchEqualsTheColdQuery)
{
    // Ellipsoids and the rounded edges of flat boxes, 1 mm into each other at random orientations: the
    // search from a normal 0.02 rad off finds the cold query's normal (MPR, then Newton from its
    // normal) within 1e-5 rad and its depth within 1e-9 m, on the ray within 5e-7 m; with at most
    // five evaluations in all but 5% of the cases. The rest start where the Minkowski support points
    // against the ray (w·u ≤ 0, no Newton step): the search gives up and takes MPR's start, still
    // exact (2 of 80 in another draw of the same generator).
    Rng rng;
    const sm::Collider ellipsoid =
        sm::make_collider(sm::test::superquadric({0.06, 0.04, 0.03}, 1.0, 1.0), {}, 0.0, 4000);
    const sm::Collider pointed =
        sm::make_collider(sm::test::superquadric({0.05, 0.04, 0.05}, 1.5, 0.8), {}, 0.0, 4000);
    int compared = 0, slow = 0;
    for (const sm::Collider* c : {&ellipsoid, &pointed}) {
        for (int k = 0; k < 40; ++k) {
            // One draw per statement: the order of a call's arguments is the compiler's choice.
            const sm::BodyView b{c, {}, rng.quat(), {}};
            const sm::Vec3 dir = rng.unit();
            const sm::Quat turn = rng.quat();
            const sm::BodyView a = place(*c, turn, b, dir, 1e-3);
            const sm::Penetration cold = sm::find_penetration(a, b, {});
            ASSERT_TRUE(cold.hit);
            if (!cold.converged)
                continue; // MPR's own answer: nothing to compare the search with
            ++compared;
            EXPECT_LT(off_ray(a, b, cold), 5e-7);
            const sm::Vec3 tilt = sm::normalized(sm::cross(cold.normal, rng.unit()));
            const sm::Penetration warm =
                sm::find_penetration(a, b, sm::normalized(cold.normal + 0.02 * tilt));
            ASSERT_TRUE(warm.converged);
            EXPECT_LT(std::acos(std::min(1.0, sm::dot(warm.normal, cold.normal))), 1e-5);
            EXPECT_NEAR(warm.depth, cold.depth, 1e-9);
            slow += warm.support_calls > 10 ? 1 : 0;
        }
    }
    EXPECT_GE(compared, 70);
    EXPECT_LE(slow, compared / 20);
}

TEST(Penetration, ASeparatingStartEndsTheSearchWithoutContact)
{
    // Two ellipsoids 1 mm apart: the search from the centre line finds that it separates them at its
    // first evaluation (two support-map calls), an exact answer.
    const sm::Collider c =
        sm::make_collider(sm::test::superquadric({0.05, 0.05, 0.05}, 1.0, 1.0), {}, 0.0, 4000);
    const sm::BodyView a{&c, {0, 0.101, 0}, {}, {}}, b{&c, {}, {}, {}};
    const sm::Penetration p = sm::find_penetration(a, b, {0, 1, 0});
    EXPECT_FALSE(p.hit);
    EXPECT_EQ(p.support_calls, 2);
}
