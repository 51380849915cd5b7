// SPDX-License-Identifier: MIT
// Headless editor scripts (docs/editor.md): a JSON list of actions run against a session and its UI,
// so CI can load a scene, edit it, press widgets, drag and push bodies, and save, with no display.
#pragma once

#include "session.h"
#include "ui.h"

#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>

namespace supermodal::editor
{

/// Why a script stopped.
enum class ScriptFailure : uint8_t {
    None,
    BadScript,   ///< Unreadable file, invalid JSON, unknown action or key, a refused value or action.
    CheckFailed, ///< An "expect" did not hold.
};

struct ScriptOutcome {
    ScriptFailure failure = ScriptFailure::None;
    Error error; ///< file: the script; where: the JSON pointer of the action or value at fault.
    int actions_run = 0;
};

/// Runs script text; relative file names are resolved against `base_dir`. One line per action goes to
/// `log`. Stops at the first failure.
[[nodiscard]] ScriptOutcome run_script_text(std::string_view text, const std::string& source,
                                            const std::filesystem::path& base_dir, EditorSession& session,
                                            EditorUi& ui, std::ostream& log);
/// Reads a script file and runs it with paths relative to its folder.
[[nodiscard]] ScriptOutcome run_script_file(const std::string& path, EditorSession& session, EditorUi& ui,
                                            std::ostream& log);

} // namespace supermodal::editor
