// SPDX-License-Identifier: MIT
#include "camera.h"

#include "supermodal/body.h"
#include "supermodal/world.h"
#include "ui.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace supermodal::editor
{
namespace
{

constexpr double k_deg = std::numbers::pi / 180.0;
// The renderer's ranges (engine/src/render/view.cpp): pitch, and the vertical field of view [°].
constexpr double k_max_pitch = 89.0;
constexpr double k_min_fov = 1.0, k_max_fov = 150.0;

double tan_half_fov(const CameraDef& camera)
{
    return std::tan(0.5 * std::clamp(camera.fov_deg, k_min_fov, k_max_fov) * k_deg);
}

/// framing_distance() times margin (≥ 1).
double fit_distance(const CameraDef& camera, const Vec3& target, std::span<const Aabb> boxes, double aspect,
                    double margin)
{
    return std::max(margin, 1.0) * framing_distance(camera, target, boxes, aspect);
}

/// The boxes, or a 2 m cube at the origin when there are none (nothing to frame).
std::vector<Aabb> boxes_or_default(std::span<const Aabb> boxes)
{
    if (boxes.empty())
        return {Aabb{{-1, -1, -1}, {1, 1, 1}}};
    return {boxes.begin(), boxes.end()};
}

Vec3 centre_of(std::span<const Aabb> boxes)
{
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const Aabb& b : boxes)
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], b.min[i]);
            hi[i] = std::max(hi[i], b.max[i]);
        }
    return 0.5 * (lo + hi);
}

} // namespace

Vec3 camera_eye(const CameraDef& camera)
{
    return camera.target.value_or(Vec3{}) + camera.distance * camera_axes(camera).back;
}

CameraDef orbit(const CameraDef& camera, double yaw_deg, double pitch_deg)
{
    CameraDef out = camera;
    out.yaw_deg = std::remainder(camera.yaw_deg + yaw_deg, 360.0);
    out.pitch_deg = std::clamp(camera.pitch_deg + pitch_deg, -k_max_pitch, k_max_pitch);
    return out;
}

CameraDef pan_pixels(const CameraDef& camera, double dx, double dy, double view_height)
{
    // At the target's depth one pixel spans 2·d·tan(fov/2) / height metres.
    const double metres_per_px = 2.0 * camera.distance * tan_half_fov(camera) / std::max(view_height, 1.0);
    const CameraAxes axes = camera_axes(camera);
    CameraDef out = camera;
    // The scene follows the cursor: the camera moves the other way (y is down on screen).
    out.target = camera.target.value_or(Vec3{}) - metres_per_px * (dx * axes.right - dy * axes.up);
    return out;
}

CameraDef zoom_towards(const CameraDef& camera, const Vec3& point, double factor,
                       const CameraControlDef& control)
{
    if (!(factor > 0.0) || !std::isfinite(factor) || !(camera.distance > 0.0))
        return camera;
    const double distance =
        std::clamp(camera.distance * factor, control.min_distance, std::max(control.max_distance, 1e-3));
    const double s = distance / camera.distance;
    // eye' = point + s·(eye − point) with the same axes: the direction from the eye to `point`, hence
    // its pixel, does not change.
    CameraDef out = camera;
    const Vec3 target = camera.target.value_or(Vec3{});
    out.target = point + s * (target - point);
    out.distance = distance;
    return out;
}

CameraDef frame_boxes(const CameraDef& camera, std::span<const Aabb> boxes_in, double aspect, double margin)
{
    const std::vector<Aabb> boxes = boxes_or_default(boxes_in);
    CameraDef out = camera;
    out.target = centre_of(boxes);
    out.distance = fit_distance(camera, *out.target, boxes, aspect, margin);
    return out;
}

CameraDef frame_scene_camera(const CameraDef& scene_camera, std::span<const Aabb> boxes_in, double aspect,
                             double margin)
{
    if (scene_camera.target && scene_camera.distance > 0.0)
        return scene_camera;
    const std::vector<Aabb> boxes = boxes_or_default(boxes_in);
    CameraDef out = scene_camera;
    if (!out.target)
        out.target = centre_of(boxes);
    if (!(out.distance > 0.0))
        out.distance = fit_distance(scene_camera, *out.target, boxes, aspect, margin);
    return out;
}

Ray view_ray(const CameraDef& camera, double width, double height, double x, double y)
{
    const double w = std::max(width, 1.0), h = std::max(height, 1.0);
    const CameraAxes axes = camera_axes(camera);
    const double tan_v = tan_half_fov(camera);
    const double ndc_x = 2.0 * x / w - 1.0, ndc_y = 1.0 - 2.0 * y / h;
    const Vec3 dir = -axes.back + (ndc_x * tan_v * (w / h)) * axes.right + (ndc_y * tan_v) * axes.up;
    return {camera_eye(camera), normalized(dir)};
}

std::optional<ViewPixel> view_pixel(const CameraDef& camera, double width, double height, const Vec3& point)
{
    const double w = std::max(width, 1.0), h = std::max(height, 1.0);
    const CameraAxes axes = camera_axes(camera);
    const Vec3 v = point - camera_eye(camera);
    const double depth = -dot(v, axes.back);
    if (!(depth > 0.0))
        return std::nullopt;
    const double tan_v = tan_half_fov(camera);
    const double ndc_x = dot(v, axes.right) / (depth * tan_v * (w / h));
    const double ndc_y = dot(v, axes.up) / (depth * tan_v);
    return ViewPixel{0.5 * (ndc_x + 1.0) * w, 0.5 * (1.0 - ndc_y) * h, depth};
}

std::optional<Aabb> body_box(const World& world, Entity body)
{
    if (!world_valid(world, body))
        return std::nullopt;
    const ShapeDef& shape = body_shape(world, body);
    if (shape.type == ShapeType::Plane)
        return std::nullopt;
    const Aabb box = world_aabb(shape, body_position(world, body), body_orientation(world, body));
    if (!is_finite(box.min) || !is_finite(box.max))
        return std::nullopt;
    return box;
}

std::vector<Aabb> body_boxes(const World& world)
{
    std::vector<Aabb> boxes;
    for (Entity b : world_bodies(world))
        if (const std::optional<Aabb> box = body_box(world, b))
            boxes.push_back(*box);
    return boxes;
}

const CameraDef& editor_camera(const EditorSession& session, EditorUi& ui)
{
    const ScreenRect& v = ui.viewport();
    const double aspect = static_cast<double>(v.width()) / std::max(v.height(), 1.0f);
    const bool loaded = ui.view_loads != session.loads();
    const bool changed = ui.view_generation != session.generation() || ui.view_aspect != aspect;
    if (!ui.view_camera || loaded || (changed && !ui.view_moved)) {
        ui.view_camera = frame_scene_camera(session.scene().camera, body_boxes(session.world()), aspect);
        ui.view_moved = false;
    }
    ui.view_loads = session.loads();
    ui.view_generation = session.generation();
    ui.view_aspect = aspect;
    return *ui.view_camera;
}

} // namespace supermodal::editor
