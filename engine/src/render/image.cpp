// SPDX-License-Identifier: MIT
// PNG files (written by Debian's libspng, read by its libstb: stb_image) and image comparison.
#include "render/png_file.h"
#include "supermodal/render.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <spng.h>
#include <stb_image.h>

namespace supermodal
{
namespace
{

bool valid_rgba(const Image& image)
{
    return image.width > 0 && image.height > 0 &&
           image.rgba.size() == static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4;
}

bool opaque(const Image& image)
{
    for (size_t i = 3; i < image.rgba.size(); i += 4)
        if (image.rgba[i] != 255)
            return false;
    return true;
}

std::vector<uint8_t> drop_alpha(const Image& image)
{
    std::vector<uint8_t> rgb(image.rgba.size() / 4 * 3);
    for (size_t p = 0, q = 0; p < image.rgba.size(); p += 4, q += 3) {
        rgb[q] = image.rgba[p];
        rgb[q + 1] = image.rgba[p + 1];
        rgb[q + 2] = image.rgba[p + 2];
    }
    return rgb;
}

struct SpngFree {
    void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};

} // namespace

Result<std::vector<uint8_t>> encode_png(const Image& image)
{
    if (!valid_rgba(image))
        return Error{"", "", "not a valid RGBA image"};
    // Rendered frames are opaque: as RGB they are 10% smaller on 1280x720 renders, for the same time,
    // and read back as the same RGBA.
    const bool rgb = opaque(image);
    const std::vector<uint8_t> packed = rgb ? drop_alpha(image) : std::vector<uint8_t>{};
    const std::vector<uint8_t>& pixels = rgb ? packed : image.rgba;
    std::unique_ptr<spng_ctx, SpngFree> ctx(spng_ctx_new(SPNG_CTX_ENCODER));
    if (!ctx)
        return Error{"", "", "cannot start the PNG encoder (out of memory)"};
    // zlib level 1 with the Sub filter on every row: 3.1x faster than stb_image_write at its fastest
    // (level 1, Sub) with 23% smaller files on 1280x720 renders; choosing the best filter per row takes
    // 2.3x the time for no smaller file (bench/render_bench.cpp, docs/rendering.md).
    spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
    spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, 1);
    spng_set_option(ctx.get(), SPNG_FILTER_CHOICE, SPNG_FILTER_CHOICE_SUB);
    spng_ihdr ihdr{};
    ihdr.width = static_cast<uint32_t>(image.width);
    ihdr.height = static_cast<uint32_t>(image.height);
    ihdr.bit_depth = 8;
    ihdr.color_type = rgb ? SPNG_COLOR_TYPE_TRUECOLOR : SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
    int e = spng_set_ihdr(ctx.get(), &ihdr);
    if (e == 0)
        e = spng_encode_image(ctx.get(), pixels.data(), pixels.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    if (e != 0)
        return Error{"", "", std::string("cannot encode the PNG: ") + spng_strerror(e)};
    size_t size = 0;
    std::unique_ptr<void, decltype(&std::free)> buffer(spng_get_png_buffer(ctx.get(), &size, &e), &std::free);
    if (!buffer || e != 0)
        return Error{"", "", std::string("cannot encode the PNG: ") + spng_strerror(e)};
    const auto* bytes = static_cast<const uint8_t*>(buffer.get());
    return std::vector<uint8_t>(bytes, bytes + size);
}

Status render::write_complete_file(const std::string& path, const std::vector<uint8_t>& bytes)
{
    const std::string part = path + ".part";
    std::FILE* f = std::fopen(part.c_str(), "wb");
    if (f == nullptr)
        return Error{path, "", "cannot write the PNG (does the directory exist and is it writable?)"};
    const bool wrote = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const bool closed = std::fclose(f) == 0;
    if (!wrote || !closed || std::rename(part.c_str(), path.c_str()) != 0) {
        std::remove(part.c_str());
        return Error{path, "", "cannot write the PNG (disk full, or the file cannot be replaced?)"};
    }
    return {};
}

Status write_png(const std::string& path, const Image& image)
{
    Result<std::vector<uint8_t>> bytes = encode_png(image);
    if (!bytes)
        return Error{path, "", bytes.error().what};
    return render::write_complete_file(path, *bytes);
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
