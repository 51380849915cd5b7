// SPDX-License-Identifier: MIT
// Where the sky has to be drawn: the viewport minus the ground grid's projected square. Internal.
#pragma once

#include <array>
#include <vector>

namespace supermodal::render
{

/// A point in clip space (x, y, z, w), as the view-projection matrix gives it.
using ClipPoint = std::array<double, 4>;

/// Triangles in NDC (x, y per corner, three corners per triangle) that cover the viewport square
/// [−1, 1]² except the convex planar polygon `ground` (corners in order, clip space). The polygon is
/// cut to the near and far planes first, as GL would. The triangles do not overlap; they reach
/// `margin` (NDC units) into the polygon, so rounding at its edges leaves no pixel uncovered. With
/// fewer than three corners left after the cut, one triangle covers the whole viewport.
[[nodiscard]] std::vector<float> sky_triangles(const std::vector<ClipPoint>& ground, double margin);

} // namespace supermodal::render
