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
#include <unistd.h>

namespace sm = supermodal;

namespace
{

const std::string k_golden = std::string(SM_SOURCE_DIR) + "/tests/editor/golden/window.png";

// Per-channel tolerance and the share of pixels allowed past it, as the render golden tests allow
// (tests/golden): llvmpipe repeats itself exactly on one Mesa build; another Mesa or LLVM rounds edges
// and text differently by a few levels.
constexpr int k_tolerance = 16;
constexpr double k_max_fraction = 0.01;

/// The editor with `args` in a 1280x720 virtual X server. `xvfb-run -a` takes the first free display
/// from -n on; two runs starting together (other builds on the machine) can both pick it and one X
/// server then fails to start, so the search starts at a number of this process's own and a failed
/// start is tried once more. The editor's own failures are not retried.
sm::test::CommandOutcome run_in_xvfb(const std::string& args)
{
    sm::test::CommandOutcome o;
    for (int attempt = 0; attempt < 2; ++attempt) {
        const int display = 100 + static_cast<int>((::getpid() * 7 + attempt * 397) % 800);
        o = sm::test::run_command("xvfb-run -a -n " + std::to_string(display) +
                                  " -s '-screen 0 1280x720x24' " + std::string(SM_EDITOR_EXE) + " " + args +
                                  " 2>&1");
        if (o.output.find("Xvfb failed to start") == std::string::npos)
            break;
    }
    return o;
}

} // namespace

TEST(EditorWindow, AScriptThroughTheWindowMatchesTheGoldenImageAndLeavesTheViewSixtyPercent)
{
    const std::filesystem::path out = std::filesystem::path(SM_EDITOR_OUT);
    std::filesystem::create_directories(out);
    const std::filesystem::path shot = out / "window.png";
    std::filesystem::remove(shot);
    const sm::test::CommandOutcome o =
        run_in_xvfb(std::string("--script ") + SM_SOURCE_DIR +
                    "/tests/editor/window_script.json --screenshot " + shot.string());
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
        run_in_xvfb(std::string("--script ") + SM_SOURCE_DIR + "/tests/editor/window_fail_script.json");
    EXPECT_EQ(o.status, 1) << o.output;
    EXPECT_NE(o.output.find("expected \"ball\" to be selected"), std::string::npos) << o.output;
}
#endif
