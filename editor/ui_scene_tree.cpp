// SPDX-License-Identifier: MIT
// The scene tree: bodies nested under their parents (click one to edit it), then the constraints.
#include "ui.h"

#include <imgui.h>

namespace supermodal::editor
{
namespace
{

const char* dynamics_tag(const SceneBody& body)
{
    if (body.def.shape.type == ShapeType::Plane)
        return "plane";
    if (body.dynamics == DynamicsType::Modal)
        return "modal";
    if (body.dynamics == DynamicsType::Full)
        return "full";
    if (body.dynamics == DynamicsType::Auto)
        return "auto";
    return body.def.motion == MotionType::Dynamic  ? "rigid"
           : body.def.motion == MotionType::Static ? "static"
                                                   : "kinematic";
}

void draw_subtree(EditorUi& ui, const Scene& scene, const std::string& parent, int depth)
{
    for (const SceneBody& body : scene.bodies) {
        if (body.parent != parent)
            continue;
        const std::string& name = body.def.name;
        if (depth > 0)
            ImGui::Indent(12.0f * ui.scale() * static_cast<float>(depth));
        const bool clicked = ImGui::Selectable(name.c_str(), ui.selected_body() == name);
        ui.track(name.c_str());
        ImGui::SameLine(200.0f * ui.scale());
        ImGui::TextDisabled("%s", dynamics_tag(body));
        if (depth > 0)
            ImGui::Unindent(12.0f * ui.scale() * static_cast<float>(depth));
        if (clicked)
            ui.select_body(name);
        // Parents come before their children in a scene, so this recursion visits each body once.
        draw_subtree(ui, scene, name, depth + 1);
    }
}

/// The edits since the load, newest last; the undone ones greyed. Shown once there is an edit.
void draw_history(EditorUi& ui)
{
    EditorSession& session = ui.session();
    const std::vector<SceneEdit>& history = session.history();
    if (history.empty() || !ImGui::CollapsingHeader("History", ImGuiTreeNodeFlags_DefaultOpen))
        return;
    if (ImGui::Button("Undo"))
        ui.report(session.undo());
    ui.track("Undo");
    ImGui::SameLine();
    if (ImGui::Button("Redo"))
        ui.report(session.redo());
    ui.track("Redo");
    for (size_t i = 0; i < history.size(); ++i) {
        const std::string line = history[i].path + " = " + value_summary(history[i].after);
        if (i < session.history_position())
            ImGui::TextUnformatted(line.c_str());
        else
            ImGui::TextDisabled("%s", line.c_str());
    }
}

} // namespace

std::string value_summary(const Json& value)
{
    // A whole section (an added part's bodies) would fill the column: its size, or the object's name
    // (or its keys: the materials' names).
    if (value.dump().size() <= 40 || !(value.is_array() || value.is_object()))
        return value.dump();
    if (value.is_array())
        return "[" + std::to_string(value.size()) + (value.size() == 1 ? " item]" : " items]");
    if (value.contains("name") && value["name"].is_string())
        return "{" + value["name"].get<std::string>() + "}";
    std::string keys;
    for (const auto& item : value.items())
        keys += (keys.empty() ? "" : ", ") + item.key();
    return "{" + keys + "}";
}

void draw_scene_tree(EditorUi& ui)
{
    dock_next_window(
        panel_layout(ImGui::GetIO().DisplaySize.x, ImGui::GetIO().DisplaySize.y, ui.scale()).scene);
    if (ImGui::Begin("Scene")) {
        EditorSession& session = ui.session();
        if (!session.has_world()) {
            ImGui::TextDisabled("no scene loaded");
        } else {
            const Scene& scene = session.scene();
            ImGui::Text("%zu bodies, %zu constraints", scene.bodies.size(), scene.constraints.size());
            ImGui::Separator();
            draw_subtree(ui, scene, "", 0);
            if (!scene.constraints.empty() && ImGui::CollapsingHeader("Constraints")) {
                for (const SceneConstraint& c : scene.constraints)
                    ImGui::BulletText("%s: %s - %s", c.def.name.empty() ? "(unnamed)" : c.def.name.c_str(),
                                      c.body_a.c_str(), c.body_b.empty() ? "world" : c.body_b.c_str());
            }
            draw_history(ui);
        }
    }
    ImGui::End();
}

} // namespace supermodal::editor
