// SPDX-License-Identifier: MIT
// The sky's triangles: the viewport less the ground's projected polygon, without overlap or gaps.
#include "render/sky_region.h"

#include <cmath>
#include <gtest/gtest.h>

namespace supermodal::render
{
namespace
{

// How many of the triangles contain (x, y) (edges count as inside).
int coverage(const std::vector<float>& tri, double x, double y)
{
    int n = 0;
    for (size_t i = 0; i + 5 < tri.size(); i += 6) {
        const double ax = tri[i], ay = tri[i + 1], bx = tri[i + 2], by = tri[i + 3], cx = tri[i + 4],
                     cy = tri[i + 5];
        const double d0 = (bx - ax) * (y - ay) - (by - ay) * (x - ax);
        const double d1 = (cx - bx) * (y - by) - (cy - by) * (x - bx);
        const double d2 = (ax - cx) * (y - cy) - (ay - cy) * (x - cx);
        const bool neg = d0 < 0 || d1 < 0 || d2<0, pos = d0> 0 || d1 > 0 || d2 > 0;
        n += (neg && pos) ? 0 : 1;
    }
    return n;
}

double area(const std::vector<float>& tri)
{
    double a = 0.0;
    for (size_t i = 0; i + 5 < tri.size(); i += 6)
        a += 0.5 * std::abs((tri[i + 2] - tri[i]) * (tri[i + 5] - tri[i + 1]) -
                            (tri[i + 4] - tri[i]) * (tri[i + 3] - tri[i + 1]));
    return a;
}

// A quad already divided by w: NDC corners (x, y) at depth z = 0, w = 1.
std::vector<ClipPoint> flat(std::initializer_list<std::array<double, 2>> corners)
{
    std::vector<ClipPoint> out;
    for (const auto& c : corners)
        out.push_back({c[0], c[1], 0.0, 1.0});
    return out;
}

TEST(SkyRegion, NoGroundCoversTheWholeViewport)
{
    const std::vector<float> tri = sky_triangles({}, 0.01);
    for (double x : {-0.99, 0.0, 0.99})
        for (double y : {-0.99, 0.0, 0.99})
            EXPECT_EQ(coverage(tri, x, y), 1) << x << ", " << y;
}

TEST(SkyRegion, GroundOverTheLowerHalfLeavesTheUpperHalf)
{
    // Clockwise on purpose: the orientation must not matter. Wider than the viewport.
    const std::vector<float> tri = sky_triangles(flat({{-2, -2}, {-2, 0}, {2, 0}, {2, -2}}), 0.01);
    EXPECT_NEAR(area(tri), 2.0 + 2.0 * 0.01, 1e-6); // the upper half and the margin band
    EXPECT_EQ(coverage(tri, 0.3, 0.5), 1);
    EXPECT_EQ(coverage(tri, 0.3, -0.005), 1); // inside the margin
    EXPECT_EQ(coverage(tri, 0.3, -0.5), 0);
}

TEST(SkyRegion, AGroundPolygonInsideTheViewIsLeftOutOnceAndTheRestCoveredOnce)
{
    // A tilted quad inside the viewport: four regions around it, none overlapping.
    const std::vector<ClipPoint> ground = flat({{-0.5, -0.6}, {0.6, -0.4}, {0.4, 0.5}, {-0.6, 0.3}});
    const std::vector<float> tri = sky_triangles(ground, 0.0);
    int outside = 0;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) {
            // Cell centres, off every edge of the regions.
            const double x = -1.0 + (i + 0.5) / 20.0 + 1e-4, y = -1.0 + (j + 0.5) / 20.0 + 2e-4;
            const int in_quad = coverage(std::vector<float>{-0.5f, -0.6f, 0.6f, -0.4f, 0.4f, 0.5f, -0.5f,
                                                            -0.6f, 0.4f, 0.5f, -0.6f, 0.3f},
                                         x, y);
            EXPECT_EQ(coverage(tri, x, y), in_quad > 0 ? 0 : 1) << x << ", " << y;
            outside += in_quad > 0 ? 0 : 1;
        }
    EXPECT_GT(outside, 0);
    // Area: the viewport's 4 less the quad's (shoelace).
    const double quad = 0.5 * ((-0.5 * -0.4 - 0.6 * -0.6) + (0.6 * 0.5 - 0.4 * -0.4) +
                               (0.4 * 0.3 - -0.6 * 0.5) + (-0.6 * -0.6 - -0.5 * 0.3));
    EXPECT_NEAR(area(tri), 4.0 - quad, 1e-5);
}

TEST(SkyRegion, TheGroundIsCutAtTheNearAndFarPlanesBeforeDividing)
{
    // A ground strip from in front of the eye (w = 1, z = 0) to beyond the far plane (z > w): GL
    // draws it only up to where z = w, here at the middle of the strip (y = 0 in NDC).
    const std::vector<ClipPoint> ground = {
        {-2, -1, 0, 1}, {2, -1, 0, 1}, {2, 1, 2, 1}, {-2, 1, 2, 1}}; // z = w at t = 0.5, y = 0
    const std::vector<float> tri = sky_triangles(ground, 0.0);
    EXPECT_EQ(coverage(tri, 0.1, 0.55), 1);  // beyond the far plane: sky
    EXPECT_EQ(coverage(tri, 0.1, -0.45), 0); // the ground
    EXPECT_NEAR(area(tri), 2.0, 1e-6);
    // Entirely behind the far plane: nothing of the ground is drawn, the sky covers all.
    const std::vector<ClipPoint> far = {{-1, -1, 2, 1}, {1, -1, 2, 1}, {1, 1, 2, 1}, {-1, 1, 2, 1}};
    EXPECT_EQ(coverage(sky_triangles(far, 0.0), 0.1, 0.05), 1);
}

} // namespace
} // namespace supermodal::render
