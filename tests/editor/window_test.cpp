// The editor in a real GLFW window under a virtual X server (xvfb-run, Debian xvfb): a script drives it
// through the window's GLFW callback chain (mouse on a body, keys, widget presses), then the window's
// own framebuffer is compared with a golden image and the 3-D view's share of the window is checked.
#ifdef SM_HAS_RENDER
#include "supermodal/render.h"
#include "support/run_command.h"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>

namespace sm = supermodal;

namespace
{

const std::string k_golden = std::string(SM_SOURCE_DIR) + "/tests/editor/golden/window.png";

// Per-channel tolerance and the share of pixels allowed past it, as the render golden tests allow
// (tests/golden): llvmpipe repeats itself exactly on one Mesa build; another Mesa or LLVM rounds edges
// and text differently by a few levels.
constexpr int k_tolerance = 16;
constexpr double k_max_fraction = 0.01;

} // namespace

TEST(EditorWindow, AScriptThroughTheWindowMatchesTheGoldenImageAndLeavesTheViewSixtyPercent)
{
    const std::filesystem::path out = std::filesystem::path(SM_EDITOR_OUT);
    std::filesystem::create_directories(out);
    const std::filesystem::path shot = out / "window.png";
    std::filesystem::remove(shot);
    // -a: a free display number, so parallel tests do not collide; the screen fits the 1280x720 window.
    const sm::test::CommandOutcome o = sm::test::run_command(
        "xvfb-run -a -s '-screen 0 1280x720x24' " + std::string(SM_EDITOR_EXE) + " --script " +
        SM_SOURCE_DIR + "/tests/editor/window_script.json --screenshot " + shot.string() + " 2>&1");
    ASSERT_EQ(o.status, 0) << "needs xvfb-run (scripts/deps.sh installs xvfb and xauth)\n" << o.output;
    // The script's viewport action checked the 60% and logged the rectangle.
    EXPECT_NE(o.output.find("viewport 800x720 at (211, 0): 62.5% of the display"), std::string::npos)
        << o.output;
    sm::Result<sm::Image> actual = sm::read_png(shot.string());
    ASSERT_TRUE(actual) << actual.error().message();
    ASSERT_EQ(actual->width, 1280);
    ASSERT_EQ(actual->height, 720);
    if (std::getenv("SUPERMODAL_UPDATE_GOLDEN") != nullptr) {
        std::filesystem::copy_file(shot, k_golden, std::filesystem::copy_options::overwrite_existing);
        GTEST_SKIP() << "rewrote " << k_golden;
    }
    sm::Result<sm::Image> golden = sm::read_png(k_golden);
    ASSERT_TRUE(golden) << golden.error().message();
    sm::Result<sm::ImageDiff> diff = sm::compare_images(*actual, *golden, k_tolerance);
    ASSERT_TRUE(diff) << diff.error().message();
    if (diff->differing_fraction > k_max_fraction)
        (void)sm::write_png((out / "window_diff.png").string(), diff->diff);
    EXPECT_LE(diff->differing_fraction, k_max_fraction)
        << diff->differing_pixels << " pixels differ (max " << diff->max_difference << "); see "
        << shot.string() << " and " << (out / "window_diff.png").string();
}

TEST(EditorWindow, AFailedCheckInTheWindowExitsWithStatus1)
{
    const sm::test::CommandOutcome o =
        sm::test::run_command("xvfb-run -a -s '-screen 0 1280x720x24' " + std::string(SM_EDITOR_EXE) +
                              " --script " + SM_SOURCE_DIR + "/tests/editor/window_fail_script.json 2>&1");
    EXPECT_EQ(o.status, 1) << o.output;
    EXPECT_NE(o.output.find("expected \"ball\" to be selected"), std::string::npos) << o.output;
}
#endif
