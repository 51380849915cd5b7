// SPDX-License-Identifier: MIT
// Mesh import: OBJ, PLY, STL, glTF/GLB, FBX (through assimp, a private dependency) into one
// TriangleMesh in metres, world frame Y-up (DESIGN.md §3), with every mesh of the file merged through
// its node transforms. See docs/pipeline.md.
#pragma once

#include "supermodal/api.h"
#include "supermodal/geometry.h"
#include "supermodal/result.h"

#include <cstdint>
#include <string>

namespace supermodal
{

/// Which axis of the file points up (it becomes world +Y by a proper rotation).
enum class UpAxis : uint8_t { FromFile, PosX, PosY, PosZ, NegX, NegY, NegZ };

/// How to import a mesh file. Start from default_import_def().
struct ImportDef {
    /// Metres per file unit; 0 takes it from the file: FBX's UnitScaleFactor (centimetres per unit,
    /// so 1 → 0.01 m), glTF's metres by specification, and 1 (metres) for formats without units
    /// (OBJ, PLY, STL). Must be finite and ≥ 0.
    double scale = 0.0;
    /// The file's up axis; FromFile reads FBX's UpAxis/UpAxisSign, glTF is Y-up by specification, and
    /// formats without the information are taken as Y-up.
    UpAxis up_axis = UpAxis::FromFile;
    /// Merge vertices at bit-identical positions (after transforms) and recompute normals as
    /// area-weighted face normals; otherwise keep the file's vertices and normals (missing ones are
    /// generated). Welding makes a per-face-normal STL a connected mesh.
    bool weld_vertices = true;
};

/// The documented defaults: units and up axis from the file, welded vertices.
[[nodiscard]] SM_API ImportDef default_import_def();

/// An imported mesh and what the import decided.
struct ImportedMesh {
    TriangleMesh mesh;             ///< All meshes merged, metres, world frame (Y-up).
    double scale = 1.0;            ///< Metres per file unit that was applied.
    UpAxis up_axis = UpAxis::PosY; ///< The file up axis that was mapped to +Y.
    int source_meshes = 0;         ///< Mesh instances (node × mesh) merged.
    std::string format;            ///< Lower-case file extension, e.g. "obj".
};

/// Reads a mesh file. Errors (Error::file is the path) for a missing or unreadable file, a file
/// assimp cannot parse (its message is passed on), a file without triangles, non-finite coordinates,
/// and bad ImportDef values.
[[nodiscard]] SM_API Result<ImportedMesh> import_mesh(const std::string& path,
                                                      const ImportDef& def = default_import_def());

/// Lower-case name of an up axis: "from_file", "+x", "+y", "+z", "-x", "-y", "-z".
[[nodiscard]] SM_API const char* up_axis_name(UpAxis axis);
/// Parses an up_axis_name() (also "x", "y", "z" for the positive axes); false when unknown.
[[nodiscard]] SM_API bool parse_up_axis(const std::string& name, UpAxis& out);

} // namespace supermodal
