// Tests for engine/src/geometry/deform.cpp.
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <random>

namespace sm = supermodal;

namespace
{

// The Done-when: the inverse reproduces points to 1e-9 of the body size where it is invertible.
constexpr double k_round_trip = 1e-9;
// Points whose Jacobian factors are all at least this far from zero count as "invertible" here: the
// inverse then amplifies round-off (1e-16) by at most 1e3, far inside k_round_trip.
constexpr double k_well_conditioned = 1e-3;
// Central differences with h = 1e-5 of the body: truncation h²·|J''| ≈ 1e-10, round-off 1e-16/h ≈ 1e-11.
constexpr double k_fd_step = 1e-5;
constexpr double k_fd_tolerance = 1e-8;
// Forward images, normals and closed forms evaluate a handful of operations: a few ulps.
constexpr double k_round_off = 1e-12;

sm::ShapeDef shape(double kx, double ky, double curvature, double angle, sm::Vec3 radii = {0.4, 0.6, 1.0})
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = radii;
    s.epsilon1 = 0.7;
    s.epsilon2 = 1.3;
    s.taper = {kx, ky};
    s.bend = {curvature, angle};
    return s;
}

/// The smallest of the taper factors and the bend's σ at undeformed p, and how close |kz| is to π.
double min_factor(const sm::ShapeDef& s, const sm::Vec3& p)
{
    const double fx = 1 + s.taper.kx * p.z / s.radii.z, fy = 1 + s.taper.ky * p.z / s.radii.z;
    const double u = std::cos(s.bend.angle) * fx * p.x + std::sin(s.bend.angle) * fy * p.y;
    const double k = s.bend.curvature;
    return std::min({fx, fy, 1 - k * u, std::numbers::pi - std::abs(k * p.z)});
}

double max_abs(const sm::Vec3& v)
{
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

/// A grid of taper and bend values (curvature times a3 up to 2.5 rad) and points in and near the body.
template <class F> void for_each_case(F&& f)
{
    const double tapers[] = {-1.0, -0.5, 0.0, 0.4, 1.0};
    const double bends[] = {0.0, 0.3, 1.0, 2.5};
    const double angles[] = {0.0, 0.7, std::numbers::pi / 2, 2.5};
    const double grid[] = {-1.3, -0.8, -0.2, 0.0, 0.5, 1.0, 1.3};
    for (double kx : tapers)
        for (double ky : {-0.3, 0.8})
            for (double k : bends)
                for (double angle : angles) {
                    const sm::ShapeDef s = shape(kx, ky, k, angle);
                    for (double x : grid)
                        for (double y : grid)
                            for (double z : grid)
                                f(s, sm::Vec3{x * s.radii.x, y * s.radii.y, z * s.radii.z});
                }
}

} // namespace

TEST(Deform, UndeformedShapeIsTheIdentity)
{
    const sm::ShapeDef s = shape(0, 0, 0, 0.3);
    const sm::Vec3 p{0.1, -0.2, 0.3};
    EXPECT_FALSE(sm::is_deformed(s));
    EXPECT_EQ(sm::deform_point(s, p), p);
    const sm::UndeformResult r = sm::undeform_point(s, p);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.point, p);
    EXPECT_TRUE(sm::is_deformed(shape(0.1, 0, 0, 0)));
    EXPECT_TRUE(sm::is_deformed(shape(0, 0, 0.5, 0)));
}

TEST(Deform, TaperFollowsBarr)
{
    const sm::ShapeDef s = shape(0.5, -0.25, 0, 0);
    const sm::Vec3 p{0.2, 0.3, 0.8};
    const sm::Vec3 q = sm::deform_point(s, p);
    EXPECT_NEAR(q.x, (1 + 0.5 * 0.8 / 1.0) * 0.2, k_round_off);
    EXPECT_NEAR(q.y, (1 - 0.25 * 0.8 / 1.0) * 0.3, k_round_off);
    EXPECT_EQ(q.z, 0.8);
}

TEST(Deform, BendMapsTheAxisOntoAnArcOfTheSameLength)
{
    // Solina–Bajcsy: the z axis becomes a circle of radius 1/k about (cos α, sin α, 0)/k, arc length z.
    const double k = 0.8, angle = 0.6;
    const sm::ShapeDef s = shape(0, 0, k, angle);
    const sm::Vec3 centre{std::cos(angle) / k, std::sin(angle) / k, 0};
    for (double z : {-1.0, -0.3, 0.2, 1.0}) {
        const sm::Vec3 q = sm::deform_point(s, {0, 0, z});
        EXPECT_NEAR(sm::length(q - centre), 1 / k, k_round_off);
        EXPECT_NEAR(std::atan2(q.z, -sm::dot(q - centre, centre) * k) / k, z, k_round_off);
    }
}

TEST(Deform, JacobianMatchesFiniteDifferences)
{
    for_each_case([](const sm::ShapeDef& s, const sm::Vec3& p) {
        const sm::Mat3 j = sm::deform_jacobian(s, p);
        for (int c = 0; c < 3; ++c) {
            sm::Vec3 h{};
            h[c] = k_fd_step * s.radii.z;
            const sm::Vec3 fd = (sm::deform_point(s, p + h) - sm::deform_point(s, p - h)) / (2 * h[c]);
            ASSERT_LT(max_abs(fd - j.col(c)), k_fd_tolerance) << "column " << c;
        }
    });
}

TEST(Deform, NormalIsTheInverseTransposeOfTheJacobian)
{
    for_each_case([](const sm::ShapeDef& s, const sm::Vec3& p) {
        if (min_factor(s, p) < k_well_conditioned)
            return;
        const sm::Vec3 n = sm::normalized(sm::Vec3{0.3, -0.5, 0.8} + p);
        const sm::Vec3 t1 = sm::normalized(sm::cross(n, {1, 0, 0})), t2 = sm::cross(n, t1);
        const sm::Mat3 j = sm::deform_jacobian(s, p);
        const sm::Vec3 m = sm::deform_normal(s, p, n);
        // Tangents map to tangents (J t ⟂ n'), and n' still points out (same side as J n).
        ASSERT_NEAR(sm::length(m), 1.0, k_round_off);
        ASSERT_NEAR(sm::dot(j * t1, m), 0.0, k_round_off * 10);
        ASSERT_NEAR(sm::dot(j * t2, m), 0.0, k_round_off * 10);
        ASSERT_GT(sm::dot(j * n, m), 0.0);
    });
}

TEST(Deform, InverseReproducesPointsWhereInvertible)
{
    int checked = 0;
    double worst = 0.0;
    for_each_case([&](const sm::ShapeDef& s, const sm::Vec3& p) {
        if (min_factor(s, p) < k_well_conditioned)
            return;
        const sm::UndeformResult r = sm::undeform_point(s, sm::deform_point(s, p));
        ASSERT_TRUE(r.converged);
        worst = std::max(worst, sm::length(r.point - p) / s.radii.z);
        ASSERT_LT(r.iterations, 4) << "the closed-form start should leave Newton almost nothing to do";
        ++checked;
    });
    EXPECT_LT(worst, k_round_trip);
    EXPECT_GT(checked, 10000);
    RecordProperty("worst_round_trip_of_size", testing::PrintToString(worst));
}

TEST(Deform, InverseReportsFailureWhereNotInvertible)
{
    // Points whose every preimage has a zero or negative Jacobian factor.
    const sm::ShapeDef bent = shape(0, 0, 0.8, 0.6);
    const sm::Vec3 centre{std::cos(0.6) / 0.8, std::sin(0.6) / 0.8, 0};
    EXPECT_FALSE(sm::undeform_point(bent, centre).converged) << "centre of curvature: σ = 0";
    EXPECT_FALSE(sm::undeform_point(bent, 3.0 * centre).converged) << "behind it: a bend of ±π";
    const sm::ShapeDef tapered = shape(1.0, 0.5, 0, 0);
    EXPECT_FALSE(sm::undeform_point(tapered, {0.1, 0.1, -1.5}).converged) << "taper factor 1 − 1.5 < 0";
    EXPECT_FALSE(sm::undeform_point(tapered, {0.0, 0.0, -1.0}).converged) << "taper factor exactly 0";
    // Points from a folded part of the body (a factor < 0): either reported, or a genuine preimage on the
    // one-to-one branch; never garbage.
    int folded = 0;
    for_each_case([&](const sm::ShapeDef& s, const sm::Vec3& p) {
        if (min_factor(s, p) > 0.0)
            return;
        ++folded;
        const sm::Vec3 q = sm::deform_point(s, p);
        const sm::UndeformResult r = sm::undeform_point(s, q);
        ASSERT_TRUE(sm::is_finite(r.point));
        if (r.converged) {
            ASSERT_GT(min_factor(s, r.point), 0.0);
            ASSERT_LT(sm::length(sm::deform_point(s, r.point) - q),
                      k_round_trip * std::max(1.0, sm::length(q)));
        }
    });
    EXPECT_GT(folded, 100);
}

TEST(Deform, ShapeMeasureUsesTheInverseMap)
{
    const sm::ShapeDef s = shape(0.6, -0.4, 0.9, 0.4);
    for (double eta : {-1.2, -0.4, 0.0, 0.9})
        for (double omega : {-2.5, -0.3, 0.8, 2.0}) {
            const sm::Vec3 p = sm::surface_point(s, eta, omega);
            EXPECT_NEAR(sm::shape_measure(s, sm::deform_point(s, p)), 0.0, k_round_trip);
            EXPECT_LT(sm::shape_measure(s, sm::deform_point(s, 0.7 * p)), 0.0);
            EXPECT_GT(sm::shape_measure(s, sm::deform_point(s, 1.3 * p)), 0.0);
        }
    // Where the inverse fails the measure says "outside".
    EXPECT_GT(sm::shape_measure(shape(0, 0, 0.8, 0), {1 / 0.8, 0, 0}), 0.0);
}

TEST(Deform, RandomInputsGiveFiniteResults)
{
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    constexpr int k_samples = 20000;
    for (int i = 0; i < k_samples; ++i) {
        const sm::ShapeDef s =
            shape(unit(rng), unit(rng), 2.5 + 2.5 * unit(rng), 4 * unit(rng),
                  {0.01 + std::abs(unit(rng)), 0.01 + std::abs(unit(rng)), 0.01 + std::abs(unit(rng))});
        // Points from the centre out to 10^6 radii, on a log scale.
        const double scale = std::pow(10.0, 6.5 + 6.5 * unit(rng)) * s.radii.z;
        const sm::Vec3 p{scale * unit(rng), scale * unit(rng), (i % 7 == 0 ? 0.0 : scale * unit(rng))};
        ASSERT_TRUE(sm::is_finite(sm::deform_point(s, p)));
        const sm::Mat3 j = sm::deform_jacobian(s, p);
        ASSERT_TRUE(sm::is_finite(j.row(0)) && sm::is_finite(j.row(1)) && sm::is_finite(j.row(2)));
        ASSERT_TRUE(sm::is_finite(sm::deform_normal(s, p, {unit(rng), unit(rng), unit(rng)})));
        ASSERT_TRUE(sm::is_finite(sm::undeform_point(s, p).point));
        ASSERT_TRUE(std::isfinite(sm::shape_measure(s, p)));
    }
}
