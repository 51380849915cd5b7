// Tests for support_jet (engine/src/geometry/support.cpp): the support map's Jacobian against central
// differences, and its point against support_point.
#include "geometry/support_internal.h"
#include "support/shapes.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;

TEST(SupportJet, JacobianMatchesCentralDifferences)
{
    // Directions away from the axes (where flat faces make the Jacobian unbounded), shapes from
    // flat (ε 0.2) to pointed (ε 1.8), unequal radii.
    uint32_t seed = 7;
    auto next = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<double>(seed >> 8) / 8388608.0 - 1.0;
    };
    // Equal exponents other than 1 take the one-level path (flat_dual): 0.3, 1.6 and 0.5 below.
    for (double e1 : {0.2, 0.3, 0.5, 1.0, 1.4, 1.6, 1.8})
        for (double e2 : {0.3, 0.5, 1.0, 1.6}) {
            const sm::ShapeDef s = sm::test::superquadric({0.05, 0.08, 0.03}, e1, e2);
            for (int k = 0; k < 20; ++k) {
                sm::Vec3 d{next(), next(), next()};
                for (int i = 0; i < 3; ++i)
                    d[i] += d[i] > 0.0 ? 0.2 : -0.2; // stay off the axis planes
                d = sm::normalized(d);
                const sm::SupportJet jet = sm::support_jet(s, d);
                const sm::Vec3 p = sm::support_point(s, d);
                EXPECT_EQ(jet.point.x, p.x);
                EXPECT_EQ(jet.point.y, p.y);
                EXPECT_EQ(jet.point.z, p.z);
                const double h = 1e-6;
                for (int j = 0; j < 3; ++j) {
                    sm::Vec3 dp = d, dm = d;
                    dp[j] += h;
                    dm[j] -= h;
                    const sm::Vec3 fd = (sm::support_point(s, dp) - sm::support_point(s, dm)) / (2.0 * h);
                    for (int i = 0; i < 3; ++i)
                        EXPECT_NEAR(jet.jacobian.m[i][j], fd[i], 1e-5 + 1e-4 * std::abs(fd[i]))
                            << "e " << e1 << " " << e2 << " i " << i << " j " << j;
                }
            }
        }
}
