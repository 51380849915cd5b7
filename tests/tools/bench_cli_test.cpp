// Tests for tools/cmd_bench.cpp: `supermodal bench` on a two-body scene, run as a separate process.
#include "support/run_command.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{

using Outcome = supermodal::test::CommandOutcome;

Outcome run_cli(const std::string& args)
{
    return supermodal::test::run_command(std::string(SM_CLI) + " " + args);
}

/// `text` as one shell word: single-quoted, each quote closed, escaped and reopened.
std::string shell_quoted(const std::string& text)
{
    std::string quoted = "'";
    for (const char c : text)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

/// Runs the CLI with `dir` as its working directory.
Outcome run_cli_in(const fs::path& dir, const std::string& args)
{
    return supermodal::test::run_command("cd " + shell_quoted(dir.string()) + " && " + SM_CLI + " " + args);
}

bool gnuplot_installed()
{
    return supermodal::test::run_command("command -v gnuplot").status == 0;
}

fs::path temp_dir(const char* name)
{
    const fs::path dir = fs::temp_directory_path() / "supermodal_bench_cli" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// A 5 cm ball resting, just touching, on a 20° incline (plane normal (sin 20°, cos 20°, 0)), 0.1 s.
/// It rolls down under friction while the penalty spring settles it into the plane. Both errors shrink
/// steadily with dt: the penalty sink g·cos θ/ω² with the default ω = 2π/(10 h) goes as h², and the
/// rolling motion's semi-implicit Euler error as h. No impact or lift-off, whose timing can make the
/// error of one dt land on either side of another's (a dropped ball's did), so the order is monotone.
const char* k_incline_scene = R"({
  "settings": { "dt": 0.002, "gravity": [0, -9.81, 0], "duration": 0.1 },
  "bodies": [
    { "name": "incline", "motion": "static",
      "shape": { "type": "plane", "normal": [0.342020143, 0.939692621, 0], "offset": 0 } },
    { "name": "ball", "shape": { "type": "superquadric", "radii": [0.05, 0.05, 0.05], "exponents": [1, 1] },
      "position": [0.017101007, 0.046984631, 0] }
  ]
})";

std::string write_scene(const fs::path& dir)
{
    const fs::path path = dir / "incline.json";
    std::ofstream(path) << k_incline_scene;
    return path.string();
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path)
{
    std::vector<std::vector<std::string>> rows;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream s(line);
        std::string cell;
        while (std::getline(s, cell, ','))
            cells.push_back(cell);
        rows.push_back(cells);
    }
    return rows;
}

} // namespace

TEST(BenchCli, SweepsTheChosenKnobsAndConvergesInDt)
{
    const fs::path dir = temp_dir("sweep");
    const std::string scene = write_scene(dir);
    const fs::path prefix = dir / "out";
    const Outcome o =
        run_cli("bench " + scene + " --repeats 1 --knobs dt,path --json --out " + prefix.string());
    ASSERT_EQ(o.status, 0) << o.output;
    const auto rows = read_csv(prefix.string() + ".csv");
    ASSERT_FALSE(rows.empty());
    const std::vector<std::string> header = rows[0];
    std::map<std::string, size_t> column;
    for (size_t i = 0; i < header.size(); ++i)
        column[header[i]] = i;
    for (const char* name : {"knob", "value", "status", "cpu_ms_per_step", "cpu_ms_per_sim_s",
                             "trajectory_rms_m", "trajectory_max_m", "max_penetration_m", "energy_drift"})
        ASSERT_TRUE(column.count(name)) << name;
    // The reference, then dt ×4, ×2, ×1, ×½, ×¼ and the three contact paths: one row each.
    ASSERT_EQ(rows.size(), 1u + 1u + 5u + 3u);
    EXPECT_EQ(rows[1][column["knob"]], "reference");
    std::map<std::string, double> dt_error;
    for (size_t r = 2; r < rows.size(); ++r) {
        ASSERT_EQ(rows[r].size(), header.size());
        EXPECT_EQ(rows[r][column["status"]], "ok");
        if (rows[r][column["knob"]] == "dt")
            dt_error[rows[r][column["value"]]] = std::stod(rows[r][column["trajectory_rms_m"]]);
    }
    ASSERT_EQ(dt_error.size(), 5u);
    // Error ∝ (h − h_ref) with h_ref = h/8 for the O(h) part predicts ratios of 0.14 (¼ vs 1) and 0.23
    // (1 vs 4); the O(h²) sink shrinks faster still. Half is a loose bound that still needs convergence.
    EXPECT_LT(dt_error["x0.25"], 0.5 * dt_error["x1"]);
    EXPECT_LT(dt_error["x1"], 0.5 * dt_error["x4"]);
    EXPECT_GT(dt_error["x0.25"], 0.0); // dt/4 is not the reference (dt/8): a real difference
    EXPECT_TRUE(fs::exists(prefix.string() + ".md"));

    const nlohmann::json j = nlohmann::json::parse(o.output);
    ASSERT_EQ(j["rows"].size(), rows.size() - 1);
    int front = 0;
    for (const auto& row : j["rows"])
        front += row["pareto"].get<bool>() ? 1 : 0;
    EXPECT_GE(front, 1); // some configuration is always undominated
}

TEST(BenchCli, BadInputExitsTwoAndWritesNothing)
{
    const fs::path dir = temp_dir("bad");
    const std::string scene = write_scene(dir);
    const fs::path prefix = dir / "out";
    const Outcome missing =
        run_cli("bench " + (dir / "no_such_scene.json").string() + " --out " + prefix.string() + " 2>&1");
    EXPECT_EQ(missing.status, 2) << missing.output;
    EXPECT_NE(missing.output.find("no_such_scene.json"), std::string::npos) << missing.output;
    const Outcome knob = run_cli("bench " + scene + " --knobs dt,warp --out " + prefix.string() + " 2>&1");
    EXPECT_EQ(knob.status, 2) << knob.output;
    EXPECT_NE(knob.output.find("unknown knob 'warp'"), std::string::npos) << knob.output;
    // The ball scene has no modal body: a sweep of only the modal knobs has nothing to run.
    const Outcome modal = run_cli("bench " + scene + " --knobs modes --out " + prefix.string() + " 2>&1");
    EXPECT_EQ(modal.status, 2) << modal.output;
    // --set as in `run`: the scene has two bodies, so /bodies/2 is not there to change.
    const Outcome set =
        run_cli("bench " + scene + " --set /bodies/2/position/0=1 --out " + prefix.string() + " 2>&1");
    EXPECT_EQ(set.status, 2) << set.output;
    EXPECT_NE(set.output.find("/bodies/2/position/0"), std::string::npos) << set.output;
    for (const char* ext : {".csv", ".md", ".png"})
        EXPECT_FALSE(fs::exists(prefix.string() + ext)) << ext;
    // Only the scene we wrote is left: no temporary files either.
    int files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
        ++files;
    EXPECT_EQ(files, 1);
}

class ModesSweep : public testing::TestWithParam<const char*>
{
};

TEST_P(ModesSweep, EndsWithTheFullLattice)
{
    // A soft board (4×1×1 20-node cells: 168 dofs) dropped flat on the ground from 1 mm. The modes knob runs
    // r = 1, 2, 4, 8, 16 and "full" (every one of the 162 elastic modes): the full row builds and runs,
    // and its lowest frequencies are the reference's own (same lattice, dense vs the reference's
    // solve: equal to the eigensolvers' accuracy, bound 1e-9). The reference keeps every mode too, so with
    // the contact frequency held across dt (--fixed-contact; otherwise the reference's 8x stiffer contact
    // dominates the comparison) the full row is closer to it than the one-mode row (measured: penalty
    // 3.0 vs 3.4 mm RMS, soft 0.068 vs 0.089 mm; before the reference kept every mode it held 8, and the
    // full row was the farthest).
    const fs::path dir = temp_dir((std::string("full_") + GetParam()).c_str());
    const fs::path path = dir / "board.json";
    std::ofstream(path) << R"({
  "settings": { "dt": 0.001, "duration": 0.05, "contact": { "solver": ")"
                        << GetParam() << R"(" } },
  "materials": { "foam": { "density": 300, "young": 2e6 } },
  "bodies": [
    { "name": "ground", "motion": "static", "shape": { "type": "plane", "normal": [0, 1, 0], "offset": 0 } },
    { "name": "board", "material": "foam", "position": [0, 0.031, 0],
      "shape": { "type": "superquadric", "radii": [0.3, 0.03, 0.08], "exponents": [0.3, 0.3] },
      "dynamics": { "type": "modal", "modes": 4, "lattice": [4, 1, 1] } }
  ]
})";
    const fs::path prefix = dir / "out";
    const Outcome o = run_cli("bench " + path.string() + " --repeats 1 --knobs modes --fixed-contact --out " +
                              prefix.string());
    ASSERT_EQ(o.status, 0) << o.output;
    const auto rows = read_csv(prefix.string() + ".csv");
    ASSERT_GE(rows.size(), 2u);
    std::map<std::string, size_t> column;
    for (size_t i = 0; i < rows[0].size(); ++i)
        column[rows[0][i]] = i;
    std::vector<std::string> values;
    for (size_t r = 2; r < rows.size(); ++r) {
        values.push_back(rows[r][column["value"]]);
        EXPECT_EQ(rows[r][column["status"]], "ok") << rows[r][column["value"]];
    }
    ASSERT_EQ(values, (std::vector<std::string>{"1", "2", "4", "8", "16", "full"}));
    EXPECT_LT(std::stod(rows.back()[column["frequency_error"]]), 1e-9);
    const size_t rms = column["trajectory_rms_m"];
    EXPECT_LT(std::stod(rows.back()[rms]), std::stod(rows[2][rms])); // full vs r = 1
}

INSTANTIATE_TEST_SUITE_P(Solvers, ModesSweep, testing::Values("soft", "penalty"));

TEST(BenchCli, OutPrefixIsOnlyEverAFileName)
{
    // --out reaches gnuplot (its script, its command line) as a file name and nothing else: a prefix in a
    // folder whose name closes a single-quoted shell word, runs $(...) and opens a new one (the plot once
    // ran `touch injected` there), and a relative prefix starting with '<' (gnuplot's "read from a
    // command"), each write their files under exactly that name and run nothing.
    const fs::path dir = temp_dir("it's $(touch injected) 'q");
    const std::string scene = write_scene(dir);
    const std::string absolute = (dir / "out").string();
    const std::string relative = "<touch injected;'x";
    for (const std::string& prefix : {absolute, relative}) {
        const Outcome o =
            run_cli_in(dir, "bench " + shell_quoted(scene) + " --repeats 1 --knobs dt --seconds 0.02 --out " +
                                shell_quoted(prefix) + " 2>&1");
        ASSERT_EQ(o.status, 0) << o.output;
        const fs::path stem = fs::path(prefix).is_absolute() ? fs::path(prefix) : dir / prefix;
        EXPECT_TRUE(fs::exists(stem.string() + ".csv")) << prefix;
        if (gnuplot_installed()) {
            EXPECT_TRUE(fs::exists(stem.string() + ".png")) << prefix << "\n" << o.output;
        }
    }
    EXPECT_FALSE(fs::exists(dir / "injected"));
    EXPECT_FALSE(fs::exists(fs::current_path() / "injected"));
    // The scene and two prefixes' .csv, .md (and .png): no temporary file is left.
    int files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
        ++files;
    EXPECT_EQ(files, gnuplot_installed() ? 7 : 5);
}
