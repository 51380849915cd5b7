// SPDX-License-Identifier: MIT
// PNG files (Debian's libstb: stb_image_write / stb_image) and image comparison.
#include "supermodal/render.h"

#include <algorithm>
#include <cstdlib>
#include <stb_image.h>
#include <stb_image_write.h>

namespace supermodal
{

Status write_png(const std::string& path, const Image& image)
{
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4)
        return Error{path, "", "not a valid RGBA image"};
    // stb's defaults (level 8, every row filter tried) cost 1.7x the time of level 1 with the Sub filter
    // for 2% smaller files on 1280x720 renders (measured, docs/rendering.md): frame capture wants speed.
    // Set once; the values never change after, so concurrent writers see the same.
    static const bool tuned = [] {
        stbi_write_png_compression_level = 1;
        stbi_write_force_png_filter = 1;
        return true;
    }();
    (void)tuned;
    if (stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4) == 0)
        return Error{path, "", "cannot write the PNG (does the directory exist and is it writable?)"};
    return {};
}

Result<Image> read_png(const std::string& path)
{
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (data == nullptr)
        return Error{path, "", std::string("cannot read the PNG: ") + stbi_failure_reason()};
    Image out{w, h, std::vector<uint8_t>(data, data + static_cast<size_t>(w) * static_cast<size_t>(h) * 4)};
    stbi_image_free(data);
    return out;
}

Result<ImageDiff> compare_images(const Image& actual, const Image& expected, int tolerance)
{
    if (actual.width != expected.width || actual.height != expected.height)
        return Error{"", "",
                     "image sizes differ: " + std::to_string(actual.width) + "x" +
                         std::to_string(actual.height) + " vs expected " + std::to_string(expected.width) +
                         "x" + std::to_string(expected.height)};
    ImageDiff d;
    d.diff = expected;
    const size_t pixels = static_cast<size_t>(actual.width) * static_cast<size_t>(actual.height);
    if (actual.rgba.size() != pixels * 4 || expected.rgba.size() != pixels * 4)
        return Error{"", "", "image data does not match its size"};
    for (size_t i = 0; i < pixels; ++i) {
        int worst = 0;
        for (size_t c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(int{actual.rgba[i * 4 + c]} - int{expected.rgba[i * 4 + c]}));
        d.max_difference = std::max(d.max_difference, worst);
        uint8_t* px = d.diff.rgba.data() + i * 4;
        if (worst > tolerance) {
            ++d.differing_pixels;
            px[0] = 255;
            px[1] = px[2] = 0;
        } else { // faded grey copy of the expected image, for context
            const auto grey = static_cast<uint8_t>(160 + (px[0] + px[1] + px[2]) / 12);
            px[0] = px[1] = px[2] = grey;
        }
        px[3] = 255;
    }
    d.differing_fraction =
        pixels > 0 ? static_cast<double>(d.differing_pixels) / static_cast<double>(pixels) : 0.0;
    return d;
}

} // namespace supermodal
