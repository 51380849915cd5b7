// SPDX-License-Identifier: MIT
// Pixels to rays and back for the frames render() draws: mouse picking in the editor. The ray is built
// from the orbit camera's axes and field of view; the projection goes through the very matrix the
// renderer draws with, so a test of one against the other checks both.
#include "render/view.h"
#include "supermodal/render.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace supermodal
{
namespace
{

double aspect_of(int width, int height)
{
    return static_cast<double>(std::max(width, 1)) / std::max(height, 1);
}

} // namespace

CameraRay camera_ray(const World& world, const CameraDef& camera_in, int width, int height, double x,
                     double y)
{
    const double aspect = aspect_of(width, height);
    const CameraDef camera = frame_bodies(world, camera_in, aspect);
    const CameraAxes axes = camera_axes(camera);
    const Vec3 target = camera.target.value_or(Vec3{});
    const Vec3 eye = target + std::max(camera.distance, 1e-3) * axes.back;
    // Normalised device coordinates of the pixel, then the view-space direction at unit depth.
    const double ndc_x = 2.0 * x / std::max(width, 1) - 1.0;
    const double ndc_y = 1.0 - 2.0 * y / std::max(height, 1);
    const double tan_v = std::tan(0.5 * std::clamp(camera.fov_deg, 1.0, 150.0) * std::numbers::pi / 180.0);
    const Vec3 dir = -axes.back + (ndc_x * tan_v * aspect) * axes.right + (ndc_y * tan_v) * axes.up;
    return {eye, normalized(dir)};
}

std::optional<std::array<double, 2>> project_to_pixel(const World& world, const CameraDef& camera_in,
                                                      int width, int height, const Vec3& point)
{
    const double aspect = aspect_of(width, height);
    const CameraDef camera = frame_bodies(world, camera_in, aspect);
    const CameraDef framed =
        frame_bodies(world, CameraDef{.target = std::nullopt, .fov_deg = camera.fov_deg}, aspect);
    const render::View view = render::make_view(camera, aspect, framed.distance);
    const auto& m = view.view_proj; // column-major
    const auto row = [&](int r) {
        return m[static_cast<size_t>(r)] * point.x + m[static_cast<size_t>(4 + r)] * point.y +
               m[static_cast<size_t>(8 + r)] * point.z + m[static_cast<size_t>(12 + r)];
    };
    const double w = row(3);
    if (!(w > 0.0))
        return std::nullopt;
    const double ndc_x = row(0) / w, ndc_y = row(1) / w;
    return std::array<double, 2>{0.5 * (ndc_x + 1.0) * width, 0.5 * (1.0 - ndc_y) * height};
}

} // namespace supermodal
