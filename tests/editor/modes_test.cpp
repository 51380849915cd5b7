// Tests for the Body window's Mode shapes section and mode animations (editor/modes.cpp): the frequencies
// shown are the basis's, an animated mode moves the surface along that mode alone, and ending the
// animation gives the world back to the bit.
#include "script.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

const std::string k_board = std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json";

/// Whether the last frame drew a visible widget with this label.
bool drawn(const ed::EditorUi& ui, const std::string& label)
{
    for (const ed::WidgetRect& w : ui.widgets())
        if (w.label == label && w.visible)
            return true;
    return false;
}

/// Runs script actions (the text between the brackets of "actions") against the session and UI.
ed::ScriptOutcome run(ed::EditorSession& s, ed::EditorUi& ui, const std::string& actions, std::string& log)
{
    std::ostringstream out;
    const ed::ScriptOutcome outcome =
        ed::run_script_text("{\"actions\": [" + actions + "]}", "test.json", SM_SOURCE_DIR, s, ui, out);
    log = out.str();
    return outcome;
}

/// Rest points of the board's surface (radii 0.5, 0.019, 0.0445 m): the top's centre, an end, a corner.
const sm::Vec3 k_points[] = {{0.0, 0.019, 0.0}, {0.5, 0.0, 0.0}, {-0.45, 0.019, 0.04}};

} // namespace

TEST(EditorModes, PanelShowsTheBasisFrequencies)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 1600); // tall enough that the whole Body window shows without scrolling
    ui.select_body("board");
    s.step(100); // 50 ms: resting on its supports, loaded by them and gravity
    ui.frame(0.0);
    const ed::ModesReadout& r = ui.modes;
    ASSERT_TRUE(r.shown);
    const sm::World& w = s.world();
    const sm::Entity board = sm::find_body(w, "board");
    const sm::ModalBasis* basis = sm::body_modal_basis(w, board);
    ASSERT_NE(basis, nullptr);
    ASSERT_EQ(r.frequencies_hz.size(), 8u);
    EXPECT_EQ(r.frequencies_hz, basis->frequencies_hz); // copied, so equal to the bit
    EXPECT_EQ(r.amplitudes, sm::body_modal_state(w, board).amplitudes);
    const sm::ModalAccuracy accuracy = sm::body_modal_accuracy(w, board);
    EXPECT_EQ(r.residual, accuracy.residual);
    EXPECT_EQ(r.truncated_energy, accuracy.truncated_energy);
    EXPECT_GT(r.truncated_energy, 0.0); // supports and gravity load modes beyond the 8 kept
    EXPECT_EQ(r.plastic_dent, 0.0);     // wood here has no yield stress
    // The drawn text: each frequency as formatted, one Animate button per mode.
    char first[64];
    std::snprintf(first, sizeof first, "%7.4g Hz", basis->frequencies_hz[0]);
    EXPECT_NE(r.lines[1].find(first), std::string::npos) << r.lines[1];
    for (int k = 1; k <= 8; ++k)
        EXPECT_TRUE(drawn(ui, "Animate " + std::to_string(k))) << k;
    EXPECT_FALSE(drawn(ui, "Animate 9"));

    // The script's log carries the same frequencies, 17 digits: read back to the same doubles.
    std::string log;
    ASSERT_EQ(run(s, ui, R"({"action": "modes", "body": "board"})", log).failure, ed::ScriptFailure::None);
    const size_t at = log.find("8 modes [Hz]");
    ASSERT_NE(at, std::string::npos) << log;
    std::istringstream in(log.substr(at + 12));
    for (double f : basis->frequencies_hz) {
        double logged = 0.0;
        in >> logged;
        EXPECT_EQ(logged, f);
    }
}

TEST(EditorModes, AnimationMovesOneModeAndRestoreGivesTheStateBack)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    s.step(100);
    s.play();
    sm::World& w = s.world();
    const sm::Entity board = sm::find_body(w, "board");
    const sm::ModalBasis& basis = *sm::body_modal_basis(w, board);
    const uint64_t hash = w.state_hash();
    const uint64_t steps = w.step_count();
    const sm::BodyModalState before = sm::body_modal_state(w, board);
    sm::Vec3 surface[3];
    for (int i = 0; i < 3; ++i)
        surface[i] = sm::body_deformed_point(w, board, k_points[i]);
    const sm::ModalAccuracy accuracy = sm::body_modal_accuracy(w, board);
    ASSERT_NE(before.amplitudes[2], 0.0); // the supports load the third mode too: a real offset to keep

    const int k = 2;
    sm::editor::ModeAnimationDef def;
    def.mode = k;
    ASSERT_TRUE(s.animate_mode("board", def));
    EXPECT_FALSE(s.playing());
    const ed::ModeAnimation a = *s.mode_animation();
    EXPECT_EQ(a.frequency_hz, basis.frequencies_hz[k]);
    // 0.1 of the lattice box's largest half-extent (the board's half-length, 0.5 m, or a little more).
    EXPECT_GE(a.peak_displacement, 0.05);
    EXPECT_LE(a.peak_displacement, 0.06);
    // A quarter of the 1 s swing: sin(π/2) = 1, the peak.
    for (int f = 0; f < 15; ++f)
        EXPECT_EQ(s.frame(1.0 / 60.0), 0); // no step runs
    EXPECT_EQ(w.step_count(), steps);
    const sm::BodyModalState during = sm::body_modal_state(w, board);
    for (size_t j = 0; j < during.amplitudes.size(); ++j) {
        if (j == static_cast<size_t>(k))
            continue;
        EXPECT_EQ(during.amplitudes[j], before.amplitudes[j]) << j; // untouched, to the bit
        EXPECT_EQ(during.velocities[j], before.velocities[j]) << j;
    }
    // 15 frames of 1/60 s sum to 0.25 s within a few ulps: sin is 1 to ~1e-15.
    EXPECT_NEAR(during.amplitudes[k] - before.amplitudes[k], a.amplitude, 1e-12 * a.amplitude);
    // The surface moved by mode k's shape times the swing, nothing else (rounding: 1e-12 m).
    std::vector<double> only_k(basis.mode_count, 0.0);
    only_k[k] = during.amplitudes[k] - before.amplitudes[k];
    double moved = 0.0;
    for (int i = 0; i < 3; ++i) {
        const sm::Vec3 expected =
            sm::rotate(sm::body_orientation(w, board), sm::modal_displacement(basis, k_points[i], only_k));
        const sm::Vec3 got = sm::body_deformed_point(w, board, k_points[i]) - surface[i];
        EXPECT_LT(sm::length(got - expected), 1e-12) << i;
        moved = std::max(moved, sm::length(got));
    }
    EXPECT_GT(moved, 0.01); // visible: centimetres at the peak
    // The panel keeps the accuracy report of the state the swing started from, and lists the swung q.
    const ed::ModesReadout shown = ed::modes_readout(s, "board");
    EXPECT_EQ(shown.animating, k);
    EXPECT_EQ(shown.residual, accuracy.residual);
    EXPECT_EQ(shown.truncated_energy, accuracy.truncated_energy);
    EXPECT_EQ(shown.amplitudes, during.amplitudes);
    ed::EditorUi ui(s);
    ui.select_body("board");
    ui.frame(0.0);
    EXPECT_EQ(ui.speed_accuracy.modal_residual, accuracy.residual);

    s.end_mode_animation();
    EXPECT_FALSE(s.mode_animation().has_value());
    EXPECT_EQ(w.state_hash(), hash);
    EXPECT_TRUE(s.playing()); // it was playing before
    const sm::BodyModalState after = sm::body_modal_state(w, board);
    EXPECT_EQ(after.amplitudes, before.amplitudes);
    EXPECT_EQ(after.velocities, before.velocities);
}

TEST(EditorModes, FromRestOtherModesStayZero)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    const sm::Entity board = sm::find_body(s.world(), "board");
    const uint64_t hash = s.world().state_hash();
    sm::editor::ModeAnimationDef def;
    def.mode = 0;
    ASSERT_TRUE(s.animate_mode("board", def));
    s.frame(0.1);
    const sm::BodyModalState during = sm::body_modal_state(s.world(), board);
    EXPECT_NE(during.amplitudes[0], 0.0);
    for (size_t j = 1; j < during.amplitudes.size(); ++j)
        EXPECT_EQ(during.amplitudes[j], 0.0) << j;
    s.end_mode_animation();
    EXPECT_EQ(s.world().state_hash(), hash);
}

TEST(EditorModes, StepEndsTheAnimationFromTheSavedState)
{
    // A step during an animation runs from the world as it was, not from the swung shape.
    ed::EditorSession plain, animated;
    ASSERT_TRUE(plain.load(k_board));
    ASSERT_TRUE(animated.load(k_board));
    plain.step(50);
    animated.step(50);
    sm::editor::ModeAnimationDef def;
    def.mode = 1;
    ASSERT_TRUE(animated.animate_mode("board", def));
    animated.frame(0.3);
    animated.step(10);
    plain.step(10);
    EXPECT_FALSE(animated.mode_animation().has_value());
    EXPECT_EQ(animated.world().state_hash(), plain.world().state_hash());
}

TEST(EditorModes, ButtonsAndScriptActions)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 1600);
    ui.select_body("board");
    s.step(20);
    const uint64_t hash = s.world().state_hash();
    ui.frame(0.0);
    ASSERT_TRUE(ui.press("Animate 2"));
    ASSERT_TRUE(s.mode_animation().has_value());
    EXPECT_EQ(s.mode_animation()->mode, 1);
    ui.frame(0.2);
    EXPECT_EQ(ui.modes.animating, 1); // the panel says so from the next frame
    EXPECT_NE(s.world().state_hash(), hash);
    ASSERT_TRUE(ui.press("Restore"));
    EXPECT_FALSE(s.mode_animation().has_value());
    EXPECT_EQ(s.world().state_hash(), hash);

    std::string log;
    ASSERT_EQ(run(s, ui,
                  R"({"action": "animate", "body": "board", "mode": 3}, {"action": "frames", "count": 10},
                     {"action": "modes"}, {"action": "animate", "restore": true})",
                  log)
                  .failure,
              ed::ScriptFailure::None)
        << log;
    EXPECT_NE(log.find("board mode 3 ("), std::string::npos) << log;
    EXPECT_NE(log.find("mode 3 animated"), std::string::npos) << log; // "modes" uses the selection
    EXPECT_NE(log.find("ended: the world is restored"), std::string::npos) << log;
    EXPECT_EQ(s.world().state_hash(), hash);

    // Refused: a mode out of range, a rigid body, both keys; nothing changes.
    ed::ScriptOutcome bad = run(s, ui, R"({"action": "animate", "body": "board", "mode": 9})", log);
    EXPECT_EQ(bad.failure, ed::ScriptFailure::BadScript);
    EXPECT_EQ(bad.error.where, "/actions/0/mode");
    EXPECT_NE(bad.error.what.find("modes 1 to 8, not 9"), std::string::npos) << bad.error.what;
    bad = run(s, ui, R"({"action": "animate", "body": "ball", "mode": 1})", log);
    EXPECT_NE(bad.error.what.find("\"ball\" is rigid"), std::string::npos) << bad.error.what;
    bad = run(s, ui, R"({"action": "animate", "mode": 1, "restore": true})", log);
    EXPECT_EQ(bad.error.where, "/actions/0");
    EXPECT_FALSE(s.mode_animation().has_value());
    EXPECT_EQ(s.world().state_hash(), hash);
}

TEST(EditorModes, RigidBodyShowsNoModes)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(k_board));
    ed::EditorUi ui(s, 1280, 1600);
    ui.select_body("ball");
    ui.frame(0.0);
    EXPECT_FALSE(ui.modes.shown);
    EXPECT_FALSE(drawn(ui, "Mode shapes##body"));
    EXPECT_FALSE(drawn(ui, "Animate 1"));
    const ed::ModesReadout r = ed::modes_readout(s, "ball");
    EXPECT_TRUE(r.rigid);
    EXPECT_FALSE(r.modal);
    EXPECT_TRUE(r.frequencies_hz.empty());
    std::string log;
    ASSERT_EQ(run(s, ui, R"({"action": "modes", "body": "ball"})", log).failure, ed::ScriptFailure::None);
    EXPECT_NE(log.find("ball: rigid, no modes"), std::string::npos) << log;
}

TEST(EditorModes, MouldedClayListsItsDentAndRebuiltModes)
{
    // The clay block of the moulding test, pressed 12 mm from above and let go: the dent it keeps is
    // listed, and the modes shown are those rebuilt for the moulded block (the dent is past the default
    // remould threshold, 2% of the block's 0.2 m).
    ed::EditorSession s;
    ASSERT_TRUE(s.load(std::string(SM_SOURCE_DIR) + "/tests/editor/clay.json"));
    s.step(300);
    const ed::ModesReadout unmoulded = ed::modes_readout(s, "clay");
    EXPECT_EQ(unmoulded.plastic_dent, 0.0);
    EXPECT_EQ(unmoulded.rebuilds, 0);
    ASSERT_TRUE(s.mould(ed::Ray{{0.0, 0.5, 0.0}, {0, -1, 0}}, 0.012, 300));
    s.step(600);
    const ed::ModesReadout r = ed::modes_readout(s, "clay");
    EXPECT_GT(r.plastic_dent, 0.005); // the moulding test keeps > half of a 10 mm press
    EXPECT_LT(r.plastic_dent, 0.05);
    EXPECT_GE(r.rebuilds, 1);
    const sm::BodyRemould remould = sm::body_remould(s.world(), sm::find_body(s.world(), "clay"));
    std::printf("clay: %d rebuilds, dent %.4g m, last rebuild %.3g s (the swap waited %.3g s)\n", r.rebuilds,
                r.plastic_dent, remould.build_seconds, remould.wait_seconds);
    // The listed frequencies are the body's current (rebuilt) basis, not the unmoulded block's.
    const sm::ModalBasis* basis = sm::body_modal_basis(s.world(), sm::find_body(s.world(), "clay"));
    ASSERT_NE(basis, nullptr);
    EXPECT_EQ(r.frequencies_hz, basis->frequencies_hz);
    EXPECT_NE(r.frequencies_hz, unmoulded.frequencies_hz);
    const std::string& dent_line = r.rebuild_pending_step != 0 ? r.lines[r.lines.size() - 2] : r.lines.back();
    EXPECT_NE(dent_line.find("plastic dent"), std::string::npos) << dent_line;
    EXPECT_NE(dent_line.find("of the moulded shape"), std::string::npos) << dent_line;
}
