// SPDX-License-Identifier: MIT
// Camera matrices for the renderer: an orbit camera turned into a view-projection matrix. Internal.
#pragma once

#include "supermodal/math.h"
#include "supermodal/scene.h"

#include <array>

namespace supermodal::render
{

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
