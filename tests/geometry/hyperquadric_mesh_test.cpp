// Tests for engine/src/geometry/hyperquadric_mesh.cpp.
#include "geometry/hyperquadric_internal.h"
#include "geometry/hyperquadric_solve.h"
#include "geometry/mass_deformed.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace sm = supermodal;

namespace
{

// Mesh vertices are ray roots: a few hundred ulps of the body size at most.
constexpr double k_round_off = 1e-12;

sm::ShapeDef hyperquadric(std::vector<sm::HyperquadricTerm> terms)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.type = sm::ShapeType::Hyperquadric;
    s.terms = std::move(terms);
    return s;
}

/// Three skew terms (the linear image of {Σ|u_i|^γ_i ≤ 1}).
sm::ShapeDef skew(double g1, double g2, double g3)
{
    return hyperquadric({{{2, 0, 0}, 0.1, g1}, {{0.5, 1.5, 0}, -0.2, g2}, {{0.3, 0.2, 1.0}, 0.0, g3}});
}

/// The 4-D hypercube Σ|X_j|^γ ≤ 1 cut by the hyperplane through h·(1, 1, 1, 1)/2 (hyperquadric_test.cpp).
sm::ShapeDef hypercube_slice(double gamma, double h)
{
    const double r2 = std::sqrt(2.0), r6 = std::sqrt(6.0), r12 = std::sqrt(12.0);
    const sm::Vec3 rows[4] = {
        {1 / r2, 1 / r6, 1 / r12}, {-1 / r2, 1 / r6, 1 / r12}, {0, -2 / r6, 1 / r12}, {0, 0, -3 / r12}};
    std::vector<sm::HyperquadricTerm> terms;
    for (const sm::Vec3& row : rows)
        terms.push_back({row, 0.5 * h, gamma});
    return hyperquadric(terms);
}

/// Largest over smallest nearest-neighbour distance among the sample points.
double spacing_ratio(const std::vector<sm::SurfaceSample>& samples)
{
    std::vector<double> nearest(samples.size(), std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < samples.size(); ++i)
        for (size_t j = i + 1; j < samples.size(); ++j) {
            const double d = sm::length(samples[i].point - samples[j].point);
            nearest[i] = std::min(nearest[i], d);
            nearest[j] = std::min(nearest[j], d);
        }
    const auto [lo, hi] = std::minmax_element(nearest.begin(), nearest.end());
    return *hi / *lo;
}

double triangle_area(const sm::TriangleMesh& m, size_t t)
{
    const sm::Vec3& a = m.positions[m.indices[t]];
    return 0.5 * sm::length(sm::cross(m.positions[m.indices[t + 1]] - a, m.positions[m.indices[t + 2]] - a));
}

double enclosed_volume(const sm::TriangleMesh& m)
{
    double v = 0.0;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        v += sm::dot(m.positions[m.indices[t]],
                     sm::cross(m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]]));
    return v / 6.0;
}

/// Every directed edge appears once and its reverse once: closed, consistently oriented, manifold.
::testing::AssertionResult watertight(const sm::TriangleMesh& m)
{
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k)
            ++directed[{m.indices[t + k], m.indices[t + (k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        const auto reverse = directed.find({edge.second, edge.first});
        if (count != 1 || reverse == directed.end() || reverse->second != 1)
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " used " << count;
    }
    for (size_t t = 0; t < m.indices.size(); t += 3)
        if (!(triangle_area(m, t) > 0.0))
            return ::testing::AssertionFailure() << "degenerate triangle " << t / 3;
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(HyperquadricMesh, MeshIsWatertightAndItsVolumeConverges)
{
    sm::ShapeDef bent = skew(4, 4, 4);
    bent.taper = {0.3, -0.2};
    bent.bend = {0.6, 0.4};
    for (const sm::ShapeDef& s : {skew(4, 4, 4), hypercube_slice(10, 0.3), skew(1.5, 3, 20), bent}) {
        // Order 4 is within 1e-7 of the volume for these shapes: far below the mesh errors measured.
        const double volume = sm::quadrature_mass(s, 1.0, 4).properties.volume;
        double previous_error = 3.0;
        for (int resolution : {8, 16, 32, 64}) {
            const sm::TriangleMesh mesh = sm::tessellate_hyperquadric(s, resolution);
            ASSERT_TRUE(watertight(mesh)) << "resolution " << resolution;
            // Euler: V − E + F = 2 for a closed surface of genus 0, E = 3F/2.
            EXPECT_EQ(2 * mesh.positions.size() - mesh.indices.size() / 3, 4u);
            for (size_t i = 0; i < mesh.positions.size(); ++i) {
                ASSERT_NEAR(sm::shape_measure(s, mesh.positions[i]), 0.0, k_round_off);
                ASSERT_NEAR(sm::length(mesh.normals[i]), 1.0, k_round_off);
            }
            const double error = std::abs(enclosed_volume(mesh) / volume - 1);
            // Second order in the cell size: each halving cuts the error by ~4 (measured 2.8 to 3.9;
            // the coarsest grids round their cell counts up, which blurs the first step).
            EXPECT_LT(error, previous_error / 2.5);
            previous_error = error;
        }
        // 64 segments around: measured 0.35% to 0.6% (polyhedral volume of an inscribed mesh).
        EXPECT_LT(previous_error, 1e-2);
    }
}

TEST(HyperquadricMesh, SamplesCarryTheSurfaceArea)
{
    const sm::ShapeDef s = hypercube_slice(6, 0.2);
    const sm::TriangleMesh fine = sm::tessellate_hyperquadric(s, 256);
    double area = 0.0;
    for (size_t t = 0; t < fine.indices.size(); t += 3)
        area += triangle_area(fine, t);
    const double spacing = 0.05;
    const std::vector<sm::SurfaceSample> samples = sm::sample_hyperquadric_surface(s, spacing, 100000);
    double sum = 0.0;
    for (const sm::SurfaceSample& x : samples) {
        sum += x.area;
        ASSERT_NEAR(sm::hyperquadric_measure(s, x.point), 0.0, k_round_off);
        ASSERT_NEAR(sm::length(x.normal), 1.0, k_round_off);
    }
    // The sample areas are a coarser mesh's: second-order error (cell size / radius)² ≈ 1e-3.
    EXPECT_NEAR(sum / area, 1.0, 3e-3);
    // One sample per spacing² of surface, within the rounding of n up to a whole number of cells.
    EXPECT_GT(samples.size(), 0.5 * area / (spacing * spacing));
    EXPECT_LT(samples.size(), 2.0 * area / (spacing * spacing));
    const std::vector<sm::SurfaceSample> capped = sm::sample_hyperquadric_surface(s, spacing, 500);
    EXPECT_LE(capped.size(), 500u);
    EXPECT_GT(capped.size(), 250u);
    double capped_sum = 0.0;
    for (const sm::SurfaceSample& x : capped)
        capped_sum += x.area;
    EXPECT_NEAR(capped_sum / area, 1.0, 3e-2);
    EXPECT_EQ(sm::sample_hyperquadric_surface(s, spacing, 5).size(), 5u);
}

TEST(HyperquadricMesh, SamplesAreEvenlySpaced)
{
    // The lattice follows the body's extents and its warp is chosen per shape: measured ratios 1.2 to 2.2
    // for round, box-like, 1:2:4 and cut-hypercube bodies (docs/geometry.md); the superquadric
    // sampler's Done-when bound is 3.
    constexpr double k_max_spacing_ratio = 2.5;
    for (double g : {2.0, 8.0, 20.0})
        for (const sm::ShapeDef& s :
             {hypercube_slice(g, 0.1),
              hyperquadric({{{1, 0, 0}, 0, g}, {{0, 2, 0}, 0, g}, {{0, 0, 0.5}, 0, g}})})
            EXPECT_LT(spacing_ratio(sm::sample_hyperquadric_surface(s, 0.12, 100000)), k_max_spacing_ratio)
                << g;
}
