// SPDX-License-Identifier: MIT
// Body colours from a scene: one hue per material, a little lighter or darker per body. The renderer
// draws them and the GLB export writes them as base colours.
#include "supermodal/scene.h"

#include <cmath>
#include <cstdint>
#include <string_view>

namespace supermodal
{
namespace
{

struct Named {
    std::string_view name;
    Vec3 rgb;
};
// Hues for the materials the samples use; others get a hue from a hash of their name.
constexpr Named k_named[] = {
    {"wood", {0.76, 0.55, 0.34}},   {"steel", {0.66, 0.69, 0.74}},   {"flesh", {0.93, 0.74, 0.62}},
    {"rubber", {0.30, 0.32, 0.36}}, {"plastic", {0.35, 0.60, 0.85}},
};
constexpr Vec3 k_palette[] = {{0.40, 0.62, 0.86}, {0.90, 0.55, 0.35}, {0.50, 0.75, 0.45}, {0.85, 0.45, 0.55},
                              {0.65, 0.55, 0.85}, {0.90, 0.78, 0.35}, {0.40, 0.75, 0.75}, {0.75, 0.60, 0.45}};
constexpr size_t k_palette_size = sizeof k_palette / sizeof k_palette[0];

Vec3 material_color(std::string_view name, size_t body_index)
{
    if (name.empty()) // no material: one palette colour per body
        return k_palette[body_index % k_palette_size];
    for (const Named& n : k_named)
        if (n.name == name)
            return n.rgb;
    uint32_t h = 2166136261u; // FNV-1a: stable across runs and platforms
    for (char c : name)
        h = (h ^ static_cast<uint8_t>(c)) * 16777619u;
    return k_palette[h % k_palette_size];
}

} // namespace

std::vector<Vec3> scene_body_colors(const Scene& scene)
{
    std::vector<Vec3> out;
    out.reserve(scene.bodies.size());
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const Vec3 base = material_color(scene.bodies[i].material, i);
        // ±7% brightness in a three-step cycle so neighbouring parts of one material stay apart.
        const double shade = 1.0 + 0.07 * (static_cast<double>(i % 3) - 1.0);
        out.push_back(
            {std::fmin(base.x * shade, 1.0), std::fmin(base.y * shade, 1.0), std::fmin(base.z * shade, 1.0)});
    }
    return out;
}

} // namespace supermodal
