// SPDX-License-Identifier: MIT
// The Shortcuts window: every mouse and key action of the editor, over the middle of the 3-D view.
#include "ui.h"

#include <algorithm>
#include <imgui.h>

namespace supermodal::editor
{

void draw_help(EditorUi& ui)
{
    const ScreenRect& v = ui.viewport();
    ImGui::SetNextWindowPos(ImVec2(0.5f * (v.x0 + v.x1), 0.5f * (v.y0 + v.y1)), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (!ImGui::Begin("Shortcuts", nullptr,
                      ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                          ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
        ImGui::End();
        return;
    }
    // The inputs in a column as wide as the longest, the actions after it.
    float column = 0.0f;
    for (const Shortcut& s : shortcuts())
        column = std::max(column, ImGui::CalcTextSize(s.input).x);
    for (const Shortcut& s : shortcuts()) {
        ImGui::TextUnformatted(s.input);
        ImGui::SameLine(column + 2.0f * ImGui::GetStyle().ItemSpacing.x);
        ImGui::TextUnformatted(s.does);
        ui.help_lines.push_back(std::string(s.input) + ": " + s.does);
    }
    ImGui::Separator();
    ImGui::TextDisabled("H or F1 closes this list");
    ImGui::End();
}

} // namespace supermodal::editor
