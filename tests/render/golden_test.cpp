// SPDX-License-Identifier: MIT
// Golden images: each tests/golden/<name>.json is rendered and compared with <name>.png. On failure the
// render and a diff image go to <build>/tests/render/golden_out/. SUPERMODAL_UPDATE_GOLDEN=1 rewrites
// the references instead (docs/rendering.md).
#include "golden_spec.h"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>

namespace supermodal::golden
{
namespace
{

bool updating()
{
    const char* v = std::getenv("SUPERMODAL_UPDATE_GOLDEN");
    return v != nullptr && std::string(v) == "1";
}

std::string reference_path(const std::string& name)
{
    return std::string(SM_SOURCE_DIR) + "/tests/golden/" + name + ".png";
}

class Golden : public ::testing::TestWithParam<std::string>
{
};

TEST_P(Golden, MatchesReference)
{
    Result<Spec> spec = load_spec(GetParam());
    ASSERT_TRUE(spec) << spec.error().message();
    Result<Image> image = render_spec(*spec);
    ASSERT_TRUE(image) << "cannot render (is EGL with Mesa installed? scripts/deps.sh): "
                       << image.error().message();
    if (updating()) {
        Status s = write_png(reference_path(spec->name), *image);
        ASSERT_TRUE(s) << s.error().message();
        GTEST_SUCCEED() << "rewrote " << reference_path(spec->name);
        return;
    }
    Result<Image> reference = read_png(reference_path(spec->name));
    ASSERT_TRUE(reference) << reference.error().message()
                           << " (make it with SUPERMODAL_UPDATE_GOLDEN=1, docs/rendering.md)";
    Result<ImageDiff> diff = compare_images(*image, *reference, spec->tolerance);
    ASSERT_TRUE(diff) << diff.error().message();
    if (diff->differing_fraction > spec->max_fraction) {
        std::filesystem::create_directories(SM_GOLDEN_OUT);
        const std::string actual = std::string(SM_GOLDEN_OUT) + "/" + spec->name + "_actual.png";
        const std::string diff_path = std::string(SM_GOLDEN_OUT) + "/" + spec->name + "_diff.png";
        (void)write_png(actual, *image);
        (void)write_png(diff_path, diff->diff);
        ADD_FAILURE() << spec->name << ": " << diff->differing_pixels << " pixels ("
                      << 100.0 * diff->differing_fraction << "%) differ by more than " << spec->tolerance
                      << "/255 (allowed " << 100.0 * spec->max_fraction << "%); max difference "
                      << diff->max_difference << ". Render: " << actual
                      << ", diff (red = differs): " << diff_path;
    }
}

INSTANTIATE_TEST_SUITE_P(Images, Golden, ::testing::ValuesIn(spec_names()),
                         [](const auto& info) { return info.param; });

// The comparison must be able to fail: a broken shader and a wrong camera both miss the reference.
class BrokenRender : public ::testing::TestWithParam<RenderFault>
{
};

TEST_P(BrokenRender, FailsTheGalleryComparison)
{
    Result<Spec> spec = load_spec("gallery");
    ASSERT_TRUE(spec) << spec.error().message();
    Result<Image> reference = read_png(reference_path("gallery"));
    ASSERT_TRUE(reference) << reference.error().message();
    Result<Image> broken = render_spec(*spec, GetParam());
    ASSERT_TRUE(broken) << broken.error().message();
    Result<ImageDiff> diff = compare_images(*broken, *reference, spec->tolerance);
    ASSERT_TRUE(diff) << diff.error().message();
    // Far beyond the allowed fraction, not just over it: the fault is visible, not noise.
    EXPECT_GT(diff->differing_fraction, 5.0 * spec->max_fraction);
}

INSTANTIATE_TEST_SUITE_P(Faults, BrokenRender,
                         ::testing::Values(RenderFault::FlatShading, RenderFault::FlippedYaw),
                         [](const auto& info) {
                             return info.param == RenderFault::FlatShading ? std::string("BrokenShader")
                                                                           : std::string("WrongCamera");
                         });

} // namespace
} // namespace supermodal::golden
