// SPDX-License-Identifier: MIT
#include "gizmo.h"

#include "render_hook.h"
#include "supermodal/body.h"
#include "ui.h"

#include <cmath>
#include <cstdio>
#include <imgui.h>

namespace supermodal::editor
{
namespace
{

constexpr int k_ring_points = 64;
using Pixel = std::array<double, 2>;

double segment_distance(const Pixel& p, const Pixel& a, const Pixel& b)
{
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double len2 = dx * dx + dy * dy;
    const double t =
        len2 > 0.0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

double polyline_distance(const Pixel& p, const std::vector<Pixel>& line)
{
    double best = INFINITY;
    for (size_t i = 0; i + 1 < line.size(); ++i)
        best = std::min(best, segment_distance(p, line[i], line[i + 1]));
    if (line.size() == 1)
        best = std::hypot(p[0] - line[0][0], p[1] - line[0][1]);
    return best;
}

/// The selected body, unless nothing (or a plane) is selected or the gizmo is off.
Entity gizmo_body(const EditorSession& session, const EditorUi& ui)
{
    if (ui.gizmo.mode == GizmoMode::Off || !session.has_world() || ui.selected_body().empty())
        return {};
    const Entity e = find_body(session.world(), ui.selected_body());
    if (e.is_null() || body_shape(session.world(), e).type == ShapeType::Plane)
        return {};
    return e;
}

/// World length that spans size_px on screen at `origin`'s depth [m].
double world_length(const EditorSession& session, EditorUi& ui, const Vec3& origin)
{
    const CameraAxes axes = camera_axes(editor_camera(session, ui));
    const std::optional<Pixel> a = screen_pixel(session, ui, origin);
    const std::optional<Pixel> b = screen_pixel(session, ui, origin + axes.right);
    if (!a || !b)
        return 0.0;
    const double px_per_m = std::hypot((*b)[0] - (*a)[0], (*b)[1] - (*a)[1]);
    return px_per_m > 0.0 ? ui.gizmo.size_px / px_per_m : 0.0;
}

Vec3 unit_axis(int axis)
{
    Vec3 v{};
    v[axis] = 1.0;
    return v;
}

/// A ring's two in-plane unit vectors for the axis.
std::pair<Vec3, Vec3> ring_basis(int axis)
{
    return {unit_axis((axis + 1) % 3), unit_axis((axis + 2) % 3)};
}

/// Where the cursor's ray passes closest to the line origin + t·direction: t [m]; nothing when the line
/// points along the ray (the drag would be undefined).
std::optional<double> along_axis(const Ray& ray, const Vec3& origin, const Vec3& direction)
{
    const Vec3 u = normalized(ray.direction);
    const Vec3 w = origin - ray.origin;
    const double b = dot(direction, u), d = dot(direction, w), e = dot(u, w);
    const double denom = 1.0 - b * b;
    if (denom < 1e-6)
        return std::nullopt;
    return (b * e - d) / denom;
}

/// Where the cursor's ray meets the ring's plane, from the origin [m]; nothing when edge-on.
std::optional<Vec3> in_ring_plane(const Ray& ray, const Vec3& origin, const Vec3& normal)
{
    const Vec3 u = normalized(ray.direction);
    const double facing = dot(u, normal);
    if (std::abs(facing) < 1e-6)
        return std::nullopt;
    const double s = dot(origin - ray.origin, normal) / facing;
    return ray.origin + s * u - origin;
}

double signed_angle(const Vec3& from, const Vec3& to, const Vec3& axis)
{
    return std::atan2(dot(cross(from, to), axis), dot(from, to));
}

} // namespace

const char* gizmo_mode_name(GizmoMode mode)
{
    switch (mode) {
    case GizmoMode::Move:
        return "move";
    case GizmoMode::Rotate:
        return "rotate";
    case GizmoMode::Scale:
        return "scale";
    default:
        return "off";
    }
}

std::vector<GizmoHandle> gizmo_handles(const EditorSession& session, EditorUi& ui)
{
    std::vector<GizmoHandle> out;
    const Entity e = gizmo_body(session, ui);
    if (e.is_null())
        return out;
    const World& world = session.world();
    Vec3 origin = body_position(world, e);
    // While an arrow is held the gizmo shows where the release will put the body.
    if (ui.gizmo_drag && ui.gizmo_drag->mode == GizmoMode::Move)
        origin = ui.gizmo_drag->origin + ui.gizmo_drag->pending.translate;
    const Quat q = body_orientation(world, e);
    const double length = world_length(session, ui, origin);
    if (!(length > 0.0))
        return out;
    for (int axis = 0; axis < 3; ++axis) {
        GizmoHandle h;
        h.axis = axis;
        h.direction = ui.gizmo.mode == GizmoMode::Scale ? rotate(q, unit_axis(axis)) : unit_axis(axis);
        if (ui.gizmo.mode == GizmoMode::Rotate) {
            const auto [a, b] = ring_basis(axis);
            for (int k = 0; k <= k_ring_points; ++k) {
                const double phi = 2.0 * M_PI * k / k_ring_points;
                if (auto p =
                        screen_pixel(session, ui, origin + length * (std::cos(phi) * a + std::sin(phi) * b)))
                    h.line.push_back(*p);
            }
        } else {
            for (double t : {0.0, 1.0})
                if (auto p = screen_pixel(session, ui, origin + t * length * h.direction))
                    h.line.push_back(*p);
        }
        if (h.line.size() >= 2)
            out.push_back(std::move(h));
    }
    return out;
}

std::optional<GizmoDrag> gizmo_grab(const EditorSession& session, EditorUi& ui, double x, double y)
{
    const std::vector<GizmoHandle> handles = gizmo_handles(session, ui);
    const GizmoHandle* best = nullptr;
    double nearest = ui.gizmo.grab_px;
    for (const GizmoHandle& h : handles) {
        // The part of an arrow near the origin belongs to all three: grab the outer 80%.
        std::vector<Pixel> line = h.line;
        if (ui.gizmo.mode != GizmoMode::Rotate)
            line.front() = {line[0][0] + 0.2 * (line[1][0] - line[0][0]),
                            line[0][1] + 0.2 * (line[1][1] - line[0][1])};
        const double d = polyline_distance({x, y}, line);
        if (d <= nearest) {
            nearest = d;
            best = &h;
        }
    }
    const Result<Ray> ray = screen_ray(session, ui, x, y);
    if (best == nullptr || !ray)
        return std::nullopt;
    const Entity e = find_body(session.world(), ui.selected_body());
    GizmoDrag drag;
    drag.body = ui.selected_body();
    drag.mode = ui.gizmo.mode;
    drag.axis = best->axis;
    drag.origin = body_position(session.world(), e);
    drag.direction = best->direction;
    drag.pending.snap = ui.gizmo.snap;
    if (drag.mode == GizmoMode::Rotate) {
        const std::optional<Vec3> arm = in_ring_plane(*ray, drag.origin, drag.direction);
        if (!arm || !(length(*arm) > 0.0))
            return std::nullopt;
        drag.start_arm = *arm;
    } else {
        const std::optional<double> t = along_axis(*ray, drag.origin, drag.direction);
        if (!t || (drag.mode == GizmoMode::Scale && !(*t > 0.0)))
            return std::nullopt;
        drag.start = *t;
    }
    return drag;
}

void gizmo_follow(const EditorSession& session, EditorUi& ui, GizmoDrag& drag, double x, double y)
{
    const Result<Ray> ray = screen_ray(session, ui, x, y);
    if (!ray)
        return;
    TransformDef t;
    t.snap = ui.gizmo.snap;
    if (drag.mode == GizmoMode::Rotate) {
        const std::optional<Vec3> arm = in_ring_plane(*ray, drag.origin, drag.direction);
        if (!arm || !(length(*arm) > 0.0))
            return;
        t.rotate_deg[drag.axis] = signed_angle(drag.start_arm, *arm, drag.direction) * 180.0 / M_PI;
    } else {
        const std::optional<double> along = along_axis(*ray, drag.origin, drag.direction);
        if (!along)
            return;
        if (drag.mode == GizmoMode::Move)
            t.translate[drag.axis] = *along - drag.start;
        else // a box dragged through the origin stops at the smallest step, not a mirror image
            t.scale[drag.axis] = std::max(*along / drag.start, ui.gizmo.steps.scale_step);
    }
    drag.pending = snapped(t, ui.gizmo.steps);
    drag.pending.snap = false; // already rounded: the release applies what was shown
}

std::optional<Pixel> gizmo_handle_pixel(const EditorSession& session, EditorUi& ui, int axis)
{
    const std::vector<GizmoHandle> handles = gizmo_handles(session, ui);
    const GizmoHandle* h = nullptr;
    for (const GizmoHandle& g : handles)
        if (g.axis == axis)
            h = &g;
    if (h == nullptr)
        return std::nullopt;
    if (ui.gizmo.mode != GizmoMode::Rotate) {
        const double f = ui.gizmo.mode == GizmoMode::Move ? 0.8 : 1.0;
        return Pixel{h->line[0][0] + f * (h->line[1][0] - h->line[0][0]),
                     h->line[0][1] + f * (h->line[1][1] - h->line[0][1])};
    }
    // The ring's point farthest from the other two rings on screen, so the press grabs this one.
    Pixel best = h->line[0];
    double clearance = -1.0;
    for (const Pixel& p : h->line) {
        double d = INFINITY;
        for (const GizmoHandle& g : handles)
            if (&g != h)
                d = std::min(d, polyline_distance(p, g.line));
        if (d > clearance) {
            clearance = d;
            best = p;
        }
    }
    return best;
}

void draw_gizmo(EditorUi& ui)
{
    const EditorSession& session = ui.session();
    std::vector<GizmoHandle> handles = gizmo_handles(session, ui);
    if (handles.empty())
        return;
    ImDrawList* list = ImGui::GetBackgroundDrawList();
    const ScreenRect& v = ui.viewport();
    list->PushClipRect(ImVec2(v.x0, v.y0), ImVec2(v.x1, v.y1));
    const ImU32 colours[3] = {IM_COL32(230, 60, 60, 255), IM_COL32(80, 200, 80, 255),
                              IM_COL32(70, 120, 240, 255)};
    const float width = 3.0f * ui.scale();
    const float box = 5.0f * ui.scale();
    const std::optional<GizmoDrag>& drag = ui.gizmo_drag;
    for (const GizmoHandle& h : handles) {
        const bool held = drag && drag->axis == h.axis;
        const ImU32 c = held ? IM_COL32(255, 220, 40, 255) : colours[h.axis];
        std::vector<ImVec2> points;
        for (const Pixel& p : h.line)
            points.push_back(ImVec2(static_cast<float>(p[0]), static_cast<float>(p[1])));
        list->AddPolyline(points.data(), static_cast<int>(points.size()), c, ImDrawFlags_None, width);
        const ImVec2 tip = points.back();
        if (ui.gizmo.mode == GizmoMode::Scale) {
            list->AddRectFilled(ImVec2(tip.x - box, tip.y - box), ImVec2(tip.x + box, tip.y + box), c);
        } else if (ui.gizmo.mode == GizmoMode::Move) {
            const ImVec2 base = points.front();
            const float dx = tip.x - base.x, dy = tip.y - base.y;
            const float n = std::max(std::hypot(dx, dy), 1.0f);
            const float ux = dx / n, uy = dy / n, head = 14.0f * ui.scale();
            list->AddTriangleFilled(ImVec2(tip.x + ux * head, tip.y + uy * head),
                                    ImVec2(tip.x - uy * head * 0.45f, tip.y + ux * head * 0.45f),
                                    ImVec2(tip.x + uy * head * 0.45f, tip.y - ux * head * 0.45f), c);
        }
    }
    if (drag && drag->mode == GizmoMode::Move) { // from where the body is to where it will go
        const auto from = screen_pixel(session, ui, drag->origin);
        const auto to = screen_pixel(session, ui, drag->origin + drag->pending.translate);
        if (from && to)
            list->AddLine(ImVec2(static_cast<float>((*from)[0]), static_cast<float>((*from)[1])),
                          ImVec2(static_cast<float>((*to)[0]), static_cast<float>((*to)[1])),
                          IM_COL32(255, 220, 40, 255), 1.5f * ui.scale());
    }
    if (drag) {
        // The value the release will apply, next to the pointer.
        char text[96];
        const char* axis = drag->axis == 0 ? "X" : drag->axis == 1 ? "Y" : "Z";
        if (drag->mode == GizmoMode::Move)
            std::snprintf(text, sizeof text, "%s %+.3f m", axis, drag->pending.translate[drag->axis]);
        else if (drag->mode == GizmoMode::Rotate)
            std::snprintf(text, sizeof text, "%s %+.1f deg", axis, drag->pending.rotate_deg[drag->axis]);
        else
            std::snprintf(text, sizeof text, "%s x%.2f", axis, drag->pending.scale[drag->axis]);
        const ImVec2 at(static_cast<float>(ui.view_input.x()) + 14.0f,
                        static_cast<float>(ui.view_input.y()) - 6.0f);
        list->AddText(at, IM_COL32(255, 255, 255, 255), text);
    }
    list->PopClipRect();
}

} // namespace supermodal::editor
