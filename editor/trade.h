// SPDX-License-Identifier: MIT
// The live speed↔accuracy plot's data: a `supermodal bench` sweep of the scene's dt and substeps, run
// as a child process in the background so the editor keeps drawing, and which of its configurations
// the scene's current settings are.
#pragma once

#include "supermodal/result.h"

#include <atomic>
#include <mutex>
#include <string>
#include <sys/types.h>
#include <thread>
#include <vector>

namespace supermodal::editor
{

/// One configuration of the sweep.
struct TradePoint {
    std::string knob;          ///< "dt" or "substeps".
    std::string value;         ///< As bench names it: "x0.5" (dt factor) or "4" (substeps).
    double dt = 0.0;           ///< Step of this run [s].
    int substeps = 1;          ///< Substeps per step [-].
    double ms_per_sim_s = 0.0; ///< CPU time per simulated second [ms/s].
    double ms_per_step = 0.0;  ///< CPU time per step [ms].
    double error_m = 0.0;      ///< Trajectory RMS against the bench's converged reference [m].
};

/// What a finished sweep found, for the plot and for scripts.
struct TradeResult {
    std::vector<TradePoint> points; ///< Runs that finished ("ok"), in bench's order.
    std::string error;              ///< Why the sweep failed, or empty.
};

/// A background sweep. Not copyable; stopping it (or destroying it) ends the child process.
class TradeSweep
{
  public:
    TradeSweep() = default;
    ~TradeSweep();
    TradeSweep(const TradeSweep&) = delete;
    TradeSweep& operator=(const TradeSweep&) = delete;

    /// Starts `cli bench scene_path --knobs dt,substeps --repeats 1 --seconds seconds --json` for a scene
    /// whose own settings are `dt` [s] and `substeps`; stops a sweep still running first. Fails when the
    /// process cannot be started.
    Status start(const std::string& cli, const std::string& scene_path, double seconds, double dt,
                 int substeps);
    /// Ends a running sweep (its child is killed) and waits for its thread.
    void stop();
    /// Waits until the sweep has finished.
    void wait();
    [[nodiscard]] bool running() const { return m_running.load(); }
    /// Whether a sweep has finished since the last start() (successfully or not).
    [[nodiscard]] bool finished() const { return m_finished.load(); }
    /// A copy of the finished sweep's result (empty while running).
    [[nodiscard]] TradeResult result() const;

  private:
    void run(int fd, double dt, int substeps);

    std::thread m_thread;
    std::atomic<bool> m_running{false};
    std::atomic<bool> m_finished{false};
    pid_t m_child = -1;
    mutable std::mutex m_mutex;
    TradeResult m_result;
};

/// Parses bench's --json output (rows of knob, value, status, cpu costs and trajectory_rms_m) for a scene
/// stepped at `dt` [s] with `substeps`: each "ok" row of the dt and substeps knobs, with its own dt and
/// substep count. Fails on text that is not that JSON.
[[nodiscard]] Result<std::vector<TradePoint>> parse_trade(const std::string& json, double dt, int substeps);

/// The point whose dt and substeps are these (dt to 1e-9 relative), or −1.
[[nodiscard]] int find_trade_point(const std::vector<TradePoint>& points, double dt, int substeps);

/// Where the `supermodal` command-line program is: beside the running program (an installed bin/ or
/// the build tree's tools/ next to editor/), else the name alone for PATH.
[[nodiscard]] std::string default_bench_cli();

} // namespace supermodal::editor
