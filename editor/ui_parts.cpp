// SPDX-License-Identifier: MIT
// The Parts panel: the library's part files as thumbnails to drag (or click, then click) into the view,
// and Attach / Detach for the selected part.
#include "supermodal/body.h"
#include "supermodal/geometry.h"
#include "ui.h"

#include <algorithm>
#include <cmath>
#include <imgui.h>
#include <utility>

namespace supermodal::editor
{
namespace
{

constexpr float k_tile = 40.0f; ///< Thumbnail size in the panel [px] (scaled with the UI).
const char* const k_types[] = {"point", "distance", "weld"};

bool button(EditorUi& ui, const char* label)
{
    const bool pressed = ImGui::Button(label);
    ui.track(label);
    return pressed;
}

/// One thumbnail (or, without one, a button with its name): pressing starts carrying the part, a click
/// (press and release over it) arms it for the next press in the view.
void draw_tile(EditorUi& ui, const PartEntry& e, size_t k)
{
    const float size = k_tile * ui.scale();
    const std::string label = e.label + ".json";
    ImGui::PushID(static_cast<int>(k));
    ImGui::BeginGroup();
    if (e.width > 0)
        ImGui::ImageButton(reinterpret_cast<ImTextureID>(k_thumbnail_texture + static_cast<intptr_t>(k)),
                           ImVec2(size, size));
    else
        ImGui::Button(e.label.c_str(), ImVec2(size, size));
    ui.track(label.c_str());
    if (ImGui::IsItemActivated())
        ui.parts.carrying = e.path;
    if (ImGui::IsItemDeactivated() && ImGui::IsItemHovered()) {
        ui.parts.armed = e.path; // a click: the next press in the view drops it
        ui.parts.carrying.clear();
    }
    if (!e.error.empty() && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", e.error.c_str());
    const bool armed = ui.parts.armed == e.path;
    ImGui::TextColored(armed ? ImVec4(1.0f, 0.85f, 0.2f, 1.0f) : ImVec4(0.8f, 0.8f, 0.8f, 1.0f), "%s",
                       e.label.c_str());
    ImGui::EndGroup();
    ImGui::PopID();
}

void draw_tiles(EditorUi& ui)
{
    const std::vector<PartEntry>& entries = ui.parts_library.entries();
    if (entries.empty()) {
        ImGui::TextDisabled("no part files in %s", ui.parts_library.folder().empty()
                                                       ? "(no folder)"
                                                       : ui.parts_library.folder().c_str());
        return;
    }
    const float step = k_tile * ui.scale() + ImGui::GetStyle().ItemSpacing.x + 8.0f;
    const int columns = std::max(1, static_cast<int>(ImGui::GetContentRegionAvail().x / step));
    for (size_t k = 0; k < entries.size(); ++k) {
        if (k % static_cast<size_t>(columns) != 0)
            ImGui::SameLine();
        draw_tile(ui, entries[k], k);
    }
}

/// Attach and Detach for the selected body (first, so that many parts do not scroll them away).
void draw_attach_buttons(EditorUi& ui)
{
    const std::string& selected = ui.selected_body();
    if (selected.empty()) {
        ImGui::TextDisabled("select a part to attach it");
        return;
    }
    if (button(ui, ui.parts.attach_armed ? "Cancel##attach" : "Attach"))
        ui.parts.attach_armed = !ui.parts.attach_armed;
    ImGui::SameLine();
    if (button(ui, "Detach"))
        ui.report(ui.session().detach(selected));
    if (ui.parts.attach_armed)
        ImGui::TextWrapped("press on a surface point of another part to attach %s there", selected.c_str());
}

/// The constraint Attach makes.
void draw_attach_settings(EditorUi& ui)
{
    int type = static_cast<int>(ui.parts.attach.type);
    if (ImGui::Combo("Type##attach", &type, k_types, 3))
        ui.parts.attach.type = static_cast<ConstraintType>(type);
    ui.track("Type##attach");
    ImGui::InputDouble("Hz##attach", &ui.parts.attach.frequency, 0.0, 0.0, "%.4g");
    ui.track("Hz##attach");
}

} // namespace

int thumbnail_index(void* texture_id, size_t count)
{
    const intptr_t k = reinterpret_cast<intptr_t>(texture_id) - k_thumbnail_texture;
    return k >= 0 && static_cast<size_t>(k) < count ? static_cast<int>(k) : -1;
}

void draw_parts(EditorUi& ui)
{
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    dock_next_window(panel_layout(display.x, display.y, ui.scale()).parts);
    if (ImGui::Begin("Parts")) {
        if (ui.session().has_world())
            draw_attach_buttons(ui);
        if (!ui.parts.armed.empty())
            ImGui::TextWrapped("press in the view to add it (Escape: cancel)");
        draw_tiles(ui);
        ImGui::Separator();
        draw_attach_settings(ui);
    }
    ImGui::End();
}

Result<double> part_bottom(const std::string& file, const Quat& orientation)
{
    Result<Scene> scene = load_scene(file);
    if (!scene)
        return scene.error();
    Result<World> world = build_world(*scene);
    if (!world)
        return world.error();
    double bottom = INFINITY;
    for (const Entity e : world_bodies(*world)) {
        const ShapeDef& shape = body_shape(*world, e);
        if (shape.type == ShapeType::Plane)
            continue;
        // The lowest surface point: the shape's support point along −y in its own frame.
        const Quat q = normalized(orientation * body_orientation(*world, e));
        const Vec3 low = rotate(q, support_point(shape, inv_rotate(q, Vec3{0.0, -1.0, 0.0})));
        bottom = std::min(bottom, rotate(orientation, body_position(*world, e)).y + low.y);
    }
    if (!std::isfinite(bottom))
        return Error{file, "", "the part has no bounded body to set on a surface"};
    return bottom;
}

namespace
{

/// A part dropped from the panel: added where the ray meets the scene, then selected.
void drop_from_panel(EditorSession& session, EditorUi& ui, const Ray& ray, const std::string& file)
{
    PartDef def;
    def.file = file;
    Result<std::string> added = drop_part(session, ray, def);
    ui.report(added ? Status{} : Status{added.error()});
    if (added)
        ui.select_body(ui.parts.last_added = *added);
}

/// Attach's press: the selected part attached to the part under the pointer, at the pressed point.
void attach_at(EditorSession& session, EditorUi& ui, const Ray& ray)
{
    const std::optional<PickHit> hit = session.pick(ray);
    if (!hit || hit->name == ui.selected_body()) {
        ui.report(Error{"", "", "attach: press on a surface point of another part"});
        return;
    }
    AttachDef def = ui.parts.attach;
    def.body = ui.selected_body();
    def.to = hit->name;
    def.point = hit->point;
    Result<std::string> made = session.attach(def);
    ui.report(made ? Status{} : Status{made.error()});
}

} // namespace

Result<std::string> drop_part(EditorSession& session, const Ray& ray, PartDef def)
{
    Vec3 at{};
    if (const std::optional<PickHit> hit = session.pick(ray)) {
        at = hit->point;
    } else {
        const Vec3 d = normalized(ray.direction);
        if (!(d.y < -1e-9))
            return Error{"", "", "nothing under the pointer to set the part on"};
        at = ray.origin + (-ray.origin.y / d.y) * d; // the ground plane y = 0
    }
    Result<double> bottom = part_bottom(def.file, def.orientation);
    if (!bottom)
        return bottom.error();
    def.position = at - Vec3{0.0, *bottom, 0.0};
    return session.add_part(def);
}

bool parts_view_action(EditorSession& session, EditorUi& ui, const Ray& ray, bool left_pressed,
                       bool left_down)
{
    PartsPanelState& p = ui.parts;
    const ScreenRect& v = ui.viewport();
    const double x = ui.view_input.x(), y = ui.view_input.y();
    const bool in_view = x >= v.x0 && x < v.x1 && y >= v.y0 && y < v.y1;
    if (!p.carrying.empty()) {
        if (left_down)
            return true; // still carried
        const std::string file = std::exchange(p.carrying, std::string());
        if (in_view)
            drop_from_panel(session, ui, ray, file);
        return true;
    }
    if (!left_pressed || !in_view)
        return false;
    if (!p.armed.empty()) {
        drop_from_panel(session, ui, ray, std::exchange(p.armed, std::string()));
        return true;
    }
    if (!p.attach_armed)
        return false;
    p.attach_armed = false;
    attach_at(session, ui, ray);
    return true;
}

} // namespace supermodal::editor
