// SPDX-License-Identifier: MIT
// Scene files, format v1 (docs/scene_format.md): JSON → Scene (plain data) → World.
// Every error names the file, the JSON pointer, what was found and what was expected.
#pragma once

#include "supermodal/api.h"
#include "supermodal/body.h"
#include "supermodal/constraint.h"
#include "supermodal/geometry.h"
#include "supermodal/mesh_io.h"
#include "supermodal/result.h"
#include "supermodal/world.h"

#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal
{

/// A named material. Contact and modal fields are read and checked now, used by later stages.
struct MaterialDef {
    std::string name;
    double density = 1000.0;         ///< [kg/m³], > 0.
    double young = 1e9;              ///< Young's modulus [Pa], > 0.
    double poisson = 0.3;            ///< Poisson's ratio [-], in (−1, 0.5).
    double friction = 0.5;           ///< Coulomb coefficient [-], ≥ 0.
    double restitution = 0.2;        ///< [-], in [0, 1].
    double rolling_resistance = 0.0; ///< Rolling lever arm [m], ≥ 0 (BodyDef::rolling_resistance).
    double damping_ratio = 0.01;     ///< Modal damping ratio [-], ≥ 0.
    double yield_stress = std::numeric_limits<double>::infinity(); ///< von Mises yield [Pa], > 0.
    double hardening = 0.0; ///< Linear hardening modulus [Pa], ≥ 0 (modal plasticity).
    double max_plastic_strain = std::numeric_limits<double>::infinity(); ///< Plastic flow limit [-], > 0.
    /// Rest-shape change [-], ≥ 0, past which a plastic body's modes are rebuilt for its moulded shape
    /// (ModalBodyDef::remould_threshold); 0: never.
    double remould_threshold = 0.02;
};

/// How a scene body deforms: rigid, modal (BodyDef::modal, from "dynamics" and the material), or auto:
/// modal with adaptive modes (ModalBodyDef::adaptive_tolerance = the scene's accuracy budget), so it
/// stays rigid until its loads need modes. Auto on a body that cannot be modal (static, kinematic, a
/// plane) is rigid. Full: modal with every elastic mode of the lattice (ModalBodyDef::mode_count =
/// k_all_modes): nothing truncated, the reference the modal trade is measured against.
enum class DynamicsType : uint8_t { Rigid, Modal, Auto, Full };

/// A scene's error budget (settings "accuracy"), for bodies with "dynamics": "auto".
struct AccuracyDef {
    double displacement = 1e-3; ///< Surface displacement an auto body may leave out [m], > 0.
};

/// One body of a scene: its BodyDef plus the scene-level fields.
struct SceneBody {
    BodyDef def;
    std::string material; ///< Material name, or empty for the default material.
    DynamicsType dynamics = DynamicsType::Rigid;
    std::string parent; ///< Parent body's name, or empty. Then def's pose and velocities are in the
                        ///< parent's frame (relative to its shape origin), resolved by build_world().
    /// Render mesh file ("mesh"), relative to the scene file's folder (as written; an included file's
    /// path is rebased onto the including file's folder), or empty. Not physics: exporters draw it
    /// instead of the tessellation, deformed by the body's modes.
    std::string mesh;
    /// The mesh, read by load_scene/parse_scene through import_mesh (metres, body frame = shape frame),
    /// shared between copies of the scene; null when `mesh` is empty.
    std::shared_ptr<const TriangleMesh> render_mesh;
    /// The mesh's texture coordinates and materials (per render_mesh vertex and triangle); null when
    /// `mesh` is empty or the file has neither.
    std::shared_ptr<const MeshLook> render_look = nullptr;
};

/// One constraint of a scene: its def with the bodies named (b empty = the world).
struct SceneConstraint {
    ConstraintDef def; ///< def.a and def.b are filled in by build_world().
    std::string body_a;
    std::string body_b;
};
/// An orbit camera (scene "camera"; docs/scene_format.md): it looks at `target` from `distance` away,
/// turned by yaw about the world's Y axis and raised by pitch above the horizon. World is Y-up.
struct CameraDef {
    std::optional<Vec3> target; ///< Point looked at [m], world; absent: the centre of the bodies' bounds.
    double distance = 0.0;      ///< From target to the eye [m], ≥ 0; 0: far enough to frame every body.
    double yaw_deg = 30.0;      ///< About +Y [°]; 0 looks from +Z towards −Z, 90 from +X.
    double pitch_deg = 20.0;    ///< Above the horizon [°], in [−89, 89]; positive looks down.
    double fov_deg = 40.0;      ///< Vertical field of view [°], in [1, 150].
};

/// A parsed, validated scene.
struct Scene {
    std::string source; ///< File it came from, or "<string>".
    WorldDef world = default_world_def();
    double duration = 5.0;                    ///< Default run length [s], > 0.
    AccuracyDef accuracy;                     ///< Error budget of "auto" bodies.
    std::vector<MaterialDef> materials;       ///< In file order.
    std::vector<SceneBody> bodies;            ///< In file order; creation order in the world.
    std::vector<SceneConstraint> constraints; ///< In file order, created after the bodies.
    CameraDef camera;                         ///< How renderers look at the scene (not physics).
};

/// A value put into the scene JSON before it is read (`supermodal run --set`), so that it is checked
/// like the file's own values. The value at `pointer` is replaced; a missing member of an existing
/// object is added. Applied to the file's own JSON (not to its includes), in order.
struct SceneOverride {
    /// JSON pointer (RFC 6901), "/materials/steel/density"; "~1" stands for "/" and "~0" for "~" in
    /// a key. Array elements must exist (0 to size − 1); the parent of the target must exist.
    std::string pointer;
    std::string value; ///< JSON text of the value: "2.5", "[0, 1, 0]", "\"steel\"".
};

/// Reads and validates a scene file.
[[nodiscard]] SM_API Result<Scene> load_scene(const std::string& path);
/// Reads a scene file, applies the overrides to its JSON, then validates. An override that cannot be
/// applied fails with Error::where = its pointer; the scene is not read.
[[nodiscard]] SM_API Result<Scene> load_scene(const std::string& path,
                                              std::span<const SceneOverride> overrides);
/// Parses and validates scene JSON text; `source` names it in errors.
[[nodiscard]] SM_API Result<Scene> parse_scene(std::string_view json_text,
                                               const std::string& source = "<string>");
/// parse_scene with overrides applied before validation, as load_scene.
[[nodiscard]] SM_API Result<Scene> parse_scene(std::string_view json_text, const std::string& source,
                                               std::span<const SceneOverride> overrides);
/// Makes a world holding the scene's bodies and then its constraints, created in file order.
[[nodiscard]] SM_API Result<World> build_world(const Scene& scene);

// ---- Writing scenes (engine/src/scene/writer.cpp) --------------------------------------------------

/// Colours for a scene's bodies in world_bodies() order: one hue per material (wood, steel, ...),
/// lightened or darkened a little per body so touching parts stay apart; RGB in [0, 1]. The renderer
/// draws them; the GLB export writes them as base colours.
[[nodiscard]] SM_API std::vector<Vec3> scene_body_colors(const Scene& scene);

/// Scene JSON, format v1, that parse_scene() reads back to an identical Scene: includes flattened
/// (materials, bodies and constraints inline, names prefixed), parents kept, every number in its
/// shortest text that reads back to the same double. Young's modulus, Poisson's ratio and (unless the
/// body's own differs) the damping ratio of a modal body are its material's, as in the file format;
/// BodyDef::friction and restitution are not written (build_world takes them from the material).
[[nodiscard]] SM_API std::string scene_to_json(const Scene& scene);
/// Writes scene_to_json(scene) to `path` atomically: a temporary file in the same folder, flushed,
/// then renamed over `path`, so a reader never sees half a file and a failure leaves `path` as it was.
[[nodiscard]] SM_API Status save_scene(const Scene& scene, const std::string& path);
/// Copies what a running world holds back into its scene so that saving keeps what the user sees:
/// every scene body's pose and velocities (in its parent's frame for parts, as the format wants) and,
/// when `include_shapes`, its current shape (after set_body_shape()). Bodies are matched by name.
/// Modal amplitudes and contact caches are not part of format v1 and are not kept. Fails, changing
/// nothing, when a scene body has no body of that name in the world.
[[nodiscard]] SM_API Status refresh_scene_from_world(Scene& scene, const World& world,
                                                     bool include_shapes = true);

} // namespace supermodal
