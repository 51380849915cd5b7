// SPDX-License-Identifier: MIT
// `supermodal bench SCENE`: sweep the speed/accuracy knobs one at a time against a converged reference
// run and report cost (CPU ms per step) against error (docs/speed_accuracy.md).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace supermodal::cli
{

struct BenchOptions {
    std::string scene;
    double seconds = 0.0;          ///< Simulated time per run [s]; 0: min(settings.duration, 1 s).
    int repeats = 3;               ///< Timed runs per configuration; the median counts.
    std::string knobs;             ///< Comma list restricting the knobs; empty: all.
    std::string out;               ///< PREFIX: writes PREFIX.csv, PREFIX.md and (with gnuplot) PREFIX.png.
    bool json = false;             ///< Print a JSON summary on stdout.
    bool fixed_contact = false;    ///< Hold the contact frequency at the scene's cap 1/(10 h) in every run.
    std::vector<std::string> sets; ///< --set /json/pointer=value, applied to the scene before it is read.
};
/// Registers the subcommand and its options on app.
CLI::App* add_bench_command(CLI::App& app, BenchOptions& options);
int bench_command(const BenchOptions& options);

} // namespace supermodal::cli
