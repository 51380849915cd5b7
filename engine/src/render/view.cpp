// SPDX-License-Identifier: MIT
// Orbit camera and body framing.
#include "render/view.h"

#include "supermodal/body.h"
#include "supermodal/geometry.h"
#include "supermodal/render.h"
#include "supermodal/world.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace supermodal
{
namespace
{

constexpr double k_deg = std::numbers::pi / 180.0;
// Room left around the framed bodies [-].
constexpr double k_frame_margin = 1.1;

} // namespace

CameraAxes camera_axes(const CameraDef& camera)
{
    const double yaw = camera.yaw_deg * k_deg, pitch = std::clamp(camera.pitch_deg, -89.0, 89.0) * k_deg;
    CameraAxes a;
    a.back = {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
    a.right = normalized(cross(-a.back, Vec3{0, 1, 0}));
    a.up = cross(a.right, -a.back);
    return a;
}

double framing_distance(const CameraDef& camera, const Vec3& target, std::span<const Aabb> boxes,
                        double aspect)
{
    // A corner at offset r from the target, seen from distance d, sits at depth d − r·back and needs
    // |r·right| ≤ depth·tan(half_h) and |r·up| ≤ depth·tan(half_v).
    const CameraAxes axes = camera_axes(camera);
    const double tan_v = std::tan(0.5 * std::clamp(camera.fov_deg, 1.0, 150.0) * k_deg);
    const double tan_h = tan_v * std::clamp(aspect, 0.1, 10.0);
    double d = 0.0;
    for (const Aabb& box : boxes)
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner{(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                              (k & 4) ? box.max.z : box.min.z};
            const Vec3 r = corner - target;
            d = std::max(d, dot(r, axes.back) + std::max(std::abs(dot(r, axes.right)) / tan_h,
                                                         std::abs(dot(r, axes.up)) / tan_v));
        }
    return std::max(d, 1e-3);
}

CameraDef frame_bodies(const World& world, const CameraDef& camera, double aspect)
{
    if (camera.target && camera.distance > 0.0)
        return camera;
    return render::frame_boxes(render::body_boxes(world), camera, aspect);
}

namespace render
{

std::vector<Aabb> body_boxes(const World& world, PoseSource poses)
{
    const bool interpolated = poses == PoseSource::Interpolated;
    std::vector<Aabb> out;
    for (Entity b : world_bodies(world)) {
        const ShapeDef& shape = body_shape(world, b);
        if (shape.type == ShapeType::Plane)
            continue;
        const Aabb box =
            world_aabb(shape, interpolated ? body_interpolated_position(world, b) : body_position(world, b),
                       interpolated ? body_interpolated_orientation(world, b) : body_orientation(world, b));
        if (!is_finite(box.min) || !is_finite(box.max))
            continue;
        out.push_back(box);
    }
    return out;
}

CameraDef frame_boxes(std::span<const Aabb> boxes, const CameraDef& camera, double aspect)
{
    CameraDef out = camera;
    if (out.target && out.distance > 0.0)
        return out;
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const Aabb& box : boxes)
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], box.min[i]);
            hi[i] = std::max(hi[i], box.max[i]);
        }
    const Aabb origin_view{{-1, -1, -1}, {1, 1, 1}}; // nothing to frame: a 2 m view of the origin
    if (boxes.empty()) {
        lo = origin_view.min;
        hi = origin_view.max;
        boxes = std::span(&origin_view, 1);
    }
    if (!out.target)
        out.target = 0.5 * (lo + hi);
    if (!(out.distance > 0.0))
        out.distance = k_frame_margin * framing_distance(camera, *out.target, boxes, aspect);
    return out;
}

Mat4 model_matrix(const Vec3& p, const Quat& q)
{
    const Mat3 r = to_mat3(q);
    Mat4 m{};
    for (int c = 0; c < 3; ++c)
        for (int rr = 0; rr < 3; ++rr)
            m[static_cast<size_t>(c * 4 + rr)] = static_cast<float>(r.m[rr][c]);
    m[12] = static_cast<float>(p.x);
    m[13] = static_cast<float>(p.y);
    m[14] = static_cast<float>(p.z);
    m[15] = 1.0f;
    return m;
}

View make_view(const CameraDef& camera, double aspect, double scene_radius)
{
    View v;
    v.target = camera.target.value_or(Vec3{});
    v.distance = std::max(camera.distance, 1e-3);
    const CameraAxes axes = camera_axes(camera);
    v.eye = v.target + v.distance * axes.back;
    // Right-handed look-at: f forward, s right, u up.
    const Vec3 f = -axes.back;
    const Vec3 s = axes.right;
    const Vec3 u = axes.up;
    // Near and far from the distance: the grid fades out by 12 distances, so nothing past that shows.
    const double near_plane = std::max(1e-3, 0.02 * v.distance);
    const double far_plane = 14.0 * v.distance + 2.0 * scene_radius;
    const double fy = 1.0 / std::tan(0.5 * std::clamp(camera.fov_deg, 1.0, 150.0) * k_deg);
    const double fx = fy / aspect;
    v.forward = f;
    v.fy = fy;
    // P · V written out. Eye coordinates: x_e = s·(p − eye), y_e = u·(p − eye), z_e = −f·(p − eye);
    // clip = (fx·x_e, fy·y_e, A·z_e + B, −z_e) with GL's A, B mapping [−near, −far] to [−1, 1].
    const double A = (far_plane + near_plane) / (near_plane - far_plane);
    const double B = 2.0 * far_plane * near_plane / (near_plane - far_plane);
    const double fe = dot(f, v.eye);
    const Vec3 rv[4] = {fx * s, fy * u, -A * f, f};
    const double tv[4] = {-fx * dot(s, v.eye), -fy * dot(u, v.eye), A * fe + B, -fe};
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 3; ++c)
            v.view_proj[static_cast<size_t>(c * 4 + r)] = static_cast<float>(rv[r][c]);
        v.view_proj[static_cast<size_t>(12 + r)] = static_cast<float>(tv[r]);
    }
    return v;
}

} // namespace render
} // namespace supermodal
