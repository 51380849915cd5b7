// SPDX-License-Identifier: MIT
// Vertex welding for imported meshes.
#pragma once

#include "supermodal/geometry.h"

namespace supermodal
{

/// Merges vertices at bit-identical positions (first appearance keeps its index order), drops
/// triangles that collapse to fewer than three distinct vertices, and sets each normal to the
/// normalised area-weighted sum of its triangles' normals (+y where that sum vanishes).
[[nodiscard]] TriangleMesh weld_mesh(const TriangleMesh& mesh);

} // namespace supermodal
