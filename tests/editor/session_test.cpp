// Tests for editor/session.cpp, parameter.cpp and pick.cpp: editing, picking, dragging, pushing.
#include "session.h"
#include "supermodal/body.h"
#include "supermodal/modal.h"

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

namespace sm = supermodal;
namespace ed = supermodal::editor;

namespace
{

const std::string k_samples = std::string(SM_SOURCE_DIR) + "/samples/";

ed::EditorSession loaded(const std::string& sample)
{
    ed::EditorSession session;
    const sm::Status status = session.load(k_samples + sample);
    EXPECT_TRUE(status) << status.error().message();
    return session;
}

sm::Vec3 position_of(const ed::EditorSession& s, const char* name)
{
    return sm::body_position(s.world(), sm::find_body(s.world(), name));
}

} // namespace

TEST(EditorSession, ShapeOfARigidBodyIsSetLiveByName)
{
    ed::EditorSession s = loaded("chair_with_dummy.json");
    s.step(20);
    const sm::Status status = s.set("/bodies/chair_seat/shape/radii/0", 0.3);
    ASSERT_TRUE(status) << status.error().message();
    EXPECT_EQ(s.last_set_effect(), ed::SetEffect::Live);
    EXPECT_EQ(s.scene().bodies[0].def.shape.radii.x, 0.3);
    EXPECT_EQ(sm::body_shape(s.world(), sm::find_body(s.world(), "chair_seat")).radii.x, 0.3);
    EXPECT_EQ(s.world().step_count(), 20u) << "a live edit keeps the run going";
    EXPECT_EQ(s.get("/bodies/chair_seat/shape/radii/0")->get<double>(), 0.3);
}

TEST(EditorSession, OtherEditsRebuildAtTheCurrentState)
{
    ed::EditorSession s = loaded("chair_with_dummy.json");
    s.step(100);
    const sm::Vec3 before = position_of(s, "dummy_torso");
    ASSERT_TRUE(s.set("/settings/substeps", 2));
    EXPECT_EQ(s.last_set_effect(), ed::SetEffect::Rebuilt);
    EXPECT_EQ(s.scene().world.substep_count, 2);
    EXPECT_EQ(s.world().settings().substep_count, 2);
    // Rebuilt from poses written back through the parent frame: equal to rounding of O(1 m) values.
    EXPECT_LT(sm::length(position_of(s, "dummy_torso") - before), 1e-12);
    // The scene still holds the initial poses: reset goes back to them and keeps the edit.
    ASSERT_TRUE(s.reset());
    EXPECT_EQ(s.world().step_count(), 0u);
    EXPECT_EQ(s.world().settings().substep_count, 2);
}

TEST(EditorSession, ResetAndRebuildsReuseTheModalBases)
{
    ed::EditorSession s = loaded("ball_on_board.json");
    const sm::Entity board = sm::find_body(s.world(), "board");
    ASSERT_TRUE(sm::world_valid(s.world(), board));
    const sm::ModalBasis* first = sm::body_modal_basis(s.world(), board);
    ASSERT_NE(first, nullptr);
    ASSERT_TRUE(s.reset());
    EXPECT_EQ(sm::body_modal_basis(s.world(), sm::find_body(s.world(), "board")), first);
    ASSERT_TRUE(s.set("/settings/substeps", 2)); // a rebuild
    EXPECT_EQ(s.last_set_effect(), ed::SetEffect::Rebuilt);
    // The same basis object, not an equal one built again.
    EXPECT_EQ(sm::body_modal_basis(s.world(), sm::find_body(s.world(), "board")), first);
}

TEST(EditorSession, RefusedValuesNameThePointerAndChangeNothing)
{
    ed::EditorSession s = loaded("chair_with_dummy.json");
    const std::string before = sm::scene_to_json(s.scene());
    sm::Status bad = s.set("/bodies/chair_seat/shape/radii/0", -1.0);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().where, "/bodies/0/shape/radii/0") << bad.error().message();
    bad = s.set("/bodies/chair_set/shape/radii/0", 0.2);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message().find("no body named \"chair_set\""), std::string::npos);
    bad = s.set("/bodies/chair_seat/shape/radii/3", 0.2);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().where, "/bodies/0/shape/radii/3") << bad.error().message();
    bad = s.set("/bodies/chair_seat/shape/radi", 0.2);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message().find("did you mean \"radii\""), std::string::npos)
        << bad.error().message();
    bad = s.set("settings/dt", 0.001);
    ASSERT_FALSE(bad);
    EXPECT_EQ(before, sm::scene_to_json(s.scene()));
}

TEST(EditorSession, PickFindsTheFirstSurfaceAlongTheRay)
{
    ed::EditorSession s = loaded("ball_on_board.json");
    // Straight down onto the ball (centre x = 0.1, y = 0.4, radius 0.025): enters at y = 0.425. The
    // bisection brackets the surface to double resolution; 1e-9 m allows for the measure's rounding.
    std::optional<ed::PickHit> hit = s.pick({{0.1, 1.0, 0.0}, {0, -2, 0}});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->name, "ball");
    EXPECT_NEAR(hit->point.y, 0.425, 1e-9);
    EXPECT_NEAR(hit->distance, 0.575, 1e-9);
    // Down onto the board's middle: its top face is flat at y = 0.119 + 0.019.
    hit = s.pick({{-0.2, 1.0, 0.0}, {0, -1, 0}});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->name, "board");
    EXPECT_NEAR(hit->point.y, 0.138, 1e-9);
    // Sideways into the board's end (a1 = 0.5 along x), from outside.
    hit = s.pick({{-2.0, 0.119, 0.0}, {1, 0, 0}});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->name, "board");
    EXPECT_NEAR(hit->point.x, -0.5, 1e-9);
    // Beside everything: the floor plane at y = 0.
    hit = s.pick({{2.0, 1.0, 0.0}, {0, -1, 0}});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->name, "floor");
    EXPECT_NEAR(hit->point.y, 0.0, 1e-12);
    EXPECT_FALSE(s.pick({{0.1, 1.0, 0.0}, {0, 1, 0}})) << "pointing at the sky";
}

TEST(EditorSession, DragHoldsTheGrabbedPointBelowTheTargetBySpringSag)
{
    ed::EditorSession s = loaded("ball_on_board.json");
    ASSERT_TRUE(s.set("/bodies/ball/velocity", sm::editor::Json::array({0, 0, 0})));
    ASSERT_TRUE(s.drag_begin({{0.1, 1.0, 0.0}, {0, -1, 0}}));
    const sm::Vec3 target{0.1, 0.8, 0.0};
    s.drag_to(target);
    s.step(2000); // 1 s at dt = 0.5 ms: many settling times 1/(ζω) = 57 ms of the 4 Hz spring
    const sm::Entity ball = s.drag()->body;
    const sm::Vec3 grabbed = sm::body_position(s.world(), ball) +
                             sm::rotate(sm::body_orientation(s.world(), ball), s.drag()->point_shape);
    // At rest the spring carries the weight: sag g/ω² = 9.81/(2π·4)² = 15.5 mm below the target.
    const double omega = 2.0 * M_PI * s.drag()->frequency_hz;
    EXPECT_NEAR(target.y - grabbed.y, 9.81 / (omega * omega), 1e-3);
    EXPECT_NEAR(grabbed.x, target.x, 1e-3);
    s.drag_end();
    EXPECT_FALSE(s.drag());
}

TEST(EditorSession, PushLoadsTheModesOfAModalBody)
{
    // Two runs of the same 40 steps, with and without a 200 N push on the board's top face.
    ed::EditorSession quiet = loaded("ball_on_board.json");
    ed::EditorSession pushed = loaded("ball_on_board.json");
    ASSERT_TRUE(pushed.push({{0.3, 1.0, 0.0}, {0, -1, 0}}, 200.0, 20));
    quiet.step(40);
    pushed.step(40);
    const auto energy = [](const ed::EditorSession& s) {
        return sm::body_modal_energy(s.world(), sm::find_body(s.world(), "board"));
    };
    // The resting board carries only its 15 N weight on the supports; the push is 13 times that, off
    // centre, so its modes hold far more energy (energy grows with the load squared).
    EXPECT_GT(energy(pushed), 10.0 * energy(quiet)) << energy(pushed) << " vs " << energy(quiet);
    EXPECT_FALSE(pushed.push({{2.0, 1.0, 0.0}, {0, -1, 0}}, 10.0, 1)) << "the floor is static";
}

TEST(EditorSession, SaveWritesTheCurrentStateAtomically)
{
    ed::EditorSession s = loaded("chair_with_dummy.json");
    ASSERT_TRUE(s.set("/bodies/chair_seat/shape/radii/2", 0.25));
    s.step(100);
    const std::string path = ::testing::TempDir() + "editor_session_save.json";
    ASSERT_TRUE(s.save(path));
    sm::Result<sm::Scene> back = sm::load_scene(path);
    ASSERT_TRUE(back) << back.error().message();
    EXPECT_EQ(back->bodies[0].def.shape.radii.z, 0.25);
    // The dummy has fallen onto the seat since the start: the saved pose is the current one.
    size_t torso = 0;
    while (back->bodies[torso].def.name != "dummy_torso")
        ++torso;
    EXPECT_NE(back->bodies[torso].def.position.y, s.scene().bodies[torso].def.position.y);
    ASSERT_TRUE(s.save(path, /*current_state=*/false));
    back = sm::load_scene(path);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->bodies[torso].def.position.y, s.scene().bodies[torso].def.position.y);
}

namespace
{

std::string file_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(EditorUndo, UndoingEveryEditSavesTheOriginalSceneByteForByteAndRedoingSavesTheEditedOne)
{
    ed::EditorSession s;
    ASSERT_TRUE(s.load(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json"));
    const std::string dir = ::testing::TempDir();
    ASSERT_TRUE(s.save(dir + "undo_original.json", false));
    const auto ball_mass = [](const ed::EditorSession& e) {
        return sm::body_mass_properties(e.world(), sm::find_body(e.world(), "ball")).mass;
    };
    const double steel_mass = ball_mass(s);
    s.step(50); // edits while the world has moved on
    // A shape (applied live), a material and a transform (rebuilds), a setting; one refused value.
    ASSERT_TRUE(s.set("/bodies/ball/shape/radii/0", 0.03));
    EXPECT_EQ(s.last_set_effect(), ed::SetEffect::Live);
    ASSERT_TRUE(s.set("/bodies/ball/material", "wood"));
    ASSERT_TRUE(s.set("/bodies/support_left/position", ed::Json::array({-0.35, 0.05, 0.0})));
    ASSERT_TRUE(s.set("/settings/dt", 0.00025));
    EXPECT_FALSE(s.set("/bodies/ball/shape/radii/0", -1.0));
    ASSERT_EQ(s.history().size(), 4u);         // the refused value left no edit
    EXPECT_LT(ball_mass(s), 0.5 * steel_mass); // wood
    ASSERT_TRUE(s.save(dir + "undo_edited.json", false));
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(s.undo()) << i;
    EXPECT_EQ(s.history_position(), 0u);
    ASSERT_TRUE(s.save(dir + "undo_undone.json", false));
    EXPECT_EQ(file_bytes(dir + "undo_undone.json"), file_bytes(dir + "undo_original.json"));
    const sm::Status nothing = s.undo();
    ASSERT_FALSE(nothing);
    EXPECT_NE(nothing.error().message().find("nothing to undo"), std::string::npos);
    // The world follows: the ball has its steel mass and old radius again.
    EXPECT_EQ(ball_mass(s), steel_mass);
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(s.redo()) << i;
    EXPECT_FALSE(s.redo());
    ASSERT_TRUE(s.save(dir + "undo_redone.json", false));
    EXPECT_EQ(file_bytes(dir + "undo_redone.json"), file_bytes(dir + "undo_edited.json"));
    // A new edit after an undo drops the undone ones; a load forgets them all.
    ASSERT_TRUE(s.undo());
    ASSERT_TRUE(s.set("/settings/substeps", 2));
    EXPECT_EQ(s.history().size(), 4u);
    EXPECT_EQ(s.history().back().path, "/settings/substeps");
    EXPECT_FALSE(s.redo());
    ASSERT_TRUE(s.load(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json"));
    EXPECT_TRUE(s.history().empty());
}
