// Tests for editor/script.cpp and the supermodal-editor program: a headless script edits the chair
// scene, presses widgets and saves; bad scripts fail with a JSON pointer and exit status 2.
#include "script.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#ifdef SM_HAS_RENDER
#include "supermodal/render.h"
#endif
#include <gtest/gtest.h>
#include <sstream>
#include <sys/wait.h>

namespace sm = supermodal;
namespace ed = supermodal::editor;
namespace fs = std::filesystem;

namespace
{

const std::string k_chair = std::string(SM_SOURCE_DIR) + "/samples/chair_with_dummy.json";

fs::path temp_dir(const std::string& name)
{
    const fs::path dir = fs::path(::testing::TempDir()) / ("sm_editor_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read_text(const fs::path& path)
{
    std::ifstream in(path);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

/// The chair script of docs/editor.md: edit two values, run, pause, step once, save.
std::string chair_script(int play_frames)
{
    return R"({ "actions": [
  { "action": "load", "file": ")" +
           k_chair + R"(" },
  { "action": "set", "path": "/bodies/chair_seat/shape/radii/0", "value": 0.26 },
  { "action": "set", "path": "/bodies/chair_leg_fl/shape/exponents/1", "value": 0.5 },
  { "action": "press", "widget": "Play" },
  { "action": "frames", "count": )" +
           std::to_string(play_frames) + R"( },
  { "action": "press", "widget": "Pause" },
  { "action": "frames", "count": 3 },
  { "action": "press", "widget": "Step" },
  { "action": "save", "file": "saved.json" }
] })";
}

/// Runs the program; returns its exit status, with stderr in `err`.
// env: assignments put before the program (e.g. sanitizer options), or empty.
int run_editor(const std::string& args, std::string& err, const std::string& env = "")
{
    // One file per test: ctest runs tests in parallel, each as its own process.
    const fs::path err_file =
        fs::path(::testing::TempDir()) /
        ("sm_editor_stderr_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
         ".txt");
    const std::string command =
        env + " " + std::string(SM_EDITOR_EXE) + " " + args + " >/dev/null 2>" + err_file.string();
    const int status = std::system(command.c_str());
    err = read_text(err_file);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

TEST(EditorScript, ChairScriptEditsPressesAndSaves)
{
    const fs::path dir = temp_dir("chair");
    ed::EditorSession session;
    ed::EditorUi ui(session);
    std::ostringstream log;
    const ed::ScriptOutcome outcome =
        ed::run_script_text(chair_script(3), "chair.json", dir, session, ui, log);
    ASSERT_EQ(outcome.failure, ed::ScriptFailure::None) << outcome.error.message() << "\n" << log.str();
    EXPECT_EQ(outcome.actions_run, 9);

    // The same run without pause and step, to count the steps that three played frames take.
    ed::EditorSession reference;
    ASSERT_TRUE(reference.load(k_chair));
    reference.play();
    for (int i = 0; i < 3; ++i)
        reference.frame(1.0 / 60.0);
    ASSERT_GT(reference.world().step_count(), 40u);
    // Pause stopped the three frames after it from stepping; Step ran exactly one step.
    EXPECT_FALSE(session.playing());
    EXPECT_EQ(session.world().step_count(), reference.world().step_count() + 1);

    sm::Result<sm::Scene> saved = sm::load_scene((dir / "saved.json").string());
    ASSERT_TRUE(saved) << saved.error().message();
    EXPECT_EQ(saved->bodies[0].def.name, "chair_seat");
    EXPECT_EQ(saved->bodies[0].def.shape.radii.x, 0.26);
    EXPECT_EQ(saved->bodies[2].def.name, "chair_leg_fl");
    EXPECT_EQ(saved->bodies[2].def.shape.epsilon2, 0.5);
    // Everything else of the seat is as loaded.
    sm::Result<sm::Scene> original = sm::load_scene(k_chair);
    ASSERT_TRUE(original);
    EXPECT_EQ(saved->bodies[0].def.shape.radii.z, original->bodies[0].def.shape.radii.z);
}

TEST(EditorScript, ProgramRunsTheScriptAndRefusesBadOnes)
{
    const fs::path dir = temp_dir("program");
    std::ofstream(dir / "good.json") << chair_script(2);
    std::string err;
    ASSERT_EQ(run_editor("--headless --script " + (dir / "good.json").string(), err), 0) << err;
    sm::Result<sm::Scene> saved = sm::load_scene((dir / "saved.json").string());
    ASSERT_TRUE(saved) << saved.error().message();
    EXPECT_EQ(saved->bodies[0].def.shape.radii.x, 0.26);

    // A bad count: the pointer of the value, exit status 2, and nothing saved.
    std::ofstream(dir / "bad_count.json") << R"({ "actions": [ { "action": "load", "file": ")" + k_chair +
                                                 R"(" }, { "action": "step", "count": 0 },
      { "action": "save", "file": "never.json" } ] })";
    EXPECT_EQ(run_editor("--headless --script " + (dir / "bad_count.json").string(), err), 2);
    EXPECT_NE(err.find("/actions/1/count"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / "never.json"));

    // A value the scene refuses: the action's pointer and the scene's own pointer.
    std::ofstream(dir / "bad_value.json")
        << R"({ "actions": [ { "action": "load", "file": ")" + k_chair +
               R"(" }, { "action": "set", "path": "/bodies/chair_seat/shape/exponents/0", "value": 9 } ] })";
    EXPECT_EQ(run_editor("--headless --script " + (dir / "bad_value.json").string(), err), 2);
    EXPECT_NE(err.find("/actions/1"), std::string::npos) << err;
    EXPECT_NE(err.find("/bodies/0/shape/exponents/0"), std::string::npos) << err;

    std::ofstream(dir / "bad_action.json") << R"({ "actions": [ { "action": "jump" } ] })";
    EXPECT_EQ(run_editor("--headless --script " + (dir / "bad_action.json").string(), err), 2);
    EXPECT_NE(err.find("/actions/0/action: unknown action \"jump\""), std::string::npos) << err;

    std::ofstream(dir / "expect.json")
        << R"({ "actions": [ { "action": "load", "file": ")" + k_chair +
               R"(" }, { "action": "pick", "ray": { "origin": [3, 0.2, 0], "direction": [0, -1, 0] }, "expect": "chair_seat" } ] })";
    EXPECT_EQ(run_editor("--headless --script " + (dir / "expect.json").string(), err), 1) << err;
    EXPECT_NE(err.find("it hit \"floor\""), std::string::npos) << err;

#ifdef SM_HAS_RENDER
    // The screenshot is the 3-D view through the EGL renderer: a PNG of the asked size whose pixels
    // are not all the background (the chair is in view). Asked size: the editor's default display.
    const fs::path shot = dir / "shot.png";
    // Mesa's drivers keep allocations LeakSanitizer cannot trace (as in tests/render): no leak check here.
    EXPECT_EQ(
        run_editor("--headless --script " + (dir / "good.json").string() + " --screenshot " + shot.string(),
                   err, "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1"),
        0)
        << err;
    sm::Result<sm::Image> image = sm::read_png(shot.string());
    ASSERT_TRUE(image) << image.error().message();
    EXPECT_EQ(image->width, 1280); // the editor's default display size
    EXPECT_EQ(image->height, 720);
    size_t distinct = 0;
    for (size_t i = 4; i < image->rgba.size(); i += 4)
        distinct += image->rgba[i] != image->rgba[0] || image->rgba[i + 1] != image->rgba[1];
    EXPECT_GT(distinct, image->rgba.size() / 4 / 10);
#else
    EXPECT_EQ(run_editor("--headless --script " + (dir / "good.json").string() + " --screenshot " +
                             (dir / "shot.png").string(),
                         err),
              2);
    EXPECT_NE(err.find("renderer"), std::string::npos) << err;
#endif
}

TEST(EditorScript, WithoutADisplayTheWindowFallsBackWithAMessage)
{
    const fs::path dir = temp_dir("nodisplay");
    std::ofstream(dir / "good.json") << chair_script(1);
    std::string err;
    // No script: nothing to run headless, so a clear refusal.
    EXPECT_EQ(run_editor(k_chair, err, "DISPLAY= WAYLAND_DISPLAY="), 2);
    EXPECT_NE(err.find("no display"), std::string::npos) << err;
    // A script runs headless, saying so.
    EXPECT_EQ(run_editor("--script " + (dir / "good.json").string(), err, "DISPLAY= WAYLAND_DISPLAY="), 0)
        << err;
    EXPECT_NE(err.find("running the script headless"), std::string::npos) << err;
    EXPECT_TRUE(fs::exists(dir / "saved.json"));
}

TEST(EditorScript, EditsUndoneByScriptKeyAndButtonAndRedoneReplayToTheSameSavedScene)
{
    const std::string dir = ::testing::TempDir();
    const auto saved = [&](const std::string& actions, const std::string& file) {
        ed::EditorSession s;
        ed::EditorUi ui(s, 1280, 720);
        std::ostringstream log;
        const ed::ScriptOutcome o = ed::run_script_text(
            R"({"actions": [{"action": "load", "file": "samples/ball_on_board.json"},)" + actions +
                R"(, {"action": "save", "file": ")" + dir + file + R"(", "state": "initial"}]})",
            "test.json", SM_SOURCE_DIR, s, ui, log);
        EXPECT_EQ(o.failure, ed::ScriptFailure::None) << o.error.message() << "\n" << log.str();
        std::ifstream in(dir + file, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        return bytes.str();
    };
    const std::string edits = R"({"action": "set", "path": "/bodies/ball/shape/exponents/0", "value": 0.5},
        {"action": "set", "path": "/bodies/board/material", "value": "steel"},
        {"action": "set", "path": "/bodies/ball/position/1", "value": 0.4})";
    const std::string original = saved(R"({"action": "step", "count": 1})", "script_undo_original.json");
    const std::string edited = saved(edits, "script_undo_edited.json");
    EXPECT_NE(edited, original);
    // Undone three ways (Ctrl+Z, the History panel's Undo, the script's undo): the original, byte for
    // byte; then redone three ways (Ctrl+Shift+Z, Ctrl+Y, redo): the edited scene, byte for byte.
    const std::string undo = R"(, {"action": "key", "key": "z", "mods": ["ctrl"]},
        {"action": "press", "widget": "Undo"}, {"action": "undo"})";
    EXPECT_EQ(saved(edits + undo, "script_undo_undone.json"), original);
    EXPECT_EQ(saved(edits + undo + R"(, {"action": "key", "key": "z", "mods": ["ctrl", "shift"]},
        {"action": "key", "key": "y", "mods": ["ctrl"]}, {"action": "redo"})",
                    "script_undo_redone.json"),
              edited);
    // Z without Ctrl does nothing; undo with nothing to undo is a bad script (status 2).
    EXPECT_EQ(saved(edits + R"(, {"action": "key", "key": "z"})", "script_undo_plain_z.json"), edited);
    ed::EditorSession s;
    ed::EditorUi ui(s, 1280, 720);
    std::ostringstream log;
    const ed::ScriptOutcome o = ed::run_script_text(
        R"({"actions": [{"action": "load", "file": "samples/ball_on_board.json"}, {"action": "undo"}]})",
        "test.json", SM_SOURCE_DIR, s, ui, log);
    EXPECT_EQ(o.failure, ed::ScriptFailure::BadScript);
    EXPECT_NE(o.error.message().find("/actions/1: nothing to undo"), std::string::npos) << o.error.message();
}
