// SPDX-License-Identifier: MIT
// Vertex welding for imported meshes.
#pragma once

#include "supermodal/geometry.h"
#include "supermodal/mesh_io.h"

namespace supermodal
{

/// Merges vertices at bit-identical positions (first appearance keeps its index order), drops
/// triangles that collapse to fewer than three distinct positions, and sets each normal to the
/// normalised area-weighted sum of the triangles at its position (+y where that sum vanishes).
/// With a look that has texture coordinates, vertices at one position stay apart where their (u, v)
/// differ; `look` is rewritten to match the welded mesh (texcoords per vertex, triangle_materials per
/// kept triangle).
[[nodiscard]] TriangleMesh weld_mesh(const TriangleMesh& mesh, MeshLook* look = nullptr);

} // namespace supermodal
