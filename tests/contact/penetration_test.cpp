// Tests for engine/src/contact/penetration.cpp: the Newton search of MPR's normal (where the ray from
// the shape centres leaves the Minkowski difference), warm-started from a nearby normal.
#include "contact/mpr.h"
#include "contact/penetration.h"
#include "support/shapes.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

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
    // Two ellipsoids 1 mm apart (not spheres: those take the closed form below): the search from the
    // centre line finds that it separates them at its first evaluation (two support-map calls), an
    // exact answer.
    const sm::Collider c =
        sm::make_collider(sm::test::superquadric({0.05, 0.05, 0.04}, 1.0, 1.0), {}, 0.0, 4000);
    const sm::BodyView a{&c, {0, 0.101, 0}, {}, {}}, b{&c, {}, {}, {}};
    const sm::Penetration p = sm::find_penetration(a, b, {0, 1, 0});
    EXPECT_FALSE(p.hit);
    EXPECT_EQ(p.support_calls, 2);
}

TEST(Penetration, TwoSpheresTakeTheClosedForm)
{
    // Spheres of radii 0.05 and 0.03 m with centres 0.07 m apart along (2, 3, 6)/7: the least overlap
    // is 0.01 m along the line of centres, with no support evaluation. The centres sit near (1, 2, 3) m,
    // where a coordinate's rounding is 4.4e-16 m; over the 0.07 m between them that turns the normal by
    // up to ~1e-14, so 1e-13 bounds every value. Turned bodies keep it (a sphere has no orientation),
    // apart is not a hit, and coincident centres leave it to the search.
    constexpr double k_round_off = 1e-13;
    const sm::Collider big =
        sm::make_collider(sm::test::superquadric({0.05, 0.05, 0.05}, 1.0, 1.0), {}, 0.0, 4000);
    const sm::Collider small =
        sm::make_collider(sm::test::superquadric({0.03, 0.03, 0.03}, 1.0, 1.0), {}, 0.0, 4000);
    const sm::Vec3 n{2.0 / 7.0, 3.0 / 7.0, 6.0 / 7.0};
    const sm::Quat turned = sm::normalized(sm::Quat{0.9, 0.1, -0.3, 0.2});
    const sm::BodyView a{&big, {1.0 + 0.02, 2.0 + 0.03, 3.0 + 0.06}, turned, {}},
        b{&small, {1, 2, 3}, {}, {}};
    const sm::Penetration p = sm::find_penetration(a, b, {});
    ASSERT_TRUE(p.hit);
    EXPECT_EQ(p.support_calls, 0);
    EXPECT_NEAR(p.depth, 0.01, k_round_off);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(p.normal[i], n[i], k_round_off);
        EXPECT_NEAR(p.on_a[i], a.position[i] - 0.05 * n[i], k_round_off);
        EXPECT_NEAR(p.on_b[i], b.position[i] + 0.03 * n[i], k_round_off);
    }
    const sm::BodyView far{&big, {1.0, 2.1, 3.0}, {}, {}};
    const sm::Penetration apart = sm::find_penetration(far, b, {});
    EXPECT_FALSE(apart.hit);
    EXPECT_NEAR(apart.depth, 0.08 - 0.1, k_round_off);
    const sm::BodyView same{&big, {1, 2, 3}, {}, {}};
    const sm::Penetration centred = sm::find_penetration(same, b, {});
    EXPECT_TRUE(centred.hit);
    EXPECT_GT(centred.support_calls, 0);
}

namespace
{

// Overlap of A and B along n (from B towards A): n·(s_B(n) − s_A(−n)) [m].
double overlap_along(const sm::BodyView& a, const sm::BodyView& b, const sm::Vec3& n)
{
    return sm::dot(n, sm::body_support(b, n) - sm::body_support(a, -1.0 * n));
}

// The least overlap near `start` by a pattern search on the unit sphere (turns of 1e-2 down to 1e-11
// rad in eight tangent directions): slow, but it needs no derivative, so the infinite curvature
// across a face plane does not disturb it.
double least_overlap_by_pattern(const sm::BodyView& a, const sm::BodyView& b, sm::Vec3 n)
{
    double best = overlap_along(a, b, n);
    for (double turn = 1e-2; turn > 1e-11; turn *= 0.5) {
        for (bool moved = true; moved;) {
            moved = false;
            const sm::Vec3 axis = std::abs(n.x) < 0.6 ? sm::Vec3{1, 0, 0} : sm::Vec3{0, 1, 0};
            const sm::Vec3 t1 = sm::normalized(sm::cross(n, axis)), t2 = sm::cross(n, t1);
            for (int k = 0; k < 8; ++k) {
                const double angle = k * std::numbers::pi / 4.0;
                const sm::Vec3 trial =
                    sm::normalized(n + turn * (std::cos(angle) * t1 + std::sin(angle) * t2));
                if (const double f = overlap_along(a, b, trial); f < best) {
                    best = f;
                    n = trial;
                    moved = true;
                }
            }
        }
    }
    return best;
}

} // namespace

TEST(Penetration, LeastOverlapConvergesWhereTheNormalCrossesAFacePlane)
{
    // A rounded box's corner on another's rounded edge (half 0.05 m, ε 0.3), 0.5 mm deep, A turned at
    // random: the least overlap lies just off the plane n·e = 0 of B's edge, where B's support function
    // grows as |n·e|^1.18 and its curvature is infinite. Newton's model overshoots that plane 4.7-fold;
    // before the search placed such steps with the plane's own power law, most of these searches ran out
    // of their twelve evaluations. From a normal 0.02 rad off, every search converges within the budget
    // and its depth is the least overlap that a derivative-free pattern search finds, to 1e-8 m (ten
    // times the stopping tolerance: the model's prediction of what is left, not a bound).
    Rng rng;
    const sm::Collider box =
        sm::make_collider(sm::test::superquadric({0.05, 0.05, 0.05}, 0.3, 0.3), {}, 0.0, 4000);
    const sm::BodyView b{&box, {}, {}, {}};
    int near_plane = 0;
    for (int k = 0; k < 40; ++k) {
        const sm::Quat qa = rng.quat();
        const sm::Vec3 dir =
            sm::normalized(sm::Vec3{1.0 + 0.3 * rng.next(), 1.0 + 0.3 * rng.next(), 0.5 * rng.next()});
        double lo = 0.0, hi = 0.3;
        for (int i = 0; i < 50; ++i) {
            const double mid = 0.5 * (lo + hi);
            (sm::find_penetration({&box, mid * dir, qa, {}}, b, {}, sm::PenetrationTarget::LeastOverlap).hit
                 ? lo
                 : hi) = mid;
        }
        const sm::BodyView a{&box, (lo - 5e-4) * dir, qa, {}};
        const sm::Penetration cold = sm::find_penetration(a, b, {}, sm::PenetrationTarget::LeastOverlap);
        ASSERT_TRUE(cold.hit);
        const double least = least_overlap_by_pattern(a, b, cold.normal);
        if (std::abs(cold.normal.z) > 0.05)
            continue; // not at B's edge plane: the rest of the tests cover it
        ++near_plane;
        const sm::Vec3 tilt = sm::normalized(sm::cross(cold.normal, rng.unit()));
        const sm::Penetration warm = sm::refine_penetration(a, b, sm::normalized(cold.normal + 0.02 * tilt),
                                                            sm::PenetrationTarget::LeastOverlap);
        EXPECT_TRUE(warm.converged) << "case " << k;
        EXPECT_TRUE(cold.converged) << "case " << k;
        EXPECT_NEAR(warm.depth, least, 1e-8) << "case " << k;
        EXPECT_NEAR(cold.depth, least, 1e-8) << "case " << k;
    }
    EXPECT_GE(near_plane, 20);
}
