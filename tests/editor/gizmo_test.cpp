// Tests for editor/gizmo.cpp, headless: the gizmo's handles grabbed and dragged by mouse events (the
// window test drives the same script through GLFW), its keys, and snapping turned off.
#include "gizmo_log.h"
#include "render_hook.h"
#include "script.h"
#include "ui.h"

#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

namespace ed = supermodal::editor;
namespace st = supermodal::test;

namespace
{

const std::string k_script = std::string(SM_SOURCE_DIR) + "/tests/editor/gizmo_script.json";

std::string script_text()
{
    std::ifstream in(k_script);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

/// Runs script text from tests/editor/ (its paths are relative to it); the log.
std::string run(const std::string& text, ed::ScriptFailure expected = ed::ScriptFailure::None)
{
    ed::EditorSession s;
    ed::EditorUi ui(s, 1280, 720);
    std::ostringstream log;
    const ed::ScriptOutcome o = ed::run_script_text(text, "gizmo_script.json",
                                                    std::string(SM_SOURCE_DIR) + "/tests/editor", s, ui, log);
    EXPECT_EQ(o.failure, expected) << o.error.message() << "\n" << log.str();
    return log.str();
}

} // namespace

#ifdef SM_HAS_RENDER
TEST(EditorGizmo, DraggingAnArrowARingAndABoxChangesOneAxisBySnappedStepsAndUndoRestoresThePose)
{
    st::check_gizmo_poses(st::logged_poses(run(script_text())));
}

TEST(EditorGizmo, WithSnappingOffTheSameDragMovesByWhatThePointerDid)
{
    std::string text = script_text();
    const std::string first_key = R"({ "action": "key", "key": "g")";
    text.replace(text.find(first_key), 0, R"({ "action": "key", "key": "n" }, )");
    const std::vector<st::LoggedPose> p = st::logged_poses(run(text));
    ASSERT_EQ(p.size(), 5u);
    // Unsnapped, the move is the pointer's point on the arrow: not a whole number of 0.05 m steps
    // (measured 0.178 m, where the snapped drag moves 0.2 m).
    const double dx = p[1].position[0] - p[0].position[0];
    EXPECT_GT(st::off_step(dx, 0.05), 0.01) << dx;
    EXPECT_EQ(p[1].position[1], p[0].position[1]);
    EXPECT_EQ(p[1].position[2], p[0].position[2]);
}

TEST(EditorGizmo, ModeKeysAndButtonsSwitchTheGizmoAndAPressOffTheHandlesStillPicks)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(std::string(SM_SOURCE_DIR) + "/samples/chair_with_dummy.json"));
    ed::EditorUi ui(s, 1280, 720);
    ui.select_body("chair_seat");
    ui.frame();
    EXPECT_TRUE(ed::gizmo_handles(s, ui).empty()); // off until asked for
    const std::pair<ed::EditorKey, ed::GizmoMode> keys[] = {{ed::EditorKey::G, ed::GizmoMode::Move},
                                                            {ed::EditorKey::R, ed::GizmoMode::Rotate},
                                                            {ed::EditorKey::E, ed::GizmoMode::Scale},
                                                            {ed::EditorKey::Q, ed::GizmoMode::Off}};
    for (const auto& [key, mode] : keys) {
        ui.on_key(key, true);
        EXPECT_EQ(ui.gizmo.mode, mode);
        EXPECT_EQ(ed::gizmo_handles(s, ui).size(), mode == ed::GizmoMode::Off ? 0u : 3u);
    }
    ui.on_key(ed::EditorKey::N, true);
    EXPECT_FALSE(ui.gizmo.snap);
    ASSERT_TRUE(ui.press("Rotate##gizmo"));
    EXPECT_EQ(ui.gizmo.mode, ed::GizmoMode::Rotate);
    ASSERT_TRUE(ui.press("Snap##gizmo"));
    EXPECT_TRUE(ui.gizmo.snap);
    // The ring's handle pixel grabs its own ring; a press on the dummy's head, away from every handle,
    // picks and pulls the head as without a gizmo, and changes no pose by an edit.
    const auto handle = ed::gizmo_handle_pixel(s, ui, 1);
    ASSERT_TRUE(handle);
    const auto grabbed = ed::gizmo_grab(s, ui, (*handle)[0], (*handle)[1]);
    ASSERT_TRUE(grabbed);
    EXPECT_EQ(grabbed->axis, 1);
    const auto head = ed::screen_pixel(
        s, ui, supermodal::body_position(s.world(), supermodal::find_body(s.world(), "dummy_head")));
    ASSERT_TRUE(head);
    EXPECT_FALSE(ed::gizmo_grab(s, ui, (*head)[0], (*head)[1]));
    ui.on_cursor((*head)[0], (*head)[1]);
    ui.on_button(ed::MouseButton::Left, true);
    ui.host_frame(1.0 / 60.0);
    EXPECT_EQ(ui.selected_body(), "dummy_head");
    EXPECT_TRUE(s.drag().has_value());
    EXPECT_TRUE(s.history().empty());
}
#endif
