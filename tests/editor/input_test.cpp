// Tests for editor/input.cpp and the panel layout (ui_context.cpp): the docked panels leave the 3-D view
// most of the display, Tab hides them, Space plays and pauses, and the script's mouse and key actions
// reach the view (headless here; tests/editor/window_test.cpp sends the same through a real window).
#ifdef SM_HAS_RENDER
#include "render_hook.h"
#include "script.h"
#include "supermodal/body.h"
#include "supermodal/render.h"
#include "ui.h"

#include <gtest/gtest.h>
#include <sstream>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

const std::string k_board = std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json";

ed::ScriptOutcome run(ed::EditorSession& s, ed::EditorUi& ui, const std::string& actions,
                      std::string* log = nullptr)
{
    std::ostringstream out;
    ed::ScriptOutcome o =
        ed::run_script_text(R"({"actions": [)" + actions + "]}", "test.json", SM_SOURCE_DIR, s, ui, out);
    if (log != nullptr)
        *log = out.str();
    return o;
}

double view_fraction(const ed::EditorUi& ui)
{
    return ui.viewport().area() / (static_cast<double>(ui.width()) * ui.height());
}

} // namespace

TEST(EditorLayout, ThePanelsLeaveTheViewOverSixtyPercentOfTheDisplay)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    for (const auto& [w, h] : {std::pair{1280, 720}, std::pair{1920, 1080}, std::pair{1600, 900}}) {
        ed::EditorUi ui(s, w, h);
        ui.select_body("board"); // the Body panel at its fullest
        ui.frame(0.0);
        EXPECT_GE(view_fraction(ui), 0.6) << w << "x" << h;
        // The view is the band between the columns, full height.
        EXPECT_GT(ui.viewport().x0, 0.0f);
        EXPECT_LT(ui.viewport().x1, static_cast<float>(w));
        EXPECT_EQ(ui.viewport().height(), static_cast<float>(h));
    }
}

TEST(EditorLayout, TabHidesAndShowsThePanels)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    std::string log;
    ASSERT_EQ(
        run(s, ui, R"({"action": "key", "key": "tab"}, {"action": "viewport", "min_fraction": 1})", &log)
            .failure,
        ed::ScriptFailure::None)
        << log;
    EXPECT_FALSE(ui.show_windows);
    ASSERT_EQ(
        run(s, ui, R"({"action": "key", "key": "tab"}, {"action": "viewport", "min_fraction": 0.6})").failure,
        ed::ScriptFailure::None);
    EXPECT_TRUE(ui.show_windows);
    EXPECT_LT(view_fraction(ui), 0.7);
}

TEST(EditorLayout, TheViewportCheckFailsWhenThePanelsCoverTooMuch)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    const ed::ScriptOutcome o = run(s, ui, R"({"action": "frames", "count": 1},
                                              {"action": "viewport", "min_fraction": 0.9})");
    EXPECT_EQ(o.failure, ed::ScriptFailure::CheckFailed);
    EXPECT_NE(o.error.message().find("min_fraction"), std::string::npos) << o.error.message();
}

TEST(EditorInput, SpacePlaysAndPauses)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    ASSERT_EQ(run(s, ui, R"({"action": "key", "key": "space"})").failure, ed::ScriptFailure::None);
    EXPECT_TRUE(s.playing());
    ASSERT_EQ(run(s, ui, R"({"action": "key", "key": "space"})").failure, ed::ScriptFailure::None);
    EXPECT_FALSE(s.playing());
    const ed::ScriptOutcome bad = run(s, ui, R"({"action": "key", "key": "hyper"})");
    EXPECT_EQ(bad.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(bad.error.message().find("keys are: tab, space"), std::string::npos) << bad.error.message();
}

TEST(EditorInput, TheLeftButtonPicksAndDragsABodyInTheView)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    const sm::Entity ball = sm::find_body(s.world(), "ball");
    const auto px = ed::screen_pixel(s, ui, sm::body_position(s.world(), ball));
    ASSERT_TRUE(px.has_value());
    const sm::Vec3 before = sm::body_position(s.world(), ball);
    const std::string at = R"("x": )" + std::to_string((*px)[0]) + R"(, "y": )" + std::to_string((*px)[1]);
    // Press on the ball: it is selected and grabbed; the mouse moves up 100 px while the world steps.
    ASSERT_EQ(
        run(s, ui, R"({"action": "mouse", )" + at + R"(, "button": "left", "down": true, "expect": "ball"})")
            .failure,
        ed::ScriptFailure::None);
    EXPECT_TRUE(ui.view_input.dragging());
    const std::string above =
        R"("x": )" + std::to_string((*px)[0]) + R"(, "y": )" + std::to_string((*px)[1] - 100);
    ASSERT_EQ(run(s, ui,
                  R"({"action": "mouse", )" + above + R"(}, {"action": "step", "count": 200},
                           {"action": "mouse", )" +
                      above + R"(, "button": "left", "down": false})")
                  .failure,
              ed::ScriptFailure::None);
    EXPECT_FALSE(ui.view_input.dragging());
    // The spring pulled the ball up towards the mouse (without it, it would rest on the board).
    EXPECT_GT(sm::body_position(s.world(), ball).y, before.y + 0.01);
    // A press on an empty part of a panel is ImGui's: nothing is picked (the ray there meets the floor).
    ui.select_body("");
    ASSERT_EQ(run(s, ui, R"({"action": "mouse", "x": 100, "y": 400, "button": "left", "down": true},
                           {"action": "mouse", "x": 100, "y": 400, "button": "left", "down": false})")
                  .failure,
              ed::ScriptFailure::None);
    EXPECT_EQ(ui.selected_body(), "");
    EXPECT_FALSE(ui.view_input.dragging());
}

TEST(EditorInput, AWrongExpectationFailsTheCheck)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    const ed::ScriptOutcome o = run(s, ui, R"({"action": "mouse", "x": 640, "y": 20, "expect": "ball"})");
    EXPECT_EQ(o.failure, ed::ScriptFailure::CheckFailed);
    const ed::ScriptOutcome off = run(s, ui, R"({"action": "mouse", "x": 5000, "y": 20})");
    EXPECT_EQ(off.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(off.error.message().find("/x"), std::string::npos) << off.error.message();
}
#endif
