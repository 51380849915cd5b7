// SPDX-License-Identifier: MIT
// Animation export (docs/pipeline.md "Export"): step a world, sample every body's pose and modal
// amplitudes at a frame rate, and write them as glTF 2.0 binary (GLB) with morph targets for the modes,
// or as a sequence of OBJ files. Meshes are the engine's tessellation in the shape frame (the frame of
// BodyDef::shape and body_position / body_orientation); planes are left out.
#pragma once

#include "supermodal/api.h"
#include "supermodal/geometry.h"
#include "supermodal/math.h"
#include "supermodal/mesh_io.h"
#include "supermodal/result.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace supermodal
{

class World;

/// How to sample and mesh an export. Start from default_export_def().
struct ExportDef {
    double seconds = 1.0;      ///< Simulated time to record [s], in (0, 3600].
    double fps = 30.0;         ///< Samples per second [1/s], in (0, 1/dt]: every sample is a distinct step.
    int tessellation = 32;     ///< Segments around a body's equator, in [8, 512] (as RenderDef).
    bool morph_targets = true; ///< Modal bodies: one morph target per mode; false exports them rigid.
};
/// 1 s at 30 frames per second, 32 segments, morph targets on.
[[nodiscard]] SM_API ExportDef default_export_def();
/// Checks the ranges in the field comments (the fps bound against a world's dt is checked by
/// record_animation).
[[nodiscard]] SM_API Status validate(const ExportDef& def);

/// One exported body: its rest mesh and its sampled motion.
struct ExportBody {
    std::string name;  ///< Body name, or "body_<index>" when it has none.
    TriangleMesh mesh; ///< Rest tessellation [m], shape frame.
    /// (r) per mode k, the displacement of every mesh vertex for q_k = 1 √kg·m [m/(√kg·m)], shape frame:
    /// the morph targets. Empty for rigid bodies (or ExportDef::morph_targets off).
    std::vector<std::vector<Vec3>> mode_displacements;
    std::vector<double> frequencies_hz; ///< (r) the modes' frequencies, for target names.
    std::vector<Vec3> positions;        ///< Per sample, body_position (shape origin) [m], world.
    std::vector<Quat> orientations;     ///< Per sample, world_from_body, sign kept continuous.
    std::vector<double> amplitudes;     ///< Per sample, r modal amplitudes q [√kg·m] (frame-major).
    /// The mesh's texture coordinates and materials (an artist's mesh, ExportBodyMesh::look); empty for
    /// a tessellation. The GLB writes one primitive per material, and TEXCOORD_0 when it has (u, v).
    MeshLook look{};
    /// Linear RGB in [0, 1]: the GLB material of a body whose look has no materials (a scene's
    /// bodies take scene_body_colors(), as the renderer draws them).
    Vec3 base_color{0.8, 0.8, 0.8};
};

/// A recorded run: sample times and the bodies (world_bodies order, planes left out).
struct ExportRecording {
    std::vector<double> times; ///< Sample times [s] from the start of the recording, increasing.
    std::vector<ExportBody> bodies;
};

/// An artist's mesh to export for a body instead of its tessellation (SceneBody::render_mesh).
struct ExportBodyMesh {
    std::string body;                         ///< Body name.
    std::shared_ptr<const TriangleMesh> mesh; ///< Vertices [m] in the body's shape frame.
    /// Its texture coordinates and materials (SceneBody::render_look), or null.
    std::shared_ptr<const MeshLook> look = nullptr;
};

/// Builds the meshes, then steps `world` for def.seconds, sampling at each step nearest k/fps (k = 0 is
/// the state before the first step). A body named in `meshes` exports that mesh, its vertices deformed
/// through the body's modal field like the tessellation's (lattice shape functions; vertices outside
/// the lattice take the field of the nearest lattice point). Errors: invalid def, fps above the world's
/// step rate, a world with nothing but planes, a mesh for no such body or an empty one, a non-finite
/// pose or amplitude (a diverging run), all with the body named.
[[nodiscard]] SM_API Result<ExportRecording> record_animation(World& world, const ExportDef& def,
                                                              std::span<const ExportBodyMesh> meshes = {});

/// The GLB bytes of a recording: one node and mesh per body, one animation "simulation" with LINEAR
/// translation, rotation and (modal bodies) morph-target weight channels. Materials are glTF
/// metallic-roughness ones (metallic 0, roughness 1): the look's, with their base colour images
/// embedded (PNG or JPEG), or one of base_color per body. Errors: inconsistent sizes, a value that
/// does not fit a float, a texture that cannot be read or is neither PNG nor JPEG.
[[nodiscard]] SM_API Result<std::vector<uint8_t>> glb_from_recording(const ExportRecording& recording);
/// Writes glb_from_recording() to `path` atomically (temporary file in the same folder, then rename).
[[nodiscard]] SM_API Status write_glb(const ExportRecording& recording, const std::string& path);
/// Writes one OBJ per sample, `dir`/frame_000000.obj, ..., each with every body's deformed mesh in the
/// world frame ("o name" groups); `dir` is made if missing; each file is written atomically.
[[nodiscard]] SM_API Status write_obj_sequence(const ExportRecording& recording, const std::string& dir);

/// A body's mesh vertex at sample `frame`, deformed by its modes and posed [m], world frame: what a
/// glTF viewer shows (in double precision). Needs frame < times.size() and vertex < the mesh's vertex count.
[[nodiscard]] SM_API Vec3 exported_vertex(const ExportBody& body, size_t frame, size_t vertex);

} // namespace supermodal
