// SPDX-License-Identifier: MIT
// Camera matrices for the renderer: an orbit camera turned into a view-projection matrix. Internal.
#pragma once

#include "supermodal/geometry.h"
#include "supermodal/math.h"
#include "supermodal/render.h"
#include "supermodal/scene.h"

#include <array>
#include <span>
#include <vector>

namespace supermodal
{
class World;
} // namespace supermodal

namespace supermodal::render
{

/// Every finite body's box at its current (or interpolated) pose, planes left out: what framing and
/// the blob shadows look at.
[[nodiscard]] std::vector<Aabb> body_boxes(const World& world, PoseSource poses = PoseSource::Current);
/// frame_bodies() over boxes already made (empty: a 2 m view of the origin).
[[nodiscard]] CameraDef frame_boxes(std::span<const Aabb> boxes, const CameraDef& camera, double aspect);

/// Column-major 4×4 float matrix, as GL wants it.
using Mat4 = std::array<float, 16>;

/// A resolved camera: where the eye is and the matrices of a frame.
struct View {
    Vec3 eye{}, target{};
    double distance = 1.0;  ///< |eye − target| [m].
    Vec3 forward{0, 0, -1}; ///< Unit, from the eye towards the target.
    double fy = 1.0;        ///< Projection's vertical scale: NDC y per unit of height over depth [-].
    Mat4 view_proj{};
};

/// world_from_shape as a GL matrix: rotation then translation.
[[nodiscard]] Mat4 model_matrix(const Vec3& position, const Quat& orientation);
/// View of an orbit camera whose target and distance are set; aspect = width / height.
[[nodiscard]] View make_view(const CameraDef& camera, double aspect, double scene_radius);

} // namespace supermodal::render
