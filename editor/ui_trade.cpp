// SPDX-License-Identifier: MIT
// The Speed / accuracy plot: cost per simulated second against trajectory error for the scene's dt and
// substeps, from a `supermodal bench` sweep run in the background, with the current setting marked.
#include "ui.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <imgui.h>
#include <unistd.h>

namespace supermodal::editor
{
namespace
{

struct Range {
    double lo = 1e300, hi = -1e300;
    void add(double v)
    {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
};

// log10 of v, floored so that an exact run (error 0) sits at the axis' low end.
double log_of(double v, double floor_value)
{
    return std::log10(std::max(v, floor_value));
}

// The plot's axes: log10 of error [m] across, log10 of cost [ms per simulated s] up.
struct Axes {
    Range x, y;
    ImVec2 origin, size;
    double floor_error = 1e-12;

    ImVec2 at(const TradePoint& p) const
    {
        const double fx = (log_of(p.error_m, floor_error) - x.lo) / std::max(x.hi - x.lo, 1e-9);
        const double fy = (std::log10(std::max(p.ms_per_sim_s, 1e-9)) - y.lo) / std::max(y.hi - y.lo, 1e-9);
        return {origin.x + static_cast<float>(fx) * size.x,
                origin.y + size.y - static_cast<float>(fy) * size.y};
    }
};

Axes fit_axes(const std::vector<TradePoint>& points, ImVec2 origin, ImVec2 size)
{
    Axes a;
    a.origin = origin;
    a.size = size;
    double smallest = 1e300;
    for (const TradePoint& p : points)
        if (p.error_m > 0.0)
            smallest = std::min(smallest, p.error_m);
    a.floor_error = smallest < 1e300 ? smallest / 10.0 : 1e-12;
    for (const TradePoint& p : points) {
        a.x.add(log_of(p.error_m, a.floor_error));
        a.y.add(std::log10(std::max(p.ms_per_sim_s, 1e-9)));
    }
    // Half a decade of room round the points, so none sits on the frame.
    a.x.lo -= 0.25, a.x.hi += 0.25, a.y.lo -= 0.25, a.y.hi += 0.25;
    return a;
}

void draw_points(const std::vector<TradePoint>& points, int marked, float scale)
{
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const ImVec2 size{std::max(ImGui::GetContentRegionAvail().x, 60.0f), 120.0f * scale};
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRect(origin, {origin.x + size.x, origin.y + size.y}, IM_COL32(140, 140, 140, 255));
    const Axes a = fit_axes(points, origin, size);
    for (size_t i = 0; i < points.size(); ++i) {
        const ImVec2 c = a.at(points[i]);
        const ImU32 colour =
            points[i].knob == "dt" ? IM_COL32(90, 170, 255, 255) : IM_COL32(120, 220, 120, 255);
        dl->AddCircleFilled(c, 3.5f * scale, colour);
        if (static_cast<int>(i) == marked)
            dl->AddCircle(c, 8.0f * scale, IM_COL32(255, 160, 40, 255), 0, 2.0f * scale);
    }
    char label[64];
    std::snprintf(label, sizeof label, "error %.2g .. %.2g m", std::pow(10.0, a.x.lo + 0.25),
                  std::pow(10.0, a.x.hi - 0.25));
    dl->AddText({origin.x + 4, origin.y + size.y - ImGui::GetTextLineHeight() - 2},
                IM_COL32(200, 200, 200, 255), label);
    std::snprintf(label, sizeof label, "CPU %.2g .. %.2g ms per sim. s", std::pow(10.0, a.y.lo + 0.25),
                  std::pow(10.0, a.y.hi - 0.25));
    dl->AddText({origin.x + 4, origin.y + 2}, IM_COL32(200, 200, 200, 255), label);
    ImGui::Dummy(size);
}

// The line above the plot.
std::string status_line(const EditorUi& ui, const TradeResult& r, int marked)
{
    if (ui.trade.running())
        return "sweeping dt and substeps in the background...";
    if (!ui.trade.finished())
        return "press Run sweep: dt and substeps, each run against a converged reference";
    if (!r.error.empty())
        return "sweep failed: " + r.error;
    if (marked < 0)
        return "the current dt and substeps are not in the sweep: run it again";
    const TradePoint& p = r.points[static_cast<size_t>(marked)];
    char text[160];
    std::snprintf(text, sizeof text, "current (%s %s): %.3g ms per sim. s, error %.3g m", p.knob.c_str(),
                  p.value.c_str(), p.ms_per_sim_s, p.error_m);
    return text;
}

} // namespace

Status EditorUi::start_trade()
{
    const WorldDef& w = session().scene().world;
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("supermodal_editor_trade_" + std::to_string(getpid()) + ".json");
    trade.stop(); // the file is about to change under it
    if (Status saved = session().save(file.string(), false); !saved)
        return saved;
    trade_dt = w.dt;
    trade_substeps = w.substep_count;
    trade_seen = false;
    return trade.start(bench_cli, file.string(), trade_seconds, w.dt, w.substep_count);
}

void draw_trade_plot(EditorUi& ui, const WorldDef& w)
{
    ui.trade_readout = TradeReadout{};
    const bool open = ImGui::CollapsingHeader("Speed vs accuracy plot##trade");
    ui.track("Speed vs accuracy plot##trade");
    if (!open)
        return;
    // The narrow column scrolls: bring the plot into view when the section opens or a sweep ends.
    const bool bring_into_view = ImGui::IsItemToggledOpen() || (ui.trade.finished() && !ui.trade_seen);
    ui.trade_seen = ui.trade.finished();
    ui.trade_readout.shown = true;
    if (ImGui::Button("Run sweep##trade"))
        ui.report(ui.start_trade());
    ui.track("Run sweep##trade");
    const TradeResult r = ui.trade.running() ? TradeResult{} : ui.trade.result();
    // The mark follows the knobs: the point run at today's dt and substeps, if the sweep has one.
    const int marked = find_trade_point(r.points, w.dt, w.substep_count);
    ui.trade_readout.points = r.points.size();
    ui.trade_readout.marked = marked;
    ui.trade_readout.status = status_line(ui, r, marked);
    ImGui::TextWrapped("%s", ui.trade_readout.status.c_str());
    if (!r.points.empty())
        draw_points(r.points, marked, ui.scale());
    if (bring_into_view)
        ImGui::SetScrollHereY(1.0f);
}

} // namespace supermodal::editor
