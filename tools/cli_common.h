// SPDX-License-Identifier: MIT
// Shared pieces of the `supermodal` command line: exit codes, atomic file output, JSON of engine types.
#pragma once

#include "frame_capture.h"
#include "supermodal/body.h"
#include "supermodal/scene.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace CLI
{
class App;
}

namespace supermodal::cli
{

inline constexpr int k_exit_ok = 0;
inline constexpr int k_exit_internal = 1;
inline constexpr int k_exit_bad_input = 2;

/// Prints "supermodal: <message>" to stderr.
void print_error(const std::string& message);

/// Writes text to path through a temporary file and a rename, so a reader never sees half a file and
/// a failure leaves nothing behind. Returns an error message, or empty on success.
[[nodiscard]] std::string write_file_atomically(const std::string& path, const std::string& text);
/// Checks up front that path's directory exists and is writable (so bad paths fail before any work).
[[nodiscard]] std::string check_writable(const std::string& path);

/// JSON text, 2-space indent. Invalid UTF-8 (a file name from argv is any bytes) becomes U+FFFD
/// instead of nlohmann's exception, which had made `export` fail as an internal error (cli fuzz).
[[nodiscard]] std::string json_text(const nlohmann::json& j);
[[nodiscard]] nlohmann::json to_json(const Vec3& v);
[[nodiscard]] nlohmann::json to_json(const Quat& q);
[[nodiscard]] const char* motion_name(MotionType motion);

/// The --set options ("/json/pointer=value", split at the first '=') as scene overrides. The value is
/// used as JSON when it parses as JSON ("2", "[0, 1, 0]", "true") and as a string otherwise ("steel").
/// Returns an error message naming the option, or empty.
[[nodiscard]] std::string parse_set_options(const std::vector<std::string>& sets,
                                            std::vector<SceneOverride>& out);
/// load_scene(path) with the --set options applied before validation.
[[nodiscard]] Result<Scene> load_scene_with(const std::string& path, const std::vector<std::string>& sets);
/// Registers a repeatable --set option filling `sets`.
void add_set_option(CLI::App& cmd, std::vector<std::string>& sets);

struct RunOptions {
    std::string scene;
    double seconds = 0.0; ///< Used when has_seconds.
    long long steps = 0;  ///< Used when has_steps.
    bool has_seconds = false;
    bool has_steps = false;
    std::string json_out;
    std::string csv_out;
    int csv_every = 1;
    bool quiet = false;
    int threads = 0;               ///< Overrides the scene's settings.threads when > 0.
    CaptureOptions capture;        ///< --frames/--video: rendered frames of the run.
    std::vector<std::string> sets; ///< --set /json/pointer=value, in order.
};
int run_command(const RunOptions& options);

struct InspectOptions {
    std::string scene;
    bool json = false;
};
int inspect_command(const InspectOptions& options);

struct ModesOptions {
    std::string scene;
    std::string body;
    int count = 0; ///< 0: every mode the body keeps.
    bool json = false;
};
int modes_command(const ModesOptions& options);

} // namespace supermodal::cli
