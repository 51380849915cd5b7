// SPDX-License-Identifier: MIT
// Run controls (play, pause, step, reset, save) and the speed↔accuracy panel: the knobs that trade
// one for the other (dt, substeps, contact path and samples, modes) next to what they cost now.
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "ui.h"

#include <algorithm>
#include <cstdio>
#include <imgui.h>

namespace supermodal::editor
{
namespace
{

constexpr ImGuiInputTextFlags k_on_enter = ImGuiInputTextFlags_EnterReturnsTrue;
const char* const k_contact_paths[] = {"auto", "sampling", "support_map"};

bool button(EditorUi& ui, const char* label)
{
    const bool pressed = ImGui::Button(label);
    ui.track(label);
    return pressed;
}

/// Draws a line of text and keeps it in the readout.
template <class... Args> void line(SpeedAccuracyReadout& r, const char* format, Args... args)
{
    char text[256];
    std::snprintf(text, sizeof text, format, args...);
    ImGui::TextWrapped("%s", text); // the column is narrow: long readouts wrap instead of being cut
    r.lines.emplace_back(text);
}

/// The settings that trade speed for accuracy: dt, substeps, contact path and sampling.
void draw_speed_knobs(EditorUi& ui, const WorldDef& w)
{
    double dt = w.dt;
    if (ImGui::InputDouble("dt [s]##speed", &dt, 0.0, 0.0, "%.6g", k_on_enter))
        ui.apply("/settings/dt", dt);
    ui.track("dt [s]##speed");
    int substeps = w.substep_count;
    if (ImGui::InputInt("Substeps##speed", &substeps, 1, 4, k_on_enter))
        ui.apply("/settings/substeps", substeps);
    ui.track("Substeps##speed");
    int path = static_cast<int>(w.contact.path);
    if (ImGui::Combo("Contact path##speed", &path, k_contact_paths, 3))
        ui.apply("/settings/contact/path", k_contact_paths[path]);
    ui.track("Contact path##speed");
    double spacing = w.contact.sample_spacing;
    if (ImGui::InputDouble("Sample spacing [m] (0 = auto)##speed", &spacing, 0.0, 0.0, "%.4g", k_on_enter))
        ui.apply("/settings/contact/sample_spacing", spacing);
    ui.track("Sample spacing [m] (0 = auto)##speed");
    int samples = w.contact.max_samples_per_body;
    if (ImGui::InputInt("Max samples per body##speed", &samples, 100, 1000, k_on_enter))
        ui.apply("/settings/contact/max_samples_per_body", samples);
    ui.track("Max samples per body##speed");
}

/// What the current settings cost: time per step, real-time factor, contacts and penetration.
void draw_cost_readout(EditorUi& ui, const WorldDef& w)
{
    EditorSession& s = ui.session();
    SpeedAccuracyReadout& r = ui.speed_accuracy;
    r.dt = w.dt;
    r.substeps = w.substep_count;
    r.ms_per_step = s.ms_per_step();
    r.max_penetration = world_max_penetration(s.world());
    for (const ContactInfo& c : world_contacts(s.world())) {
        ++r.contacts;
        r.contact_points += c.point_count;
    }
    line(r, "%.3f ms/step (mean of the last %zu)", r.ms_per_step, EditorSession::k_timing_window);
    // Real-time factor: simulated seconds per wall-clock second at this cost.
    if (r.ms_per_step > 0.0)
        line(r, "%.2fx real time at dt = %.3g s", r.dt * 1000.0 / r.ms_per_step, r.dt);
    line(r, "contacts %d, contact points %d", r.contacts, r.contact_points);
    line(r, "max penetration %.3g m", r.max_penetration);
}

/// The selected body's modes: how many, how far the reduced solution is from the full lattice (the
/// modal residual of its last loads) and how well the eigen solve holds.
void draw_modal_readout(EditorUi& ui)
{
    EditorSession& s = ui.session();
    SpeedAccuracyReadout& r = ui.speed_accuracy;
    const Entity e = find_body(s.world(), ui.selected_body());
    const ModalBasis* basis = e.is_null() ? nullptr : body_modal_basis(s.world(), e);
    if (basis == nullptr) {
        ImGui::TextDisabled("select a modal body for its modes");
        return;
    }
    // While one of its modes swings, the report of the state it swings from (as the Mode shapes list).
    const std::optional<ModeAnimation>& swing = s.mode_animation();
    const ModalAccuracy accuracy =
        swing && swing->body == e ? swing->accuracy : body_modal_accuracy(s.world(), e);
    const auto& res = basis->diagnostics.mode_residuals;
    r.modal_body = ui.selected_body();
    r.modes = basis->mode_count;
    r.modal_residual = accuracy.residual;
    r.truncated_fraction = accuracy.truncated_fraction;
    r.eigen_residual = res.empty() ? 0.0 : *std::max_element(res.begin(), res.end());
    r.modal_energy = body_modal_energy(s.world(), e);
    line(r, "%s: %d modes, modal residual %.3e", r.modal_body.c_str(), r.modes, r.modal_residual);
    line(r, "truncated energy %.3e of the static response", r.truncated_fraction);
    line(r, "eigen residual %.2e, f1 = %.4g Hz", r.eigen_residual,
         basis->frequencies_hz.empty() ? 0.0 : basis->frequencies_hz.front());
    line(r, "modal energy %.4g J", r.modal_energy);
    // Last: changing the mode count rebuilds the world, and with it `basis` and `e`.
    int modes = basis->mode_count;
    if (ImGui::InputInt("Modes##speed", &modes, 1, 4, k_on_enter))
        ui.apply("/bodies/" + ui.selected_body() + "/dynamics/modes", modes);
    ui.track("Modes##speed");
}

} // namespace

void draw_controls(EditorUi& ui)
{
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    dock_next_window(panel_layout(display.x, display.y, ui.scale()).run);
    if (ImGui::Begin("Run")) {
        EditorSession& s = ui.session();
        if (button(ui, "Play"))
            s.play();
        ImGui::SameLine();
        if (button(ui, "Pause"))
            s.pause();
        ImGui::SameLine();
        if (button(ui, "Step"))
            s.step(ui.step_count);
        if (button(ui, "Reset"))
            ui.report(s.reset());
        ImGui::SameLine();
        if (button(ui, "Save"))
            ui.report(s.save(ui.save_path));
        ImGui::SetNextItemWidth(120);
        ImGui::InputInt("steps per Step", &ui.step_count);
        ui.step_count = std::clamp(ui.step_count, 1, 100000);
        ui.track("steps per Step");
        if (s.has_world())
            ImGui::Text("%s  t = %.4f s  steps %llu", s.playing() ? "playing" : "paused", s.world().time(),
                        static_cast<unsigned long long>(s.world().step_count()));
        if (!ui.last_error().empty())
            ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", ui.last_error().c_str());
    }
    ImGui::End();
}

void draw_speed_accuracy(EditorUi& ui)
{
    ui.speed_accuracy = SpeedAccuracyReadout{};
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    dock_next_window(panel_layout(display.x, display.y, ui.scale()).speed);
    if (ImGui::Begin("Speed / accuracy")) {
        EditorSession& s = ui.session();
        if (!s.has_world()) {
            ImGui::TextDisabled("no scene loaded");
            ImGui::End();
            return;
        }
        ui.speed_accuracy.shown = true;
        ImGui::PushItemWidth(-110.0f * ui.scale()); // room for the labels in the narrow column
        // A copy: an applied edit replaces the session's scene and world while this window is drawn.
        const WorldDef w = s.scene().world;
        draw_speed_knobs(ui, w);
        ImGui::Separator();
        draw_cost_readout(ui, w);
        draw_modal_readout(ui);
        ImGui::PopItemWidth();
        draw_trade_plot(ui, w);
    }
    ImGui::End();
}

} // namespace supermodal::editor
