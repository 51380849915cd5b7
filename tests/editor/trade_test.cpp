// Tests for editor/trade.cpp and ui_trade.cpp: the Speed / accuracy plot's background sweep, its
// parsing of bench's JSON and the mark that follows the dt and substeps knobs.
#include "script.h"
#include "session.h"
#include "trade.h"
#include "ui.h"

#include <gtest/gtest.h>
#include <sstream>

namespace ed = supermodal::editor;

namespace
{

const std::string k_scene = std::string(SM_SOURCE_DIR) + "/tests/editor/trade_drop.json";

ed::ScriptOutcome run(ed::EditorSession& s, ed::EditorUi& ui, const std::string& actions,
                      std::ostringstream& log)
{
    return ed::run_script_text(R"({"actions": )" + actions + "}", "test", ".", s, ui, log);
}

} // namespace

TEST(EditorTrade, ParsesBenchRowsIntoSettings)
{
    // Bench's own field names; a failed row and the reference are left out, a dt row scales the scene's dt.
    const std::string json = R"({"rows": [
      {"knob": "reference", "value": "converged", "status": "ok", "cpu_ms_per_sim_s": 9, "trajectory_rms_m": 0},
      {"knob": "dt", "value": "x2", "status": "ok", "cpu_ms_per_sim_s": 1.5, "cpu_ms_per_step": 0.012,
       "trajectory_rms_m": 0.008},
      {"knob": "dt", "value": "x0.5", "status": "failed", "cpu_ms_per_sim_s": 3, "trajectory_rms_m": null},
      {"knob": "substeps", "value": "4", "status": "ok", "cpu_ms_per_sim_s": 6, "cpu_ms_per_step": 0.024,
       "trajectory_rms_m": 3e-4}]})";
    const auto points = ed::parse_trade(json, 0.004, 1);
    ASSERT_TRUE(points) << points.error().message();
    ASSERT_EQ(points->size(), 2u);
    EXPECT_DOUBLE_EQ((*points)[0].dt, 0.008);
    EXPECT_EQ((*points)[0].substeps, 1);
    EXPECT_DOUBLE_EQ((*points)[1].dt, 0.004);
    EXPECT_EQ((*points)[1].substeps, 4);
    EXPECT_EQ(ed::find_trade_point(*points, 0.004, 4), 1);
    EXPECT_EQ(ed::find_trade_point(*points, 0.004, 1), -1);
    EXPECT_FALSE(ed::parse_trade("not json", 0.004, 1));
    EXPECT_FALSE(ed::parse_trade(R"({"rows": 3})", 0.004, 1));
}

TEST(EditorTrade, SweepMarksTheCurrentSettingAndTheMarkFollowsTheKnobs)
{
    ed::EditorSession s;
    ed::EditorUi ui(s, 1280, 720);
    ui.bench_cli = SM_CLI;
    std::ostringstream log;
    ed::ScriptOutcome o = run(
        s, ui, R"([{"action": "load", "file": ")" + k_scene + R"("}, {"action": "trade", "seconds": 0.3}])",
        log);
    ASSERT_EQ(o.failure, ed::ScriptFailure::None) << o.error.message() << log.str();
    const ed::TradeResult r = ui.trade.result();
    // bench's dt knob runs x4 .. x0.25 and its substeps knob 1, 2, 4: eight configurations.
    ASSERT_EQ(r.points.size(), 8u) << log.str();
    EXPECT_NE(log.str().find("current dt x1"), std::string::npos) << log.str();
    // Finer steps are more accurate on this drop (measured: x0.25 is 20 times closer than x1).
    const int base = ed::find_trade_point(r.points, 0.004, 1);
    const int fine = ed::find_trade_point(r.points, 0.001, 1);
    ASSERT_GE(base, 0);
    ASSERT_GE(fine, 0);
    EXPECT_LT(r.points[static_cast<size_t>(fine)].error_m, r.points[static_cast<size_t>(base)].error_m);

    // The plot's section open: it shows the points with the current one marked; halving dt moves the
    // mark to the x0.5 run without another sweep.
    ui.frame();
    const supermodal::Status pressed = ui.press("Speed vs accuracy plot");
    ASSERT_TRUE(pressed.ok()) << pressed.error().message();
    ui.frame();
    ASSERT_TRUE(ui.trade_readout.shown);
    EXPECT_EQ(ui.trade_readout.points, 8u);
    EXPECT_EQ(ui.trade_readout.marked, base);
    ASSERT_TRUE(s.set("/settings/dt", 0.002).ok());
    ui.frame();
    const int half = ed::find_trade_point(r.points, 0.002, 1);
    ASSERT_GE(half, 0);
    EXPECT_EQ(r.points[static_cast<size_t>(half)].value, "x0.5");
    EXPECT_EQ(ui.trade_readout.marked, half);
    ASSERT_TRUE(s.set("/settings/dt", 0.003).ok());
    ui.frame();
    EXPECT_EQ(ui.trade_readout.marked, -1);
    EXPECT_NE(ui.trade_readout.status.find("run it again"), std::string::npos) << ui.trade_readout.status;
}

TEST(EditorTrade, BadSecondsAndAMissingProgramAreRefused)
{
    ed::EditorSession s;
    ed::EditorUi ui(s, 1280, 720);
    ui.bench_cli = SM_CLI;
    std::ostringstream log;
    ASSERT_EQ(run(s, ui, R"([{"action": "load", "file": ")" + k_scene + R"("}])", log).failure,
              ed::ScriptFailure::None);
    ed::ScriptOutcome bad = run(s, ui, R"([{"action": "trade", "seconds": -1}])", log);
    EXPECT_EQ(bad.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(bad.error.message().find("/actions/0/seconds"), std::string::npos) << bad.error.message();
    ui.bench_cli = "/nonexistent/supermodal";
    ed::ScriptOutcome missing = run(s, ui, R"([{"action": "trade", "seconds": 0.1}])", log);
    EXPECT_NE(missing.failure, ed::ScriptFailure::None);
    EXPECT_NE(missing.error.message().find("/nonexistent/supermodal"), std::string::npos)
        << missing.error.message();
}
