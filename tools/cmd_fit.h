// SPDX-License-Identifier: MIT
// `supermodal fit MESH`: import a mesh, fit superquadrics, print the scene and the fit report.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace supermodal::cli
{

struct FitOptions {
    std::string mesh;
    int parts = 1;
    bool taper = false;
    bool bend = false;
    bool json = false;
    std::string scene_out; ///< Also write the scene (loadable as is) here.
    double scale = 0.0;    ///< Metres per file unit; 0: from the file.
    std::string up = "from_file";
    std::string name;    ///< Body name; default: the mesh file's stem.
    bool attach = false; ///< Write the mesh in the fitted body's frame next to the scene, as its "mesh".
};
/// Registers the subcommand and its options on app.
CLI::App* add_fit_command(CLI::App& app, FitOptions& options);
int fit_command(const FitOptions& options);

} // namespace supermodal::cli
