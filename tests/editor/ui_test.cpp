// Tests for editor/ui_*.cpp: the ImGui windows drawn with no graphics backend, driven by synthetic mouse
// input that presses widgets by label.
#include "supermodal/modal.h"
#include "ui.h"

#include <gtest/gtest.h>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

const std::string k_samples = std::string(SM_SOURCE_DIR) + "/samples/";

} // namespace

TEST(EditorUi, PauseAndStepButtonsActOnTheSession)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_samples + "chair_with_dummy.json"));
    ed::EditorUi ui(s);
    ASSERT_TRUE(ui.press("Play"));
    EXPECT_TRUE(s.playing());
    ui.frame(0.05); // 50 steps of 1 ms while playing
    const uint64_t played = s.world().step_count();
    EXPECT_GE(played, 49u);
    ASSERT_TRUE(ui.press("Pause"));
    EXPECT_FALSE(s.playing());
    ui.frame(0.05);
    EXPECT_EQ(s.world().step_count(), played) << "paused: frames do not step";
    ASSERT_TRUE(ui.press("Step"));
    EXPECT_EQ(s.world().step_count(), played + 1);
    ASSERT_TRUE(ui.press("Reset"));
    EXPECT_EQ(s.world().step_count(), 0u);
}

TEST(EditorUi, TreeSelectsABodyAndTheBodyWindowMakesItModal)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_samples + "ball_on_board.json"));
    ed::EditorUi ui(s);
    ASSERT_TRUE(ui.press("ball"));
    EXPECT_EQ(ui.selected_body(), "ball");
    ASSERT_TRUE(ui.press("Modal")) << "the text before ## finds \"Modal##body\"";
    EXPECT_TRUE(ui.last_error().empty()) << ui.last_error();
    EXPECT_EQ(s.scene().bodies[4].dynamics, sm::DynamicsType::Modal);
    EXPECT_NE(sm::body_modal_basis(s.world(), sm::find_body(s.world(), "ball")), nullptr);
    ASSERT_TRUE(ui.press("Rigid"));
    EXPECT_EQ(s.scene().bodies[4].dynamics, sm::DynamicsType::Rigid);
}

TEST(EditorUi, PressingAMissingWidgetListsTheOnesThereAre)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_samples + "ball_on_board.json"));
    ed::EditorUi ui(s);
    const sm::Status status = ui.press("Paws");
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message().find("no visible widget labelled \"Paws\""), std::string::npos);
    EXPECT_NE(status.error().message().find("Pause"), std::string::npos) << status.error().message();
}
