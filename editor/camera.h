// SPDX-License-Identifier: MIT
// The 3-D view's orbit camera: orbit, pan, zoom towards a point, framing boxes, and the maps between a
// view rectangle's pixels and world rays. Pure math on CameraDef (target, distance, yaw, pitch, fov)
// with the renderer's conventions (engine/src/render/view.cpp), so what is drawn is what is computed
// here; tests/editor/camera_test.cpp checks both against each other.
#pragma once

#include "session.h"
#include "supermodal/geometry.h"
#include "supermodal/render.h"
#include "supermodal/scene.h"

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace supermodal::editor
{

class EditorUi;

// Axes (camera_axes) and framing distances come from the renderer's public functions
// (supermodal/render.h), so the view and the drawing agree by construction.
/// target + distance · back [m]; the camera's target must be set.
[[nodiscard]] Vec3 camera_eye(const CameraDef& camera);

/// How far the view's gestures and keys move the camera. Start from the defaults.
struct CameraControlDef {
    double orbit_deg_per_px = 0.3; ///< Orbit per pixel of cursor travel [°/px]: 600 px turn 180°.
    double orbit_key_deg = 15.0;   ///< One arrow key press [°].
    double zoom_per_notch = 0.85;  ///< Distance factor of one wheel notch or '+' [-]; '-' divides.
    double pan_key_fraction = 0.1; ///< One W/A/S/D press, a fraction of the view's height at the
                                   ///< target's depth [-].
    double frame_margin = 1.1;     ///< Framing leaves this factor of room around the boxes [-], ≥ 1.
    double min_distance = 1e-3;    ///< Closest the eye comes to the target [m].
    double max_distance = 1e5;     ///< Farthest [m].
    double zoom_depth_cap = 4.0;   ///< The point zoomed towards is at most this many distances
                                   ///< along the cursor's ray [-]: a far floor does not fling the eye.
};

/// Turns the eye about the target by yaw and pitch [°]; the distance is kept, the pitch stays within
/// [−89, 89] (the renderer's range) and the yaw within [−180, 180].
[[nodiscard]] CameraDef orbit(const CameraDef& camera, double yaw_deg, double pitch_deg);
/// Moves target and eye together so that a point at the target's depth follows the cursor by
/// (dx, dy) [px] (x right, y down) in a view `view_height` [px] tall.
[[nodiscard]] CameraDef pan_pixels(const CameraDef& camera, double dx, double dy, double view_height);
/// Scales the distance by `factor` (> 0; < 1 comes closer) keeping `point` [m] where it is on screen:
/// target and eye move along the lines from `point`, so every point on the ray from the eye through
/// `point` stays under the same pixel. The distance stays within the control's limits.
[[nodiscard]] CameraDef zoom_towards(const CameraDef& camera, const Vec3& point, double factor,
                                     const CameraControlDef& control = {});
/// Aims at the centre of the boxes' union and sets the distance at which every box corner lies inside
/// the view (vertical fov, `aspect` = width / height) with `margin` of room; yaw, pitch, fov kept.
/// No boxes: a 2 m cube at the origin.
[[nodiscard]] CameraDef frame_boxes(const CameraDef& camera, std::span<const Aabb> boxes, double aspect,
                                    double margin = 1.1);
/// The scene's camera with an absent target or a zero distance filled in to frame the boxes (a given
/// target is kept and only the distance fitted), as the renderer's frame_bodies() does.
[[nodiscard]] CameraDef frame_scene_camera(const CameraDef& scene_camera, std::span<const Aabb> boxes,
                                           double aspect, double margin = 1.1);

/// The world ray through pixel (x, y) of a width × height view [px] (top-left origin, y down).
[[nodiscard]] Ray view_ray(const CameraDef& camera, double width, double height, double x, double y);
/// Where a world point [m] is drawn in that view [px], and its depth in front of the eye [m]; nothing
/// behind the eye.
struct ViewPixel {
    double x = 0, y = 0, depth = 0;
};
[[nodiscard]] std::optional<ViewPixel> view_pixel(const CameraDef& camera, double width, double height,
                                                  const Vec3& point);

/// World boxes of the world's bodies, planes left out (they have no bounds).
[[nodiscard]] std::vector<Aabb> body_boxes(const World& world);
/// One body's world box; nothing for a plane or an invalid body.
[[nodiscard]] std::optional<Aabb> body_box(const World& world, Entity body);

/// The camera of the 3-D view and the mouse (ui.view_camera): on a load, the scene's camera framed for
/// the view's aspect; after a reset or a change of the view's shape framed again unless the user has
/// moved it since (then it stays where the user put it).
[[nodiscard]] const CameraDef& editor_camera(const EditorSession& session, EditorUi& ui);

} // namespace supermodal::editor
