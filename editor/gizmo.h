// SPDX-License-Identifier: MIT
// The transform gizmo: axis arrows (move), rings (rotate) and boxes (scale) drawn over the selected body
// in the 3-D view, grabbed with the left button. A drag only previews; the release applies one
// EditorSession::transform(), so each gizmo edit is one undoable edit.
#pragma once

#include "session.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace supermodal::editor
{

class EditorUi;

enum class GizmoMode : uint8_t {
    Off,    ///< No gizmo: the left button picks and pulls bodies.
    Move,   ///< Arrows along the world X, Y and Z axes.
    Rotate, ///< Rings about the world X, Y and Z axes.
    Scale,  ///< Boxes on the body's own shape axes: each scales one radius.
};
/// "off", "move", "rotate", "scale".
[[nodiscard]] const char* gizmo_mode_name(GizmoMode mode);

/// How the gizmo looks and snaps.
struct GizmoDef {
    GizmoMode mode = GizmoMode::Off;
    bool snap = true; ///< Drags round to `steps` (N or the Snap checkbox toggles it).
    SnapDef steps;
    double size_px = 90.0; ///< Length of an arrow and radius of a ring on screen [px].
    double grab_px = 8.0;  ///< How near a handle a press must be to grab it [px].
};

/// One handle as drawn: a polyline on the display [px].
struct GizmoHandle {
    int axis = 0;     ///< 0 = X, 1 = Y, 2 = Z.
    Vec3 direction{}; ///< The handle's axis, unit, world.
    std::vector<std::array<double, 2>> line;
};

/// A handle held with the left button.
struct GizmoDrag {
    std::string body;
    GizmoMode mode = GizmoMode::Move;
    int axis = 0;
    Vec3 origin{};        ///< The body's origin when grabbed [m], world.
    Vec3 direction{};     ///< The handle's axis, unit, world.
    double start = 0.0;   ///< Where the press was: along the axis [m], or its angle about it [rad].
    Vec3 start_arm{};     ///< Rotate: from the origin to the press in the ring's plane [m].
    TransformDef pending; ///< What the release applies (snapped when the gizmo snaps).
};

/// The handles of the selected body's gizmo now (while an arrow is held, at the pose the release
/// gives); empty when it is off, nothing is selected, or the selection is a plane.
[[nodiscard]] std::vector<GizmoHandle> gizmo_handles(const EditorSession& session, EditorUi& ui);
/// The handle nearest pixel (x, y) within def.grab_px, as a drag starting there; nothing when none.
[[nodiscard]] std::optional<GizmoDrag> gizmo_grab(const EditorSession& session, EditorUi& ui, double x,
                                                  double y);
/// The drag's transform with the pointer at (x, y) (snapped when the gizmo snaps).
void gizmo_follow(const EditorSession& session, EditorUi& ui, GizmoDrag& drag, double x, double y);
/// The pixel a script points at to grab a handle: 80% of the way along an arrow or to a box, or the
/// ring's point farthest from the others' lines on screen.
[[nodiscard]] std::optional<std::array<double, 2>> gizmo_handle_pixel(const EditorSession& session,
                                                                      EditorUi& ui, int axis);
/// Draws the gizmo into ImGui's background list (over the 3-D view, under the panels), with the drag's
/// value next to the pointer.
void draw_gizmo(EditorUi& ui);

} // namespace supermodal::editor
