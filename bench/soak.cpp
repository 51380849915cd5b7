// SPDX-License-Identifier: MIT
// Soak run (docs/reliability.md): steps a scene for a long simulated time and prints one CSV row per report
// interval: simulated time, wall time, step time over the interval (mean and max wall, mean CPU),
// resident memory, and whether every body is still finite. Not a test: scripts/soak.sh runs it and
// plots the rows; growth in memory or step time over the hour is what it looks for.
//
// Usage: soak SCENE SIMULATED_SECONDS REPORT_EVERY_SECONDS
#include "supermodal/body.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>

namespace sm = supermodal;

namespace
{

// Resident set size [KiB] from /proc/self/status (VmRSS), or -1 where /proc is missing.
long rss_kib()
{
    std::ifstream in("/proc/self/status");
    std::string key;
    while (in >> key) {
        if (key == "VmRSS:") {
            long kib = -1;
            in >> kib;
            return kib;
        }
        in.ignore(1 << 12, '\n');
    }
    return -1;
}

double cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

bool all_finite(const sm::World& w)
{
    for (const sm::Entity e : sm::world_bodies(w))
        if (!sm::is_finite(sm::body_position(w, e)) || !sm::is_finite(sm::body_linear_velocity(w, e)))
            return false;
    return true;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 4) {
        std::fprintf(stderr, "usage: soak SCENE SIMULATED_SECONDS REPORT_EVERY_SECONDS\n");
        return 2;
    }
    const double seconds = std::atof(argv[2]), every = std::atof(argv[3]);
    if (!(seconds > 0.0) || !(every > 0.0)) {
        std::fprintf(stderr, "soak: expected SIMULATED_SECONDS > 0 and REPORT_EVERY_SECONDS > 0\n");
        return 2;
    }
    sm::Result<sm::Scene> scene = sm::load_scene(argv[1]);
    if (!scene) {
        std::fprintf(stderr, "soak: %s\n", scene.error().message().c_str());
        return 2;
    }
    sm::Result<sm::World> built = sm::build_world(*scene);
    if (!built) {
        std::fprintf(stderr, "soak: %s\n", built.error().message().c_str());
        return 2;
    }
    sm::World& w = *built;
    const double dt = w.settings().dt;
    const auto steps_per_report = static_cast<uint64_t>(std::max(1.0, std::round(every / dt)));
    const auto total_steps = static_cast<uint64_t>(std::round(seconds / dt));
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    std::printf("sim_s,wall_s,steps,mean_ms,max_ms,cpu_ms,rss_kib,finite,non_finite_bodies\n");
    std::fflush(stdout);
    uint64_t done = 0;
    while (done < total_steps) {
        const uint64_t n = std::min(steps_per_report, total_steps - done);
        double max_ms = 0.0;
        const auto t0 = Clock::now();
        const double c0 = cpu_seconds();
        for (uint64_t i = 0; i < n; ++i) {
            w.step();
            max_ms = std::max(max_ms, w.profile().total_ms);
        }
        const double wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        const double cpu_ms = 1e3 * (cpu_seconds() - c0);
        done += n;
        std::printf("%.3f,%.1f,%llu,%.4f,%.3f,%.4f,%ld,%d,%llu\n", w.time(),
                    std::chrono::duration<double>(Clock::now() - start).count(),
                    static_cast<unsigned long long>(done), wall_ms / static_cast<double>(n), max_ms,
                    cpu_ms / static_cast<double>(n), rss_kib(), all_finite(w) ? 1 : 0,
                    static_cast<unsigned long long>(w.warnings().non_finite_bodies));
        std::fflush(stdout);
    }
    std::fprintf(stderr, "soak: %llu steps, state hash %016llx\n", static_cast<unsigned long long>(done),
                 static_cast<unsigned long long>(w.state_hash()));
    return 0;
}
