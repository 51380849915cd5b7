// Tests for engine/src/geometry/superquadric.cpp.
#include "geometry/measure_internal.h"
#include "geometry/superquadric.h"
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

// The extremes the engine supports (docs/geometry.md): ε from 0.01 (box) through 2 (octahedron) to 4 (concave
// star).
constexpr std::array<double, 8> k_extreme_eps = {0.01, 0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
// Aspect ratios up to 1:1000 along every axis.
const std::array<sm::Vec3, 5> k_extreme_radii = {sm::Vec3{1, 1, 1}, sm::Vec3{1, 1, 1000},
                                                 sm::Vec3{1000, 1, 1}, sm::Vec3{0.001, 1, 1},
                                                 sm::Vec3{1, 0.001, 1000}};

double max_radius(const sm::ShapeDef& s)
{
    return std::max({s.radii.x, s.radii.y, s.radii.z});
}

} // namespace

TEST(Superquadric, SphereMatchesAnalyticValues)
{
    // Each value is a handful of logs and exps of exact inputs: a few ulps.
    constexpr double k_round_off = 1e-14;
    const sm::ShapeDef s = superquadric({2, 2, 2}, 1, 1);
    const sm::Vec3 p{1.2, -0.9, 2.0}; // |p| = 2.5
    EXPECT_NEAR(sm::inside_outside(s, p), 2.5 * 2.5 / 4.0, k_round_off);
    EXPECT_NEAR(sm::inside_outside_log(s, p), std::log(2.5 * 2.5 / 4.0), k_round_off);
    EXPECT_NEAR(sm::contact_measure(s, p), 2.5 / 2.0 - 1.0, k_round_off);
    EXPECT_NEAR(sm::radial_distance(s, p), 0.5, k_round_off);
    const sm::Vec3 g = sm::contact_measure_gradient(s, p), n = sm::implicit_normal(s, p);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(g[i], p[i] / 2.5 / 2.0, k_round_off); // ∇(|p|/a − 1) = p̂ / a
        EXPECT_NEAR(n[i], p[i] / 2.5, k_round_off);
    }
}

TEST(Superquadric, EllipsoidMatchesAnalyticValues)
{
    constexpr double k_round_off = 1e-13;
    const sm::ShapeDef s = superquadric({1, 2, 3}, 1, 1);
    const sm::Vec3 p{0.3, -1.5, 2.0};
    const double f = 0.09 + 1.5 * 1.5 / 4.0 + 4.0 / 9.0;
    EXPECT_NEAR(sm::inside_outside(s, p), f, k_round_off);
    EXPECT_NEAR(sm::contact_measure(s, p), std::sqrt(f) - 1.0, k_round_off);
    EXPECT_NEAR(sm::radial_distance(s, p), sm::length(p) * (1.0 - 1.0 / std::sqrt(f)), k_round_off);
    const sm::Vec3 g = sm::contact_measure_gradient(s, p);
    const sm::Vec3 expected{0.3 / std::sqrt(f), -1.5 / 4.0 / std::sqrt(f), 2.0 / 9.0 / std::sqrt(f)};
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(g[i], expected[i], k_round_off);
}

TEST(Superquadric, EllipsoidShortcutAgreesWithLogSpace)
{
    // Ellipsoids skip the log space while max |p_i / a_i| ∈ [1e-100, 1e100]; both paths round
    // differently, by a few ulps of ln F (absolute, since ln F is O(1)…O(460) here).
    constexpr double k_paths_agree = 1e-13;
    const sm::ShapeDef s = superquadric({0.5, 2, 1000}, 1, 1);
    for (const sm::Vec3& p : {sm::Vec3{0.1, -0.3, 20}, sm::Vec3{0.5, 0, 0}, sm::Vec3{1e-90, 3e-90, 0},
                              sm::Vec3{4e99, -1e99, 1e101}, sm::Vec3{-0.25, 1.0, 700}})
        EXPECT_NEAR(sm::inside_outside_log(s, p), sm::sq::log_terms(s, p).log_f,
                    k_paths_agree * (1.0 + std::abs(sm::sq::log_terms(s, p).log_f)));
}

TEST(Superquadric, EllipsoidGradientShortcutAgreesWithLogSpace)
{
    // The gradient's shortcut (one square root) against the log-space terms it skips, component by
    // component relative to the gradient's length: both round a few ulps, the logs' more (exp of a
    // sum of logs of size up to ~460 carries ~460 ulps relative).
    constexpr double k_paths_agree = 1e-12;
    const sm::ShapeDef s = superquadric({0.5, 2, 1000}, 1, 1);
    for (const sm::Vec3& p : {sm::Vec3{0.1, -0.3, 20}, sm::Vec3{0.5, 0, 0}, sm::Vec3{1e-90, 3e-90, 0},
                              sm::Vec3{4e99, -1e99, 1e101}, sm::Vec3{-0.25, 1.0, 700}}) {
        const sm::sq::LogTerms t = sm::sq::log_terms(s, p);
        const sm::sq::LogGradient lg = sm::sq::log_gradient(s, p, t);
        sm::Vec3 expected;
        for (int i = 0; i < 3; ++i)
            expected[i] = lg.sign[i] * std::exp(0.5 * t.log_f + lg.log_mag[i]) / s.radii[i];
        const sm::Vec3 g = sm::contact_measure_gradient(s, p);
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(g[i], expected[i], k_paths_agree * sm::length(expected)) << i;
    }
}

TEST(Superquadric, MeasurePointIsTheTwoCallsBitForBit)
{
    // One evaluation of the terms serves the value and the gradient: no rounding of its own, so equal.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> coord(-3.0, 3.0);
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps) {
            const sm::ShapeDef s = superquadric({1, 0.5, 2}, e1, e2);
            for (int k = 0; k < 16; ++k) {
                const sm::Vec3 p = k == 0 ? sm::Vec3{} : sm::Vec3{coord(rng), coord(rng), 1e-3 * coord(rng)};
                const sm::MeasurePoint at(s, p);
                EXPECT_EQ(at.value(), sm::contact_measure(s, p)) << e1 << " " << e2;
                const sm::Vec3 g = at.gradient(), expected = sm::contact_measure_gradient(s, p);
                for (int i = 0; i < 3; ++i)
                    EXPECT_EQ(g[i], expected[i]) << e1 << " " << e2 << " " << i;
            }
        }
}

TEST(Superquadric, BoxAndOctahedronLimits)
{
    constexpr double k_round_off = 1e-13;
    // ε = 0.01 at (0.9 a): F = 3·0.9^200, so the gauge is 0.9·3^0.005, within 0.55% of the box's 0.9.
    const sm::ShapeDef box = superquadric({1, 2, 3}, 0.01, 0.01);
    EXPECT_NEAR(sm::contact_measure(box, {0.9, 1.8, 2.7}), 0.9 * std::pow(3.0, 0.005) - 1.0, k_round_off);
    EXPECT_NEAR(sm::inside_outside_log(box, {0.9, 1.8, 2.7}), std::log(3.0) + 200.0 * std::log(0.9),
                1e-10); // ln F ≈ −20: relative round-off of the terms times 200
    // On an axis the gauge is |x| / a for every ε, so the measure is exact.
    for (double e : k_extreme_eps)
        EXPECT_NEAR(sm::contact_measure(superquadric({1, 2, 3}, e, e), {0, 0, 3.3}), 0.1, k_round_off);
    // ε = 2 is the octahedron: the gauge is Σ|x_i| / a_i exactly.
    const sm::ShapeDef oct = superquadric({1, 2, 4}, 2, 2);
    EXPECT_NEAR(sm::contact_measure(oct, {0.2, -0.6, 1.2}), 0.2 + 0.3 + 0.3 - 1.0, k_round_off);
    EXPECT_NEAR(sm::inside_outside_log(oct, {0, 0, 0}), -1e300, 0.0);
    EXPECT_EQ(sm::contact_measure(oct, {0, 0, 0}), -1.0);
}

TEST(Superquadric, SignedPower)
{
    EXPECT_EQ(sm::signed_power(-8.0, 1.0 / 3.0), -std::pow(8.0, 1.0 / 3.0));
    EXPECT_EQ(sm::signed_power(0.25, 0.5), 0.5);
    EXPECT_EQ(sm::signed_power(0.0, 0.01), 0.0);
    EXPECT_EQ(sm::signed_power(0.0, -1.0), 0.0); // sign(0) = 0, never |0|^−1
}

TEST(Superquadric, SurfacePointsLieOnTheSurface)
{
    // The gauge is homogeneous of degree one, so the measure at a parametric point is the relative
    // round-off of its coordinates: a few ulps, even when raised to the power 2/ε = 200.
    constexpr double k_on_surface = 1e-12;
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps)
            for (const sm::Vec3& a : k_extreme_radii) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                for (int i = 0; i <= 16; ++i)
                    for (int j = 0; j < 32; ++j) {
                        const double eta = -k_pi / 2 + k_pi * i / 16, omega = -k_pi + 2 * k_pi * j / 32;
                        const sm::Vec3 x = sm::surface_point(s, eta, omega);
                        ASSERT_NEAR(sm::contact_measure(s, x), 0.0, k_on_surface) << e1 << " " << e2;
                    }
            }
}

TEST(Superquadric, ParametricNormalMatchesImplicitNormal)
{
    // Both normals are unit vectors computed from the same point by different formulas; away from
    // the ridges and poles, where each is a one-sided choice, they agree to round-off of the logs.
    constexpr double k_normal_agreement = 1e-10;
    for (double e1 : {0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0})
        for (double e2 : {0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0}) {
            const sm::ShapeDef s = superquadric({1, 2, 0.5}, e1, e2);
            for (double eta : {-1.2, -0.4, 0.3, 1.1})
                for (double omega : {-2.8, -1.0, 0.2, 2.0}) {
                    const sm::Vec3 np = sm::surface_normal(s, eta, omega);
                    const sm::Vec3 ni = sm::implicit_normal(s, sm::surface_point(s, eta, omega));
                    EXPECT_NEAR(sm::length(np), 1.0, k_normal_agreement);
                    for (int i = 0; i < 3; ++i)
                        EXPECT_NEAR(np[i], ni[i], k_normal_agreement) << e1 << " " << e2;
                }
        }
}

TEST(Superquadric, GradientMatchesFiniteDifferences)
{
    // Central differences with h = 1e-5 (relative): truncation ~h²·M''' and cancellation ~1e-16/h
    // leave about 1e-8 relative error for powers up to 2/ε = 20; compare at 1e-6.
    constexpr double k_fd_rel = 1e-6;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> coord(0.2, 1.6);
    for (double e1 : {0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0})
        for (double e2 : {0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0}) {
            const sm::ShapeDef s = superquadric({1, 0.5, 2}, e1, e2);
            for (int k = 0; k < 8; ++k) {
                // Away from the coordinate planes, where ε ≥ 2 has ridges.
                const sm::Vec3 p{(k & 1 ? 1 : -1) * coord(rng), (k & 2 ? 0.5 : -0.5) * coord(rng),
                                 (k & 4 ? 2 : -2) * coord(rng)};
                const sm::Vec3 g = sm::contact_measure_gradient(s, p);
                for (int i = 0; i < 3; ++i) {
                    const double h = 1e-5 * std::abs(p[i]);
                    sm::Vec3 pp = p, pm = p;
                    pp[i] += h;
                    pm[i] -= h;
                    const double fd = (sm::contact_measure(s, pp) - sm::contact_measure(s, pm)) / (2 * h);
                    EXPECT_NEAR(g[i], fd, k_fd_rel * (sm::length(g) + 1e-300)) << e1 << " " << e2 << " " << i;
                }
                const sm::Vec3 n = sm::implicit_normal(s, p);
                const sm::Vec3 gn = g / sm::length(g);
                for (int i = 0; i < 3; ++i)
                    EXPECT_NEAR(n[i], gn[i], 1e-12);
            }
        }
}

TEST(Superquadric, RadialDistanceIsTheDistanceAlongTheRay)
{
    // Point and surface hit differ by round-off of the gauge, relative to their size.
    constexpr double k_round_off_rel = 1e-12;
    const sm::ShapeDef s = superquadric({1, 2, 3}, 0.3, 2.5);
    for (const sm::Vec3& p : {sm::Vec3{0.1, 0.2, 0.3}, sm::Vec3{3, -1, 2}, sm::Vec3{-1e6, 2e6, 5e5},
                              sm::Vec3{1e-200, 0, -1e-200}}) {
        const double d = sm::radial_distance(s, p);
        const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        const sm::Vec3 u = sm::normalized(p / m); // |p| itself underflows for the 1e-200 point
        const sm::Vec3 hit = u * (m * sm::length(p / m) - d);
        EXPECT_NEAR(sm::contact_measure(s, hit), 0.0, k_round_off_rel * (1.0 + sm::length(p)));
        EXPECT_EQ(d > 0.0, sm::contact_measure(s, p) > 0.0);
    }
    EXPECT_EQ(sm::radial_distance(s, {0, 0, 0}), -3.0);
}

namespace
{

// Brute force over the cube chart of the surface (point = w / gauge(w), w = a ∘ c, c on the unit
// cube): a dense grid, then ten rounds of 21×21 grids each a third the size around the best. Barr's
// (η, ω) cannot serve: at ε = 0.01 no double η reaches the middle of a box's face.
double brute_force_distance(const sm::ShapeDef& s, const sm::Vec3& p)
{
    const auto point = [&](sm::Vec3 c) {
        c = c / std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
        const sm::Vec3 w = sm::hadamard(s.radii, c);
        return w / (sm::contact_measure(s, w) + 1.0);
    };
    constexpr int k_grid = 48;
    double best = INFINITY;
    sm::Vec3 best_c;
    int best_face = 0;
    for (int face = 0; face < 6; ++face)
        for (int i = 0; i <= k_grid; ++i)
            for (int j = 0; j <= k_grid; ++j) {
                sm::Vec3 c;
                const int k = face / 2;
                c[k] = face % 2 ? -1 : 1;
                c[(k + 1) % 3] = -1 + 2.0 * i / k_grid;
                c[(k + 2) % 3] = -1 + 2.0 * j / k_grid;
                const double d = sm::length(p - point(c));
                if (d < best) {
                    best = d;
                    best_c = c;
                    best_face = k;
                }
            }
    double h = 2.0 / k_grid;
    for (int round = 0; round < 10; ++round, h /= 3) {
        const sm::Vec3 centre = best_c;
        for (int i = -10; i <= 10; ++i)
            for (int j = -10; j <= 10; ++j) {
                sm::Vec3 c = centre;
                c[(best_face + 1) % 3] += h * i / 5;
                c[(best_face + 2) % 3] += h * j / 5;
                const double d = sm::length(p - point(c));
                if (d < best) {
                    best = d;
                    best_c = c / std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
                    best_face = std::abs(best_c.z) == 1 ? 2 : (std::abs(best_c.y) == 1 ? 1 : 0);
                }
            }
    }
    return best;
}

} // namespace

TEST(Superquadric, ClosestPointOfSphereAndEllipsoid)
{
    constexpr double k_round_off = 1e-12;
    // Newton stops once t²/(|r| + r·n) ≤ 1e-13 × size (t the tangential part of r = p − x): the
    // distance is then right to that, the point only to t ≤ √(2·|r|·1e-13·size) = √(2·3·2e-13) ≈ 1.1e-6
    // (measured: 6e-10 with the closed-form ellipsoid support, 0 before), the normal to t / radius.
    constexpr double k_point = 1.1e-6, k_normal = k_point / 2.0;
    const sm::ShapeDef sphere = superquadric({2, 2, 2}, 1, 1);
    const sm::SurfaceProjection r = sm::closest_point(sphere, {3, 4, 0});
    EXPECT_TRUE(r.converged);
    EXPECT_NEAR(r.distance, 3.0, k_round_off);
    EXPECT_NEAR(r.point.x, 1.2, k_point);
    EXPECT_NEAR(r.point.y, 1.6, k_point);
    EXPECT_NEAR(r.normal.x, 0.6, k_normal);
    const sm::SurfaceProjection in = sm::closest_point(sphere, {0.3, 0, 0.4});
    EXPECT_NEAR(in.distance, -1.5, k_round_off);
    // Ellipsoid from inside, on its long axis: minimising x² + (z − 2)² with x² = 1 − z²/100 gives
    // z = 2/0.99 on the long side, not the pole 8 away.
    const sm::SurfaceProjection e = sm::closest_point(superquadric({1, 1, 10}, 1, 1), {0, 0, 2});
    const double z = 2.0 / 0.99;
    EXPECT_NEAR(e.distance, -std::sqrt(1.0 - z * z / 100.0 + (z - 2.0) * (z - 2.0)), k_round_off);
    EXPECT_NEAR(std::abs(e.point.z), z, 1e-6); // the distance is stationary there: z only to √round-off
}

TEST(Superquadric, ClosestPointErrorBoundHoldsAgainstBruteForce)
{
    // Both distances are lengths of differences of points computed to a few ulps of the size.
    constexpr double k_round_off_rel = 1e-11;
    // Shapes with ε ≤ 1 are twice differentiable, so Newton converges to its stopping bound of 1e-13 of
    // the size. (For 1 < ε < 2 the curvature is unbounded at the ridges |x|^(2/ε), and ε = 2 has
    // kinks: the bound there is honest but larger.)
    constexpr double k_converged_bound_rel = 1e-12;
    // Concave shapes: best effort; on this grid the found distance is within this fraction of the
    // largest radius of the brute force's (measured worst 0.02 over a 1536-case grid: 0.044).
    constexpr double k_concave_quality_rel = 0.05;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (double e1 : {0.01, 0.5, 1.0, 1.9, 2.0, 3.0, 4.0})
        for (double e2 : {0.01, 0.5, 1.0, 1.9, 2.0, 4.0})
            for (const sm::Vec3& a : {sm::Vec3{1, 1, 1}, sm::Vec3{0.1, 1, 5}}) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                const double size = max_radius(s);
                for (double scale : {0.5, 1.1, 3.0}) {
                    const sm::Vec3 p{unit(rng) * a.x * scale, unit(rng) * a.y * scale,
                                     unit(rng) * a.z * scale};
                    const sm::SurfaceProjection r = sm::closest_point(s, p);
                    const double bf = brute_force_distance(s, p);
                    ASSERT_TRUE(std::isfinite(r.error_bound));
                    EXPECT_NEAR(sm::contact_measure(s, r.point), 0.0, 1e-12);
                    EXPECT_LE(std::abs(r.distance) - bf, r.error_bound + k_round_off_rel * size)
                        << e1 << " " << e2 << " p " << p.x << " " << p.y << " " << p.z;
                    if (e1 <= 1.0 && e2 <= 1.0) {
                        EXPECT_TRUE(r.converged)
                            << e1 << " " << e2 << " p " << p.x << " " << p.y << " " << p.z;
                        EXPECT_LE(r.error_bound, k_converged_bound_rel * size);
                    }
                    if (e1 > 2.0 || e2 > 2.0) {
                        EXPECT_LE(std::abs(r.distance) - bf, k_concave_quality_rel * size);
                    }
                }
            }
}

namespace
{

// A point of one of eight classes for shape s: centre, on an axis, on a coordinate plane, near the
// surface, 10^6 radii away, denormal-small, exactly on the surface, or anywhere in the 2×-box.
sm::Vec3 extreme_point(std::mt19937_64& rng, const sm::ShapeDef& s, int kind)
{
    std::uniform_real_distribution<double> unit(-1, 1);
    const sm::Vec3 u{unit(rng), unit(rng), unit(rng)}, a = s.radii;
    sm::Vec3 p;
    switch (kind) {
    case 0:
        return p;
    case 1:
        p[int(3 * std::abs(u.x)) % 3] = 2 * u.y * a[int(3 * std::abs(u.x)) % 3];
        return p;
    case 2:
        p = sm::hadamard(u, a) * 2.0;
        p[int(3 * std::abs(u.z)) % 3] = 0;
        return p;
    case 3:
        return sm::surface_point(s, u.x * k_pi / 2, u.y * k_pi) * (1.0 + 1e-3 * u.z);
    case 4:
        return sm::hadamard(u, a) * 1e6;
    case 5:
        return u * 1e-300;
    case 6:
        return sm::surface_point(s, u.x * k_pi / 2, u.y * k_pi);
    default:
        return sm::hadamard(u, a) * 2.0;
    }
}

// Evaluations per (ε1, ε2, radii) case so that the extremes grid gets 10^6 in all.
constexpr int k_per_case = 1'000'000 / (8 * 8 * 5) + 1;

} // namespace

TEST(Superquadric, NoNanOrInfFromPointFunctions)
{
    // 10^6 points over ε × aspect × point class, each through every point function.
    std::mt19937_64 rng(3);
    std::uniform_int_distribution<int> kind(0, 7);
    long evaluations = 0;
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps)
            for (const sm::Vec3& a : k_extreme_radii) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                for (int n = 0; n < k_per_case; ++n, ++evaluations) {
                    const sm::Vec3 p = extreme_point(rng, s, kind(rng));
                    ASSERT_TRUE(std::isfinite(sm::inside_outside_log(s, p)));
                    ASSERT_TRUE(std::isfinite(sm::inside_outside(s, p)));
                    ASSERT_TRUE(std::isfinite(sm::contact_measure(s, p)));
                    ASSERT_TRUE(sm::is_finite(sm::contact_measure_gradient(s, p)));
                    ASSERT_NEAR(sm::length(sm::implicit_normal(s, p)), 1.0, 1e-12)
                        << p.x << " " << p.y << " " << p.z;
                    ASSERT_TRUE(std::isfinite(sm::radial_distance(s, p)));
                }
            }
    EXPECT_GE(evaluations, 1'000'000);
}

TEST(Superquadric, NoNanOrInfFromParametricFunctions)
{
    // 10^6 (η, ω) pairs, a share of them exactly at the poles and on the ω = 0 meridian.
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> unit(-1, 1);
    long evaluations = 0;
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps)
            for (const sm::Vec3& a : k_extreme_radii) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                for (int n = 0; n < k_per_case; ++n, ++evaluations) {
                    const double eta = n % 17 == 0 ? k_pi / 2 : unit(rng) * k_pi / 2;
                    const double omega = n % 13 == 0 ? 0.0 : unit(rng) * k_pi;
                    ASSERT_TRUE(sm::is_finite(sm::surface_point(s, eta, omega)));
                    ASSERT_NEAR(sm::length(sm::surface_normal(s, eta, omega)), 1.0, 1e-12);
                }
            }
    EXPECT_GE(evaluations, 1'000'000);
}

TEST(Superquadric, NoNanOrInfFromClosestPoint)
{
    // Every point class on every case of the grid: 2560 projections (~20 µs each).
    std::mt19937_64 rng(6);
    for (double e1 : k_extreme_eps)
        for (double e2 : k_extreme_eps)
            for (const sm::Vec3& a : k_extreme_radii) {
                const sm::ShapeDef s = superquadric(a, e1, e2);
                for (int kind = 0; kind < 8; ++kind) {
                    const sm::SurfaceProjection r = sm::closest_point(s, extreme_point(rng, s, kind));
                    ASSERT_TRUE(sm::is_finite(r.point) && sm::is_finite(r.normal));
                    ASSERT_TRUE(std::isfinite(r.distance) && std::isfinite(r.error_bound));
                }
            }
}
