// SPDX-License-Identifier: MIT
// The parameter window of the selected body: shape (radii, exponents, taper, bend), material,
// rigid or modal, modes and lattice. Values apply when the user presses Enter in a field; every change
// goes through EditorSession::set, so the scene loader checks it.
#include "supermodal/body.h"
#include "ui.h"

#include <imgui.h>
#include <string>
#include <vector>

namespace supermodal::editor
{
namespace
{

constexpr ImGuiInputTextFlags k_on_enter = ImGuiInputTextFlags_EnterReturnsTrue;

/// An editable row of n doubles; applies the whole array at `path` when the user commits it.
void doubles(EditorUi& ui, const char* label, const std::string& path, double* values, int n)
{
    if (ImGui::InputScalarN(label, ImGuiDataType_Double, values, n, nullptr, nullptr, "%.6g", k_on_enter)) {
        Json array = Json::array();
        for (int i = 0; i < n; ++i)
            array.push_back(values[i]);
        ui.apply(path, n == 1 ? Json(values[0]) : array);
    }
    ui.track(label);
}

void draw_shape(EditorUi& ui, const std::string& base, const ShapeDef& shape)
{
    if (shape.type == ShapeType::Plane) {
        double n[3] = {shape.plane_normal.x, shape.plane_normal.y, shape.plane_normal.z};
        doubles(ui, "Normal##body", base + "/shape/normal", n, 3);
        double offset = shape.plane_offset;
        doubles(ui, "Offset [m]##body", base + "/shape/offset", &offset, 1);
        return;
    }
    if (shape.type == ShapeType::Hyperquadric) {
        ImGui::Text("hyperquadric, %zu terms (edit them in the scene file)", shape.terms.size());
        return;
    }
    double radii[3] = {shape.radii.x, shape.radii.y, shape.radii.z};
    doubles(ui, "Radii [m]##body", base + "/shape/radii", radii, 3);
    double exponents[2] = {shape.epsilon1, shape.epsilon2};
    doubles(ui, "Exponents##body", base + "/shape/exponents", exponents, 2);
    double taper[2] = {shape.taper.kx, shape.taper.ky};
    doubles(ui, "Taper##body", base + "/shape/taper", taper, 2);
    double curvature = shape.bend.curvature, angle = shape.bend.angle;
    doubles(ui, "Bend curvature [1/m]##body", base + "/shape/bend/curvature", &curvature, 1);
    doubles(ui, "Bend angle [rad]##body", base + "/shape/bend/angle", &angle, 1);
}

void draw_material(EditorUi& ui, const std::string& base, const std::vector<std::string>& materials,
                   const SceneBody& body)
{
    const char* current = body.material.empty() ? "(default)" : body.material.c_str();
    if (ImGui::BeginCombo("Material##body", current)) {
        for (const std::string& name : materials) {
            if (ImGui::Selectable(name.c_str(), name == body.material))
                ui.apply(base + "/material", name);
        }
        ImGui::EndCombo();
    }
    ui.track("Material##body");
}

/// The gizmo's mode and snapping (keys G, R, E, Q and N do the same).
void draw_gizmo_controls(EditorUi& ui)
{
    GizmoDef& g = ui.gizmo;
    const GizmoMode modes[] = {GizmoMode::Off, GizmoMode::Move, GizmoMode::Rotate, GizmoMode::Scale};
    const char* labels[] = {"Off##gizmo", "Move##gizmo", "Rotate##gizmo", "Scale##gizmo"};
    for (int i = 0; i < 4; ++i) {
        if (i > 0)
            ImGui::SameLine();
        if (ImGui::RadioButton(labels[i], g.mode == modes[i])) {
            g.mode = modes[i];
            ui.gizmo_drag.reset();
        }
        ui.track(labels[i]);
    }
    ImGui::Checkbox("Snap##gizmo", &g.snap);
    ui.track("Snap##gizmo");
    if (!g.snap)
        return;
    // Steps stay > 0: a zero step would snap everything to nothing.
    double step = g.steps.move_step;
    if (ImGui::InputDouble("Move step [m]##gizmo", &step, 0.0, 0.0, "%.4g", k_on_enter) && step > 0.0)
        g.steps.move_step = step;
    step = g.steps.rotate_step_deg;
    if (ImGui::InputDouble("Turn step [deg]##gizmo", &step, 0.0, 0.0, "%.4g", k_on_enter) && step > 0.0)
        g.steps.rotate_step_deg = step;
    step = g.steps.scale_step;
    if (ImGui::InputDouble("Scale step##gizmo", &step, 0.0, 0.0, "%.4g", k_on_enter) && step > 0.0)
        g.steps.scale_step = step;
}

void draw_dynamics(EditorUi& ui, const std::string& base, const SceneBody& body)
{
    const bool modal = body.dynamics == DynamicsType::Modal;
    if (ImGui::RadioButton("Rigid##body", !modal) && modal)
        ui.apply(base + "/dynamics/type", "rigid");
    ui.track("Rigid##body");
    ImGui::SameLine();
    if (ImGui::RadioButton("Modal##body", modal) && !modal)
        ui.apply(base + "/dynamics/type", "modal");
    ui.track("Modal##body");
    int modes = body.def.modal.mode_count;
    if (ImGui::InputInt("Modes##body", &modes, 1, 4, k_on_enter))
        ui.apply(base + "/dynamics/modes", modes);
    ui.track("Modes##body");
    int lattice[3] = {body.def.modal.lattice[0], body.def.modal.lattice[1], body.def.modal.lattice[2]};
    if (ImGui::InputInt3("Lattice (0 = auto)##body", lattice, k_on_enter))
        ui.apply(base + "/dynamics/lattice", Json::array({lattice[0], lattice[1], lattice[2]}));
    ui.track("Lattice (0 = auto)##body");
}

/// The modes of a modal body: each with its frequency, amplitude and a button that animates it; the
/// modal residual and truncated energy of its last loads; a kept plastic dent.
void draw_modes(EditorUi& ui, const std::string& name)
{
    if (!ImGui::CollapsingHeader("Mode shapes##body", ImGuiTreeNodeFlags_DefaultOpen)) {
        ui.track("Mode shapes##body");
        return;
    }
    ui.track("Mode shapes##body");
    EditorSession& session = ui.session();
    ui.modes = modes_readout(session, name);
    if (!ui.modes.modal)
        return; // a Rigid press above has just rebuilt the body without modes
    ui.modes.shown = true;
    const ModesReadout r = ui.modes; // a copy: a pressed button changes the world drawn from
    if (r.animating >= 0) {
        if (ImGui::Button("Restore##modes"))
            session.end_mode_animation();
        ui.track("Restore##modes");
        ImGui::SameLine();
        ImGui::TextWrapped("mode %d swings (paused; Restore ends it)", r.animating + 1);
    }
    ImGui::TextWrapped("%s", r.lines.front().c_str());
    for (size_t k = 0; k < r.frequencies_hz.size(); ++k) {
        const std::string label = "Animate " + std::to_string(k + 1);
        if (static_cast<int>(k) == r.animating)
            ImGui::BeginDisabled();
        if (ImGui::SmallButton(label.c_str())) {
            ModeAnimationDef def;
            def.mode = static_cast<int>(k);
            ui.report(session.animate_mode(name, def));
        }
        if (static_cast<int>(k) == r.animating)
            ImGui::EndDisabled();
        ui.track(label.c_str());
        ImGui::SameLine();
        ImGui::TextUnformatted(r.lines[k + 1].c_str());
    }
    for (size_t i = 1 + r.frequencies_hz.size(); i < r.lines.size(); ++i)
        ImGui::TextWrapped("%s", r.lines[i].c_str());
}

} // namespace

void draw_body_window(EditorUi& ui)
{
    ui.modes = ModesReadout{};
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    dock_next_window(panel_layout(display.x, display.y, ui.scale()).body);
    if (ImGui::Begin("Body")) {
        ImGui::PushItemWidth(-110.0f * ui.scale()); // room for the labels in the narrow column
        EditorSession& session = ui.session();
        const Scene* scene = session.has_world() ? &session.scene() : nullptr;
        size_t index = 0;
        while (scene != nullptr && index < scene->bodies.size() &&
               scene->bodies[index].def.name != ui.selected_body())
            ++index;
        if (scene == nullptr || index == scene->bodies.size()) {
            ImGui::TextDisabled("select a body in the scene tree");
        } else {
            // Copies: an applied edit replaces the session's scene (and may rebuild its world) while the
            // rest of this window is still being drawn from these values.
            const SceneBody body = scene->bodies[index];
            std::vector<std::string> materials;
            for (const MaterialDef& m : scene->materials)
                materials.push_back(m.name);
            const std::string base = "/bodies/" + std::to_string(index);
            ImGui::Text("%s", body.def.name.c_str());
            const Entity e = find_body(session.world(), body.def.name);
            if (!e.is_null() && body.def.motion == MotionType::Dynamic)
                ImGui::Text("mass %.4g kg, density %.4g kg/m^3",
                            body_mass_properties(session.world(), e).mass, body.def.density);
            draw_material(ui, base, materials, body);
            ImGui::Separator();
            ImGui::TextUnformatted("Shape");
            draw_shape(ui, base, body.def.shape);
            if (body.def.shape.type != ShapeType::Plane) {
                ImGui::Separator();
                ImGui::TextUnformatted("Gizmo");
                draw_gizmo_controls(ui);
                ImGui::Separator();
                ImGui::TextUnformatted("Dynamics");
                draw_dynamics(ui, base, body);
                // Last: Animate pauses the world and an edit above may rebuild it.
                if (body.dynamics == DynamicsType::Modal)
                    draw_modes(ui, body.def.name);
            }
        }
        ImGui::PopItemWidth();
    }
    ImGui::End();
}

} // namespace supermodal::editor
