// Tests for the Speed / accuracy window (editor/ui_controls.cpp): what it shows is the engine's values.
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "ui.h"

#include <cstdio>
#include <gtest/gtest.h>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

bool shows(const ed::SpeedAccuracyReadout& r, const std::string& text)
{
    for (const std::string& line : r.lines)
        if (line.find(text) != std::string::npos)
            return true;
    return false;
}

std::string formatted(const char* format, double v)
{
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

} // namespace

TEST(EditorPanel, SpeedAccuracyShowsTheEnginesValues)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json"));
    ed::EditorUi ui(s);
    ui.select_body("board");
    // 50 ms: the board rests on its supports, the ball (0.4 m up, 3 m/s down) is still falling (it
    // strikes at about 70 ms and the board jumps off its supports).
    s.step(100);
    ui.frame(0.0);
    const ed::SpeedAccuracyReadout& r = ui.speed_accuracy;
    ASSERT_TRUE(r.shown);
    const sm::World& w = s.world();
    const sm::Entity board = sm::find_body(w, "board");
    EXPECT_EQ(r.dt, w.settings().dt);
    EXPECT_EQ(r.ms_per_step, s.ms_per_step());
    EXPECT_GT(r.ms_per_step, 0.0);
    EXPECT_EQ(r.max_penetration, sm::world_max_penetration(w));
    int contacts = 0, points = 0;
    for (const sm::ContactInfo& c : sm::world_contacts(w)) {
        ++contacts;
        points += c.point_count;
    }
    EXPECT_EQ(r.contacts, contacts);
    EXPECT_EQ(r.contact_points, points);
    EXPECT_GE(contacts, 2); // the two supports at least
    EXPECT_EQ(r.modal_body, "board");
    EXPECT_EQ(r.modes, sm::body_modal_basis(w, board)->mode_count);
    // Same function on the same state: equal to the last bit.
    const sm::ModalAccuracy accuracy = sm::body_modal_accuracy(w, board);
    EXPECT_EQ(r.modal_residual, accuracy.residual);
    EXPECT_EQ(r.truncated_fraction, accuracy.truncated_fraction);
    EXPECT_GT(r.modal_residual, 0.0); // loaded by the supports and gravity: 8 modes cannot be exact
    EXPECT_EQ(r.modal_energy, sm::body_modal_energy(w, board));
    // And the text drawn says so.
    EXPECT_TRUE(shows(r, "modal residual " + formatted("%.3e", accuracy.residual)));
    EXPECT_TRUE(shows(r, formatted("%.3f ms/step", s.ms_per_step())));
    EXPECT_TRUE(
        shows(r, "contacts " + std::to_string(contacts) + ", contact points " + std::to_string(points)));

    // A rigid selection: no modal values.
    ui.select_body("ball");
    ui.frame(0.0);
    EXPECT_TRUE(ui.speed_accuracy.modal_body.empty());
    EXPECT_EQ(ui.speed_accuracy.modal_residual, 0.0);
    // Hidden windows show nothing.
    ui.show_windows = false;
    ui.frame(0.0);
    EXPECT_FALSE(ui.speed_accuracy.shown);
}
