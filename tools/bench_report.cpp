// SPDX-License-Identifier: MIT
#include "bench_report.h"

#include "cli_common.h"
#include "frame_capture.h"

#include <array>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <map>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

namespace supermodal::cli
{
namespace
{

std::string number(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}
std::string optional_number(const std::optional<double>& v)
{
    return v ? number(*v) : std::string();
}

std::string csv_field(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string q = "\"";
    for (char c : s)
        q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
    return q + "\"";
}

/// Distinct on white, none of them pale (gnuplot's default set has a yellow).
const std::array<const char*, 10> k_colours = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                               "#8c564b", "#e377c2", "#17becf", "#000080", "#808000"};

bool ok(const BenchRow& r)
{
    return r.status == "ok" && r.knob != "reference";
}

/// The plot's points: one data block per knob (gnuplot's `index`), in first-seen order, and the front.
struct PlotData {
    std::map<std::string, std::string> blocks;
    std::vector<std::string> order;
    std::vector<const BenchRow*> front; ///< By cost, cheapest first.
};

PlotData plot_data(const BenchSummary& s)
{
    PlotData p;
    for (const BenchRow& r : s.rows) {
        if (!ok(r) || !(r.errors.trajectory_rms > 0.0) || !(r.cpu_ms_per_second > 0.0))
            continue; // a log axis has no place for zero
        if (r.pareto)
            p.front.push_back(&r);
        // The scene's own settings appear under several knobs; they are drawn once, as their own point.
        const std::string block = r.base ? "scene's own settings" : r.knob;
        if (p.blocks.count(block) && r.base)
            continue;
        if (!p.blocks.count(block))
            p.order.push_back(block);
        p.blocks[block] += number(r.cpu_ms_per_second) + " " + number(r.errors.trajectory_rms) + " \"" +
                           (r.base ? std::string() : r.value) + "\"\n";
    }
    std::sort(p.front.begin(), p.front.end(), [](const BenchRow* a, const BenchRow* b) {
        return a->cpu_ms_per_second < b->cpu_ms_per_second;
    });
    return p;
}

/// `text` as a gnuplot single-quoted string. Inside one gnuplot reads nothing but a doubled quote, which
/// stands for a quote: whatever a path holds, the script reads it as that path and runs nothing of it.
std::string gnuplot_quoted(const std::string& text)
{
    std::string quoted = "'";
    for (const char c : text) {
        quoted += c;
        if (c == '\'')
            quoted += '\'';
    }
    return quoted + "'";
}

/// The gnuplot script drawing STEM.dat (blocks in `order`, then the front) into STEM.png.
std::string gnuplot_script(const BenchSummary& s, const std::vector<std::string>& order,
                           const std::string& stem)
{
    std::string script =
        "set terminal pngcairo size 1100,750 font 'Sans,11'\nset output " + gnuplot_quoted(stem + ".png") +
        "\n"
        "set logscale xy\nset grid\nset key outside right top noenhanced\nset termoption noenhanced\n"
        "set xlabel 'cost: CPU ms per simulated second (median ms/step x steps/s)'\n"
        "set ylabel 'trajectory error vs reference: RMS of body centres [m]'\n"
        "set title " +
        gnuplot_quoted("Speed vs accuracy: " + std::filesystem::path(s.scene).filename().string() + ", " +
                       number(s.seconds) + " s simulated") +
        "\n";
    script += "plot ";
    for (size_t i = 0; i < order.size(); ++i) {
        const bool own = order[i] == "scene's own settings";
        script +=
            gnuplot_quoted(stem + ".dat") + " index " + std::to_string(i) + " using 1:2 with points pt " +
            (own ? std::string("3 ps 3 lw 3 lc rgb 'black'")
                 : std::to_string(i + 4) + " ps 1.6 lw 2 lc rgb '" + k_colours[i % k_colours.size()] + "'") +
            " title \"" + order[i] + "\", ";
        script += "'' index " + std::to_string(i) +
                  " using 1:2:3 with labels offset 0.6,0.6 left font ',8' "
                  "notitle, ";
    }
    script += gnuplot_quoted(stem + ".dat") + " index " + std::to_string(order.size()) +
              " using 1:2 with lines lw 2 lc rgb 'black' dt 2 title 'Pareto front'\n";
    return script;
}

/// Runs `gnuplot SCRIPT` with no shell in between, so the path reaches gnuplot as one argument whatever
/// it holds (quotes, $, spaces). gnuplot's output goes to stderr: stdout is the command's JSON or CSV.
/// True when it exited with 0.
bool run_gnuplot_script(const std::string& script_path)
{
    std::string program = "gnuplot";
    std::string path = script_path;
    char* argv[] = {program.data(), path.data(), nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, program.c_str(), &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
        return false;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return false;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// Writes STEM.dat and STEM.gp, runs gnuplot and moves STEM.png to png_path; removes the temporary
/// files either way. An error message, or empty.
std::string run_gnuplot(const std::string& stem, const std::string& data, const std::string& script,
                        const std::string& png_path)
{
    namespace fs = std::filesystem;
    std::string e = write_file_atomically(stem + ".dat", data);
    if (e.empty())
        e = write_file_atomically(stem + ".gp", script);
    if (e.empty() && !run_gnuplot_script(stem + ".gp"))
        e = "gnuplot failed on " + stem + ".gp";
    std::error_code ec;
    if (e.empty()) {
        fs::rename(stem + ".png", png_path, ec);
        if (ec)
            e = png_path + ": " + ec.message();
    }
    fs::remove(stem + ".dat", ec);
    fs::remove(stem + ".gp", ec);
    fs::remove(stem + ".png", ec);
    return e;
}

} // namespace

void mark_pareto_front(std::vector<BenchRow>& rows)
{
    for (BenchRow& r : rows) {
        r.pareto = false;
        if (!ok(r))
            continue;
        bool dominated = false;
        for (const BenchRow& o : rows)
            if (&o != &r && ok(o) && o.cpu_ms_per_second <= r.cpu_ms_per_second &&
                o.errors.trajectory_rms <= r.errors.trajectory_rms &&
                (o.cpu_ms_per_second < r.cpu_ms_per_second ||
                 o.errors.trajectory_rms < r.errors.trajectory_rms))
                dominated = true;
        r.pareto = !dominated;
    }
}

std::string bench_csv(const BenchSummary& s)
{
    std::string out =
        "knob,value,status,steps,cpu_ms_per_step,cpu_ms_per_sim_s,setup_ms,trajectory_rms_m,trajectory_max_m,"
        "max_penetration_m,energy_drift,constraint_error_m,frequency_error,pareto,base\n";
    for (const BenchRow& r : s.rows) {
        out += csv_field(r.knob) + "," + csv_field(r.value) + "," + csv_field(r.status) + "," +
               std::to_string(r.steps) + "," + number(r.cpu_ms_per_step) + "," + number(r.cpu_ms_per_second) +
               "," + number(r.setup_ms) + "," + number(r.errors.trajectory_rms) + "," +
               number(r.errors.trajectory_max) + "," + number(r.max_penetration) + "," +
               optional_number(r.errors.energy_drift) + "," + optional_number(r.constraint_error) + "," +
               optional_number(r.errors.frequency_error) + "," + (r.pareto ? "1" : "0") + "," +
               (r.base ? "1" : "0") + "\n";
    }
    return out;
}

std::string bench_markdown(const BenchSummary& s)
{
    std::string out = "# Speed/accuracy sweep: " + s.scene + "\n\n";
    out += "Simulated " + number(s.seconds) + " s; cost is the median over " + std::to_string(s.repeats) +
           " run(s) of process CPU time per step; the Pareto front compares it per simulated second (ms/step "
           "× steps/s), so a larger dt counts as the saving it is. Errors are against the reference (" +
           s.reference +
           "), sampled every 10 ms of simulated time. Written by `supermodal bench`; method in "
           "docs/speed_accuracy.md.\n\n";
    out += "| knob | value | status | ms/step | ms per sim. s | setup ms | traj RMS [m] | traj max [m] | max "
           "pen. [m] | "
           "energy drift | constraint err [m] | freq. err | Pareto |\n";
    out += "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n";
    auto cell = [](const std::optional<double>& v) { return v ? number(*v) : std::string("–"); };
    for (const BenchRow& r : s.rows) {
        const bool ref = r.knob == "reference";
        out += "| " + r.knob + " | " + r.value + " | " + r.status + " | " + number(r.cpu_ms_per_step) +
               " | " + number(r.cpu_ms_per_second) + " | " + number(r.setup_ms) + " | " +
               (ref ? "0 (ref)" : number(r.errors.trajectory_rms)) + " | " +
               (ref ? "0 (ref)" : number(r.errors.trajectory_max)) + " | " + number(r.max_penetration) +
               " | " + cell(r.errors.energy_drift) + " | " + cell(r.constraint_error) + " | " +
               cell(ref ? std::optional<double>() : r.errors.frequency_error) + " | " +
               (r.pareto ? "●" : "") + " |\n";
    }
    out += "\nPareto front (cheapest first):";
    std::vector<const BenchRow*> front;
    bool base_listed = false;
    for (const BenchRow& r : s.rows)
        if (r.pareto && !(r.base && base_listed)) {
            front.push_back(&r);
            base_listed = base_listed || r.base;
        }
    std::sort(front.begin(), front.end(), [](const BenchRow* a, const BenchRow* b) {
        return a->cpu_ms_per_second < b->cpu_ms_per_second;
    });
    for (const BenchRow* r : front)
        out += " " + (r->base ? std::string("the scene's own settings") : r->knob + " " + r->value) + " (" +
               number(r->cpu_ms_per_second) + " ms/s, " + number(r->errors.trajectory_rms) + " m);";
    out += "\n";
    return out;
}

nlohmann::json bench_json(const BenchSummary& s)
{
    nlohmann::json rows = nlohmann::json::array();
    auto opt = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
    for (const BenchRow& r : s.rows)
        rows.push_back({{"knob", r.knob},
                        {"value", r.value},
                        {"status", r.status},
                        {"steps", r.steps},
                        {"cpu_ms_per_step", r.cpu_ms_per_step},
                        {"cpu_ms_per_sim_s", r.cpu_ms_per_second},
                        {"setup_ms", r.setup_ms},
                        {"trajectory_rms_m", r.errors.trajectory_rms},
                        {"trajectory_max_m", r.errors.trajectory_max},
                        {"max_penetration_m", r.max_penetration},
                        {"energy_drift", opt(r.errors.energy_drift)},
                        {"constraint_error_m", opt(r.constraint_error)},
                        {"frequency_error", opt(r.errors.frequency_error)},
                        {"pareto", r.pareto},
                        {"base", r.base}});
    return {{"scene", s.scene},
            {"seconds", s.seconds},
            {"repeats", s.repeats},
            {"reference", s.reference},
            {"rows", rows}};
}

std::string bench_plot(const BenchSummary& s, const std::string& png_path)
{
    if (!on_path("gnuplot"))
        return "gnuplot not found";
    const PlotData plot = plot_data(s);
    if (plot.order.empty())
        return "nothing to plot: no configuration ran with a trajectory error above 0 (a static scene "
               "moves nothing; the log axis has no place for 0)";
    // Starting with '/' or "./": gnuplot reads a name starting with '-' as an option, and a file name
    // starting with '<' or an output starting with '|' as a shell command.
    const std::string dir = png_path.starts_with('/') ? "" : "./";
    const std::string stem = dir + png_path + ".tmp." + std::to_string(::getpid());
    std::string data;
    for (const std::string& k : plot.order)
        data += plot.blocks.at(k) + "\n\n";
    for (const BenchRow* r : plot.front)
        data += number(r->cpu_ms_per_second) + " " + number(r->errors.trajectory_rms) + " \"\"\n";
    return run_gnuplot(stem, data, gnuplot_script(s, plot.order, stem), png_path);
}

} // namespace supermodal::cli
