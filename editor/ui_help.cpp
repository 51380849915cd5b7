// SPDX-License-Identifier: MIT
// The Shortcuts window: every mouse and key action of the editor, in the 3-D view's top-left corner
// (framed scenes sit in the middle of the view).
#include "ui.h"

#include <algorithm>
#include <imgui.h>

namespace supermodal::editor
{

void draw_help(EditorUi& ui)
{
    const ScreenRect& v = ui.viewport();
    const float inset = 8.0f * ui.scale(); // [px] from the view's edges
    ImGui::SetNextWindowPos(ImVec2(v.x0 + inset, v.y0 + inset), ImGuiCond_Always);
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
    const float second = ImGui::GetCursorPosX() + column + 2.0f * ImGui::GetStyle().ItemSpacing.x;
    for (const Shortcut& s : shortcuts()) {
        ImGui::TextUnformatted(s.input);
        ImGui::SameLine(second);
        ImGui::TextUnformatted(s.does);
        ui.help_lines.push_back(std::string(s.input) + ": " + s.does);
    }
    ImGui::Separator();
    ImGui::TextDisabled("H or F1 closes this list");
    ImGui::End();
}

} // namespace supermodal::editor
