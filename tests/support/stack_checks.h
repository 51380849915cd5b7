// Checks shared by tests of one body resting on another.
#pragma once

#include "supermodal/body.h"
#include "supermodal/world.h"

#include <cmath>
#include <gtest/gtest.h>

namespace supermodal::test
{

/// Expects the box `high` (half-size `half` [m]) to stand on the box `low`, and `low` to be where it had
/// settled (`settled` [m]): heights within `sink` [m], `low` moved sideways < 1 mm and `high` off its
/// middle < 1 cm, both slower than 1 mm/s.
inline void expect_box_stands_on_box(const World& world, Entity low, Entity high, const Vec3& settled,
                                     double half, double sink)
{
    const Vec3 lo = body_position(world, low), hi = body_position(world, high);
    EXPECT_NEAR(lo.y, settled.y, sink);
    EXPECT_LT(std::hypot(lo.x - settled.x, lo.z - settled.z), 1e-3);
    EXPECT_NEAR(hi.y - lo.y, 2.0 * half, sink);
    EXPECT_LT(std::hypot(hi.x - lo.x, hi.z - lo.z), 0.01);
    EXPECT_LT(length(body_linear_velocity(world, high)), 1e-3);
    EXPECT_LT(length(body_linear_velocity(world, low)), 1e-3);
}

} // namespace supermodal::test
