// SPDX-License-Identifier: MIT
// Data preparation for the fit: area-weighted points of a mesh surface, thinning, and moments.
#pragma once

#include "fit/fit_model.h"

namespace supermodal::fit
{

/// Mesh vertices weighted by a third of each adjacent triangle's area, plus evenly spread samples
/// inside triangles larger than (mean spacing)², spacing = √(area / target_count). Weights sum to 1.
/// Empty when the mesh has no area.
[[nodiscard]] WeightedPoints mesh_surface_points(const TriangleMesh& mesh, int target_count);
/// Every k-th point so at most max_count remain, weights renormalised to sum 1.
[[nodiscard]] WeightedPoints thin(const WeightedPoints& data, int max_count);

/// Weighted centroid and principal axes of the points.
struct Moments {
    Vec3 centroid{};
    Mat3 axes = Mat3::identity(); ///< Columns: principal directions, largest variance first; det +1.
    double rms_radius = 0.0;      ///< √(Σ w·|p − centroid|²) [m].
};
[[nodiscard]] Moments moments(const WeightedPoints& data);

} // namespace supermodal::fit
