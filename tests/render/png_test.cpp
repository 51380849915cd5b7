// SPDX-License-Identifier: MIT
// PNG files: encode_png/write_png (libspng) round trips, and PngWriter's threads write the same bytes, in
// order, and nothing after an error. Also the renderer's view rectangle (Renderer::render's `view`).
#include "supermodal/render.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

// A frame with gradients, edges and (optionally) transparency: enough structure for every filter.
sm::Image pattern(int w, int h, int seed, bool opaque = true)
{
    sm::Image img{w, h, std::vector<uint8_t>(static_cast<size_t>(w) * h * 4)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t* p = img.rgba.data() + (static_cast<size_t>(y) * w + x) * 4;
            p[0] = static_cast<uint8_t>(x * 255 / w);
            p[1] = static_cast<uint8_t>((y + seed) * 7);
            p[2] = static_cast<uint8_t>((x / 8 + y / 8 + seed) % 2 ? 220 : 30);
            p[3] = opaque ? 255 : static_cast<uint8_t>(x + y);
        }
    return img;
}

std::vector<char> bytes_of(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path fresh_dir(const char* name)
{
    const fs::path dir = fs::temp_directory_path() / ("supermodal_png_" + std::string(name));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

} // namespace

TEST(Png, OpaqueAndTranslucentImagesReadBackExactly)
{
    const fs::path dir = fresh_dir("roundtrip");
    for (const bool opaque : {true, false}) {
        const sm::Image img = pattern(97, 61, 3, opaque); // odd sizes: no row happens to align
        const std::string path = (dir / (opaque ? "opaque.png" : "alpha.png")).string();
        ASSERT_TRUE(sm::write_png(path, img));
        sm::Result<sm::Image> back = sm::read_png(path);
        ASSERT_TRUE(back) << back.error().message();
        EXPECT_EQ(back->width, 97);
        EXPECT_EQ(back->height, 61);
        EXPECT_EQ(back->rgba, img.rgba) << (opaque ? "opaque (written as RGB)" : "with alpha");
    }
    // An opaque image is stored as RGB (colour type 2 in the header), one with alpha as RGBA (6).
    EXPECT_EQ(bytes_of(dir / "opaque.png").at(25), 2);
    EXPECT_EQ(bytes_of(dir / "alpha.png").at(25), 6);
    EXPECT_FALSE(fs::exists(dir / "opaque.png.part"));
}

TEST(Png, ABadPathLeavesNothingAndNamesIt)
{
    const sm::Status s = sm::write_png("/nonexistent_dir_for_supermodal/x.png", pattern(16, 16, 0));
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message().find("/nonexistent_dir_for_supermodal/x.png"), std::string::npos);
    const sm::Status empty = sm::write_png((fresh_dir("bad") / "e.png").string(), sm::Image{});
    EXPECT_FALSE(empty);
    EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "supermodal_png_bad" / "e.png"));
}

TEST(PngWriter, ThreadsWriteTheSameBytesAsWritePngInOrder)
{
    const fs::path dir = fresh_dir("threads");
    constexpr int k_frames = 12;
    for (int i = 0; i < k_frames; ++i)
        ASSERT_TRUE(
            sm::write_png((dir / ("ref_" + std::to_string(i) + ".png")).string(), pattern(200, 120, i)));
    for (const int threads : {0, 1, 3}) {
        sm::Result<std::unique_ptr<sm::PngWriter>> w =
            sm::PngWriter::create({.threads = threads, .queue = 2});
        ASSERT_TRUE(w) << w.error().message();
        std::vector<fs::file_time_type> times;
        for (int i = 0; i < k_frames; ++i) {
            sm::Image img = pattern(200, 120, i);
            ASSERT_TRUE((*w)->submit(
                (dir / ("t" + std::to_string(threads) + "_" + std::to_string(i) + ".png")).string(),
                std::move(img)));
        }
        ASSERT_TRUE((*w)->finish());
        EXPECT_EQ((*w)->files_written(), k_frames);
        for (int i = 0; i < k_frames; ++i) {
            const fs::path p = dir / ("t" + std::to_string(threads) + "_" + std::to_string(i) + ".png");
            EXPECT_EQ(bytes_of(p), bytes_of(dir / ("ref_" + std::to_string(i) + ".png"))) << p;
            times.push_back(fs::last_write_time(p));
        }
        // Renamed into place in submission order: no file is newer than the one after it.
        for (int i = 1; i < k_frames; ++i)
            EXPECT_LE(times[i - 1], times[i]) << threads << " threads, frame " << i;
    }
}

TEST(PngWriter, AfterAnErrorNothingMoreIsWrittenAndTheErrorComesBack)
{
    const fs::path dir = fresh_dir("error");
    sm::Result<std::unique_ptr<sm::PngWriter>> w = sm::PngWriter::create({.threads = 2, .queue = 1});
    ASSERT_TRUE(w);
    ASSERT_TRUE((*w)->submit((dir / "a.png").string(), pattern(64, 64, 1)));
    (void)(*w)->submit((dir / "missing" / "b.png").string(), pattern(64, 64, 2)); // no such folder
    sm::Status later = sm::Status{};
    for (int i = 0; i < 4 && later; ++i)
        later = (*w)->submit((dir / ("c" + std::to_string(i) + ".png")).string(), pattern(64, 64, 3));
    const sm::Status finished = (*w)->finish();
    ASSERT_FALSE(finished);
    EXPECT_NE(finished.error().message().find("b.png"), std::string::npos) << finished.error().message();
    EXPECT_TRUE(fs::exists(dir / "a.png"));
    for (int i = 0; i < 4; ++i)
        EXPECT_FALSE(fs::exists(dir / ("c" + std::to_string(i) + ".png"))) << i;
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_NE(entry.path().extension(), ".part") << entry.path();
    EXPECT_EQ((*w)->files_written(), 1);
    EXPECT_FALSE(sm::PngWriter::create({.threads = -1}));
    EXPECT_FALSE(sm::PngWriter::create({.threads = 1, .queue = 0}));
}

TEST(RenderView, ARectangleDrawsTheSceneThereAndTheSkyColourAround)
{
    sm::Result<sm::Scene> scene = sm::load_scene(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json");
    ASSERT_TRUE(scene);
    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world);
    sm::RenderDef def = sm::default_render_def();
    def.width = 200;
    def.height = 100;
    sm::Result<sm::Renderer> r = sm::Renderer::create(def);
    ASSERT_TRUE(r) << r.error().message();
    const sm::PixelRect rect{60, 10, 100, 80};
    sm::Image framed;
    ASSERT_TRUE(r->render(*world, scene->camera, framed, sm::PoseSource::Current, {}, rect));
    // The same camera on a renderer of the rectangle's size draws the same pixels (4x MSAA resolves
    // the same samples; llvmpipe is deterministic).
    def.width = rect.width;
    def.height = rect.height;
    sm::Result<sm::Renderer> small = sm::Renderer::create(def);
    ASSERT_TRUE(small);
    sm::Image alone;
    ASSERT_TRUE(small->render(*world, scene->camera, alone));
    long long inside_differ = 0, outside_not_sky = 0;
    const auto sky = [&](int c) { return static_cast<int>(std::lround(255.0 * def.sky_bottom[c])); };
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 200; ++x) {
            const uint8_t* p = framed.rgba.data() + (static_cast<size_t>(y) * 200 + x) * 4;
            if (x >= rect.x && x < rect.x + rect.width && y >= rect.y && y < rect.y + rect.height) {
                const uint8_t* q =
                    alone.rgba.data() + (static_cast<size_t>(y - rect.y) * rect.width + x - rect.x) * 4;
                inside_differ +=
                    std::abs(p[0] - q[0]) > 1 || std::abs(p[1] - q[1]) > 1 || std::abs(p[2] - q[2]) > 1;
            } else {
                outside_not_sky += std::abs(p[0] - sky(0)) > 1 || std::abs(p[1] - sky(1)) > 1 ||
                                   std::abs(p[2] - sky(2)) > 1 || p[3] != 255;
            }
        }
    EXPECT_EQ(inside_differ, 0);
    EXPECT_EQ(outside_not_sky, 0);
    // A rectangle outside the image is refused, naming it.
    const sm::Status bad =
        r->render(*world, scene->camera, framed, sm::PoseSource::Current, {}, {150, 0, 100, 50});
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message().find("render/view"), std::string::npos) << bad.error().message();
}
