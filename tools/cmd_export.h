// SPDX-License-Identifier: MIT
// `supermodal export SCENE`: run a scene and write the animation as glTF binary and/or OBJ files.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace supermodal::cli
{

struct ExportOptions {
    std::string scene;
    double seconds = 0.0; ///< Simulated time [s]; 0: the scene's settings.duration.
    double fps = 30.0;    ///< Samples per second.
    std::string out;      ///< GLB file, or empty.
    std::string obj_dir;  ///< OBJ sequence directory, or empty.
    int tessellation = 32;
    bool no_morph = false; ///< Export modal bodies rigid (no morph targets).
    bool json = false;     ///< Print the report as JSON.
};
/// Registers the subcommand and its options on app.
CLI::App* add_export_command(CLI::App& app, ExportOptions& options);
int export_command(const ExportOptions& options);

} // namespace supermodal::cli
