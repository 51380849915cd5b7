// Tests for engine/src/geometry/support.cpp.
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

constexpr std::array<double, 8> k_extreme_eps = {0.01, 0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0};

// Directions on a Fibonacci sphere: even coverage without the poles' crowding.
sm::Vec3 fibonacci_direction(int i, int n)
{
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z);
    const double phi = i * k_pi * (3.0 - std::sqrt(5.0));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace

TEST(Support, SphereAndEllipsoidMatchClosedForm)
{
    constexpr double k_round_off = 1e-14;
    const sm::Vec3 s = sm::support_point(superquadric({2, 2, 2}, 1, 1), {3, 0, 4});
    EXPECT_NEAR(s.x, 1.2, k_round_off);
    EXPECT_NEAR(s.y, 0.0, k_round_off);
    EXPECT_NEAR(s.z, 1.6, k_round_off);
    // Ellipsoid: the support point of d is A²d / |Ad|.
    const sm::Vec3 a{1, 2, 3}, d{0.3, -0.5, 0.8};
    const sm::Vec3 ad = sm::hadamard(a, d);
    const sm::Vec3 expected = sm::hadamard(a, ad) / sm::length(ad);
    const sm::Vec3 e = sm::support_point(superquadric(a, 1, 1), d);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(e[i], expected[i], k_round_off);
}

TEST(Support, EllipsoidShortcutAgreesWithTheNestedFormulaNearby)
{
    // ε1 = ε2 = 1 takes a closed form; ε = 1 ± 1e-9 takes the nested dual levels. The support point
    // moves by O(δε · size) between them, so they agree to 1e-8 of the size over many directions and
    // aspects up to 1:1000 (a wrong shortcut would differ by O(size)).
    constexpr double k_agree_rel = 1e-8;
    constexpr int k_directions = 200;
    for (const sm::Vec3& a : {sm::Vec3{1, 1, 1}, sm::Vec3{0.06, 0.04, 0.03}, sm::Vec3{1000, 1, 0.5}})
        for (int k = 0; k < k_directions; ++k) {
            const sm::Vec3 d = fibonacci_direction(k, k_directions);
            const sm::Vec3 exact = sm::support_point(superquadric(a, 1, 1), d);
            const double size = std::max({a.x, a.y, a.z});
            for (double e : {1.0 - 1e-9, 1.0 + 1e-9}) {
                const sm::Vec3 nested = sm::support_point(superquadric(a, e, e), d);
                for (int i = 0; i < 3; ++i)
                    EXPECT_NEAR(exact[i], nested[i], k_agree_rel * size) << k;
            }
        }
}

TEST(Support, EqualExponentsOneLevelAgreesWithTheNestedFormulaNearby)
{
    // ε1 = ε2 ≠ 1 (below 2) takes one ℓq level over all three components; ε2 = ε1·(1 ± 1e-12) takes
    // the nested levels. The point moves by O(δε · size) between them (larger near a flat face's edge,
    // where the point slides fastest with ε), so they agree to 1e-8 of the size; a wrong level would
    // differ by O(size).
    constexpr double k_agree_rel = 1e-8;
    constexpr int k_directions = 200;
    for (double e : {0.1, 0.3, 0.7, 1.5, 1.9})
        for (const sm::Vec3& a : {sm::Vec3{1, 1, 1}, sm::Vec3{0.1, 0.05, 0.02}, sm::Vec3{1000, 1, 0.5}})
            for (int k = 0; k < k_directions; ++k) {
                const sm::Vec3 d = fibonacci_direction(k, k_directions);
                const sm::Vec3 one = sm::support_point(superquadric(a, e, e), d);
                const double size = std::max({a.x, a.y, a.z});
                for (double f : {1.0 - 1e-12, 1.0 + 1e-12}) {
                    const sm::Vec3 nested = sm::support_point(superquadric(a, e, e * f), d);
                    for (int i = 0; i < 3; ++i)
                        EXPECT_NEAR(one[i], nested[i], k_agree_rel * size) << e << " " << k;
                }
            }
}

TEST(Support, BoxOctahedronAndHullLimits)
{
    // ε = 0.01: a generic direction's support point is the corner sign(d)·a up to factors
    // (r^q / Σ r^q)^(ε/2) per nesting level, r the component ratios (≥ 0.3 here): each at most
    // 0.005·|ln 0.23| ≈ 0.7% below one, so the coordinates are within 1.5% of the corner's.
    constexpr double k_box_rel = 0.015;
    const sm::Vec3 box = sm::support_point(superquadric({1, 2, 3}, 0.01, 0.01), {0.3, -0.5, 0.2});
    EXPECT_NEAR(box.x, 1.0, k_box_rel * 1.0);
    EXPECT_NEAR(box.y, -2.0, k_box_rel * 2.0);
    EXPECT_NEAR(box.z, 3.0, k_box_rel * 3.0);
    // ε = 2: the vertex with the largest a_i|d_i| (here z: 3·0.3 > 2·0.4 > 1·0.5), exactly.
    EXPECT_EQ(sm::support_point(superquadric({1, 2, 3}, 2, 2), {0.5, -0.4, 0.3}), (sm::Vec3{0, 0, 3}));
    // ε = 2 on an exact tie: the middle of the octahedron's edge, which is on the surface.
    const sm::ShapeDef oct = superquadric({1, 1, 1}, 2, 2);
    const sm::Vec3 mid = sm::support_point(oct, {1, 1, 0});
    EXPECT_EQ(mid, (sm::Vec3{0.5, 0.5, 0}));
    // Concave (both ε > 2): the hull is the octahedron of the axis tips, and a tie picks a tip.
    EXPECT_EQ(sm::support_point(superquadric({1, 2, 3}, 4, 3), {0.5, -0.4, 0.3}), (sm::Vec3{0, 0, 3}));
    EXPECT_EQ(sm::support_point(superquadric({1, 1, 1}, 4, 4), {1, 1, 0}), (sm::Vec3{1, 0, 0}));
    // Zero and non-finite directions give the +z pole.
    EXPECT_EQ(sm::support_point(oct, {0, 0, 0}), (sm::Vec3{0, 0, 1}));
    EXPECT_EQ(sm::support_point(oct, {NAN, 0, 0}), (sm::Vec3{0, 0, 1}));
}

TEST(Support, NearOctahedronIsContinuousAndFinite)
{
    // q = 2/(2 − ε) reaches 2e12 at ε = 2 − 1e-12: the powers must underflow to 0, never overflow.
    // Approaching ε = 2 the support point slides to the vertex; at a tie it stays at the edge middle.
    constexpr double k_near_vertex = 1e-6;
    for (double e : {1.999, 1.999999, 2.0 - 1e-12}) {
        const sm::ShapeDef s = superquadric({1, 2, 3}, e, e);
        const sm::Vec3 v = sm::support_point(s, {0.5, -0.4, 0.3});
        ASSERT_TRUE(sm::is_finite(v));
        if (e < 1.9999)
            continue;
        EXPECT_NEAR(v.z, 3.0, 3.0 * k_near_vertex);
        const sm::Vec3 mid = sm::support_point(superquadric({1, 1, 1}, e, e), {1, 1, 0});
        EXPECT_NEAR(mid.x, 0.5, k_near_vertex);
        EXPECT_NEAR(mid.y, 0.5, k_near_vertex);
    }
}

TEST(Support, DominatesDenseParametricGridAndLiesOnTheSurface)
{
    // Support values are maxima of d·x; a grid point may reach them up to the round-off of the
    // products, relative to the size. The support point itself is on the surface to round-off (the
    // measure is ~ relative coordinate error; near ε = 2 the powers q ~ 10^3 amplify it a little).
    constexpr double k_dominance_rel = 1e-12;
    constexpr double k_on_surface = 1e-10;
    constexpr int k_directions = 64, k_eta = 48, k_omega = 96;
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps)
            for (const sm::Vec3& a : {sm::Vec3{1, 1, 1}, sm::Vec3{1, 10, 0.1}, sm::Vec3{1000, 1, 1}}) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                const double size = std::max({a.x, a.y, a.z});
                std::vector<sm::Vec3> grid;
                for (int i = 0; i <= k_eta; ++i)
                    for (int j = 0; j < k_omega; ++j)
                        grid.push_back(sm::surface_point(s, -k_pi / 2 + k_pi * i / k_eta,
                                                         -k_pi + 2 * k_pi * j / k_omega));
                for (int k = 0; k < k_directions; ++k) {
                    const sm::Vec3 d = fibonacci_direction(k, k_directions);
                    const sm::Vec3 sp = sm::support_point(s, d);
                    ASSERT_NEAR(sm::contact_measure(s, sp), 0.0, k_on_surface) << e1 << " " << e2;
                    const double h = sm::dot(sp, d);
                    double best = -INFINITY;
                    for (const sm::Vec3& x : grid)
                        best = std::max(best, sm::dot(x, d));
                    ASSERT_GE(h, best - k_dominance_rel * size) << e1 << " " << e2 << " dir " << k;
                    // Central symmetry: the opposite direction gives the opposite point.
                    const sm::Vec3 opposite = sm::support_point(s, -d);
                    for (int i = 0; i < 3; ++i)
                        ASSERT_EQ(opposite[i], -sp[i]);
                }
            }
}

TEST(Support, NoNanOrInfOverTheExtremes)
{
    // 10^6 directions over ε × aspect: random, axis-aligned, with zero components, 1e±300 scales.
    constexpr int k_per_case = 1'000'000 / (8 * 8 * 4) + 1;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    long evaluations = 0;
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps)
            for (const sm::Vec3& a :
                 {sm::Vec3{1, 1, 1}, sm::Vec3{1, 1, 1000}, sm::Vec3{0.001, 1, 1}, sm::Vec3{1, 0.001, 1000}}) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                for (int n = 0; n < k_per_case; ++n, ++evaluations) {
                    sm::Vec3 d{unit(rng), unit(rng), unit(rng)};
                    switch (n % 5) {
                    case 0:
                        d[n % 3] = 0.0;
                        break;
                    case 1:
                        d = {0, 0, 0};
                        d[n % 3] = unit(rng);
                        break;
                    case 2:
                        d = d * 1e300;
                        break;
                    case 3:
                        d = d * 1e-300;
                        break;
                    default:
                        break;
                    }
                    const sm::Vec3 sp = sm::support_point(s, d);
                    ASSERT_TRUE(sm::is_finite(sp)) << d.x << " " << d.y << " " << d.z;
                    ASSERT_LE(std::abs(sp.x), a.x);
                    ASSERT_LE(std::abs(sp.y), a.y);
                    ASSERT_LE(std::abs(sp.z), a.z);
                }
            }
    EXPECT_GE(evaluations, 1'000'000);
}
