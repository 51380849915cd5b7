// SPDX-License-Identifier: MIT
// `supermodal run --frames/--every/--size/--video`, run as a separate process like a user would.
#include "supermodal/render.h"
#include "support/run_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

namespace
{

using Outcome = supermodal::test::CommandOutcome;

Outcome run_cli(const std::string& args)
{
    return supermodal::test::run_command(std::string(SM_CLI) + " " + args + " 2>&1");
}

std::filesystem::path fresh_dir(const char* name)
{
    auto dir = std::filesystem::temp_directory_path() / ("supermodal_capture_" + std::string(name));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

nlohmann::json read_json(const std::filesystem::path& p)
{
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

const std::string k_scene = "run " + std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json";

// Capturing reads the world and never writes it: the state hash is the same with and without frames.
TEST(Capture, FramesDoNotChangeTheSimulation)
{
    const auto dir = fresh_dir("hash");
    const Outcome plain = run_cli(k_scene + " --steps 240 --json " + (dir / "plain.json").string());
    ASSERT_EQ(plain.status, 0) << plain.output;
    const Outcome framed = run_cli(k_scene + " --steps 240 --frames " + (dir / "frames").string() +
                                   " --every 60 --size 96x64 --json " + (dir / "framed.json").string());
    ASSERT_EQ(framed.status, 0) << framed.output;
    const nlohmann::json a = read_json(dir / "plain.json"), b = read_json(dir / "framed.json");
    EXPECT_EQ(a["state_hash"], b["state_hash"]);
    // Frames before step 1 and after steps 60, 120, 180, 240.
    EXPECT_EQ(b["capture"]["frames"], 5);
    for (int i = 0; i < 5; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%06d.png", i);
        supermodal::Result<supermodal::Image> img = supermodal::read_png((dir / "frames" / name).string());
        ASSERT_TRUE(img) << img.error().message();
        EXPECT_EQ(img->width, 96);
        EXPECT_EQ(img->height, 64);
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "frames" / "frame_000005.png"));
}

TEST(Capture, BadOptionsExitWithStatus2)
{
    const auto dir = fresh_dir("bad");
    const std::string frames = " --frames " + (dir / "f").string();
    const struct {
        std::string args, says;
    } cases[] = {{k_scene + frames + " --size 100", "--size"},
                 {k_scene + frames + " --size 8x8", "--size"},
                 {k_scene + frames + " --size 100x100x3", "--size"},
                 {k_scene + frames + " --every 0", "--every"},
                 {k_scene + " --size 64x64", "--frames"},
                 {k_scene + " --every 3", "--frames"}};
    for (const auto& c : cases) {
        const Outcome o = run_cli(c.args + " --steps 2");
        EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
        EXPECT_NE(o.output.find(c.says), std::string::npos) << c.args << "\n" << o.output;
    }
}

TEST(Capture, VideoWithoutFfmpegSaysSo)
{
    const auto dir = fresh_dir("video");
    // An empty PATH has no ffmpeg; with ffmpeg present the same run must write the file.
    const std::string env_path = "env PATH=" + dir.string() + " ";
    FILE* p = ::popen(
        (env_path + SM_CLI + " " + k_scene + " --steps 4 --video " + (dir / "v.mp4").string() + " 2>&1")
            .c_str(),
        "r");
    ASSERT_NE(p, nullptr);
    std::string out;
    char buf[1024];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0)
        out.append(buf, n);
    const int raw = ::pclose(p);
    EXPECT_EQ(WEXITSTATUS(raw), 2) << out;
    EXPECT_NE(out.find("ffmpeg"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir / "v.mp4"));
}

} // namespace
