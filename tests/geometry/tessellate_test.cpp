// Tests for engine/src/geometry/tessellate.cpp.
#include "supermodal/geometry.h"
#include "supermodal/shape.h"
#include "support/shapes.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <string>
#include <utility>
#include <vector>

namespace sm = supermodal;

namespace
{

using supermodal::test::superquadric;

// Every directed edge appears once and its reverse once: each edge has exactly two triangles and they
// agree on orientation (a closed, consistently oriented 2-manifold). Also checks index range.
::testing::AssertionResult watertight(const sm::TriangleMesh& m)
{
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = m.indices[t + k], b = m.indices[t + (k + 1) % 3];
            if (a >= m.positions.size() || b >= m.positions.size() || a == b)
                return ::testing::AssertionFailure() << "bad index in triangle " << t / 3;
            edges.emplace_back(a, b);
        }
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end())
        return ::testing::AssertionFailure() << "a directed edge is used twice";
    for (const auto& [a, b] : edges)
        if (!std::binary_search(edges.begin(), edges.end(), std::pair{b, a}))
            return ::testing::AssertionFailure() << "edge " << a << "-" << b << " has one triangle";
    return ::testing::AssertionSuccess();
}

// Triangle height over longest edge, 2A/L²: 0 for a collapsed triangle, 0.87 for an equilateral one.
double worst_shape_quality(const sm::TriangleMesh& m)
{
    double worst = 1.0;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const sm::Vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                       c = m.positions[m.indices[t + 2]];
        const double twice_area = sm::length(sm::cross(b - a, c - a));
        const double longest =
            std::max({sm::dot(b - a, b - a), sm::dot(c - b, c - b), sm::dot(a - c, a - c)});
        worst = std::min(worst, twice_area / longest);
    }
    return worst;
}

double barr_inside_outside(const sm::ShapeDef& s, const sm::Vec3& p)
{
    const double e1 = s.epsilon1, e2 = s.epsilon2;
    const double xy =
        std::pow(std::abs(p.x / s.radii.x), 2 / e2) + std::pow(std::abs(p.y / s.radii.y), 2 / e2);
    return std::pow(xy, e2 / e1) + std::pow(std::abs(p.z / s.radii.z), 2 / e1);
}

double volume_error(const sm::ShapeDef& s, int resolution)
{
    return sm::mesh_volume(sm::tessellate(s, resolution)) / sm::superquadric_volume(s) - 1.0;
}

} // namespace

TEST(Tessellate, WatertightWithoutDegenerateTrianglesAcrossTheGrid)
{
    // A triangle whose height is below 1e-9 of its longest edge is flat in double precision for any
    // downstream use. The worst measured is 1.4e-7: the ε1 = 4 spike tip of a 1:1:1000 needle at
    // resolution 100, where the first ring's radius is ~(ring step)² (a cusp).
    constexpr double k_min_quality = 1e-9;
    // Vertex normals are divided by their own length: unit to round-off.
    constexpr double k_unit = 1e-12;
    const double eps[] = {0.01, 0.1, 0.5, 1.0, 2.0, 3.0, 4.0};
    for (const sm::Vec3& r :
         {sm::Vec3{1, 1, 1}, sm::Vec3{1, 2, 3}, sm::Vec3{1000, 1, 1}, sm::Vec3{1, 1, 1000}})
        for (int resolution : {4, 24})
            for (double e1 : eps)
                for (double e2 : eps) {
                    const sm::TriangleMesh m = sm::tessellate(superquadric(r, e1, e2), resolution);
                    ASSERT_TRUE(watertight(m))
                        << r.x << " " << r.z << " " << e1 << " " << e2 << " " << resolution;
                    EXPECT_GT(worst_shape_quality(m), k_min_quality)
                        << r.x << " " << r.z << " " << e1 << " " << e2;
                    EXPECT_GT(sm::mesh_volume(m), 0.0); // outward: counter-clockwise from outside
                    ASSERT_EQ(m.normals.size(), m.positions.size());
                    for (size_t i = 0; i < m.positions.size(); ++i) {
                        ASSERT_TRUE(sm::is_finite(m.positions[i]) && sm::is_finite(m.normals[i]));
                        EXPECT_NEAR(sm::length(m.normals[i]), 1.0, k_unit);
                    }
                }
}

TEST(Tessellate, MeshVolumeConvergesToClosedForm)
{
    // Error falls like resolution⁻² for smooth shapes (×16 from 64 to 256: measured 4.0e-3 → 2.5e-4 for
    // the sphere) and exactly 0 for the ε = 2 octahedron, whose faces are planar and whose vertices are
    // always mesh vertices. Bounds at resolution 256 with ~1.5× margin over the measured errors; ε ≥ 3
    // converges later because the cusps' thin flanks need fine rings (measured 6e-3 at ε = 4).
    // 4× the resolution must cut the error at least 3× (O(h^0.8)); the slowest measured is the ε = 0.01
    // box at 5.5× (its rounded edges are resolved only gradually). Below k_exact the error is round-off.
    constexpr double k_min_gain = 3.0;
    constexpr double k_exact = 1e-12;
    struct Case {
        sm::Vec3 radii;
        double e1, e2, tolerance_at_256;
    };
    const Case cases[] = {{{1, 1, 1}, 1.0, 1.0, 4e-4},    {{1, 2, 3}, 0.5, 1.5, 3e-4},
                          {{1, 2, 3}, 0.01, 0.01, 3e-4},  {{1, 2, 3}, 0.1, 0.1, 4e-4},
                          {{1, 2, 3}, 2.0, 2.0, k_exact}, {{1, 1, 10}, 1.0, 0.3, 2e-4},
                          {{1, 2, 3}, 3.0, 4.0, 3e-3},    {{1, 2, 3}, 4.0, 4.0, 9e-3}};
    for (const Case& c : cases) {
        const sm::ShapeDef s = superquadric(c.radii, c.e1, c.e2);
        const double coarse = volume_error(s, 64), fine = volume_error(s, 256);
        RecordProperty("volume_error_64_256_e" + std::to_string(c.e1) + "_" + std::to_string(c.e2),
                       testing::PrintToString(coarse) + " " + testing::PrintToString(fine));
        EXPECT_LT(std::abs(fine), c.tolerance_at_256) << c.e1 << " " << c.e2;
        if (std::abs(coarse) > k_exact) {
            EXPECT_LT(std::abs(fine), std::abs(coarse) / k_min_gain) << c.e1 << " " << c.e2;
        }
    }
}

TEST(Tessellate, VerticesOnTheSurfaceAndNormalsAgreeWithFaces)
{
    // Vertices come from the log-space superellipses: F = 1 to round-off. For convex shapes the mesh
    // faces around a vertex tilt by at most half a cell from its normal, so face and vertex normals
    // always point the same way.
    constexpr double k_round_off = 1e-12;
    for (double e1 : {0.1, 0.5, 1.0, 2.0})
        for (double e2 : {0.1, 0.5, 1.0, 2.0}) {
            const sm::ShapeDef s = superquadric({1, 2, 3}, e1, e2);
            const sm::TriangleMesh m = sm::tessellate(s, 32);
            for (const sm::Vec3& p : m.positions)
                EXPECT_NEAR(barr_inside_outside(s, p), 1.0, k_round_off);
            for (size_t t = 0; t < m.indices.size(); t += 3) {
                const uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
                const sm::Vec3 face =
                    sm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
                EXPECT_GT(sm::dot(face, m.normals[a] + m.normals[b] + m.normals[c]), 0.0) << e1 << " " << e2;
            }
        }
}

TEST(Tessellate, PolesAreSingleVerticesAndBoxEdgesAreKept)
{
    // The corner (φ = π/4) of both superellipses is always a vertex, so the mesh keeps the ε → 0 box's
    // corners: the vertex there has x/a1 = y/a2 = 2^(−ε) and z/a3 = 2^(−ε/2) exactly.
    constexpr double k_round_off = 1e-12;
    const double e = 0.01;
    const sm::ShapeDef s = superquadric({1, 2, 3}, e, e);
    const sm::TriangleMesh m = sm::tessellate(s, 16);
    EXPECT_EQ(std::count(m.positions.begin(), m.positions.end(), sm::Vec3{0, 0, 3}), 1);
    EXPECT_EQ(std::count(m.positions.begin(), m.positions.end(), sm::Vec3{0, 0, -3}), 1);
    double corner = 0.0;
    for (const sm::Vec3& p : m.positions)
        corner = std::max(corner, std::abs(p.x) / 1 + std::abs(p.y) / 2 + std::abs(p.z) / 3);
    EXPECT_NEAR(corner, 2 * std::pow(2.0, -e) + std::pow(2.0, -e / 2), k_round_off);
}

TEST(Tessellate, DeformedMeshIsClosedAndEnclosesTheDeformedVolume)
{
    // Taper and bend change the volume to V + kx·ky/a3²·∫z² dV (see sampling_test.cpp); vertices are
    // mapped exactly, so the error is the mesh's O(resolution⁻²), measured 8.1e-4 at resolution 128.
    constexpr double k_volume_rel = 1.2e-3;
    sm::ShapeDef s = superquadric({1, 1.5, 2}, 0.5, 1.0);
    s.taper = {0.4, -0.3};
    s.bend = {0.2, 0.5};
    const sm::MassProperties mp = sm::compute_mass_properties(superquadric(s.radii, 0.5, 1.0), 1.0);
    const double szz = 0.5 * (mp.inertia_diagonal.x + mp.inertia_diagonal.y - mp.inertia_diagonal.z);
    const double volume = mp.volume + s.taper.kx * s.taper.ky * szz / (s.radii.z * s.radii.z);
    const sm::TriangleMesh m = sm::tessellate(s, 128);
    ASSERT_TRUE(watertight(m));
    EXPECT_NEAR(sm::mesh_volume(m) / volume, 1.0, k_volume_rel);
}

TEST(Tessellate, ResolutionIsClampedAndPlanesGiveNoMesh)
{
    const sm::ShapeDef s = superquadric({1, 1, 1}, 1, 1);
    const sm::TriangleMesh low = sm::tessellate(s, -3);
    EXPECT_TRUE(watertight(low));
    EXPECT_EQ(low.indices.size(), sm::tessellate(s, 4).indices.size());
    sm::ShapeDef plane = sm::default_shape_def();
    plane.type = sm::ShapeType::Plane;
    EXPECT_TRUE(sm::tessellate(plane, 16).indices.empty());
    EXPECT_EQ(sm::mesh_volume(sm::tessellate(plane, 16)), 0.0);
}

TEST(MeshVolume, CubeAnywhere)
{
    // Exact in exact arithmetic; the centring keeps it to round-off even 10^6 m from the origin.
    constexpr double k_round_off = 1e-9;
    sm::TriangleMesh cube;
    for (int i = 0; i < 8; ++i)
        cube.positions.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
    // Two counter-clockwise triangles per face (seen from outside).
    cube.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                    2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    ASSERT_TRUE(watertight(cube));
    EXPECT_NEAR(sm::mesh_volume(cube), 1.0, k_round_off);
    for (sm::Vec3& p : cube.positions)
        p += sm::Vec3{1e6, -2e6, 3e6};
    EXPECT_NEAR(sm::mesh_volume(cube), 1.0, k_round_off);
    EXPECT_EQ(sm::mesh_volume(sm::TriangleMesh{}), 0.0);
}

namespace
{

// Largest radial gap between the mesh's edge midpoints and triangle centroids and an ellipsoid's surface
// [m]: the point p is moved along its own direction onto the surface (F(t·p) = 1).
double ellipsoid_gap(const sm::ShapeDef& s, const sm::TriangleMesh& m)
{
    double gap = 0.0;
    const auto measure = [&](const sm::Vec3& p) {
        const double f = barr_inside_outside(s, p);
        gap = std::max(gap, sm::length(p) * std::abs(1.0 / std::sqrt(f) - 1.0));
    };
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const sm::Vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                       c = m.positions[m.indices[t + 2]];
        measure((a + b + c) / 3.0);
        measure(0.5 * (a + b));
        measure(0.5 * (b + c));
        measure(0.5 * (c + a));
    }
    return gap;
}

} // namespace

// Curvature spacing puts the vertices where the surface turns: on a limb-like ellipsoid (0.045 x 0.15
// x 0.045 m) its mesh at 20 segments stands closer to the surface than the even mesh at 32 (measured:
// 2.4 against 3.1 mm; 39% of the triangles), and tessellation_gap estimates the gap it leaves (from
// chords of circles: within a factor of two of the measured one, and falling as 1/segments²). The curvature
// mesh is as closed and well shaped as the even one across the exponent grid.
TEST(Tessellate, CurvatureSpacingNeedsFewerSegmentsForTheSameGap)
{
    const sm::ShapeDef limb = superquadric({0.045, 0.15, 0.045}, 1.0, 1.0);
    const double even32 = ellipsoid_gap(limb, sm::tessellate(limb, 32));
    const double curved20 = ellipsoid_gap(limb, sm::tessellate(limb, 20, sm::MeshSpacing::Curvature));
    EXPECT_LT(curved20, even32);
    for (int n : {12, 16, 24, 32, 48}) {
        const double measured = ellipsoid_gap(limb, sm::tessellate(limb, n, sm::MeshSpacing::Curvature));
        const double estimate = sm::tessellation_gap(limb, n);
        EXPECT_GT(estimate, 0.5 * measured) << n;
        EXPECT_LT(estimate, 2.0 * measured) << n;
        std::printf("%d segments: gap %.3f mm, estimate %.3f mm\n", n, 1e3 * measured, 1e3 * estimate);
        EXPECT_NEAR(estimate * n * n, sm::tessellation_gap(limb, 1), 1e-12) << n;
    }
    for (double e1 : {0.01, 0.3, 1.0, 2.0, 4.0})
        for (double e2 : {0.01, 0.3, 1.0, 2.0, 4.0}) {
            const sm::TriangleMesh m =
                sm::tessellate(superquadric({1, 2, 3}, e1, e2), 16, sm::MeshSpacing::Curvature);
            ASSERT_TRUE(watertight(m)) << e1 << " " << e2;
            EXPECT_GT(worst_shape_quality(m), 1e-9) << e1 << " " << e2;
        }
    sm::ShapeDef plane = sm::default_shape_def();
    plane.type = sm::ShapeType::Plane;
    EXPECT_EQ(sm::tessellation_gap(plane, 16), 0.0);
}
