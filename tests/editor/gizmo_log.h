// Reading and checking the poses tests/editor/gizmo_script.json logs (the gizmo's tests, headless and
// through the window).
#pragma once

#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <regex>
#include <string>
#include <vector>

namespace supermodal::test
{

/// One "pose" line: position [m], orientation [w, x, y, z], radii [m], read back to the logged doubles.
struct LoggedPose {
    std::array<double, 3> position{}, radii{};
    std::array<double, 4> orientation{};
};

inline std::vector<LoggedPose> logged_poses(const std::string& log)
{
    std::vector<LoggedPose> out;
    const std::string n = R"((\S+))";
    const std::regex line("pose \\S+: position \\[" + n + ", " + n + ", " + n + "\\] orientation \\[" + n +
                          ", " + n + ", " + n + ", " + n + "\\] radii \\[" + n + ", " + n + ", " + n + "\\]");
    for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator(); ++it) {
        LoggedPose p;
        for (int i = 0; i < 3; ++i) {
            p.position[i] = std::stod((*it)[1 + i]);
            p.radii[i] = std::stod((*it)[8 + i]);
        }
        for (int i = 0; i < 4; ++i)
            p.orientation[i] = std::stod((*it)[4 + i]);
        out.push_back(p);
    }
    return out;
}

/// How far x is from the nearest multiple of step, in steps [-].
inline double off_step(double x, double step)
{
    return std::abs(x / step - std::round(x / step));
}

/// The script's four poses: loaded, moved along X, turned about Y, scaled along X, undone. Each drag
/// changes only its own axis, by a whole number of steps (0.05 m, 15°, 0.1), and three undos give back
/// the loaded pose to the bit.
inline void check_gizmo_poses(const std::vector<LoggedPose>& p)
{
    ASSERT_EQ(p.size(), 5u);
    const LoggedPose &loaded = p[0], &moved = p[1], &turned = p[2], &scaled = p[3], &undone = p[4];
    // Moved: along X only (Y and Z to the bit), a nonzero whole number of 0.05 m steps (1e-9 steps:
    // the sum of two doubles), nothing else changed.
    const double dx = moved.position[0] - loaded.position[0];
    EXPECT_GE(std::abs(dx), 0.05 - 1e-12);
    EXPECT_LT(off_step(dx, 0.05), 1e-9) << dx;
    EXPECT_EQ(moved.position[1], loaded.position[1]);
    EXPECT_EQ(moved.position[2], loaded.position[2]);
    EXPECT_EQ(moved.orientation, loaded.orientation);
    EXPECT_EQ(moved.radii, loaded.radii);
    // Turned: about Y only (x and z of the quaternion 0), by a nonzero whole number of 15° (1e-9°), in place.
    EXPECT_EQ(turned.orientation[1], 0.0);
    EXPECT_EQ(turned.orientation[3], 0.0);
    const double degrees = 2.0 * std::atan2(turned.orientation[2], turned.orientation[0]) * 180.0 / M_PI;
    EXPECT_GE(std::abs(degrees), 15.0 - 1e-9);
    EXPECT_LT(off_step(degrees, 15.0) * 15.0, 1e-9) << degrees;
    EXPECT_EQ(turned.position, moved.position);
    EXPECT_EQ(turned.radii, moved.radii);
    // Scaled: the X radius only, by a whole number of 0.1 (1e-9), larger.
    const double factor = scaled.radii[0] / turned.radii[0];
    EXPECT_GT(factor, 1.05);
    EXPECT_LT(off_step(factor, 0.1), 1e-9) << factor;
    EXPECT_EQ(scaled.radii[1], turned.radii[1]);
    EXPECT_EQ(scaled.radii[2], turned.radii[2]);
    EXPECT_EQ(scaled.position, turned.position);
    EXPECT_EQ(scaled.orientation, turned.orientation);
    // Undone: the loaded pose and radii to the bit.
    EXPECT_EQ(undone.position, loaded.position);
    EXPECT_EQ(undone.orientation, loaded.orientation);
    EXPECT_EQ(undone.radii, loaded.radii);
}

} // namespace supermodal::test
