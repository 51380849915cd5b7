// SPDX-License-Identifier: MIT
// The `supermodal` command line: its options (CLI11) and the dispatch to the commands.
#include "cli_app.h"

#include "supermodal/version.h"

#include <CLI/CLI.hpp>
#include <exception>

namespace supermodal::cli
{

namespace
{

/// The options of `run` whose presence, not only value, matters.
struct RunFlags {
    CLI::App* cmd = nullptr;
    CLI::Option* seconds = nullptr;
    CLI::Option* steps = nullptr;
    CLI::Option* every = nullptr;
    CLI::Option* size = nullptr;
};

RunFlags add_run_command(CLI::App& app, RunOptions& run)
{
    RunFlags f;
    f.cmd = app.add_subcommand("run", "Step a scene and write a JSON summary (stdout by default)");
    f.cmd->add_option("scene", run.scene, "Scene file (JSON, format v1: docs/scene_format.md)")->required();
    f.seconds = f.cmd->add_option("--seconds", run.seconds,
                                  "Simulated time to run [s] (default: the "
                                  "scene's settings.duration)");
    f.steps = f.cmd->add_option("--steps", run.steps, "Number of fixed steps to run instead of --seconds")
                  ->excludes(f.seconds);
    f.cmd->add_option("--json", run.json_out, "Write the summary here instead of stdout");
    f.cmd->add_option(
        "--csv", run.csv_out,
        "Write a per-step trace: step,time,body,position,orientation,velocity,angular velocity");
    f.cmd->add_option("--csv-every", run.csv_every, "Trace every K-th step")->check(CLI::PositiveNumber);
    f.cmd
        ->add_option("--threads", run.threads,
                     "Threads for the contact stages (default: the scene's settings.threads); results are "
                     "identical for any count")
        ->check(CLI::Range(1, 64));
    f.cmd->add_option("--frames", run.capture.frames_dir,
                      "Write PNG frames (frame_000000.png, ...) into this directory, made if missing");
    f.every = f.cmd->add_option("--every", run.capture.every, "A frame every K steps (default 1)")
                  ->check(CLI::PositiveNumber);
    f.size = f.cmd->add_option("--size", run.capture.size, "Frame size WxH in pixels (default 1280x720)");
    f.cmd
        ->add_option("--msaa", run.capture.msaa,
                     "Anti-aliasing samples per pixel, 1 (fastest) to 16 (default 4)")
        ->check(CLI::Range(1, 16));
    f.cmd->add_option("--video", run.capture.video, "Also encode the frames into this .mp4 (needs ffmpeg)");
    f.cmd->add_flag("--quiet", run.quiet, "No progress bar (it is shown only on a terminal anyway)");
    add_set_option(*f.cmd, run.sets);
    return f;
}

CLI::App* add_inspect_command(CLI::App& app, InspectOptions& inspect)
{
    CLI::App* cmd =
        app.add_subcommand("inspect", "Report per-body mass, volume, centre of mass, inertia and bounds");
    cmd->add_option("scene", inspect.scene, "Scene file")->required();
    cmd->add_flag("--json", inspect.json, "Machine-readable output");
    return cmd;
}

CLI::App* add_modes_command(CLI::App& app, ModesOptions& modes)
{
    CLI::App* cmd = app.add_subcommand(
        "modes", "List a modal body's vibration modes: frequencies, kind guesses, residuals, build cost");
    cmd->add_option("scene", modes.scene, "Scene file")->required();
    cmd->add_option("--body", modes.body, "Name of a body with \"dynamics\": {\"type\": \"modal\"}")
        ->required();
    cmd->add_option("--count", modes.count, "Show only the lowest K modes")->check(CLI::PositiveNumber);
    cmd->add_flag("--json", modes.json, "Machine-readable output");
    return cmd;
}

} // namespace

int parse_command_line(int argc, const char* const* argv, Invocation& out)
{
    CLI::App app{"supermodal: superquadric bodies with modal dynamics and penalty contact.\n"
                 "Exit status: 0 ok, 2 bad input (the message names the file and JSON pointer), 1 internal "
                 "failure."};
    app.set_version_flag("--version", std::string("supermodal ") + version(), "Print the version and exit");
    app.require_subcommand(1);
    const RunFlags run = add_run_command(app, out.run);
    const std::pair<CLI::App*, Command> commands[] = {
        {run.cmd, Command::Run},
        {add_inspect_command(app, out.inspect), Command::Inspect},
        {add_modes_command(app, out.modes), Command::Modes},
        {add_fit_command(app, out.fit), Command::Fit},
        {add_export_command(app, out.export_options), Command::Export},
        {add_bench_command(app, out.bench), Command::Bench}};
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return k_exit_bad_input;
    }
    out.run.has_seconds = run.seconds->count() > 0;
    out.run.has_steps = run.steps->count() > 0;
    out.run.capture.every_given = run.every->count() > 0;
    out.run.capture.size_given = run.size->count() > 0;
    for (const auto& [cmd, which] : commands)
        if (cmd->parsed())
            out.command = which;
    return k_parsed;
}

int run_invocation(const Invocation& in)
{
    try {
        switch (in.command) {
        case Command::Run:
            return run_command(in.run);
        case Command::Inspect:
            return inspect_command(in.inspect);
        case Command::Modes:
            return modes_command(in.modes);
        case Command::Fit:
            return fit_command(in.fit);
        case Command::Export:
            return export_command(in.export_options);
        case Command::Bench:
            return bench_command(in.bench);
        case Command::None:
            break;
        }
    } catch (const std::exception& e) {
        print_error(std::string("internal error: ") + e.what());
    }
    return k_exit_internal;
}

int run_command_line(int argc, const char* const* argv)
{
    Invocation invocation;
    const int status = parse_command_line(argc, argv, invocation);
    return status == k_parsed ? run_invocation(invocation) : status;
}

} // namespace supermodal::cli
