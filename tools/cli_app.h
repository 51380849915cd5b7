// SPDX-License-Identifier: MIT
// The `supermodal` command line as functions: parsing apart from running, so the option parser can be
// fuzzed (tests/fuzz/cli_fuzz.cpp) without the harness running every command it parses.
#pragma once

#include "cli_common.h"
#include "cmd_bench.h"
#include "cmd_export.h"
#include "cmd_fit.h"

namespace supermodal::cli
{

enum class Command { None, Run, Inspect, Modes, Fit, Export, Bench };

/// One parsed command line: which command, and its options.
struct Invocation {
    Command command = Command::None;
    RunOptions run;
    InspectOptions inspect;
    ModesOptions modes;
    FitOptions fit;
    ExportOptions export_options;
    BenchOptions bench;
};

/// Sentinel of parse_command_line: the line parsed and `out` says what to run.
inline constexpr int k_parsed = -1;

/// Parses argv into `out`. Returns k_parsed, or the exit status when parsing ends the program: 0 after
/// --help or --version (printed), k_exit_bad_input after a parse error (printed by CLI11 to stderr).
[[nodiscard]] int parse_command_line(int argc, const char* const* argv, Invocation& out);

/// Runs a parsed command; returns its exit status (0 ok, 2 bad input, 1 internal failure).
[[nodiscard]] int run_invocation(const Invocation& invocation);

/// parse_command_line, then run_invocation: the whole program.
[[nodiscard]] int run_command_line(int argc, const char* const* argv);

} // namespace supermodal::cli
