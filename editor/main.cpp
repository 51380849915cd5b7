// SPDX-License-Identifier: MIT
// supermodal-editor: the Dear ImGui scene editor. Headless (--headless --script actions.json) it runs a
// script of editor actions with no display, for CI and tests; with a display, a GLFW window.
#include "render_hook.h"
#include "script.h"
#include "session.h"
#include "supermodal/version.h"
#include "ui.h"
#include "window.h"

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace
{

// Exit statuses, as the supermodal tool: 0 ok, 1 a check failed or an internal failure, 2 bad input.
constexpr int k_exit_ok = 0;
constexpr int k_exit_failed = 1;
constexpr int k_exit_bad_input = 2;

/// The command line.
struct EditorArgs {
    bool headless = false;
    std::string script, screenshot, scene;
    std::vector<int> size{1280, 720};
    bool quiet = false;
    std::string parts = SUPERMODAL_EDITOR_PARTS_DIR; ///< The Parts panel's folder.
    std::string thumbnail_cache;                     ///< Empty: the user's cache folder.
};

/// $XDG_CACHE_HOME/supermodal/thumbnails, else ~/.cache/supermodal/thumbnails; empty without either.
std::string default_thumbnail_cache()
{
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0')
        return std::string(xdg) + "/supermodal/thumbnails";
    if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
        return std::string(home) + "/.cache/supermodal/thumbnails";
    return {};
}

/// Without a display a script still runs headless; with neither there is nothing to do. -1 to go on,
/// else the exit status (the message printed).
int choose_mode(EditorArgs& a)
{
    if (!a.headless && !supermodal::editor::display_available()) {
        if (a.script.empty()) {
            std::cerr << "supermodal-editor: no display ($DISPLAY and $WAYLAND_DISPLAY are unset), so no "
                         "window; use --headless --script actions.json [--screenshot out.png]\n";
            return k_exit_bad_input;
        }
        std::cerr << "supermodal-editor: no display ($DISPLAY and $WAYLAND_DISPLAY are unset): running "
                     "the script headless\n";
        a.headless = true;
    }
    if (a.headless && a.script.empty() && a.scene.empty()) {
        std::cerr << "supermodal-editor: --headless needs --script actions.json (or a scene)\n";
        return k_exit_bad_input;
    }
    return -1;
}

/// Loads the scene; in a window runs the script there (and shoots the window), headless runs it and
/// writes the screenshot.
int run_editor(const EditorArgs& a)
{
    using namespace supermodal::editor;
    EditorSession session;
    EditorUi ui(session, a.size[0], a.size[1]);
    // Listed now, drawn by the first frame (a missing folder leaves the panel empty: it says so).
    ThumbnailDef thumbnails;
    thumbnails.cache_dir = a.thumbnail_cache.empty() ? default_thumbnail_cache() : a.thumbnail_cache;
    if (!a.parts.empty())
        (void)ui.parts_library.scan(a.parts, thumbnails);
    if (!a.scene.empty())
        if (supermodal::Status status = session.load(a.scene); !status) {
            std::cerr << status.error().message() << "\n";
            return k_exit_bad_input;
        }
    std::ostringstream discard;
    std::ostream& log = a.quiet ? static_cast<std::ostream&>(discard) : std::cout;
    if (!a.headless) {
        WindowUnavailable why;
        const int status = run_window(session, ui, WindowRun{a.script, a.screenshot, &log}, why);
        if (!why.message.empty())
            std::cerr << "supermodal-editor: cannot open a window: " << why.message
                      << "; use --headless --script actions.json\n";
        return status;
    }
    if (!a.script.empty()) {
        const ScriptOutcome outcome = run_script_file(a.script, session, ui, log);
        if (outcome.failure != ScriptFailure::None) {
            std::cerr << outcome.error.message() << "\n";
            return outcome.failure == ScriptFailure::CheckFailed ? k_exit_failed : k_exit_bad_input;
        }
    }
    if (!a.screenshot.empty()) {
        ui.frame(0.0);
        // The UI's size: --size, or what a script's resize made it.
        if (supermodal::Status status = render_screenshot(session, ui, a.screenshot, ui.width(), ui.height());
            !status) {
            std::cerr << status.error().message() << "\n";
            return k_exit_bad_input;
        }
    }
    return k_exit_ok;
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"supermodal-editor: edit superquadric scenes; --headless runs a script of actions"};
    EditorArgs a;
    app.add_flag("--headless", a.headless, "No window: run --script and exit");
    app.add_option("--script", a.script, "Actions to run (JSON, docs/editor.md)")->check(CLI::ExistingFile);
    app.add_option("--screenshot", a.screenshot,
                   "PNG of the editor after the script (in a window: its framebuffer, then it closes)");
    app.add_option("--size", a.size, "Display size W H [pixels]")->expected(2)->check(CLI::Range(16, 16384));
    app.add_option("--parts", a.parts,
                   "Folder of part files for the Parts panel (default: the samples' parts)")
        ->check(CLI::ExistingDirectory);
    app.add_option(
        "--thumbnail-cache", a.thumbnail_cache,
        "Folder of cached part thumbnails (default: $XDG_CACHE_HOME or ~/.cache, supermodal/thumbnails)");
    app.add_option("scene", a.scene, "Scene to load first (format v1)");
    app.add_flag("-q,--quiet", a.quiet, "No per-action log");
    app.set_version_flag("--version", std::string("supermodal ") + supermodal::version(),
                         "Print the version and exit");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? k_exit_ok : k_exit_bad_input;
    }
    if (const int status = choose_mode(a); status >= 0)
        return status;
    return run_editor(a);
}
