// SPDX-License-Identifier: MIT
// `supermodal run`: load a scene, step it, write a JSON summary (and optionally a CSV trace).
#include "cli_common.h"
#include "constraint_summary.h"
#include "modal_summary.h"
#include "supermodal/constraint.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace supermodal::cli
{
namespace
{

// A run longer than this many steps is surely a typo (10^9 steps of 1 ms is 11 days of simulated time).
constexpr long long k_max_steps = 1'000'000'000;

struct Energies {
    double kinetic = 0.0, potential = 0.0;
};
Energies total_energy(const World& world)
{
    Energies e;
    for (Entity b : world_bodies(world)) {
        e.kinetic += body_kinetic_energy(world, b);
        e.potential += body_potential_energy(world, b);
    }
    return e;
}

void trace_rows(const World& world, std::ostringstream& csv)
{
    char buf[512];
    for (Entity b : world_bodies(world)) {
        const Vec3 p = body_position(world, b), v = body_linear_velocity(world, b);
        const Vec3 w = body_angular_velocity(world, b);
        const Quat q = body_orientation(world, b);
        std::snprintf(
            buf, sizeof buf,
            "%llu,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
            static_cast<unsigned long long>(world.step_count()), world.time(), body_name(world, b).c_str(),
            p.x, p.y, p.z, q.w, q.x, q.y, q.z, v.x, v.y, v.z, w.x, w.y, w.z);
        csv << buf;
    }
}

class Progress
{
  public:
    Progress(long long total, bool enabled) : m_total(total), m_enabled(enabled && ::isatty(2)) {}
    void update(long long done)
    {
        if (!m_enabled)
            return;
        const int percent = static_cast<int>(100 * done / std::max(1LL, m_total));
        if (percent == m_last)
            return;
        m_last = percent;
        std::fprintf(stderr, "\r[%-40s] %3d%%",
                     std::string(static_cast<size_t>(percent * 40 / 100), '#').c_str(), percent);
        if (done == m_total)
            std::fprintf(stderr, "\n");
    }

  private:
    long long m_total;
    bool m_enabled;
    int m_last = -1;
};

nlohmann::json body_summary(const World& world, Entity b)
{
    return {{"name", body_name(world, b)},
            {"motion", motion_name(body_motion(world, b))},
            {"position", to_json(body_position(world, b))},
            {"orientation", to_json(body_orientation(world, b))},
            {"velocity", to_json(body_linear_velocity(world, b))},
            {"angular_velocity", to_json(body_angular_velocity(world, b))},
            {"kinetic_energy", body_kinetic_energy(world, b)},
            {"potential_energy", body_potential_energy(world, b)}};
}

// Contact counts over the run, from the per-step contact list and events.
struct ContactTally {
    size_t max_contacts = 0;
    double max_penetration = 0.0; ///< Deepest over all steps [m].
    uint64_t begins = 0, ends = 0;

    void add(const World& world)
    {
        max_contacts = std::max(max_contacts, world_contacts(world).size());
        max_penetration = std::max(max_penetration, world_max_penetration(world));
        for (const ContactEvent& e : world_contact_events(world)) {
            begins += e.kind == ContactEventKind::Begin ? 1 : 0;
            ends += e.kind == ContactEventKind::End ? 1 : 0;
        }
    }
    [[nodiscard]] nlohmann::json summary(const World& world) const
    {
        return {{"contacts", world_contacts(world).size()},
                {"max_contacts", max_contacts},
                {"penetration", world_max_penetration(world)},
                {"max_penetration", max_penetration},
                {"begin_events", begins},
                {"end_events", ends}};
    }
};

std::string hex(uint64_t v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// The options' own consistency; k_exit_ok or the code to exit with (the error printed).
int check_options(const RunOptions& opt)
{
    if (opt.has_seconds && opt.has_steps) {
        print_error("give --seconds or --steps, not both");
        return k_exit_bad_input;
    }
    if (opt.has_seconds && !(std::isfinite(opt.seconds) && opt.seconds > 0.0)) {
        print_error("--seconds: expected a finite time > 0 s, found " + std::to_string(opt.seconds));
        return k_exit_bad_input;
    }
    if (opt.has_steps && opt.steps < 1) {
        print_error("--steps: expected an integer >= 1, found " + std::to_string(opt.steps));
        return k_exit_bad_input;
    }
    for (const std::string& out : {opt.json_out, opt.csv_out})
        if (!out.empty())
            if (std::string err = check_writable(out); !err.empty()) {
                print_error(err);
                return k_exit_bad_input;
            }
    return k_exit_ok;
}

// The run's step count from --steps, --seconds or the scene's duration; 0 when out of range (printed).
long long run_length(const RunOptions& opt, const Scene& scene, const World& world)
{
    const double dt = world.settings().dt;
    const double seconds = opt.has_seconds ? opt.seconds : scene.duration;
    const double wanted = opt.has_steps ? static_cast<double>(opt.steps) : std::ceil(seconds / dt - 1e-9);
    if (!(wanted >= 1.0 && wanted <= static_cast<double>(k_max_steps))) {
        print_error("run length: expected 1 to 1e9 steps, got " + std::to_string(wanted) +
                    " (dt = " + std::to_string(dt) + " s)");
        return 0;
    }
    return static_cast<long long>(wanted);
}

// Opens the frame capture when asked for; k_exit_ok or the code to exit with (the error printed).
int open_capture(const RunOptions& opt, const Scene& scene, const World& world,
                 std::unique_ptr<FrameCapture>& out)
{
    if (!(opt.capture.enabled() || opt.capture.every_given || opt.capture.size_given))
        return k_exit_ok;
    Result<std::unique_ptr<FrameCapture>> opened = FrameCapture::open(opt.capture, scene, world);
    if (!opened) {
        print_error(opened.error().message());
        // A machine without EGL is not the user's input's fault.
        return opened.error().where == "render" ? k_exit_internal : k_exit_bad_input;
    }
    out = std::move(*opened);
    return k_exit_ok;
}

// Captures step `step`'s frame when capturing; false on a capture error (printed).
bool capture_frame(FrameCapture* capture, const World& world, long long step)
{
    if (capture == nullptr)
        return true;
    Status s = capture->maybe_capture(world, step);
    if (!s)
        print_error("frame capture: " + s.error().message());
    return static_cast<bool>(s);
}

// What a run records while it steps.
struct RunRecord {
    std::ostringstream csv; ///< The trace, when asked for.
    Energies e0;            ///< Before the first step.
    std::vector<double> step_ms;
    std::array<double, static_cast<size_t>(Stage::Count)> stage_total{};
    ContactTally tally;
    double peak_constraint_error = 0.0;
};

// Steps the world `steps` times, recording as it goes; k_exit_ok or the code to exit with.
int step_run(const RunOptions& opt, World& world, long long steps, FrameCapture* capture, RunRecord& rec)
{
    if (!capture_frame(capture, world, 0))
        return k_exit_internal;
    if (!opt.csv_out.empty()) {
        rec.csv << "step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
        trace_rows(world, rec.csv);
    }
    rec.e0 = total_energy(world);
    rec.step_ms.reserve(static_cast<size_t>(std::min(steps, 10'000'000LL)));
    Progress progress(steps, !opt.quiet);
    for (long long i = 1; i <= steps; ++i) {
        world.step();
        rec.peak_constraint_error = std::max(rec.peak_constraint_error, world_max_constraint_error(world));
        rec.tally.add(world);
        rec.step_ms.push_back(world.profile().total_ms);
        for (size_t s = 0; s < rec.stage_total.size(); ++s)
            rec.stage_total[s] += world.profile().stage_ms[s];
        if (!opt.csv_out.empty() && (i % opt.csv_every == 0 || i == steps))
            trace_rows(world, rec.csv);
        if (i % 64 == 0 || i == steps)
            progress.update(i);
        if (!capture_frame(capture, world, i))
            return k_exit_internal;
    }
    if (capture != nullptr)
        if (Status s = capture->finish(); !s) {
            print_error(s.error().message());
            return k_exit_internal;
        }
    return k_exit_ok;
}

// Mean, median and max of the steps' wall times [ms].
nlohmann::json step_timing(const std::vector<double>& step_ms, long long steps)
{
    std::vector<double> sorted = step_ms;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    double sum = 0.0;
    for (double ms : step_ms)
        sum += ms;
    return {{"mean", sum / static_cast<double>(steps)},
            {"median", sorted[sorted.size() / 2]},
            {"max", *std::max_element(step_ms.begin(), step_ms.end())}};
}

nlohmann::json run_summary(const RunOptions& opt, const World& world, long long steps, const RunRecord& rec)
{
    const Energies e1 = total_energy(world);
    nlohmann::json stages = nlohmann::json::object();
    for (size_t s = 0; s < rec.stage_total.size(); ++s)
        stages[std::string(stage_name(static_cast<Stage>(s)))] =
            rec.stage_total[s] / static_cast<double>(steps);
    nlohmann::json bodies = nlohmann::json::array();
    for (Entity b : world_bodies(world))
        bodies.push_back(body_summary(world, b));
    add_modal_summaries(world, bodies);
    return {{"scene", opt.scene},
            {"steps", steps},
            {"time", world.time()},
            {"dt", world.settings().dt},
            {"substeps", world.settings().substep_count},
            {"threads", world.settings().thread_count},
            {"split_islands", world.settings().split_islands},
            {"body_count", bodies.size()},
            {"sleeping", world_sleeping_count(world)}, // bodies asleep at the end
            {"state_hash", hex(world.state_hash())},
            {"ms_per_step", step_timing(rec.step_ms, steps)},
            {"stage_ms_mean", stages},
            {"contact", rec.tally.summary(world)},
            {"energy",
             {{"initial_kinetic", rec.e0.kinetic},
              {"initial_potential", rec.e0.potential},
              {"kinetic", e1.kinetic},
              {"potential", e1.potential},
              {"total_drift", (e1.kinetic + e1.potential) - (rec.e0.kinetic + rec.e0.potential)}}},
            {"warnings",
             {{"non_finite_bodies", world.warnings().non_finite_bodies},
              {"gyroscopic_fallbacks", world.warnings().gyroscopic_fallbacks},
              {"modal_integrator_switches", world.warnings().modal_integrator_switches},
              {"modal_non_finite", world.warnings().modal_non_finite}}},
            {"constraints", constraint_summary(world, rec.peak_constraint_error)},
            {"bodies", bodies}};
}

// Writes the CSV trace (when asked for) and the JSON summary (to a file, or stdout).
int write_outputs(const RunOptions& opt, const std::string& text, const std::string& csv)
{
    if (!opt.csv_out.empty())
        if (std::string err = write_file_atomically(opt.csv_out, csv); !err.empty()) {
            print_error(err);
            return k_exit_internal;
        }
    if (opt.json_out.empty()) {
        std::fputs(text.c_str(), stdout);
    } else if (std::string err = write_file_atomically(opt.json_out, text); !err.empty()) {
        print_error(err);
        return k_exit_internal;
    }
    return k_exit_ok;
}

} // namespace

int run_command(const RunOptions& opt)
{
    if (int rc = check_options(opt); rc != k_exit_ok)
        return rc;
    Result<Scene> scene = load_scene_with(opt.scene, opt.sets);
    if (!scene) {
        print_error(scene.error().message());
        return k_exit_bad_input;
    }
    if (opt.threads > 0)
        scene->world.thread_count = opt.threads;
    Result<World> built = build_world(*scene);
    if (!built) {
        print_error(built.error().message());
        return k_exit_bad_input;
    }
    World& world = *built;
    const long long steps = run_length(opt, *scene, world);
    if (steps == 0)
        return k_exit_bad_input;
    std::unique_ptr<FrameCapture> capture;
    if (int rc = open_capture(opt, *scene, world, capture); rc != k_exit_ok)
        return rc;
    RunRecord rec;
    if (int rc = step_run(opt, world, steps, capture.get(), rec); rc != k_exit_ok)
        return rc;
    // Frame capture adds its block to a copy: the summary stays as it always was.
    nlohmann::json out = run_summary(opt, world, steps, rec);
    if (capture)
        out["capture"] = capture->summary();
    return write_outputs(opt, json_text(out) + "\n", rec.csv.str());
}

} // namespace supermodal::cli
