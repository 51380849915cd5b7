// Tests for editor/input.cpp and the panel layout (ui_context.cpp): the docked panels leave the 3-D view
// most of the display, Tab hides them, Space plays and pauses, and the script's mouse and key actions
// reach the view (headless here; tests/editor/window_test.cpp sends the same through a real window).
#ifdef SM_HAS_RENDER
#include "render_hook.h"
#include "script.h"
#include "supermodal/body.h"
#include "supermodal/render.h"
#include "ui.h"

#include <array>
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

std::string at(const std::array<double, 2>& px)
{
    return R"("x": )" + std::to_string(px[0]) + R"(, "y": )" + std::to_string(px[1]);
}

/// Runs actions that must succeed.
void ok(ed::EditorSession& s, ed::EditorUi& ui, const std::string& actions)
{
    std::string log;
    const ed::ScriptOutcome o = run(s, ui, actions, &log);
    ASSERT_EQ(o.failure, ed::ScriptFailure::None) << o.error.message() << "\n" << log;
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

TEST(EditorCameraInput, AMiddleDragOrbitsKeepingTheDistanceAndTheLeftButtonStillPicks)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    const sm::CameraDef c0 = ed::editor_camera(s, ui);
    // 100 px right and 50 px down at 0.3 °/px: the eye goes 30° left and 15° up about the target.
    ok(s, ui, R"({"action": "mouse", "x": 500, "y": 300, "button": "middle", "down": true},
                 {"action": "mouse", "x": 600, "y": 350},
                 {"action": "mouse", "x": 600, "y": 350, "button": "middle", "down": false})");
    const sm::CameraDef c1 = ed::editor_camera(s, ui);
    EXPECT_NEAR(c1.yaw_deg, c0.yaw_deg - 30.0, 1e-9);
    EXPECT_NEAR(c1.pitch_deg, c0.pitch_deg + 15.0, 1e-9);
    EXPECT_EQ(c1.distance, c0.distance);
    EXPECT_NEAR(sm::length(ed::camera_eye(c1) - *c1.target), c0.distance, 1e-12);
    EXPECT_EQ(ui.view_input.gesture(), ed::ViewInput::Gesture::None);
    EXPECT_EQ(ui.selected_body(), ""); // orbiting selects nothing
    // Alt + left drag orbits too, and selects nothing although it starts on the ball.
    const auto ball = ed::screen_pixel(s, ui, sm::body_position(s.world(), sm::find_body(s.world(), "ball")));
    ASSERT_TRUE(ball.has_value());
    const std::string left50 = at({(*ball)[0] - 50, (*ball)[1]});
    ok(s, ui,
       R"({"action": "mouse", )" + at(*ball) + R"(, "button": "left", "down": true, "mods": ["alt"]},
                 {"action": "mouse", )" +
           left50 + R"(},
                 {"action": "mouse", )" +
           left50 + R"(, "button": "left", "down": false})");
    EXPECT_EQ(ui.selected_body(), "");
    EXPECT_FALSE(ui.view_input.dragging());
    EXPECT_NEAR(ed::editor_camera(s, ui).yaw_deg, c1.yaw_deg + 15.0, 1e-9);
    // The plain left button still picks and grabs what is under it in the moved view.
    const auto moved =
        ed::screen_pixel(s, ui, sm::body_position(s.world(), sm::find_body(s.world(), "ball")));
    ASSERT_TRUE(moved.has_value());
    ok(s, ui,
       R"({"action": "mouse", )" + at(*moved) + R"(, "button": "left", "down": true, "expect": "ball"},
                 {"action": "mouse", )" +
           at(*moved) + R"(, "button": "left", "down": false})");
}

TEST(EditorCameraInput, AShiftMiddleDragPansAndTheWheelZoomsTowardsThePointUnderTheCursor)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    const sm::CameraDef c0 = ed::editor_camera(s, ui);
    const sm::Vec3 target_pixel_probe = *c0.target;
    const auto before = ed::screen_pixel(s, ui, target_pixel_probe);
    ok(s, ui, R"({"action": "mouse", "x": 500, "y": 300, "button": "middle", "down": true, "mods": ["shift"]},
                 {"action": "mouse", "x": 560, "y": 280},
                 {"action": "mouse", "x": 560, "y": 280, "button": "middle", "down": false})");
    const sm::CameraDef c1 = ed::editor_camera(s, ui);
    EXPECT_EQ(c1.yaw_deg, c0.yaw_deg);
    EXPECT_EQ(c1.distance, c0.distance);
    // The old target's point followed the cursor (60, −20) px; the renderer's float matrix: 0.01 px.
    const auto after = ed::screen_pixel(s, ui, target_pixel_probe);
    ASSERT_TRUE(before && after);
    EXPECT_NEAR((*after)[0] - (*before)[0], 60.0, 0.01);
    EXPECT_NEAR((*after)[1] - (*before)[1], -20.0, 0.01);

    // Two notches in over the ball: 0.85² of the distance, the ball's centre stays on its pixel (its
    // centre is on the cursor's ray, which zooming leaves in place).
    const sm::Vec3 centre = sm::body_position(s.world(), sm::find_body(s.world(), "ball"));
    const auto ball = ed::screen_pixel(s, ui, centre);
    ASSERT_TRUE(ball.has_value());
    ok(s, ui, R"({"action": "mouse", )" + at(*ball) + R"(, "wheel": 2})");
    const sm::CameraDef c2 = ed::editor_camera(s, ui);
    EXPECT_NEAR(c2.distance, c1.distance * 0.85 * 0.85, 1e-12);
    const auto ball_after = ed::screen_pixel(s, ui, centre);
    ASSERT_TRUE(ball_after.has_value());
    EXPECT_NEAR((*ball_after)[0], (*ball)[0], 0.01);
    EXPECT_NEAR((*ball_after)[1], (*ball)[1], 0.01);
    // The wheel over a panel scrolls the panel, not the camera.
    ok(s, ui, R"({"action": "mouse", "x": 100, "y": 300, "wheel": -3})");
    EXPECT_EQ(ed::editor_camera(s, ui).distance, c2.distance);
    const ed::ScriptOutcome bad = run(s, ui, R"({"action": "mouse", "x": 600, "y": 300, "wheel": 0})");
    EXPECT_EQ(bad.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(bad.error.message().find("/wheel"), std::string::npos) << bad.error.message();
}

TEST(EditorCameraInput, KeysOrbitZoomPanAndFrame)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    const sm::CameraDef c0 = ed::editor_camera(s, ui);
    ok(s, ui, R"({"action": "key", "key": "left"}, {"action": "key", "key": "up"})");
    EXPECT_NEAR(ed::editor_camera(s, ui).yaw_deg, c0.yaw_deg - 15.0, 1e-9);
    EXPECT_NEAR(ed::editor_camera(s, ui).pitch_deg, c0.pitch_deg + 15.0, 1e-9);
    ok(s, ui,
       R"({"action": "key", "key": "plus"}, {"action": "key", "key": "plus"}, {"action": "key", "key": "minus"})");
    EXPECT_NEAR(ed::editor_camera(s, ui).distance, c0.distance * 0.85, 1e-12);
    const sm::Vec3 t = *ed::editor_camera(s, ui).target;
    ok(s, ui, R"({"action": "key", "key": "w"}, {"action": "key", "key": "d"})");
    const sm::CameraDef panned = ed::editor_camera(s, ui);
    const sm::CameraAxes axes = sm::camera_axes(panned);
    EXPECT_GT(sm::dot(*panned.target - t, axes.up), 0.0);    // W: the view moved up
    EXPECT_GT(sm::dot(*panned.target - t, axes.right), 0.0); // D: and right
    // Zoomed in 6 notches the scene no longer fits: the framing check fails (status 1) ...
    ok(s, ui,
       R"({"action": "key", "key": "plus"}, {"action": "key", "key": "plus"}, {"action": "key", "key": "plus"},
                 {"action": "key", "key": "plus"}, {"action": "key", "key": "plus"}, {"action": "key", "key": "plus"})");
    const ed::ScriptOutcome cut = run(s, ui, R"({"action": "camera", "framed": "all"})");
    EXPECT_EQ(cut.failure, ed::ScriptFailure::CheckFailed);
    EXPECT_NE(cut.error.message().find("outside the 3-D view"), std::string::npos) << cut.error.message();
    // ... Home frames every body again from the new angle (yaw and pitch kept) ...
    ok(s, ui, R"({"action": "key", "key": "home"}, {"action": "camera", "framed": "all"})");
    EXPECT_NEAR(ed::editor_camera(s, ui).yaw_deg, c0.yaw_deg - 15.0, 1e-9);
    // ... and F frames the selected ball: closer than everything, the ball's box inside.
    ok(s, ui, R"({"action": "select", "body": "ball"}, {"action": "key", "key": "f"},
                 {"action": "camera", "framed": ["ball"]})");
    const sm::CameraDef ball = ed::editor_camera(s, ui);
    EXPECT_LT(ball.distance, 0.5 * c0.distance);
    EXPECT_NEAR(sm::length(*ball.target - sm::body_position(s.world(), sm::find_body(s.world(), "ball"))),
                0.0, 1e-9);
    const ed::ScriptOutcome board = run(s, ui, R"({"action": "camera", "framed": ["board"]})");
    EXPECT_EQ(board.failure, ed::ScriptFailure::CheckFailed);
    // With the floor (a plane: no bounds) selected, F frames everything as Home does.
    ok(s, ui, R"({"action": "key", "key": "home"})");
    const double all = ed::editor_camera(s, ui).distance;
    ok(s, ui, R"({"action": "select", "body": "ball"}, {"action": "key", "key": "f"},
                 {"action": "select", "body": "floor"}, {"action": "key", "key": "f"})");
    EXPECT_EQ(ed::editor_camera(s, ui).distance, all);
}

TEST(EditorCameraInput, AMovedCameraSurvivesResetAndTabButALoadFramesTheNewScene)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    ui.frame(0.0);
    const sm::CameraDef c0 = ed::editor_camera(s, ui);
    // Unmoved, the view re-frames for a new aspect (Tab: the whole window).
    ok(s, ui, R"({"action": "key", "key": "tab"})");
    EXPECT_NE(ed::editor_camera(s, ui).distance, c0.distance);
    ok(s, ui, R"({"action": "key", "key": "tab"}, {"action": "key", "key": "right"})");
    const sm::CameraDef moved = ed::editor_camera(s, ui);
    ok(s, ui, R"({"action": "reset"}, {"action": "key", "key": "tab"}, {"action": "frames", "count": 1})");
    EXPECT_EQ(ed::editor_camera(s, ui).yaw_deg, moved.yaw_deg);
    EXPECT_EQ(ed::editor_camera(s, ui).distance, moved.distance);
    ok(s, ui, R"({"action": "key", "key": "tab"}, {"action": "load", "file": "samples/ball_on_board.json"},
                 {"action": "frames", "count": 1})");
    EXPECT_EQ(ed::editor_camera(s, ui).yaw_deg, c0.yaw_deg);
    EXPECT_NEAR(ed::editor_camera(s, ui).distance, c0.distance, 1e-12);
}

TEST(EditorCameraInput, HShowsTheShortcutListWithEveryBindingAndF1HidesIt)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    ok(s, ui, R"({"action": "key", "key": "h"})");
    ASSERT_TRUE(ui.show_help);
    ASSERT_EQ(ui.help_lines.size(), ed::shortcuts().size());
    std::string all;
    for (const std::string& line : ui.help_lines)
        all += line + "\n";
    for (const char* input : {"Middle drag", "Shift + middle drag", "Wheel", "Arrows", "+ / -", "W A S D",
                              "F", "Home", "Space", "Tab", "Escape", "H, F1", "Left drag", "Right click"})
        EXPECT_NE(all.find(input), std::string::npos) << input << " missing from\n" << all;
    ok(s, ui, R"({"action": "key", "key": "f1"})");
    EXPECT_FALSE(ui.show_help);
    EXPECT_TRUE(ui.help_lines.empty());
}

TEST(EditorLayout, AResizedDisplayMovesThePanelsAndTheViewFollows)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 720);
    std::string log;
    ASSERT_EQ(run(s, ui, R"({"action": "resize", "width": 960, "height": 540}, {"action": "viewport"})", &log)
                  .failure,
              ed::ScriptFailure::None)
        << log;
    // 960 px: the columns at their minimum widths (180 + 240 px), the view the 540 px between them.
    EXPECT_NE(log.find("resize 960x540"), std::string::npos) << log;
    EXPECT_NE(log.find("viewport 540x540 at (180, 0)"), std::string::npos) << log;
    // The framing followed the new aspect (1:1): every body inside the view.
    ok(s, ui, R"({"action": "camera", "framed": "all"})");
    EXPECT_DOUBLE_EQ(ui.view_aspect, 1.0);
    // Pixels are checked against the new size.
    const ed::ScriptOutcome off = run(s, ui, R"({"action": "mouse", "x": 1000, "y": 20})");
    EXPECT_EQ(off.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(off.error.message().find("[0, 960]"), std::string::npos) << off.error.message();
    const ed::ScriptOutcome bad = run(s, ui, R"({"action": "resize", "width": 8, "height": 540})");
    EXPECT_EQ(bad.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(bad.error.message().find("/width"), std::string::npos) << bad.error.message();
    EXPECT_EQ(ui.width(), 960);
}

TEST(EditorLayout, TheHiDpiScaleDoublesFontsAndPanelsOnADoubleSizeDisplay)
{
    // X11 or Windows at 200%: window and framebuffer count the same pixels, so the UI scales by 2;
    // macOS or Wayland at 200%: the framebuffer is twice the window, the coordinates already scale.
    EXPECT_EQ(ed::hidpi_ui_scale(2.0f, 2560, 2560), 2.0f);
    EXPECT_EQ(ed::hidpi_ui_scale(2.0f, 1280, 2560), 1.0f);
    EXPECT_EQ(ed::hidpi_ui_scale(1.5f, 1000, 1000), 1.5f);
    EXPECT_EQ(ed::hidpi_ui_scale(1.0f, 0, 0), 1.0f); // minimised
    EXPECT_EQ(ed::hidpi_ui_scale(100.0f, 10, 10), 4.0f);
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi small(s, 1280, 720), large(s, 2560, 1440);
    large.set_scale(ed::hidpi_ui_scale(2.0f, 2560, 2560));
    small.select_body("board");
    large.select_body("board");
    small.frame(0.0);
    large.frame(0.0);
    // The same layout at twice the pixels: every panel edge doubles (the columns' limits scale too).
    const ed::PanelLayout a = ed::panel_layout(1280, 720), b = ed::panel_layout(2560, 1440, 2.0f);
    for (const auto& [r1, r2] : {std::pair{a.scene, b.scene}, std::pair{a.run, b.run},
                                 std::pair{a.body, b.body}, std::pair{a.speed, b.speed}}) {
        EXPECT_FLOAT_EQ(r2.x0, 2 * r1.x0);
        EXPECT_FLOAT_EQ(r2.x1, 2 * r1.x1);
        EXPECT_FLOAT_EQ(r2.y0, 2 * r1.y0);
        EXPECT_FLOAT_EQ(r2.y1, 2 * r1.y1);
    }
    EXPECT_FLOAT_EQ(large.viewport().x0, 2 * small.viewport().x0);
    EXPECT_FLOAT_EQ(large.viewport().x1, 2 * small.viewport().x1);
    // Text and padding double: the Play button is twice as tall and wide (ImGui rounds positions to
    // whole pixels: 1 px), and a press by label finds it where the doubled layout put it.
    const auto play = [](const ed::EditorUi& ui) {
        for (const ed::WidgetRect& w : ui.widgets())
            if (w.label == "Play")
                return w;
        return ed::WidgetRect{};
    };
    EXPECT_GT(play(small).max_y - play(small).min_y, 10.0f);
    EXPECT_NEAR(play(large).max_y - play(large).min_y, 2.0f * (play(small).max_y - play(small).min_y), 1.0f);
    EXPECT_NEAR(play(large).max_x - play(large).min_x, 2.0f * (play(small).max_x - play(small).min_x), 1.0f);
    ok(s, large, R"({"action": "press", "widget": "Play"})");
    EXPECT_TRUE(s.playing());
}
#endif
