// SPDX-License-Identifier: MIT
// The editor's model: a scene (what the user edits and saves) and the world running it. Everything the
// UI and the script runner do goes through here, so both behave the same and tests need no pixels.
#pragma once

#include "supermodal/constraint.h"
#include "supermodal/entity.h"
#include "supermodal/math.h"
#include "supermodal/modal.h"
#include "supermodal/result.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <deque>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace supermodal::editor
{

using Json = nlohmann::ordered_json;

/// A ray in the world frame: origin [m] and direction (any length > 0).
struct Ray {
    Vec3 origin{};
    Vec3 direction{0, 0, -1};
};

/// Where a ray first enters a body.
struct PickHit {
    Entity body{};
    std::string name;
    double distance = 0.0; ///< Along the unit ray direction [m].
    Vec3 point{};          ///< Hit point [m], world.
    Vec3 point_shape{};    ///< The same point in the body's shape frame [m] (rest shape).
};

/// How the last set() reached the world.
enum class SetEffect : uint8_t {
    Live,    ///< Applied to the running world (set_body_shape on rigid bodies): the run goes on.
    Rebuilt, ///< The world was rebuilt from the edited scene at the current poses and velocities.
};

/// A spring pulling a body-fixed point towards a target while the user drags it.
struct DragSpring {
    Entity body{};
    Vec3 point_shape{};         ///< Grabbed point, shape frame [m].
    Vec3 target{};              ///< Where the mouse is [m], world.
    double frequency_hz = 4.0;  ///< Natural frequency against the body's mass [Hz]: soft enough to
                                ///< feel like a spring, far below the 1/(10·dt) stability cap.
    double damping_ratio = 0.7; ///< [-]; 0.7 settles without ringing.
};

/// How a mode shape is shown: one body swinging in one of its modes while the world is held still.
struct ModeAnimationDef {
    int mode = 0;               ///< Index into the body's modes, 0 = the lowest [-].
    double peak_fraction = 0.1; ///< Largest lattice-node displacement of the swing, as a fraction of the
                                ///< body's largest half-extent (its lattice box) [-]: visible, still small.
    double period = 1.0;        ///< Wall time of one shown swing [s]: a mode's own period (milliseconds
                                ///< for a wooden board) is far too short to watch.
};

/// A mode animation running: q_k = q_k,0 + amplitude · sin(2π time / period), every other amplitude
/// and rate kept at what it was when the animation began.
struct ModeAnimation {
    Entity body{};
    std::string name;
    int mode = 0;                   ///< [-], 0 = the lowest.
    double frequency_hz = 0.0;      ///< The mode's natural frequency [Hz].
    double amplitude = 0.0;         ///< Swing of q_k [√kg·m].
    double peak_displacement = 0.0; ///< Largest lattice-node displacement at the swing's peak [m].
    double period = 1.0;            ///< [s], wall time.
    double time = 0.0;              ///< Wall time animated so far [s].
    ModalAccuracy accuracy;         ///< The body's accuracy report when it began (the swing is no load).
};

/// One applied set(): enough to undo and redo it.
struct SceneEdit {
    std::string path;           ///< As given to set() (body names allowed).
    std::string resolved;       ///< With indices: replayed after a rename too.
    std::optional<Json> before; ///< The value there before; nothing when set() added the key.
    Json after;                 ///< The value set.
    bool joined = false;        ///< Undone and redone together with the edit before it (one transform).
};

/// Steps a snapped transform rounds to.
struct SnapDef {
    double move_step = 0.05;     ///< Translation, per world axis [m].
    double rotate_step_deg = 15; ///< Rotation, per world axis [°].
    double scale_step = 0.1;     ///< Scale factor, per shape axis [-].
};

/// One move, turn and resize of a body (the gizmo's, or a script's "transform").
struct TransformDef {
    Vec3 translate{};          ///< Added to the body's position, world axes [m].
    Vec3 rotate_deg{};         ///< Turns about the world X, then Y, then Z axis through its origin [°].
    Vec3 scale{1.0, 1.0, 1.0}; ///< Multiplies the radii, shape axes [-], each > 0.
    bool snap = false;         ///< Rounds each component of the three to SnapDef's steps first.
};

/// A part file added to the scene (the Parts panel's drop, a script's "add_part").
struct PartDef {
    std::string file;             ///< Scene file of the part (its bodies, constraints and materials).
    Vec3 position{};              ///< Where the part's origin goes, world [m] (as an include's position).
    Quat orientation{1, 0, 0, 0}; ///< Turns the part about its origin (as an include's orientation).
    std::string name;   ///< New name of its root body (the first without a parent); empty: the file's name.
    std::string prefix; ///< Put before the names of its other bodies and constraints.
};

/// A constraint made between two parts at a picked surface point (the Parts panel's Attach).
struct AttachDef {
    std::string body; ///< The part attached (the constraint's b).
    std::string to;   ///< The part it is attached to (a).
    Vec3 point{};     ///< The picked point, world [m]: each side's anchor is the direction from
                      ///< its shape origin through it, so it stays on the surface on a resize.
    ConstraintType type = ConstraintType::Weld;
    double frequency = 200.0;   ///< [Hz]: stiff, as the chair's legs (light parts carrying heavy ones).
    double damping_ratio = 1.0; ///< [-], critical.
    std::string name;           ///< Empty: "<body>_joint", made unique.
};

/// `def` with its components rounded to the steps when def.snap (a snapped scale is at least one step).
[[nodiscard]] TransformDef snapped(const TransformDef& def, const SnapDef& steps);

class EditorSession
{
  public:
    EditorSession() = default;
    // The world's step listener points at its session: a move points it at the new one.
    EditorSession(EditorSession&& other) noexcept;
    EditorSession& operator=(EditorSession&& other) noexcept;
    EditorSession(const EditorSession&) = delete;
    EditorSession& operator=(const EditorSession&) = delete;

    /// Reads a scene file and builds its world. On failure the session keeps what it had.
    Status load(const std::string& path);
    /// Takes a parsed scene and builds its world.
    Status load_scene(Scene scene);
    /// Rebuilds the world from the scene: back to its initial poses, with every edit kept.
    Status reset();

    /// Plays (a running mode animation ends first).
    void play();
    void pause() { m_playing = false; }
    [[nodiscard]] bool playing() const { return m_playing; }
    /// Runs `count` fixed steps now, playing or not, with the drag spring and push loads applied.
    void step(int count);
    /// One frame of `real_seconds` [s]: while playing, World::advance() runs the whole steps of dt it
    /// holds (its backlog cap and interpolation alpha included).
    /// Returns the steps run.
    int frame(double real_seconds);

    /// Sets one scene value by its JSON pointer in the written scene (scene_to_json), with body and
    /// constraint names allowed in place of indices: "/bodies/seat/shape/radii/0", "/settings/dt",
    /// "/materials/wood/density", "/bodies/board/dynamics/modes". The edited scene is read back by the
    /// scene loader, so a bad value is refused with the loader's own message and pointer, and nothing
    /// changes. A shape change of rigid bodies is applied to the running world; anything else rebuilds
    /// the world at the current poses and velocities.
    Status set(std::string_view path, const Json& value);
    /// The current value at a path (same syntax as set), from the scene as it would be written.
    [[nodiscard]] Result<Json> get(std::string_view path) const;
    [[nodiscard]] SetEffect last_set_effect() const { return m_last_effect; }

    /// Takes back the last applied edit (its value put back, or its key removed), as set() would apply
    /// it; fails when there is nothing to undo. The world follows as for set().
    Status undo();
    /// Applies again the last undone edit; fails when there is none. A new set() drops the undone ones.
    Status redo();
    /// Moves, turns and resizes a body as one edit: its scene position, orientation (in its parent's
    /// frame for a part) and radii are set() together, so one undo() takes all of them back. The body's
    /// assembly follows in the world (its children keep their poses relative to it); a resize keeps the
    /// direction anchors of its constraints on its surface (set_body_shape). Starts from the body's pose
    /// in the world now. Fails, changing nothing, for an unknown body, a plane, a step or value not finite,
    /// or a scale not > 0.
    Status transform(std::string_view body, const TransformDef& def, const SnapDef& steps = {});

    /// Adds the bodies, constraints and materials of a part file as one edit (one undo() removes them
    /// all). Names that are taken get "_2", "_3", ... Returns the root body's name. Fails, changing
    /// nothing, for an unreadable or invalid file or a material of the same name defined differently.
    Result<std::string> add_part(const PartDef& def);
    /// Makes a constraint from def.to to def.body at the picked point as one edit, with direction anchors
    /// (where the ray from each shape origin through the point leaves the surface). A body without a
    /// parent also gets def.to as its parent when def.to comes earlier in the scene (its pose then kept
    /// in def.to's frame, as a part's). Returns the constraint's name.
    Result<std::string> attach(const AttachDef& def);
    /// Removes every constraint on a body and its parent link (its pose then kept in the world frame), as
    /// one edit. Fails when it has neither.
    Status detach(std::string_view body);

    /// Every edit since the load, in order; the first history_position() of them are applied.
    [[nodiscard]] const std::vector<SceneEdit>& history() const { return m_history; }
    [[nodiscard]] size_t history_position() const { return m_history_position; }
    /// Edits kept for undo; the oldest go first.
    static constexpr size_t k_max_history = 1000;

    /// The first body the ray enters (rest shapes; planes included), or nothing.
    [[nodiscard]] std::optional<PickHit> pick(const Ray& ray) const;
    /// Grabs the picked point of a dynamic body with a spring; fails when the ray misses or the body
    /// cannot move.
    Status drag_begin(const Ray& ray);
    /// Moves the spring's target [m], world.
    void drag_to(const Vec3& target);
    void drag_end() { m_drag.reset(); }
    [[nodiscard]] const std::optional<DragSpring>& drag() const { return m_drag; }
    /// Presses on the surface where the ray enters a dynamic body, with `force` [N] along the ray, held
    /// for the next `steps` steps. On a modal body the load also drives its modes (apply_force).
    Status push(const Ray& ray, double force, int steps);

    /// Moulds a modal body like clay: a finger presses the surface point where the ray enters, along the
    /// ray, until that point has sunk `depth` [m] (in the body's frame), for the next `steps` steps, then
    /// lets go. The finger's force starts at the body's weight and grows by 5% a step while the point is
    /// shallower than `depth`, shrinking by 10% while deeper (it stays within [10⁻³, 10⁶] weights). A
    /// plastic material (yield_stress) keeps the dent; an elastic one springs back. Fails for a miss, a
    /// rigid or static body, or a depth not in (0, 1] m.
    Status mould(const Ray& ray, double depth, int steps);
    /// How deep the last mould pressed [m]: its deepest point while pressing.
    [[nodiscard]] double mould_depth_reached() const { return m_mould_reached; }
    /// How far the material point at `point_shape` (rest, shape frame) [m] has moved along
    /// `direction_shape` (unit, shape frame) since the rest shape, in the body's frame [m].
    [[nodiscard]] double sink_along(Entity body, const Vec3& point_shape, const Vec3& direction_shape) const;

    /// Shows a mode shape: pauses, remembers the whole world (World::snapshot), then each frame() sets the
    /// body's amplitude of mode `def.mode` to its value then plus a sine swing; no step runs. Anything that
    /// changes or runs the world (play, step, an edit, undo, reset, load, drag, push, mould) ends it first.
    /// Fails for an unknown or rigid body, a mode out of range, or a period or fraction not > 0.
    Status animate_mode(std::string_view body, const ModeAnimationDef& def = {});
    /// Ends a mode animation: the world is restored from its snapshot (state_hash() as before, to the
    /// bit) and plays again if it was playing. Nothing when none runs.
    void end_mode_animation();
    [[nodiscard]] const std::optional<ModeAnimation>& mode_animation() const { return m_animation; }

    /// Saves what the world shows now (poses, velocities, edited shapes) when `current_state`, else the
    /// scene as loaded and edited (its initial poses). Atomic (save_scene).
    Status save(const std::string& path, bool current_state = true) const;

    [[nodiscard]] const Scene& scene() const { return m_scene; }
    [[nodiscard]] bool has_world() const { return m_world.has_value(); }
    [[nodiscard]] World& world() { return *m_world; }
    [[nodiscard]] const World& world() const { return *m_world; }
    /// Mean wall time of one step over the last k_timing_window steps [ms]; 0 before any step.
    [[nodiscard]] double ms_per_step() const;
    /// Counts loads and resets (a host re-frames its view on a change) [-].
    [[nodiscard]] uint64_t generation() const { return m_generation; }
    /// Counts loads only: a reset keeps the view where the user put it, a new scene is framed [-].
    [[nodiscard]] uint64_t loads() const { return m_loads; }
    /// Steps run since the last load or reset [-].
    [[nodiscard]] uint64_t steps_run() const { return m_steps_run; }

    /// Steps averaged by ms_per_step().
    static constexpr size_t k_timing_window = 60;

  private:
    void share_bases(Scene& scene) const;
    Status install(Scene scene);
    /// set() after the path is resolved; nothing for `value` removes the key.
    Status apply_edit(const std::string& path, const std::string& resolved, const std::optional<Json>& value);
    /// Rebuilds the world from `edited` at the current poses and velocities, except that the bodies in
    /// `moved` (indices whose scene pose the edit changed) take their edited pose, their parts along.
    Status rebuild_keeping_state(const Scene& edited, const std::vector<size_t>& moved = {});
    /// set()s of several paths as one edit (joined in the history); all or nothing.
    Status set_joined(const std::vector<std::pair<std::string, Json>>& edits);
    void apply_loads();
    void attach_step_listener();
    void before_step();
    void record_last_step();
    void apply_mould();
    void apply_mode_animation();

    struct PushLoad {
        Entity body{};
        Vec3 point_shape{};
        Vec3 force{}; ///< [N], world.
        int steps_left = 0;
    };

    struct MouldFinger {
        Entity body{};
        Vec3 point_shape{};                   ///< Rest point pressed [m], shape frame.
        Vec3 direction_shape{};               ///< Unit push direction, shape frame.
        double start_sink = 0.0, depth = 0.0; ///< [m]
        double force = 0.0, weight = 0.0;     ///< [N]
        int steps_left = 0;
    };

    Scene m_scene;
    // Bases outlive the worlds an edit rebuilds: a reset or a material edit of another body finds the
    // modal bodies' bases here instead of solving them again (seconds for a fine lattice).
    std::shared_ptr<ModalBasisCache> m_basis_cache = std::make_shared<ModalBasisCache>();
    std::optional<MouldFinger> m_mould;
    double m_mould_reached = 0.0;
    std::optional<World> m_world;
    bool m_playing = false;
    SetEffect m_last_effect = SetEffect::Rebuilt;
    std::optional<DragSpring> m_drag;
    std::optional<PushLoad> m_push;
    std::deque<double> m_step_ms;
    bool m_step_pending = false; ///< A step ran whose time is not yet in m_step_ms.
    uint64_t m_steps_run = 0;
    uint64_t m_generation = 0;
    uint64_t m_loads = 0;
    std::vector<SceneEdit> m_history;
    size_t m_history_position = 0;
    std::optional<ModeAnimation> m_animation;
    std::optional<Snapshot> m_animation_start;        ///< The world when the animation began.
    std::vector<double> m_animation_q, m_animation_v; ///< The body's amplitudes and rates then.
    bool m_animation_was_playing = false;
};

/// The pointer with body and constraint names replaced by their indices in `scene`
/// ("/bodies/seat/shape" → "/bodies/0/shape"); an unknown name is an error naming the path.
[[nodiscard]] Result<std::string> resolve_scene_path(const Scene& scene, std::string_view path);

} // namespace supermodal::editor
