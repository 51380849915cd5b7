// SPDX-License-Identifier: MIT
// Surface samples and meshes of hyperquadric shapes, for sampling.cpp and tessellate.cpp. A hyperquadric
// with every γ ≥ 1 is convex, so it is star-shaped about an interior point: both functions cast rays from
// that point over a cube-sphere grid and root-find H = 1 along each ray (docs/geometry.md).
#pragma once

#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <vector>

namespace supermodal
{

/// Surface samples of a hyperquadric shape (shape.type == ShapeType::Hyperquadric), about `spacing` [m]
/// apart, with areas [m²] that sum to the surface area; at most max_count samples (spacing widens to fit).
[[nodiscard]] std::vector<SurfaceSample> sample_hyperquadric_surface(const ShapeDef& shape, double spacing,
                                                                     int max_count);

/// Watertight mesh of a hyperquadric shape with about `resolution` segments around its equator (≥ 4).
[[nodiscard]] TriangleMesh tessellate_hyperquadric(const ShapeDef& shape, int resolution);

} // namespace supermodal
