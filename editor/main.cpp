// SPDX-License-Identifier: MIT
// supermodal-editor: the Dear ImGui scene editor. Headless (--headless --script actions.json) it runs a
// script of editor actions with no display, for CI and tests; with a display, a GLFW window.
#include "render_hook.h"
#include "script.h"
#include "session.h"
#include "ui.h"
#include "window.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <sstream>

namespace
{

// Exit statuses, as the supermodal tool: 0 ok, 1 a check failed or an internal failure, 2 bad input.
constexpr int k_exit_ok = 0;
constexpr int k_exit_failed = 1;
constexpr int k_exit_bad_input = 2;

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"supermodal-editor: edit superquadric scenes; --headless runs a script of actions"};
    bool headless = false;
    std::string script, screenshot, scene;
    std::vector<int> size{1280, 720};
    bool quiet = false;
    app.add_flag("--headless", headless, "No window: run --script and exit");
    app.add_option("--script", script, "Actions to run (JSON, docs/editor.md)")->check(CLI::ExistingFile);
    app.add_option("--screenshot", screenshot, "PNG of the editor after the script");
    app.add_option("--size", size, "Display size W H [pixels]")->expected(2)->check(CLI::Range(16, 16384));
    app.add_option("scene", scene, "Scene to load first (format v1)");
    app.add_flag("-q,--quiet", quiet, "No per-action log");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? k_exit_ok : k_exit_bad_input;
    }
    using namespace supermodal::editor;
    if (!headless && !display_available()) {
        // No display: a script still runs headless; without one there is nothing to do.
        if (script.empty()) {
            std::cerr << "supermodal-editor: no display ($DISPLAY and $WAYLAND_DISPLAY are unset), so no "
                         "window; use --headless --script actions.json [--screenshot out.png]\n";
            return k_exit_bad_input;
        }
        std::cerr << "supermodal-editor: no display ($DISPLAY and $WAYLAND_DISPLAY are unset): running "
                     "the script headless\n";
        headless = true;
    }
    if (headless && script.empty() && scene.empty()) {
        std::cerr << "supermodal-editor: --headless needs --script actions.json (or a scene)\n";
        return k_exit_bad_input;
    }

    EditorSession session;
    EditorUi ui(session, size[0], size[1]);
    if (!scene.empty())
        if (supermodal::Status status = session.load(scene); !status) {
            std::cerr << status.error().message() << "\n";
            return k_exit_bad_input;
        }
    if (!script.empty()) {
        std::ostringstream discard;
        const ScriptOutcome outcome = run_script_file(script, session, ui, quiet ? discard : std::cout);
        if (outcome.failure != ScriptFailure::None) {
            std::cerr << outcome.error.message() << "\n";
            return outcome.failure == ScriptFailure::CheckFailed ? k_exit_failed : k_exit_bad_input;
        }
    }
    if (!headless) {
        WindowUnavailable why;
        const int status = run_window(session, ui, why);
        if (status != k_exit_ok)
            std::cerr << "supermodal-editor: cannot open a window: " << why.message
                      << "; use --headless --script actions.json\n";
        return status;
    }
    if (!screenshot.empty()) {
        ui.frame(0.0);
        if (supermodal::Status status = render_screenshot(session, ui, screenshot, size[0], size[1]);
            !status) {
            std::cerr << status.error().message() << "\n";
            return k_exit_bad_input;
        }
    }
    return k_exit_ok;
}
