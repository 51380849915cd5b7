// SPDX-License-Identifier: MIT
// Mesh import: OBJ, PLY, STL, glTF/GLB, FBX (through assimp, a private dependency) into one
// TriangleMesh in metres, world frame Y-up, with every mesh of the file merged through
// its node transforms. See docs/pipeline.md.
#pragma once

#include "supermodal/api.h"
#include "supermodal/geometry.h"
#include "supermodal/result.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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
    /// Also read the look (ImportedMesh::look): texture coordinates and materials. Welding then keeps
    /// vertices with the same position apart where their texture coordinates differ (UV seams); their
    /// normals are still summed over every triangle at that position, so shading has no seam.
    bool keep_look = false;
};

/// The documented defaults: units and up axis from the file, welded vertices.
[[nodiscard]] SM_API ImportDef default_import_def();

/// A surface material of an imported mesh, in glTF's metallic-roughness terms.
struct MeshMaterial {
    std::string name;
    /// Linear RGBA in [0, 1]: glTF's baseColorFactor, or OBJ/FBX diffuse colour (Kd) with opacity (d).
    std::array<double, 4> base_color{1.0, 1.0, 1.0, 1.0};
    /// Image of the base colour (glTF baseColorTexture, OBJ map_Kd) as a path on disk, resolved against
    /// the mesh file's folder; empty for none. Images embedded in the mesh file are not read.
    std::string base_color_texture;
};

/// What a renderer or an exporter needs beyond the triangles (ImportDef::keep_look).
struct MeshLook {
    /// Per vertex (u, v), 2 numbers each, with v up from the image's bottom row (OBJ's convention;
    /// glTF's v runs down, exporters flip it). Empty when the file has none.
    std::vector<double> texcoords;
    std::vector<MeshMaterial> materials; ///< Materials the triangles use; empty when the file names none.
    std::vector<uint32_t> triangle_materials; ///< Per triangle, an index into materials (empty with them).
};

/// An imported mesh and what the import decided.
struct ImportedMesh {
    TriangleMesh mesh;             ///< All meshes merged, metres, world frame (Y-up).
    double scale = 1.0;            ///< Metres per file unit that was applied.
    UpAxis up_axis = UpAxis::PosY; ///< The file up axis that was mapped to +Y.
    int source_meshes = 0;         ///< Mesh instances (node × mesh) merged.
    std::string format;            ///< Lower-case file extension, e.g. "obj".
    MeshLook look;                 ///< Texture coordinates and materials, with ImportDef::keep_look.
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
