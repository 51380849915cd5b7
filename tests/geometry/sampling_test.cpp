// Tests for engine/src/geometry/sampling.cpp.
#include "geometry/hyperquadric_internal.h"
#include "geometry/sampling.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"
#include "support/shapes.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace sm = supermodal;

namespace
{

using supermodal::test::superquadric;

double total_area(const std::vector<sm::SurfaceSample>& samples)
{
    double a = 0.0;
    for (const sm::SurfaceSample& s : samples)
        a += s.area;
    return a;
}

// Spacing that gives about `count` samples: the count grows like area / spacing².
double spacing_for(const sm::ShapeDef& s, int count)
{
    return std::sqrt(total_area(sm::sample_surface(s, 1e9, 2)) / count);
}

// Reference surface area, independent of the code under test: |∂p/∂η × ∂p/∂ω| in Barr's angles over one
// octant, times 8. Each half of [0, π/2] is substituted as (distance to its end) = (π/4)·e^(−v), which
// turns the ε → 0 endpoint layers (where Barr's angles put whole faces) into smooth functions of v on a
// scale 1/ε, integrated by 8-point Gauss–Legendre panels. Everything is formed in logarithms, so no
// power underflows. Halving every panel changes the result by < 1e-12 relative over ε ∈ [0.01, 4].
struct Node {
    double log_sin, log_cos, log_jacobian, weight;
};

std::vector<Node> reference_nodes(double epsilon_min)
{
    static constexpr double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                     0.9602898564975363};
    static constexpr double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                     0.1012285362903763};
    const double v_max = 60.0 / epsilon_min + 60.0; // there u^ε < e^(−60): nothing left to integrate
    std::vector<Node> nodes;
    for (double v0 = 0.0; v0 < v_max;) {
        const double v1 = std::min(v_max, v0 + std::max(0.25, 0.2 * v0));
        for (int i = 0; i < 8; ++i) {
            const double v = 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * (i < 4 ? -gx[i] : gx[i - 4]);
            const double w = 0.5 * (v1 - v0) * gw[i < 4 ? i : i - 4];
            const double log_u = std::log(std::numbers::pi / 4) - v, u = std::exp(log_u);
            const double ls = u < 1e-8 ? log_u : std::log(std::sin(u));
            const double lc = u < 1e-8 ? -0.5 * u * u : std::log(std::cos(u));
            nodes.push_back({ls, lc, log_u, w}); // angle = u
            nodes.push_back({lc, ls, log_u, w}); // angle = π/2 − u
        }
        v0 = v1;
    }
    return nodes;
}

double reference_area(const sm::ShapeDef& s)
{
    const double e1 = s.epsilon1, e2 = s.epsilon2;
    const sm::Vec3 a = s.radii;
    const std::vector<Node> n = reference_nodes(std::min(e1, e2));
    // |cross| = C1·hypot(a3·S1'·|h'|, C1'·(h × h')), with C1 = cos^ε1 η, h(ω) the horizontal curve.
    std::vector<double> alpha(n.size()), gamma(n.size()), beta(n.size()), delta(n.size());
    for (size_t i = 0; i < n.size(); ++i) {
        const Node& q = n[i];
        const double log_c1 = e1 * q.log_cos;
        alpha[i] = std::exp(log_c1 + std::log(a.z * e1) + (e1 - 1) * q.log_sin + q.log_cos + q.log_jacobian);
        gamma[i] = std::exp(log_c1 + std::log(e1) + (e1 - 1) * q.log_cos + q.log_sin + q.log_jacobian);
        const double l1 = std::log(a.x * e2) + (e2 - 1) * q.log_cos + q.log_sin + q.log_jacobian;
        const double l2 = std::log(a.y * e2) + (e2 - 1) * q.log_sin + q.log_cos + q.log_jacobian;
        beta[i] = std::hypot(std::exp(l1), std::exp(l2));
        delta[i] = std::exp(std::log(a.x * a.y * e2) + (e2 - 1) * (q.log_cos + q.log_sin) + q.log_jacobian);
    }
    double sum = 0.0;
    for (size_t i = 0; i < n.size(); ++i) {
        double row = 0.0;
        for (size_t j = 0; j < n.size(); ++j)
            row += n[j].weight * std::hypot(alpha[i] * beta[j], gamma[i] * delta[j]);
        sum += n[i].weight * row;
    }
    return 8.0 * sum;
}

double nearest_neighbour_ratio(const std::vector<sm::SurfaceSample>& v)
{
    double lo = 1e300, hi = 0.0;
    for (size_t i = 0; i < v.size(); ++i) {
        double best = 1e300;
        for (size_t j = 0; j < v.size(); ++j) {
            const sm::Vec3 d = v[i].point - v[j].point;
            if (i != j)
                best = std::min(best, sm::dot(d, d));
        }
        lo = std::min(lo, best);
        hi = std::max(hi, best);
    }
    return std::sqrt(hi / lo);
}

// Barr's inside-outside function, written out here so the test does not lean on superquadric.cpp.
double barr_inside_outside(const sm::ShapeDef& s, const sm::Vec3& p)
{
    const double e1 = s.epsilon1, e2 = s.epsilon2;
    const double xy =
        std::pow(std::abs(p.x / s.radii.x), 2 / e2) + std::pow(std::abs(p.y / s.radii.y), 2 / e2);
    return std::pow(xy, e2 / e1) + std::pow(std::abs(p.z / s.radii.z), 2 / e1);
}

const double k_grid[] = {0.01, 0.1, 0.5, 1.0, 2.0, 3.0, 4.0};

} // namespace

TEST(Sampling, SphereAreasSumToFourPiRSquared)
{
    // The polyline tables (512 segments a quadrant) carry an O(h²) area error of 3.1e-6 for the sphere,
    // whatever the spacing, since the areas integrate the tables exactly.
    constexpr double k_polyline_rel = 1e-5;
    const sm::ShapeDef s = superquadric({0.7, 0.7, 0.7}, 1, 1);
    for (double spacing : {0.5, 0.1, 0.02}) {
        const auto v = sm::sample_surface(s, spacing);
        EXPECT_NEAR(total_area(v) / (4 * std::numbers::pi * 0.49), 1.0, k_polyline_rel) << spacing;
    }
}

TEST(Sampling, AreasSumToConvergedSurfaceArea)
{
    // Measured: ≤ 3e-5 for ε ≥ 0.05; 2.4e-4 at ε = 0.01, where 512 segments put only a dozen across the
    // corner (its polyline arc is 1.2e-4 short per curve), and 1.7e-4 on the ε = 0.01 needle.
    constexpr double k_area_rel = 4e-4;
    struct Case {
        sm::Vec3 radii;
        double e1, e2;
    };
    const Case cases[] = {{{1, 2, 3}, 0.01, 0.01},    {{1, 2, 3}, 0.01, 1.0},    {{1, 2, 3}, 0.1, 0.5},
                          {{1, 2, 3}, 1.0, 1.0},      {{1, 2, 3}, 2.0, 0.1},     {{1, 2, 3}, 4.0, 4.0},
                          {{1, 1, 1000}, 0.01, 4.0},  {{1, 1, 1000}, 4.0, 0.01}, {{1000, 1000, 1}, 0.5, 0.01},
                          {{1000, 1000, 1}, 3.0, 2.0}};
    for (const Case& c : cases) {
        const sm::ShapeDef s = superquadric(c.radii, c.e1, c.e2);
        const double area = total_area(sm::sample_surface(s, spacing_for(s, 2000)));
        EXPECT_NEAR(area / reference_area(s), 1.0, k_area_rel) << c.radii.z << " " << c.e1 << " " << c.e2;
    }
}

TEST(Sampling, NearestNeighbourSpacingRatioBelowThree)
{
    // The criterion for ε in [0.1, 2]. Measured worst over this grid: 2.2 (the 5:5:1 double
    // cone, ε1 = 2, whose equator is a 23° wedge).
    constexpr double k_max_ratio = 3.0;
    const double eps[] = {0.1, 0.3, 1.0, 2.0};
    double worst = 0.0;
    for (const sm::Vec3& r : {sm::Vec3{1, 1, 1}, sm::Vec3{1, 2, 3}, sm::Vec3{5, 5, 1}})
        for (double e1 : eps)
            for (double e2 : eps) {
                const sm::ShapeDef s = superquadric(r, e1, e2);
                const double ratio = nearest_neighbour_ratio(sm::sample_surface(s, spacing_for(s, 600)));
                EXPECT_LT(ratio, k_max_ratio) << r.x << " " << r.z << " " << e1 << " " << e2;
                worst = std::max(worst, ratio);
            }
    RecordProperty("worst_ratio", std::to_string(worst));
}

TEST(Sampling, NoHolesOnElongatedFaces)
{
    // Rings are scaled copies of the loop, so on the top of a 1 × 4 box they run 2.5 spacings apart
    // next to the short sides unless the wide bands split into sub-rows. Covering radius (largest
    // distance from a surface point to its nearest sample) over a 6× finer sample set: measured 0.82
    // spacing with sub-rows, 1.26 without; 0.70 for the sphere.
    constexpr double k_max_cover = 1.0;
    for (const sm::Vec3& r : {sm::Vec3{1, 4, 1}, sm::Vec3{1, 4, 0.5}}) {
        const sm::ShapeDef s = superquadric(r, 0.1, 0.1);
        const double spacing = spacing_for(s, 800);
        const auto v = sm::sample_surface(s, spacing);
        double cover = 0.0;
        for (const sm::SurfaceSample& f : sm::sample_surface(s, spacing / 6)) {
            double nearest = 1e300;
            for (const sm::SurfaceSample& x : v)
                nearest = std::min(nearest, sm::dot(f.point - x.point, f.point - x.point));
            cover = std::max(cover, nearest);
        }
        EXPECT_LT(std::sqrt(cover), k_max_cover * spacing) << r.z;
    }
}

TEST(Sampling, CountFollowsAreaOverSpacingSquared)
{
    // Ring and per-ring counts round to whole (even) numbers, which moves the count by a few per cent at
    // a few hundred samples (measured 2.3 % at 642) and averages out as the count grows.
    constexpr double k_count_rel = 0.05;
    const sm::ShapeDef s = superquadric({1, 2, 3}, 0.3, 1.5);
    const double area = reference_area(s);
    for (double spacing : {0.3, 0.1, 0.03}) {
        const auto v = sm::sample_surface(s, spacing);
        EXPECT_NEAR(double(v.size()) * spacing * spacing / area, 1.0, k_count_rel) << spacing;
    }
}

TEST(Sampling, SamplesLieOnTheSurfaceWithItsNormal)
{
    // Points come from the log-space superellipses, so F = 1 to round-off. The gradient's powers (up to
    // 2/ε ≈ 7) amplify the round-off of both normals, hence a looser bound for them.
    constexpr double k_round_off = 1e-12;
    constexpr double k_normal_round_off = 1e-9;
    for (double e1 : {0.3, 1.0, 2.5})
        for (double e2 : {0.3, 1.0, 2.5}) {
            const sm::ShapeDef s = superquadric({1, 2, 3}, e1, e2);
            for (const sm::SurfaceSample& x : sm::sample_surface(s, 0.3)) {
                EXPECT_NEAR(barr_inside_outside(s, x.point), 1.0, k_round_off);
                const sm::Vec3 q =
                    sm::Vec3{x.point.x / s.radii.x, x.point.y / s.radii.y, x.point.z / s.radii.z};
                if (std::abs(q.x) < 1e-3 || std::abs(q.y) < 1e-3 || std::abs(q.z) < 1e-3)
                    continue; // the power form below is singular on the axes (ε > 2) or underflows
                const double g = std::pow(std::abs(q.x), 2 / e2) + std::pow(std::abs(q.y), 2 / e2);
                const double common = (2 / e1) * std::pow(g, e2 / e1 - 1);
                const sm::Vec3 grad{
                    common * std::pow(std::abs(q.x), 2 / e2 - 1) * std::copysign(1.0, q.x) / s.radii.x,
                    common * std::pow(std::abs(q.y), 2 / e2 - 1) * std::copysign(1.0, q.y) / s.radii.y,
                    (2 / e1) * std::pow(std::abs(q.z), 2 / e1 - 1) * std::copysign(1.0, q.z) / s.radii.z};
                EXPECT_NEAR(sm::length(sm::normalized(grad) - x.normal), 0.0, k_normal_round_off);
            }
        }
}

TEST(Sampling, MatchesBarrParametricForm)
{
    // tan φ = tan^ε θ maps our polar angle to Barr's; where Barr's form is well conditioned (moderate ε,
    // away from the poles) both must give the same point and normal to round-off.
    constexpr double k_round_off = 1e-9;
    for (double e1 : {0.5, 1.0, 3.0})
        for (double e2 : {0.5, 1.0, 3.0}) {
            const sm::ShapeDef s = superquadric({1, 2, 3}, e1, e2);
            const sm::SphericalProduct sp = sm::make_spherical_product(s, sm::k_quadrant_segments);
            for (double phi_m : {0.1, 0.7, 1.3})
                for (double phi_h : {0.2, 0.8, 1.4}) {
                    const double eta = std::atan(std::pow(std::tan(phi_m), 1 / e1));
                    const double omega = std::atan(std::pow(std::tan(phi_h), 1 / e2));
                    const sm::SurfacePoint got = sm::spherical_product_point(
                        sp, sm::ring_point(sp, {phi_m, 1.0}), sm::LoopPoint{phi_h, 1.0, 1.0});
                    const sm::Vec3 p = sm::surface_point(s, eta, omega),
                                   n = sm::surface_normal(s, eta, omega);
                    EXPECT_NEAR(sm::length(got.point - p), 0.0, k_round_off);
                    EXPECT_NEAR(sm::length(got.normal - n), 0.0, k_round_off);
                }
        }
}

TEST(Sampling, DivergenceTheoremRecoversVolume)
{
    // ∮ p·n dA = 3V checks areas and normals together against the Beta-function volume. Each sample
    // stands for its patch with one point, a midpoint rule: error O(spacing²) on smooth surfaces. At
    // ε = 0.01 the samples next to an edge also stand for half of its rounded strip (radius ~0.5 % of
    // the size) with the face normal, which caps the accuracy near 4e-3 until the spacing resolves the
    // rounding. Measured worst over this grid at 6000 samples: 4.2e-3 (the ε = 0.01 box).
    constexpr double k_midpoint_rel = 6e-3;
    for (double e1 : k_grid)
        for (double e2 : {0.01, 0.5, 1.0, 2.0}) {
            const sm::ShapeDef s = superquadric({1, 2, 3}, e1, e2);
            double three_v = 0.0;
            for (const sm::SurfaceSample& x : sm::sample_surface(s, spacing_for(s, 6000)))
                three_v += sm::dot(x.point, x.normal) * x.area;
            EXPECT_NEAR(three_v / (3 * sm::superquadric_volume(s)), 1.0, k_midpoint_rel) << e1 << " " << e2;
        }
}

TEST(Sampling, DivergenceTheoremConvergesAtCusps)
{
    // For ε2 > 2 the normal turns through 90° near each cusp, so the midpoint error is large at coarse
    // spacing (measured 2.7e-2 at 1000 samples for ε = (1, 4)) but falls like spacing²: 16× more samples
    // must cut it at least 8× (measured 22× for ε = (1, 4), 13× for (4, 4)).
    constexpr double k_min_gain = 8.0;
    for (auto [e1, e2] : {std::pair{1.0, 4.0}, {4.0, 4.0}}) {
        const sm::ShapeDef s = superquadric({1, 2, 3}, e1, e2);
        double error[2];
        for (int i = 0; i < 2; ++i) {
            double three_v = 0.0;
            for (const sm::SurfaceSample& x : sm::sample_surface(s, spacing_for(s, i == 0 ? 1000 : 16000)))
                three_v += sm::dot(x.point, x.normal) * x.area;
            error[i] = std::abs(three_v / (3 * sm::superquadric_volume(s)) - 1.0);
        }
        EXPECT_GT(error[0] / error[1], k_min_gain) << e1 << " " << e2;
    }
}

TEST(Sampling, SymmetricUnderHalfTurns)
{
    // Every sample's images under half-turns about x, y and z are samples with the same area, so a
    // uniform pressure on any face gives no torque.
    constexpr double k_match = 1e-9;
    const sm::ShapeDef s = superquadric({1, 2, 3}, 0.2, 1.7);
    const auto v = sm::sample_surface(s, 0.4);
    for (const sm::SurfaceSample& x : v)
        for (const sm::Vec3 flip : {sm::Vec3{1, -1, -1}, sm::Vec3{-1, 1, -1}, sm::Vec3{-1, -1, 1}}) {
            const sm::Vec3 image = sm::hadamard(x.point, flip);
            const auto it = std::min_element(v.begin(), v.end(), [&](const auto& a, const auto& b) {
                return sm::length(a.point - image) < sm::length(b.point - image);
            });
            EXPECT_NEAR(sm::length(it->point - image), 0.0, k_match);
            EXPECT_NEAR(it->area, x.area, k_match * x.area);
        }
}

TEST(Sampling, ExtremesStayFiniteAndRespectMaxCount)
{
    // The area sum does not depend on the layout beyond the midpoint split of table segments at band
    // edges (second order in the table step), so every layout of one shape agrees to about 1e-6.
    constexpr double k_layout_rel = 1e-5;
    // Normals are divided by their own length: unit to round-off.
    constexpr double k_unit = 1e-12;
    const double nan = std::numeric_limits<double>::quiet_NaN(),
                 inf = std::numeric_limits<double>::infinity();
    for (const sm::Vec3& r : {sm::Vec3{1, 1, 1}, sm::Vec3{1, 1, 1000}, sm::Vec3{1000, 1, 1}})
        for (double e1 : {0.01, 4.0})
            for (double e2 : {0.01, 4.0}) {
                const sm::ShapeDef s = superquadric(r, e1, e2);
                const double area = total_area(sm::sample_surface(s, 0.0, 3000));
                for (double spacing : {-1.0, nan, inf, 1e-12})
                    for (int max_count : {0, 7, 3000}) {
                        const auto v = sm::sample_surface(s, spacing, max_count);
                        ASSERT_GE(v.size(), 1u);
                        EXPECT_LE(int(v.size()), std::max(1, max_count));
                        for (const sm::SurfaceSample& x : v) {
                            ASSERT_TRUE(sm::is_finite(x.point) && sm::is_finite(x.normal));
                            EXPECT_NEAR(sm::length(x.normal), 1.0, k_unit);
                            EXPECT_GE(x.area, 0.0);
                        }
                        EXPECT_NEAR(total_area(v) / area, 1.0, k_layout_rel);
                    }
            }
}

TEST(Sampling, TaperedAndBentAreasFollowTheDeformation)
{
    // Taper scales x, y by (1 + k·z/a3) and the bend by σ = 1 − k·u, so the deformed volume is
    // V + kx·ky/a3²·∫z² dV (odd moments vanish). Nanson-scaled areas with mapped normals must give it
    // through ∮ p·n dA = 3V, to midpoint-rule accuracy (measured 1e-7 here: a smooth shape, 3446 samples;
    // the bound is the undeformed ellipsoid's 1e-4 at this count with margin).
    constexpr double k_midpoint_rel = 5e-4;
    sm::ShapeDef s = superquadric({1, 1.5, 2}, 0.5, 1.0);
    s.taper = {0.4, -0.3};
    s.bend = {0.2, 0.5};
    const sm::MassProperties mp = sm::compute_mass_properties(superquadric(s.radii, 0.5, 1.0), 1.0);
    const double szz = 0.5 * (mp.inertia_diagonal.x + mp.inertia_diagonal.y - mp.inertia_diagonal.z);
    const double volume = mp.volume + s.taper.kx * s.taper.ky * szz / (s.radii.z * s.radii.z);
    const auto v = sm::sample_surface(s, 0.1);
    double three_v = 0.0;
    for (const sm::SurfaceSample& x : v) {
        ASSERT_TRUE(sm::is_finite(x.point) && sm::is_finite(x.normal) && std::isfinite(x.area));
        three_v += sm::dot(x.point, x.normal) * x.area;
    }
    EXPECT_NEAR(three_v / (3 * volume), 1.0, k_midpoint_rel);
}

TEST(Sampling, PlaneHasNoSamplesAndHyperquadricDelegates)
{
    sm::ShapeDef plane = sm::default_shape_def();
    plane.type = sm::ShapeType::Plane;
    EXPECT_TRUE(sm::sample_surface(plane, 0.1).empty());
    sm::ShapeDef h = sm::default_shape_def();
    h.type = sm::ShapeType::Hyperquadric;
    h.terms = {{{2, 0, 0}, 0, 4}, {{0, 2, 0}, 0, 4}, {{0, 0, 2}, 0, 4}};
    EXPECT_EQ(sm::sample_surface(h, 0.1, 500).size(), sm::sample_hyperquadric_surface(h, 0.1, 500).size());
}
