// SPDX-License-Identifier: MIT
// Fuzz target for the `supermodal` command line (libFuzzer): the input is the argument list, one
// argument per line. Every line must either parse or be refused with exit status 2; a parsed command
// that is cheap enough runs for real, in a private directory holding a small scene (s.json, a modal
// board and a ball) and a mesh (m.obj), and must end with 0 or 2, never 1 (internal failure), a
// crash, a hang or a sanitizer report. Not run: `bench` (a sweep is hundreds of runs), frame capture,
// long runs; arguments with a '/' are skipped so every path stays inside the private directory (so a
// --set value never holds a JSON pointer here: tests/scene/overrides_test.cpp covers the pointers).
#include "cli_app.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
namespace cli = supermodal::cli;
namespace fs = std::filesystem;

constexpr const char* k_scene = R"({
  "settings": { "dt": 0.0005, "duration": 0.01 },
  "materials": { "wood": { "density": 450, "young": 11e9, "poisson": 0.3, "damping_ratio": 0.02 } },
  "bodies": [
    { "name": "board", "material": "wood",
      "shape": { "type": "superquadric", "radii": [0.5, 0.019, 0.0445], "exponents": [0.05, 0.05] },
      "dynamics": { "type": "modal", "modes": 6, "lattice": [8, 1, 1] } },
    { "name": "ball", "shape": { "type": "superquadric", "radii": [0.05, 0.05, 0.05] },
      "position": [0, 0.1, 0] }
  ]
})";
constexpr const char* k_mesh =
    "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
constexpr size_t k_max_args = 24;
// Longest simulated time a dispatched run or export may ask for: 400 steps of the scene's 0.5 ms.
constexpr double k_max_seconds = 0.2;
constexpr long long k_max_steps = 400;
constexpr double k_max_export_frames = 100;

fs::path g_dir;  // the commands' working directory while one runs
fs::path g_home; // libFuzzer's own (its corpus and artifact paths are relative to it)

void write_fixtures()
{
    std::ofstream(g_dir / "s.json", std::ios::trunc) << k_scene;
    std::ofstream(g_dir / "m.obj", std::ios::trunc) << k_mesh;
}

// Whatever a command wrote goes, and the fixtures come back (an output may have overwritten them).
void reset_directory()
{
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(g_dir, ec))
        fs::remove_all(e.path(), ec);
    write_fixtures();
}

// Non-finite values are let through: the command must refuse them at once, or the fuzzer sees a hang.
bool long_time(double seconds)
{
    return std::isfinite(seconds) && seconds > k_max_seconds;
}

bool cheap(const cli::Invocation& in)
{
    switch (in.command) {
    case cli::Command::Run:
        return in.run.capture.frames_dir.empty() && in.run.capture.video.empty() &&
               !(in.run.has_steps && in.run.steps > k_max_steps) &&
               !(in.run.has_seconds && long_time(in.run.seconds));
    case cli::Command::Export: {
        const cli::ExportOptions& e = in.export_options;
        const double seconds = e.seconds > 0.0 ? e.seconds : 0.01;
        return !long_time(e.seconds) && !(std::isfinite(e.fps) && seconds * e.fps > k_max_export_frames);
    }
    case cli::Command::Fit:
        return in.fit.parts <= 4;
    case cli::Command::Inspect:
    case cli::Command::Modes:
        return true;
    case cli::Command::Bench:
    case cli::Command::None:
        return false;
    }
    return false;
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    char dir[] = "/tmp/supermodal_cli_fuzz_XXXXXX";
    if (::mkdtemp(dir) == nullptr)
        std::abort();
    g_dir = dir;
    g_home = fs::current_path();
    write_fixtures();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::vector<std::string> args{"supermodal"};
    std::string arg;
    for (size_t i = 0; i <= size; ++i) {
        if (i < size && data[i] != '\n') {
            arg += static_cast<char>(data[i]);
            continue;
        }
        if (arg.find('/') != std::string::npos || args.size() > k_max_args)
            return 0;
        args.push_back(arg);
        arg.clear();
    }
    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());

    cli::Invocation invocation;
    int status = cli::parse_command_line(static_cast<int>(argv.size()), argv.data(), invocation);
    if (status == cli::k_parsed) {
        if (!cheap(invocation))
            return 0;
        fs::current_path(g_dir);
        status = cli::run_invocation(invocation);
        reset_directory();
        fs::current_path(g_home);
    }
    if (status != cli::k_exit_ok && status != cli::k_exit_bad_input)
        std::abort(); // exit status 1 is an internal failure: every bad input must be a 2
    return 0;
}
