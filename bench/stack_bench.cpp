// SPDX-License-Identifier: MIT
// Stacking: do resting boxes stay put? Rounded boxes (half 0.1 m, ε = 0.3, μ = 0.5, density 1000 kg/m³,
// restitution 0) placed touching, each with ±1 mm horizontal and ±1° yaw jitter (fixed seed): a column
// of 20, a pyramid of 10 rows (55 boxes, 1 cm apart in a row) and 1000 boxes in one layer on the floor
// (1 cm apart). Each runs 10 s at dt = 1/60, 1/240 and 1/1000 s, one substep, default settings.
// Reported: the drift of the top box from its start (horizontal, vertical, total; for the floor layer
// the box that moved most), the largest speed of any body after 2 s and at the end, ms per step, and
// whether it stands: drift ≤ 1 cm and every speed < 1 cm/s after 2 s. The same for Bullet's btBoxShape
// (half 0.1 m), sleeping off and on, when built with Bullet.
//
// supermodal's contact settings come from --set key=value (ContactDef fields) and --solver NAME.
// bench/stack_report.py plots the CSV (docs/bench/stack.csv, stack.png).
#include "peer/peer_scene.h"
#ifdef SM_BENCH_BULLET
#include "peer/bullet_world.h"
#endif

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

namespace
{

using namespace peer;

constexpr double k_half = 0.1;                          // box half size [m]
constexpr double k_gap = 0.01;                          // gap between neighbours in a row [m]
constexpr double k_jitter = 0.001;                      // ± horizontal position jitter [m]
constexpr double k_yaw_jitter = std::numbers::pi / 180; // ± yaw jitter [rad]
constexpr double k_settle = 2.0;                        // speeds count after this time [s]
constexpr double k_stand_drift = 0.01;                  // stands: drift at most this [m]
constexpr double k_stand_speed = 0.01;                  // stands: every speed below this after 2 s [m/s]

struct Options {
    int column = 20, pyramid = 10, grid = 1000; // boxes, rows, boxes [-]
    double seconds = 10.0;                      // simulated [s]
    std::vector<double> rates{60, 240, 1000};   // steps per second, 1/dt [1/s]
    std::string engine = "all";
    std::string csv;
    double trace = 0.0; // print time, the largest speed and its body every this many seconds (0: off) [s]
    SupermodalOptions supermodal;
};

struct Stack {
    std::string name;
    SceneSpec scene;
    std::vector<int> watched; // whose drift counts
};

// An empty stack on the floor, the half-space y ≤ 0.
Stack on_floor(std::string name)
{
    Stack s{std::move(name), {}, {}};
    s.scene.planes = {{{0, 1, 0}, 0.0}};
    return s;
}

struct Result {
    std::string engine, scene;
    int bodies = 0;
    double dt = 0.0;                      // [s]
    double ms = 0.0, cpu_ms = 0.0;        // per step [ms]
    double dh = 0.0, dv = 0.0, drift = 0; // drift of the watched box: horizontal, vertical (+ up), total [m]
    double speed_after = 0.0, speed_end = 0.0; // largest body speed after k_settle, at the end [m/s]
    [[nodiscard]] bool stands() const { return drift <= k_stand_drift && speed_after < k_stand_speed; }
};

void add_box(Stack& s, Lcg& rng, double x, double y, double z)
{
    BodySpec b;
    b.kind = Kind::Box;
    b.half = {k_half, k_half, k_half};
    b.position = {x + k_jitter * rng.next(), y, z + k_jitter * rng.next()};
    b.orientation = sm::quat_from_rotation_vector({0, k_yaw_jitter * rng.next(), 0});
    s.scene.bodies.push_back(b);
}

// Boxes touching the floor (y = 0) and each other vertically; the top box is watched.
Stack column(int n)
{
    Stack s = on_floor("column");
    s.watched = {n - 1};
    Lcg rng;
    for (int i = 0; i < n; ++i)
        add_box(s, rng, 0, k_half * (2 * i + 1), 0);
    return s;
}

Stack pyramid(int rows)
{
    Stack s = on_floor("pyramid");
    Lcg rng;
    const double pitch = 2 * k_half + k_gap; // [m]
    for (int r = 0; r < rows; ++r)
        for (int i = 0; i < rows - r; ++i)
            add_box(s, rng, pitch * (i - 0.5 * (rows - r - 1)), k_half * (2 * r + 1), 0);
    s.watched = {static_cast<int>(s.scene.bodies.size()) - 1};
    return s;
}

Stack grid(int n)
{
    Stack s = on_floor("floor_grid");
    Lcg rng;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    const double pitch = 2 * k_half + k_gap; // [m]
    for (int i = 0; i < n; ++i) {
        add_box(s, rng, pitch * (i % side - 0.5 * (side - 1)), k_half, pitch * (i / side - 0.5 * (side - 1)));
        s.watched.push_back(i);
    }
    return s;
}

// One --trace line to stderr: time, the largest body speed and which body, that body's height, and the
// last watched box's drift from `start` (horizontal, vertical).
void trace_line(PeerWorld& w, int bodies, double t, int watched, const sm::Vec3& start)
{
    int fastest = 0;
    for (int b = 1; b < bodies; ++b)
        if (w.speed(b) > w.speed(fastest))
            fastest = b;
    const sm::Vec3 d = w.position(watched) - start;
    std::fprintf(stderr, "%.3f s: %.3g m/s, body %d at y %.4f m; watched %d drift dh %.5f dv %.5f m\n", t,
                 w.speed(fastest), fastest, w.position(fastest).y, watched, std::hypot(d.x, d.z), d.y);
}

// Steps the stack for o.seconds; only step() is timed.
Result run_stack(PeerWorld& w, const Stack& s, const Options& o)
{
    Result r;
    r.dt = s.scene.dt;
    r.bodies = static_cast<int>(s.scene.bodies.size());
    const long steps = std::lround(o.seconds / r.dt), settle = std::lround(k_settle / r.dt);
    std::vector<sm::Vec3> start;
    for (int b : s.watched)
        start.push_back(w.position(b));
    double wall = 0.0, cpu = 0.0;
    for (long i = 1; i <= steps; ++i) {
        const double w0 = wall_seconds(), c0 = process_cpu_seconds();
        w.step();
        wall += wall_seconds() - w0;
        cpu += process_cpu_seconds() - c0;
        r.speed_end = 0.0;
        for (int b = 0; b < r.bodies; ++b)
            r.speed_end = std::max(r.speed_end, w.speed(b));
        if (i >= settle)
            r.speed_after = std::max(r.speed_after, r.speed_end);
        if (o.trace > 0.0 && i % std::max(1L, std::lround(o.trace / r.dt)) == 0)
            trace_line(w, r.bodies, static_cast<double>(i) * r.dt, s.watched.back(), start.back());
    }
    for (size_t k = 0; k < s.watched.size(); ++k) {
        const sm::Vec3 d = w.position(s.watched[k]) - start[k];
        if (sm::length(d) >= r.drift) {
            r.dh = std::hypot(d.x, d.z);
            r.dv = d.y;
            r.drift = sm::length(d);
        }
    }
    r.ms = 1e3 * wall / static_cast<double>(steps);
    r.cpu_ms = 1e3 * cpu / static_cast<double>(steps);
    r.scene = s.name;
    return r;
}

std::vector<Result> run_all(const Options& o)
{
    std::vector<Stack> stacks;
    if (o.column > 0)
        stacks.push_back(column(o.column));
    if (o.pyramid > 0)
        stacks.push_back(pyramid(o.pyramid));
    if (o.grid > 0)
        stacks.push_back(grid(o.grid));
    std::vector<Result> results;
    for (Stack& s : stacks)
        for (double rate : o.rates) {
            s.scene.dt = 1.0 / rate;
            auto add = [&](std::string engine, PeerWorld& w) {
                results.push_back(run_stack(w, s, o));
                results.back().engine = std::move(engine);
                std::fprintf(stderr, "stack_bench: %s %s 1/dt = %g done\n", results.back().engine.c_str(),
                             s.name.c_str(), rate);
            };
            if (o.engine != "bullet")
                add("supermodal", *make_supermodal_world(s.scene, o.supermodal));
#ifdef SM_BENCH_BULLET
            if (o.engine != "supermodal")
                for (const bool sleep : {false, true})
                    add(sleep ? "bullet_sleep" : "bullet",
                        *make_bullet_world(s.scene, {.deactivation = sleep}));
#endif
        }
    return results;
}

void report(const std::vector<Result>& results, const Options& o)
{
    std::printf("%-12s %-10s %5s %7s %8s %8s %8s %8s %9s %9s %s\n", "engine", "scene", "N", "1/dt", "ms/step",
                "dh[m]", "dv[m]", "drift[m]", "v>2s[m/s]", "v_end", "stands");
    for (const Result& r : results)
        std::printf("%-12s %-10s %5d %7.0f %8.3f %8.4f %8.4f %8.4f %9.4f %9.4f %s\n", r.engine.c_str(),
                    r.scene.c_str(), r.bodies, 1.0 / r.dt, r.ms, r.dh, r.dv, r.drift, r.speed_after,
                    r.speed_end, r.stands() ? "yes" : "no");
    if (o.csv.empty())
        return;
    std::ofstream f(o.csv);
#ifdef SM_BENCH_BULLET
    f << "# peer: " << bullet_name() << ", Bullet box margin " << BulletOptions{}.margin << " m\n";
#endif
    f << "date,machine,engine,scene,bodies,dt_s,substeps,seconds,ms_per_step,cpu_ms_per_step,top_dh_m,top_dv_"
         "m,"
         "top_drift_m,max_speed_after_2s,end_max_speed,stands\n";
    const std::string date = today(), machine = machine_name();
    for (const Result& r : results) {
        char line[320];
        std::snprintf(line, sizeof line,
                      "%s,\"%s\",%s,%s,%d,%.6g,%d,%g,%.4f,%.4f,%.3e,%.3e,%.3e,%.3e,%.3e,%s\n", date.c_str(),
                      machine.c_str(), r.engine.c_str(), r.scene.c_str(), r.bodies, r.dt,
                      r.engine == "supermodal" ? o.supermodal.substeps : 1, o.seconds, r.ms, r.cpu_ms, r.dh,
                      r.dv, r.drift, r.speed_after, r.speed_end, r.stands() ? "yes" : "no");
        f << line;
    }
}

} // namespace

int main(int argc, char** argv)
{
    Options o;
    std::vector<std::string> sets;
    std::string solver = "soft"; // the engine's default (ContactDef::solver)
    CLI::App app{"Stacking: a column, a pyramid and a floor layer of boxes, supermodal against Bullet"};
    app.add_option("--column", o.column, "Boxes in the column [-], 0: none")->check(CLI::NonNegativeNumber);
    app.add_option("--pyramid", o.pyramid, "Rows of the pyramid [-], 0: none")->check(CLI::NonNegativeNumber);
    app.add_option("--grid", o.grid, "Boxes on the floor [-], 0: none")->check(CLI::NonNegativeNumber);
    app.add_option("--seconds", o.seconds, "Simulated time [s]")->check(CLI::PositiveNumber);
    app.add_option("--rate", o.rates, "Steps per second, 1/dt [1/s]")
        ->check(CLI::PositiveNumber)
        ->delimiter(',');
    app.add_option("--substeps", o.supermodal.substeps, "supermodal substeps per step [-]")
        ->check(CLI::Range(1, 1000));
    app.add_option("--engine", o.engine, "all, supermodal or bullet")
        ->check(CLI::IsMember({"all", "supermodal", "bullet"}));
    app.add_option("--csv", o.csv, "Write the table as CSV here");
    app.add_option("--trace", o.trace, "Print the largest speed every this many seconds [s] (0: off)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--set", sets, "supermodal ContactDef field, key=value (repeatable)");
    app.add_option("--solver", solver, "supermodal contact solver: soft (the default) or penalty");
    CLI11_PARSE(app, argc, argv);
    for (const std::string& kv : sets)
        if (const std::string error = apply_contact_setting(o.supermodal.contact, kv); !error.empty())
            return std::fprintf(stderr, "stack_bench: --set %s\n", error.c_str()), 2;
    if (const std::string error = apply_contact_solver(o.supermodal.contact, solver); !error.empty())
        return std::fprintf(stderr, "stack_bench: --solver: %s\n", error.c_str()), 2;
    std::printf("stacking, %g s simulated, one thread, %s\n", o.seconds, machine_name().c_str());
    report(run_all(o), o);
    return 0;
}
