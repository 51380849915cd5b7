// SPDX-License-Identifier: MIT
// The pile of bench/pile_bench.cpp stepped by supermodal and by Bullet in one run, on one thread: N bodies
// (density 1000 kg/m³) on a jittered grid (pitch 0.2 m, 10 layers) fall into an open box (static
// half-spaces), dt = 1/240 s, 720 steps, μ = 0.5, restitution 0. Measured over the last 240 steps, the
// engines' steps interleaved in blocks of 24 so every engine is timed through the same spells of a
// shared machine's speed: ms per step (wall, and process CPU) and the deepest overlap after the last
// step (supermodal: its contacts; Bullet: the distances of its contact manifolds' points). Boxes are
// supermodal's rounded box (ε = 0.3) against btBoxShape, ellipsoids a btMultiSphereShape of one scaled
// sphere; Bullet runs with deactivation off, then on. Both engines get the same gravity, pair friction,
// restitution, mass, inertia and step (Bullet: fixed step dt, one internal step per step).
//
// Usage: peer_pile [N=1000] [substeps=1] [--seeds K] [--csv FILE] [--set key=value]...
// (bench/peer/peer_scene.h)
#include "peer/peer_scene.h"
#ifdef SM_BENCH_BULLET
#include "peer/bullet_world.h"
#endif

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <span>

namespace
{

using namespace peer;

constexpr double k_pitch = 0.2;   // grid pitch [m]
constexpr int k_layers = 10;      // grid layers [-]
constexpr double k_jitter = 0.02; // ± jitter of each grid position [m]

struct Options {
    int n = 1000;
    int substeps = 1;
    int steps = 720;       // whole run [-]
    int timed_steps = 240; // measured at the end [-]
    int seeds = 1;         // piles from this many jitters [-]; the first is the one of pile_bench.cpp
    std::vector<std::string> shapes{"box", "sphere", "ellipsoid"};
    std::string engine = "all"; // all, supermodal or bullet
    std::string csv;
    SupermodalOptions supermodal;
};

struct Row {
    std::string engine;
    Kind kind = Kind::Box;
    int substeps = 1;
    int seed = 0;
    double ms = 0.0, cpu_ms = 0.0; // per step [ms]
    double overlap = 0.0;          // deepest after the last step [m]
    double ratio = 0.0;            // supermodal / this engine, CPU ms per step [-]; 0: not a peer row
};

BodySpec pile_body(Kind kind)
{
    BodySpec b;
    b.kind = kind;
    b.half = kind == Kind::Ellipsoid ? sm::Vec3{0.06, 0.04, 0.03} : sm::Vec3{0.05, 0.05, 0.05};
    return b;
}

// The same bodies, in the same order and from the same random numbers, as pile_bench.cpp (seed 0); each
// other seed jitters and turns them anew.
SceneSpec pile_scene(Kind kind, int n, int seed)
{
    SceneSpec s;
    s.dt = 1.0 / 240.0;
    const int per_layer = (n + k_layers - 1) / k_layers;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(per_layer))));
    const double half = 0.5 * side * k_pitch; // inner half-width of the box [m]
    s.planes = {
        {{0, 1, 0}, 0.0}, {{1, 0, 0}, -half}, {{-1, 0, 0}, -half}, {{0, 0, 1}, -half}, {{0, 0, -1}, -half}};
    Lcg rng;
    rng.state += static_cast<uint32_t>(seed);
    for (int i = 0; i < n; ++i) {
        const int layer = i / per_layer, cell = i % per_layer;
        BodySpec b = pile_body(kind);
        b.position = {-half + k_pitch * (cell % side + 0.5) + k_jitter * rng.next(),
                      k_pitch * (layer + 0.5) + k_jitter * rng.next(),
                      -half + k_pitch * (cell / side + 0.5) + k_jitter * rng.next()};
        const sm::Quat q{rng.next(), rng.next(), rng.next(), rng.next()};
        b.orientation = sm::normalized(q);
        s.bodies.push_back(b);
    }
    return s;
}

// Timed steps per engine in turn [-]: 0.1 s of the pile, long enough that an engine's caches warm again.
// On the 2-core VM one engine's time varied 2.5-fold between whole runs a minute apart (Bullet's box pile:
// 7.6 to 19 ms per step), so engines timed one after the other compared different machines.
constexpr int k_block_steps = 24;

// Runs every world to the timed part, then times the worlds' steps in turn, a block each, to the end.
void measure(std::span<const std::unique_ptr<PeerWorld>> worlds, std::span<Row> rows, const Options& o)
{
    for (const auto& world : worlds)
        for (int i = 0; i < o.steps - o.timed_steps; ++i)
            world->step();
    for (int done = 0; done < o.timed_steps; done += k_block_steps)
        for (size_t k = 0; k < worlds.size(); ++k) {
            const double wall = wall_seconds(), cpu = process_cpu_seconds();
            for (int i = 0; i < std::min(k_block_steps, o.timed_steps - done); ++i)
                worlds[k]->step();
            rows[k].ms += 1e3 * (wall_seconds() - wall) / o.timed_steps;
            rows[k].cpu_ms += 1e3 * (process_cpu_seconds() - cpu) / o.timed_steps;
        }
    for (size_t k = 0; k < worlds.size(); ++k)
        rows[k].overlap = worlds[k]->max_penetration();
}

std::vector<Row> run_shape(Kind kind, int seed, const Options& o)
{
    const SceneSpec scene = pile_scene(kind, o.n, seed);
    std::vector<std::unique_ptr<PeerWorld>> worlds;
    std::vector<Row> rows;
    auto add = [&](std::string engine, std::unique_ptr<PeerWorld> world, int substeps) {
        worlds.push_back(std::move(world));
        rows.push_back({.engine = std::move(engine), .kind = kind, .substeps = substeps, .seed = seed});
    };
    if (o.engine != "bullet")
        add("supermodal", make_supermodal_world(scene, o.supermodal), o.supermodal.substeps);
#ifdef SM_BENCH_BULLET
    if (o.engine != "supermodal")
        for (const bool sleep : {false, true})
            add(sleep ? "bullet_sleep" : "bullet", make_bullet_world(scene, {.deactivation = sleep}), 1);
#endif
    measure(worlds, rows, o);
#ifdef SM_BENCH_BULLET
    if (!rows.empty() && rows.front().engine == "supermodal")
        for (Row& r : rows)
            if (r.engine != "supermodal")
                r.ratio = rows.front().cpu_ms / r.cpu_ms;
#endif
    return rows;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Over the seeds, per engine and shape: the median ratio and the median and largest end-of-run overlap. One
// pile's deepest point moves by tenths of a millimetre with any change of its trajectory; the seeds' spread
// says how far one run can be trusted.
void report_seeds(const std::vector<Row>& rows)
{
    std::printf("\nover the seeds:\n%-13s %-10s %5s %12s %16s %16s\n", "engine", "shape", "runs",
                "sm/peer med", "overlap med[mm]", "overlap max[mm]");
    std::vector<std::pair<std::string, Kind>> done;
    for (const Row& first : rows) {
        const std::pair<std::string, Kind> key{first.engine, first.kind};
        if (std::find(done.begin(), done.end(), key) != done.end())
            continue;
        done.push_back(key);
        std::vector<double> ratios, overlaps;
        for (const Row& r : rows)
            if (r.engine == first.engine && r.kind == first.kind) {
                ratios.push_back(r.ratio);
                overlaps.push_back(1e3 * r.overlap);
            }
        char ratio[16] = "-";
        if (first.engine != "supermodal")
            std::snprintf(ratio, sizeof ratio, "%.2f", median(ratios));
        std::printf("%-13s %-10s %5zu %12s %16.3f %16.3f\n", first.engine.c_str(),
                    kind_name(first.kind).data(), overlaps.size(), ratio, median(overlaps),
                    *std::max_element(overlaps.begin(), overlaps.end()));
    }
}

void report(const std::vector<Row>& rows, const Options& o)
{
    std::printf("%-13s %-10s %6s %4s %9s %9s %12s %10s\n", "engine", "shape", "substp", "seed", "ms/step",
                "cpu_ms", "overlap[mm]", "sm/peer");
    for (const Row& r : rows)
        std::printf("%-13s %-10s %6d %4d %9.3f %9.3f %12.3f %10.2f\n", r.engine.c_str(),
                    kind_name(r.kind).data(), r.substeps, r.seed, r.ms, r.cpu_ms, 1e3 * r.overlap, r.ratio);
    if (o.seeds > 1)
        report_seeds(rows);
    if (o.csv.empty())
        return;
    // Appends, so repeated runs (this VM's speed drifts) collect in one table; the header goes first only.
    const bool fresh = !std::ifstream(o.csv).good();
    std::ofstream f(o.csv, std::ios::app);
    if (fresh) {
#ifdef SM_BENCH_BULLET
        f << "# peer: " << bullet_name() << ", Bullet box and ellipsoid margin " << BulletOptions{}.margin
          << " m\n";
#endif
        f << "date,machine,engine,shape,n,substeps,ms_per_step,cpu_ms_per_step,end_overlap_m,ratio_sm_over_"
             "peer\n";
    }
    const std::string date = today(), machine = machine_name();
    for (const Row& r : rows) {
        char line[256];
        std::snprintf(line, sizeof line, "%s,\"%s\",%s,%s,%d,%d,%.4f,%.4f,%.6f,%s\n", date.c_str(),
                      machine.c_str(), r.engine.c_str(), kind_name(r.kind).data(), o.n, r.substeps, r.ms,
                      r.cpu_ms, r.overlap, r.ratio > 0.0 ? std::to_string(r.ratio).c_str() : "");
        f << line;
    }
}

} // namespace

int main(int argc, char** argv)
{
    Options o;
    std::vector<std::string> sets;
    std::string solver = "soft"; // the engine's default (ContactDef::solver)
    CLI::App app{"Pile of N bodies in an open box: supermodal against Bullet, one thread"};
    app.add_option("n", o.n, "Bodies [-]")->check(CLI::PositiveNumber);
    app.add_option("substeps", o.substeps, "supermodal substeps per step [-]")->check(CLI::Range(1, 1000));
    app.add_option("--steps", o.steps, "Steps of the whole run [-]")->check(CLI::PositiveNumber);
    app.add_option("--timed", o.timed_steps, "Steps measured at the end [-]")->check(CLI::PositiveNumber);
    app.add_option("--seeds", o.seeds, "Piles from this many jitters, each run in turn [-]")
        ->check(CLI::Range(1, 1000));
    app.add_option("--shape", o.shapes, "Shapes: box, sphere, ellipsoid")
        ->check(CLI::IsMember({"box", "sphere", "ellipsoid"}))
        ->delimiter(',');
    app.add_option("--engine", o.engine, "all, supermodal or bullet")
        ->check(CLI::IsMember({"all", "supermodal", "bullet"}));
    app.add_option("--csv", o.csv, "Append the table to this CSV file (header when new)");
    app.add_option("--set", sets, "supermodal ContactDef field, key=value (repeatable)");
    app.add_option("--solver", solver, "supermodal contact solver: soft (the default) or penalty");
    CLI11_PARSE(app, argc, argv);
    o.timed_steps = std::min(o.timed_steps, o.steps);
    for (const std::string& kv : sets)
        if (const std::string error = apply_contact_setting(o.supermodal.contact, kv); !error.empty())
            return std::fprintf(stderr, "peer_pile: --set %s\n", error.c_str()), 2;
    if (const std::string error = apply_contact_solver(o.supermodal.contact, solver); !error.empty())
        return std::fprintf(stderr, "peer_pile: --solver: %s\n", error.c_str()), 2;
    std::vector<Row> rows;
    for (int seed = 0; seed < o.seeds; ++seed)
        for (const std::string& name : o.shapes) {
            const Kind kind = name == "box" ? Kind::Box : name == "sphere" ? Kind::Sphere : Kind::Ellipsoid;
            for (const Row& r : run_shape(kind, seed, o))
                rows.push_back(r);
            std::fprintf(stderr, "peer_pile: seed %d/%d %s done\n", seed + 1, o.seeds, name.c_str());
        }
    std::printf("pile, N = %d, dt = 1/240 s, steps %d-%d, one thread, %s\n", o.n, o.steps - o.timed_steps + 1,
                o.steps, machine_name().c_str());
    report(rows, o);
    return 0;
}
