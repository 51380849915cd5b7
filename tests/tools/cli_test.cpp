// Tests for tools/ (the supermodal command line), run as a separate process like a user would.
#include "support/run_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

namespace
{

using Outcome = supermodal::test::CommandOutcome;

Outcome run_cli(const std::string& args)
{
    return supermodal::test::run_command(std::string(SM_CLI) + " " + args + " 2>&1");
}

std::string scene(const char* name)
{
    return std::string(SM_SCENES) + "/" + name;
}

std::filesystem::path temp_dir(const char* name)
{
    auto dir = std::filesystem::temp_directory_path() / ("supermodal_cli_" + std::string(name));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

nlohmann::json read_json(const std::filesystem::path& p)
{
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

} // namespace

TEST(Cli, ProjectileSceneMatchesTheDiscreteClosedForm)
{
    // 1000 steps of 1 ms from (0,10,0) at (3,4,−1): semi-implicit Euler gives
    // y = 10 + 4 t − g h² n(n+1)/2 exactly; round-off of 1000 additions stays below 1e-10 m.
    const auto dir = temp_dir("projectile");
    const Outcome o = run_cli("run " + scene("projectile.json") + " --json " + (dir / "s.json").string());
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json s = read_json(dir / "s.json");
    EXPECT_EQ(s["steps"], 1000);
    const auto& p = s["bodies"][0]["position"];
    const double h = 0.001, n = 1000;
    EXPECT_NEAR(p[0].get<double>(), 3.0, 1e-10);
    EXPECT_NEAR(p[1].get<double>(), 10.0 + 4.0 - 9.81 * h * h * n * (n + 1) / 2, 1e-10);
    EXPECT_NEAR(p[2].get<double>(), -1.0, 1e-10);
    // Total energy drift of semi-implicit Euler in a uniform field: m g (h/2)·Δv_y-sized, O(h).
    EXPECT_TRUE(s.contains("state_hash"));
    EXPECT_GT(s["ms_per_step"]["median"].get<double>(), 0.0);
}

TEST(Cli, ASummaryToADeviceLeavesTheDeviceInPlace)
{
    // The summary is written through a temporary file renamed into place, except to a device or pipe:
    // renaming over /dev/null once made it a regular file for every later user of the machine.
    const Outcome o = run_cli("run " + scene("projectile.json") + " --steps 3 --json /dev/null");
    ASSERT_EQ(o.status, 0) << o.output;
    EXPECT_TRUE(std::filesystem::is_character_file("/dev/null"));
}

TEST(Cli, FreeSpinConservesEnergyOverTenSeconds)
{
    // Implicit midpoint keeps rotational kinetic energy to ~1e-12 relative; docs/dynamics.md states 1e-6.
    const auto dir = temp_dir("spin");
    const Outcome o = run_cli("run " + scene("free_spin.json") + " --json " + (dir / "s.json").string());
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json s = read_json(dir / "s.json");
    const double e0 = s["energy"]["initial_kinetic"].get<double>();
    EXPECT_NEAR(s["energy"]["kinetic"].get<double>(), e0, 1e-6 * e0);
    EXPECT_NEAR(s["time"].get<double>(), 10.0, 1e-9);
}

TEST(Cli, BadFieldExitsTwoNamingThePointerAndWritesNothing)
{
    const auto dir = temp_dir("bad");
    const Outcome o = run_cli("run " + scene("bad_field.json") + " --json " + (dir / "s.json").string() +
                              " --csv " + (dir / "t.csv").string());
    EXPECT_EQ(o.status, 2) << o.output;
    EXPECT_NE(o.output.find("/bodies/1/shape/exponents/0"), std::string::npos) << o.output;
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(Cli, SetChangesTheSceneBeforeItIsRead)
{
    // projectile.json with dt 0.002 and launch velocity (3, 8, -1): 500 steps of the same closed form
    // y = 10 + 8 t − g h² n(n+1)/2 as ProjectileSceneMatchesTheDiscreteClosedForm, to the same 1e-10 m.
    // --set before the scene: each --set takes one argument, never the scene's.
    const auto dir = temp_dir("set");
    const Outcome o =
        run_cli("run --set /settings/dt=0.002 --set '/bodies/0/velocity=[3, 8, -1]' " +
                scene("projectile.json") + " --set /bodies/0/name=shot --json " + (dir / "s.json").string());
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json s = read_json(dir / "s.json");
    EXPECT_EQ(s["steps"], 500);
    EXPECT_EQ(s["dt"], 0.002);
    EXPECT_EQ(s["bodies"][0]["name"], "shot"); // not JSON, so taken as a string
    const auto& p = s["bodies"][0]["position"];
    const double h = 0.002, n = 500;
    EXPECT_NEAR(p[0].get<double>(), 3.0, 1e-10);
    EXPECT_NEAR(p[1].get<double>(), 10.0 + 8.0 - 9.81 * h * h * n * (n + 1) / 2, 1e-10);
}

TEST(Cli, SetBadPointerExitsTwoNamingItAndWritesNothing)
{
    const auto dir = temp_dir("set_pointer");
    const std::string outputs = " --json " + (dir / "s.json").string() + " --csv " + (dir / "t.csv").string();
    // projectile.json has one body: /bodies/1 is not there.
    const Outcome missing =
        run_cli("run " + scene("projectile.json") + " --set /bodies/1/position/0=1" + outputs);
    EXPECT_EQ(missing.status, 2) << missing.output;
    EXPECT_NE(missing.output.find("/bodies/1/position/0"), std::string::npos) << missing.output;
    EXPECT_NE(missing.output.find("has 1 element"), std::string::npos) << missing.output;
    const Outcome unknown = run_cli("run " + scene("projectile.json") + " --set /settings/dtt=0.1" + outputs);
    EXPECT_EQ(unknown.status, 2) << unknown.output;
    EXPECT_NE(unknown.output.find("/settings/dtt"), std::string::npos) << unknown.output;
    const Outcome relative = run_cli("run " + scene("projectile.json") + " --set settings/dt=0.1" + outputs);
    EXPECT_EQ(relative.status, 2) << relative.output;
    EXPECT_NE(relative.output.find("settings/dt"), std::string::npos) << relative.output;
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(Cli, SetBadValueExitsTwoNamingThePointerAndWritesNothing)
{
    const auto dir = temp_dir("set_value");
    const std::string outputs = " --json " + (dir / "s.json").string() + " --csv " + (dir / "t.csv").string();
    const Outcome word = run_cli("run " + scene("projectile.json") + " --set /settings/dt=fast" + outputs);
    EXPECT_EQ(word.status, 2) << word.output;
    EXPECT_NE(word.output.find("/settings/dt"), std::string::npos) << word.output;
    const Outcome negative = run_cli("run " + scene("projectile.json") + " --set /settings/dt=-1" + outputs);
    EXPECT_EQ(negative.status, 2) << negative.output;
    EXPECT_NE(negative.output.find("/settings/dt"), std::string::npos) << negative.output;
    const Outcome no_value = run_cli("run " + scene("projectile.json") + " --set /settings/dt" + outputs);
    EXPECT_EQ(no_value.status, 2) << no_value.output;
    EXPECT_NE(no_value.output.find("--set /settings/dt"), std::string::npos) << no_value.output;
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(Cli, TwoRunsPrintTheSameHash)
{
    const Outcome a = run_cli("run " + scene("free_spin.json") + " --steps 500");
    const Outcome b = run_cli("run " + scene("free_spin.json") + " --steps 500");
    ASSERT_EQ(a.status, 0) << a.output;
    const auto ha = nlohmann::json::parse(a.output)["state_hash"];
    EXPECT_EQ(ha, nlohmann::json::parse(b.output)["state_hash"]);
    EXPECT_EQ(ha.get<std::string>().size(), 18u);
}

TEST(Cli, CsvTraceHasOneRowPerBodyPerTracedStep)
{
    const auto dir = temp_dir("csv");
    const Outcome o = run_cli("run " + scene("projectile.json") + " --steps 100 --csv-every 10 --csv " +
                              (dir / "t.csv").string() + " --json " + (dir / "s.json").string());
    ASSERT_EQ(o.status, 0) << o.output;
    std::ifstream in(dir / "t.csv");
    std::string line;
    int rows = 0;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("step,time,body,px", 0), 0u);
    while (std::getline(in, line))
        ++rows;
    EXPECT_EQ(rows, 11); // step 0 and every 10th step to 100
}

TEST(Cli, InspectReportsMassProperties)
{
    const Outcome o = run_cli("inspect " + scene("free_spin.json") + " --json");
    ASSERT_EQ(o.status, 0) << o.output;
    const auto j = nlohmann::json::parse(o.output);
    const auto& b = j["bodies"][0];
    const double m = 100.0 * 4.0 / 3.0 * M_PI * 6.0;
    EXPECT_NEAR(b["mass"].get<double>(), m, 1e-9 * m);
    EXPECT_NEAR(b["inertia_diagonal"][1].get<double>(), m * 10.0 / 5.0, 1e-9 * m);
}

TEST(Cli, ModesListsTheBoardsFrequencies)
{
    const Outcome o = run_cli("modes " + scene("modal_board.json") + " --body board --count 4 --json");
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json j = nlohmann::json::parse(o.output);
    ASSERT_EQ(j["frequencies_hz"].size(), 4u);
    ASSERT_EQ(j["kinds"].size(), 4u);
    // The first mode is flatwise bending: within 3% of Euler–Bernoulli's 193.1 Hz (docs/modal.md).
    EXPECT_NEAR(j["frequencies_hz"][0].get<double>(), 193.12, 0.03 * 193.12);
    EXPECT_EQ(j["kinds"][0], "bend");
    for (size_t k = 1; k < 4; ++k)
        EXPECT_GE(j["frequencies_hz"][k].get<double>(), j["frequencies_hz"][k - 1].get<double>());
    // Rayleigh–Ritz on K and M leaves residuals at round-off level.
    for (const auto& r : j["residuals"])
        EXPECT_LT(r.get<double>(), 1e-8);
    EXPECT_EQ(j["lattice"]["cells"], nlohmann::json::array({8, 1, 1}));
    EXPECT_GT(j["build_seconds"].get<double>(), 0.0);

    const Outcome rigid = run_cli("modes " + scene("modal_board.json") + " --body ball");
    EXPECT_EQ(rigid.status, 2);
    EXPECT_NE(rigid.output.find("is rigid"), std::string::npos) << rigid.output;
    EXPECT_EQ(run_cli("modes " + scene("modal_board.json") + " --body nobody").status, 2);
}

TEST(Cli, UsageErrorsExitTwo)
{
    EXPECT_EQ(run_cli("run").status, 2);
    EXPECT_EQ(run_cli("frobnicate x").status, 2);
    EXPECT_EQ(run_cli("run " + scene("projectile.json") + " --steps 5 --seconds 1").status, 2);
    EXPECT_EQ(run_cli("run /nonexistent/scene.json").status, 2);
    EXPECT_EQ(run_cli("run " + scene("projectile.json") + " --json /nonexistent/dir/out.json").status, 2);
    EXPECT_EQ(run_cli("run " + scene("projectile.json") + " --seconds -1").status, 2);
    EXPECT_EQ(run_cli("run " + scene("projectile.json") + " --seconds 0").status, 2);
    EXPECT_EQ(run_cli("run " + scene("projectile.json") + " --steps 0").status, 2);
    EXPECT_EQ(run_cli("run " + scene("projectile.json") + " --steps 1e12").status, 2);
}

TEST(Cli, HelpDocumentsTheCommands)
{
    const Outcome o = run_cli("--help");
    EXPECT_EQ(o.status, 0);
    EXPECT_NE(o.output.find("run"), std::string::npos);
    EXPECT_NE(o.output.find("inspect"), std::string::npos);
    const Outcome r = run_cli("run --help");
    EXPECT_NE(r.output.find("--csv"), std::string::npos);
}

TEST(Cli, DemoSceneRuns)
{
    const Outcome o = run_cli("run " + std::string(SM_SOURCE_DIR) + "/samples/demo.json --steps 50");
    ASSERT_EQ(o.status, 0) << o.output;
    EXPECT_EQ(nlohmann::json::parse(o.output)["body_count"], 4);
    EXPECT_EQ(nlohmann::json::parse(o.output)["sleeping"], 0); // nothing rests yet after 0.2 s
}

TEST(Cli, TheSummaryEchoesTheIslandSplit)
{
    nlohmann::json demo = read_json(std::string(SM_SOURCE_DIR) + "/samples/demo.json");
    demo["settings"]["split_islands"] = true;
    const auto dir = temp_dir("split");
    std::ofstream(dir / "split.json") << demo.dump();
    const Outcome o = run_cli("run " + (dir / "split.json").string() + " --steps 2");
    ASSERT_EQ(o.status, 0) << o.output;
    EXPECT_EQ(nlohmann::json::parse(o.output)["split_islands"], true);
}

TEST(Cli, ThreadsGiveTheSameHashAndContactsAreReported)
{
    // The demo lands three bodies on the ground within 1000 steps (2 s).
    const std::string demo = std::string(SM_SOURCE_DIR) + "/samples/demo.json --steps 1000";
    const Outcome one = run_cli("run " + demo);
    const Outcome two = run_cli("run " + demo + " --threads 2");
    ASSERT_EQ(one.status, 0) << one.output;
    ASSERT_EQ(two.status, 0) << two.output;
    const auto s1 = nlohmann::json::parse(one.output), s2 = nlohmann::json::parse(two.output);
    EXPECT_EQ(s1["state_hash"], s2["state_hash"]);
    EXPECT_EQ(s1["threads"], 1);
    EXPECT_EQ(s2["threads"], 2);
    EXPECT_EQ(s1["split_islands"], false);
    const auto& c = s1["contact"];
    EXPECT_GE(c["contacts"].get<int>(), 1);
    EXPECT_GE(c["begin_events"].get<int>(), c["end_events"].get<int>());
    EXPECT_GT(c["max_penetration"].get<double>(), 0.0);
    EXPECT_LT(c["max_penetration"].get<double>(), 0.05); // nothing sank through the ground
    EXPECT_EQ(run_cli("run " + demo + " --threads 0").status, 2);
    EXPECT_EQ(run_cli("run " + demo + " --threads 65").status, 2);
}
