// SPDX-License-Identifier: MIT
// `supermodal bench` output: the rows of a sweep as CSV, a markdown table, JSON and a gnuplot Pareto plot.
#pragma once

#include "bench_sweep.h"

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace supermodal::cli
{

/// One measured configuration (or the reference, knob "reference").
struct BenchRow {
    std::string knob;
    std::string value;
    std::string status = "ok"; ///< "ok", "unstable: ..." or "refused: <reason>".
    long long steps = 0;
    double cpu_ms_per_step = 0.0; ///< Median over the repeats [ms].
    /// cpu_ms_per_step × steps / simulated seconds [ms/s]: what the Pareto front compares, since a larger
    /// dt is cheaper per simulated second at the same cost per step.
    double cpu_ms_per_second = 0.0;
    double setup_ms = 0.0; ///< World build, modal bases included [ms CPU].
    BenchErrors errors;
    double max_penetration = 0.0;           ///< [m]
    std::optional<double> constraint_error; ///< Max over steps and constraints [m]; none without any.
    bool pareto = false;                    ///< On the cost/trajectory-RMS Pareto front.
    bool base = false; ///< The scene's own settings (the same run under several knobs: dt x1, ...).
};

/// What a report says about the run as a whole.
struct BenchSummary {
    std::string scene;
    double seconds = 0.0;
    int repeats = 0;
    std::string reference;      ///< How the reference was made, in words.
    std::vector<BenchRow> rows; ///< rows[0] is the reference.
};

/// Marks the rows (status ok, not the reference) that no other such row beats in both cost per simulated
/// second and RMS trajectory error.
void mark_pareto_front(std::vector<BenchRow>& rows);

[[nodiscard]] std::string bench_csv(const BenchSummary& s);
[[nodiscard]] std::string bench_markdown(const BenchSummary& s);
[[nodiscard]] nlohmann::json bench_json(const BenchSummary& s);
/// Writes png_path (through a temporary file) with gnuplot when it is on PATH. Returns an error message,
/// or empty on success; "gnuplot not found" is one such message (the caller treats it as a note).
[[nodiscard]] std::string bench_plot(const BenchSummary& s, const std::string& png_path);

} // namespace supermodal::cli
