// SPDX-License-Identifier: MIT
// `supermodal bench`: run the sweep of bench_sweep.h and write the report of bench_report.h.
#include "cmd_bench.h"

#include "bench_report.h"
#include "bench_sweep.h"
#include "cli_common.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace supermodal::cli
{
namespace
{

/// Splits "dt,path" into names and checks each; an error message names the first unknown one.
std::string parse_knobs(const std::string& text, std::vector<std::string>& knobs)
{
    std::stringstream in(text);
    std::string k;
    while (std::getline(in, k, ',')) {
        if (k.empty())
            continue;
        if (std::find(bench_knobs().begin(), bench_knobs().end(), k) == bench_knobs().end()) {
            std::string known;
            for (const std::string& n : bench_knobs())
                known += (known.empty() ? "" : ", ") + n;
            return "bench: unknown knob '" + k + "' (known: " + known + ")";
        }
        knobs.push_back(k);
    }
    if (!text.empty() && knobs.empty())
        return "bench: --knobs names no knob";
    return {};
}

/// What makes two configurations the same run: the scene text plus the settings it may not spell out.
std::string config_key(const Scene& s)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, "|%.17g|%d|%d|%.17g|%.17g", s.world.dt, s.world.substep_count,
                  static_cast<int>(s.world.contact.path), s.world.contact.frequency_hz,
                  s.world.contact.sample_spacing);
    std::string key = scene_to_json(s) + buf;
    for (const SceneBody& b : s.bodies)
        if (b.def.modal.enabled)
            key += "|" + std::to_string(b.def.modal.mode_count) + "," +
                   std::to_string(b.def.modal.lattice[0]) + "," + std::to_string(b.def.modal.lattice[1]) +
                   "," + std::to_string(b.def.modal.lattice[2]) + "," +
                   std::to_string(static_cast<int>(b.def.modal.integrator));
    return key;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// Runs one configuration `repeats` times; the first run's trace is the one compared.
BenchRow measure(const Scene& scene, const BenchBase& base, double seconds, int repeats, BenchTrace& trace)
{
    BenchRow row;
    trace = run_bench(scene, base, seconds, std::min(0.01, seconds));
    row.steps = trace.steps;
    row.setup_ms = trace.setup_ms;
    if (!trace.refused.empty()) {
        row.status = "refused: " + trace.refused;
        return row;
    }
    std::vector<double> costs{trace.cpu_ms_per_step};
    for (int i = 1; i < repeats; ++i)
        costs.push_back(run_bench(scene, base, seconds, std::min(0.01, seconds), false).cpu_ms_per_step);
    row.cpu_ms_per_step = median(costs);
    row.cpu_ms_per_second = row.cpu_ms_per_step * static_cast<double>(row.steps) / seconds;
    row.max_penetration = trace.max_penetration;
    if (trace.non_finite)
        row.status = "unstable: a body's state turned NaN/Inf";
    return row;
}

/// Checks --knobs and the --out files up front; an error message, or empty.
std::string check_bench_options(const BenchOptions& o, std::vector<std::string>& knobs)
{
    if (std::string e = parse_knobs(o.knobs, knobs); !e.empty())
        return e;
    if (!o.out.empty())
        for (const char* ext : {".csv", ".md", ".png"})
            if (std::string e = check_writable(o.out + ext); !e.empty())
                return e;
    return {};
}

/// Runs the converged reference into `reference` and adds its row to the summary; an error message,
/// or empty. Modal bodies: every mode of the lattice where it is small enough for the dense solve (the
/// modal solution without truncation, so more modes come closer to it); else twice the scene's modes;
/// else the scene's own.
std::string measure_reference(const Scene& scene, const BenchBase& base, const BenchOptions& o,
                              BenchSummary& summary, BenchTrace& reference)
{
    BenchRow ref_row;
    const std::pair<ReferenceModes, const char*> tries[] = {
        {ReferenceModes::All, ", every elastic mode of each lattice"},
        {ReferenceModes::Doubled, ", modes doubled (every mode refused: lattice over the dense limit)"},
        {ReferenceModes::Scene, ", the scene's mode counts (every mode and doubling refused)"}};
    for (const auto& [modes, label] : tries) {
        if (base.modal_bodies.empty() && modes != ReferenceModes::Scene)
            continue;
        reference = {};
        ref_row = measure(reference_scene(scene, base, modes), base, summary.seconds, o.repeats, reference);
        if (ref_row.status.rfind("refused", 0) != 0) {
            if (!base.modal_bodies.empty())
                summary.reference += std::string(label) + ", exact modal integrator";
            break;
        }
    }
    if (ref_row.status != "ok")
        return "bench: the reference run failed (" + ref_row.status + "): " + o.scene;
    ref_row.knob = "reference";
    ref_row.value = "converged";
    ref_row.errors.energy_drift = energy_drift(reference);
    if (reference.max_constraint_error > 0.0 || !scene.constraints.empty())
        ref_row.constraint_error = reference.max_constraint_error;
    summary.rows.push_back(ref_row);
    std::fprintf(stderr, "bench: reference %.4g ms/step (%lld steps)\n", ref_row.cpu_ms_per_step,
                 ref_row.steps);
    return {};
}

/// Runs every configuration of the sweep and adds its row, compared with the reference.
void measure_sweep(const Scene& scene, const BenchBase& base, const std::vector<BenchConfig>& configs,
                   const BenchOptions& o, const BenchTrace& reference, BenchSummary& summary)
{
    const std::string base_key = config_key(scene);
    // Identical configurations (dt x1, substeps = the scene's, ...) run once.
    std::map<std::string, BenchRow> done;
    for (size_t i = 0; i < configs.size(); ++i) {
        const BenchConfig& c = configs[i];
        const std::string key = config_key(c.scene);
        BenchRow row;
        if (auto it = done.find(key); it != done.end()) {
            row = it->second;
        } else {
            BenchTrace trace;
            row = measure(c.scene, base, summary.seconds, o.repeats, trace);
            if (row.status.rfind("refused", 0) != 0) {
                row.errors = compare_to_reference(trace, reference);
                if (!scene.constraints.empty())
                    row.constraint_error = trace.max_constraint_error;
            }
            done[key] = row;
        }
        row.knob = c.knob;
        row.value = c.value;
        row.base = key == base_key;
        std::fprintf(stderr, "bench: [%zu/%zu] %s %s: %s, %.4g ms/step, trajectory RMS %.3g m\n", i + 1,
                     configs.size(), c.knob.c_str(), c.value.c_str(), row.status.c_str(), row.cpu_ms_per_step,
                     row.errors.trajectory_rms);
        summary.rows.push_back(std::move(row));
    }
}

/// Writes PREFIX.csv/.md/.png and prints the JSON or CSV as asked; an exit code.
int write_bench(const BenchOptions& o, const BenchSummary& summary)
{
    if (!o.out.empty()) {
        for (auto [ext, text] :
             {std::pair{".csv", bench_csv(summary)}, std::pair{".md", bench_markdown(summary)}})
            if (const std::string e = write_file_atomically(o.out + ext, text); !e.empty()) {
                print_error(e);
                return k_exit_internal;
            }
        if (const std::string e = bench_plot(summary, o.out + ".png"); !e.empty())
            std::fprintf(stderr, "bench: no plot: %s\n", e.c_str());
    }
    if (o.json)
        std::printf("%s\n", json_text(bench_json(summary)).c_str());
    else if (o.out.empty())
        std::printf("%s", bench_csv(summary).c_str());
    return k_exit_ok;
}

} // namespace

CLI::App* add_bench_command(CLI::App& app, BenchOptions& o)
{
    CLI::App* cmd = app.add_subcommand(
        "bench", "Sweep dt, substeps, modes, lattice, contact sampling/path/frequency and the modal "
                 "integrator one at a time; report CPU cost per step against error vs a converged reference");
    cmd->add_option("scene", o.scene, "Scene file (JSON, format v1)")->required();
    cmd->add_option("--seconds", o.seconds, "Simulated time per run [s] (default: min(settings.duration, 1))")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--repeats", o.repeats, "Timed runs per configuration; the median counts (default 3)")
        ->check(CLI::Range(1, 100));
    cmd->add_option("--knobs", o.knobs,
                    "Comma list of knobs to sweep (dt,substeps,modes,lattice,spacing,"
                    "path,integrator,frequency); default all");
    cmd->add_option("--out", o.out, "Write PREFIX.csv, PREFIX.md and, with gnuplot, PREFIX.png");
    cmd->add_flag("--json", o.json, "Print a JSON summary on stdout");
    cmd->add_flag("--fixed-contact", o.fixed_contact,
                  "Hold the contact frequency at the scene's default in every run (penalty: 1/(10 h); soft: "
                  "min(1/(2 h), 60 Hz)); the default ties it to each run's substep, so a smaller dt also "
                  "means stiffer contact");
    add_set_option(*cmd, o.sets);
    return cmd;
}

namespace
{

// Sets the contact frequencies left at 0 (which follow the substep) to what they are at the scene's own.
void hold_contact_frequencies(WorldDef& world)
{
    ContactDef& c = world.contact;
    const double h = world.dt / world.substep_count;
    if (!(c.frequency_hz > 0.0))
        c.frequency_hz = 1.0 / (10.0 * h);
    if (!(c.soft.frequency_hz > 0.0))
        c.soft.frequency_hz = std::min(soft_solver_substeps(c.soft, h) / (2.0 * h), 60.0);
}

} // namespace

int bench_command(const BenchOptions& o)
{
    std::vector<std::string> knobs;
    if (const std::string e = check_bench_options(o, knobs); !e.empty()) {
        print_error(e);
        return k_exit_bad_input;
    }
    Result<Scene> scene = load_scene_with(o.scene, o.sets);
    if (!scene) {
        print_error(scene.error().message());
        return k_exit_bad_input;
    }
    // The default frequencies (0) follow the substep h (penalty: the cap 1/(10 h); soft: min(1/(2 h),
    // 60 Hz), ContactDef): refining dt then also stiffens the contact. --fixed-contact holds them at the
    // scene's values, so dt and substeps show discretisation error alone.
    if (o.fixed_contact)
        hold_contact_frequencies(scene->world);
    BenchBase base;
    if (const std::string e = resolve_base(*scene, base); !e.empty()) {
        print_error(e);
        return k_exit_bad_input;
    }
    const std::vector<BenchConfig> configs = make_sweep(*scene, base, knobs);
    if (configs.empty()) {
        print_error("bench: nothing to sweep: the chosen knobs need modal bodies and " + o.scene +
                    " has none");
        return k_exit_bad_input;
    }

    BenchSummary summary;
    summary.scene = o.scene;
    summary.seconds = o.seconds > 0.0 ? o.seconds : std::min(scene->duration, 1.0);
    summary.repeats = o.repeats;
    summary.reference = "dt/8, same substeps, sample spacing/2";
    if (o.fixed_contact) {
        const ContactDef& c = scene->world.contact;
        const bool soft = c.solver == ContactSolver::Soft;
        char buf[112];
        std::snprintf(buf, sizeof buf, ", %s contact frequency held at %.4g Hz in every run",
                      soft ? "soft" : "penalty", soft ? c.soft.frequency_hz : c.frequency_hz);
        summary.reference += buf;
    }
    BenchTrace reference;
    if (const std::string e = measure_reference(*scene, base, o, summary, reference); !e.empty()) {
        print_error(e);
        return k_exit_bad_input;
    }
    measure_sweep(*scene, base, configs, o, reference, summary);
    mark_pareto_front(summary.rows);
    return write_bench(o, summary);
}

} // namespace supermodal::cli
