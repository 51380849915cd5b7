// SPDX-License-Identifier: MIT
#include "trade.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace supermodal::editor
{
namespace
{

// A row's dt and substeps: a dt row scales the scene's dt by its factor ("x0.5"), a substeps row sets
// the count at the scene's dt. False for any other row.
bool row_setting(const std::string& knob, const std::string& value, double dt, int substeps, TradePoint& p)
{
    p.dt = dt;
    p.substeps = substeps;
    if (knob == "dt" && value.size() > 1 && value[0] == 'x') {
        char* end = nullptr;
        const double factor = std::strtod(value.c_str() + 1, &end);
        p.dt = dt * factor;
        return end != nullptr && *end == '\0' && factor > 0.0;
    }
    if (knob == "substeps") {
        char* end = nullptr;
        const long n = std::strtol(value.c_str(), &end, 10);
        p.substeps = static_cast<int>(n);
        return end != nullptr && *end == '\0' && n > 0 && n < INT_MAX;
    }
    return false;
}

std::string read_all(int fd)
{
    std::string out;
    char buf[4096];
    for (;;) {
        const ssize_t n = read(fd, buf, sizeof buf);
        if (n > 0)
            out.append(buf, static_cast<size_t>(n));
        else if (n == 0 || errno != EINTR)
            break;
    }
    return out;
}

} // namespace

Result<std::vector<TradePoint>> parse_trade(const std::string& text, double dt, int substeps)
{
    const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("rows") || !doc["rows"].is_array())
        return Error{"", "", "bench printed no JSON summary with rows"};
    std::vector<TradePoint> points;
    for (const nlohmann::json& row : doc["rows"]) {
        if (!row.is_object() || row.value("status", "") != "ok")
            continue;
        TradePoint p;
        p.knob = row.value("knob", "");
        p.value = row.value("value", "");
        if (!row_setting(p.knob, p.value, dt, substeps, p))
            continue;
        const auto number = [&](const char* key) {
            return row.contains(key) && row[key].is_number() ? row[key].get<double>() : NAN;
        };
        p.ms_per_sim_s = number("cpu_ms_per_sim_s");
        p.ms_per_step = number("cpu_ms_per_step");
        p.error_m = number("trajectory_rms_m");
        if (std::isfinite(p.ms_per_sim_s) && std::isfinite(p.error_m))
            points.push_back(p);
    }
    return points;
}

int find_trade_point(const std::vector<TradePoint>& points, double dt, int substeps)
{
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i].substeps == substeps && std::abs(points[i].dt - dt) <= 1e-9 * std::abs(dt))
            return static_cast<int>(i);
    return -1;
}

std::string default_bench_cli()
{
    char self[4096];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        std::string dir(self);
        dir.erase(dir.find_last_of('/') + 1);
        for (const std::string& candidate : {dir + "supermodal", dir + "../tools/supermodal"})
            if (access(candidate.c_str(), X_OK) == 0)
                return candidate;
    }
    return "supermodal";
}

TradeSweep::~TradeSweep()
{
    stop();
}

Status TradeSweep::start(const std::string& cli, const std::string& scene_path, double seconds, double dt,
                         int substeps)
{
    stop();
    int fds[2];
    if (pipe(fds) != 0)
        return Error{"", "", std::string("cannot make a pipe: ") + std::strerror(errno)};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    const std::string secs = std::to_string(seconds);
    const char* argv[] = {cli.c_str(), "bench",     scene_path.c_str(), "--knobs", "dt,substeps", "--repeats",
                          "1",         "--seconds", secs.c_str(),       "--json",  nullptr};
    pid_t pid = -1;
    const int rc =
        posix_spawnp(&pid, cli.c_str(), &actions, nullptr, const_cast<char* const*>(argv), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fds[1]);
    if (rc != 0) {
        close(fds[0]);
        return Error{"", cli, std::string("cannot run the bench program: ") + std::strerror(rc)};
    }
    m_finished = false;
    m_running = true;
    {
        const std::lock_guard lock(m_mutex);
        m_child = pid;
        m_result = TradeResult{};
    }
    m_thread = std::thread([this, fd = fds[0], dt, substeps] { run(fd, dt, substeps); });
    return {};
}

void TradeSweep::run(int fd, double dt, int substeps)
{
    const std::string out = read_all(fd);
    close(fd);
    pid_t child = -1;
    {
        const std::lock_guard lock(m_mutex);
        child = m_child;
    }
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    TradeResult r;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        r.error = "bench ended with status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    } else if (Result<std::vector<TradePoint>> points = parse_trade(out, dt, substeps)) {
        r.points = std::move(*points);
    } else {
        r.error = points.error().message();
    }
    {
        const std::lock_guard lock(m_mutex);
        m_child = -1; // reaped: stop() must not signal a process that may now have its number
        m_result = std::move(r);
    }
    m_running = false;
    m_finished = true;
}

void TradeSweep::stop()
{
    {
        const std::lock_guard lock(m_mutex);
        // SIGKILL, not SIGTERM: the bench child keeps nothing to clean up, and stop() then joins the
        // reading thread, which must not wait on a child that could catch or block a gentler signal.
        if (m_child > 0)
            kill(m_child, SIGKILL);
    }
    wait();
}

void TradeSweep::wait()
{
    if (m_thread.joinable())
        m_thread.join();
}

TradeResult TradeSweep::result() const
{
    const std::lock_guard lock(m_mutex);
    return m_result;
}

} // namespace supermodal::editor
