// Tests for tools/cmd_export.cpp: `supermodal export` run as a separate process on the ball on the
// board, then the GLB read back by the engine's own import (assimp) and the report checked.
#include "supermodal/geometry.h"
#include "supermodal/mesh_io.h"
#include "support/run_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

using Outcome = supermodal::test::CommandOutcome;

/// Runs the CLI; stdout only (stderr goes to the test log), so JSON output parses as is.
Outcome run_cli(const std::string& args)
{
    return supermodal::test::run_command(std::string(SM_CLI) + " " + args);
}

// One folder per test: ctest runs the tests of this file in parallel processes.
fs::path fresh_dir()
{
    const fs::path dir = fs::temp_directory_path() / "supermodal_export_cli" /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

const std::string k_scene = std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json";

TEST(ExportCli, WritesAGlbAndAnObjSequenceAndReportsThem)
{
    const fs::path dir = fresh_dir();
    const fs::path glb = dir / "anim.glb", objs = dir / "objs";
    const Outcome o = run_cli("export " + k_scene + " --seconds 0.2 --fps 30 --out " + glb.string() +
                              " --obj " + objs.string() + " --json");
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json r = nlohmann::json::parse(o.output);
    EXPECT_EQ(r["bodies"], 4);                               // the floor plane is left out
    EXPECT_EQ(r["frames"], 7);                               // 0, 1/30, ..., 6/30 s
    EXPECT_EQ(r["morph_targets"], 8);                        // the board's eight modes
    EXPECT_NEAR(r["last_time"].get<double>(), 0.2, 0.00025); // the step nearest 0.2 s (dt = 0.5 ms)
    EXPECT_EQ(r["glb_bytes"].get<size_t>(), fs::file_size(glb));
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(objs)) {
        (void)e;
        ++files;
    }
    EXPECT_EQ(files, 7u);
    // The engine's importer merges the four bodies' meshes at their first poses.
    const sm::Result<sm::ImportedMesh> m = sm::import_mesh(glb.string());
    ASSERT_TRUE(m) << m.error().message();
    EXPECT_EQ(m->source_meshes, 4);
    EXPECT_EQ(m->format, "glb");
}

TEST(ExportCli, ASceneBodysRenderMeshReplacesItsTessellation)
{
    const fs::path dir = fresh_dir();
    // A tetrahedron inside the ball (radius 25 mm) as the ball's render mesh.
    std::ofstream(dir / "tet.obj") << "v 0.01 0 0\nv 0 0.01 0\nv 0 0 0.01\nv 0 0 0\n"
                                      "f 1 2 3\nf 1 4 2\nf 2 4 3\nf 3 4 1\n";
    std::ifstream in(k_scene);
    nlohmann::json scene = nlohmann::json::parse(in);
    ASSERT_EQ(scene["bodies"][4]["name"], "ball");
    scene["bodies"][4]["mesh"] = "tet.obj";
    std::ofstream(dir / "scene.json") << scene.dump();
    const Outcome plain =
        run_cli("export " + k_scene + " --seconds 0.05 --out " + (dir / "a.glb").string() + " --json");
    const Outcome meshed = run_cli("export " + (dir / "scene.json").string() + " --seconds 0.05 --out " +
                                   (dir / "b.glb").string() + " --json");
    ASSERT_EQ(plain.status, 0);
    ASSERT_EQ(meshed.status, 0);
    // The 32-segment tessellation of the ball (radius 25 mm, ε = 1) that the tetrahedron replaces.
    sm::ShapeDef ball = sm::default_shape_def();
    ball.radii = {0.025, 0.025, 0.025};
    ball.epsilon1 = ball.epsilon2 = 1.0;
    const size_t ball_vertices = sm::tessellate(ball, 32).positions.size();
    EXPECT_EQ(nlohmann::json::parse(meshed.output)["vertices"].get<size_t>() + ball_vertices - 4,
              nlohmann::json::parse(plain.output)["vertices"].get<size_t>());
    scene["bodies"][4]["mesh"] = "missing.obj";
    std::ofstream(dir / "bad.json") << scene.dump();
    EXPECT_EQ(run_cli("export " + (dir / "bad.json").string() + " --out " + (dir / "c.glb").string()).status,
              2);
    EXPECT_FALSE(fs::exists(dir / "c.glb"));
}

TEST(ExportCli, BadInputExitsWithTwoAndWritesNothing)
{
    const fs::path dir = fresh_dir();
    const std::string out = (dir / "a.glb").string();
    EXPECT_EQ(run_cli("export " + (dir / "missing.json").string() + " --out " + out).status, 2);
    EXPECT_EQ(run_cli("export " + k_scene + " --out " + (dir / "no" / "a.glb").string()).status, 2);
    EXPECT_EQ(run_cli("export " + k_scene).status, 2); // neither --out nor --obj
    EXPECT_EQ(run_cli("export " + k_scene + " --fps 5000 --seconds 0.01 --out " + out).status, 2); // > 1/dt
    EXPECT_EQ(run_cli("export " + k_scene + " --fps -1 --out " + out).status, 2);
    EXPECT_EQ(run_cli("export " + k_scene + " --seconds 0.01 --tessellation 2 --out " + out).status, 2);
    std::ofstream(dir / "file") << "x";
    EXPECT_EQ(run_cli("export " + k_scene + " --seconds 0.01 --obj " + (dir / "file").string()).status, 2);
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        (void)e;
        ++entries;
    }
    EXPECT_EQ(entries, 1u); // only "file": no GLB, no temporary files
}

} // namespace

TEST(ExportCli, AFileNameThatIsNotUtf8IsWrittenAndReportedWithoutAnInternalError)
{
    // Found by the command-line fuzzer (tests/fuzz/cli_fuzz.cpp): "--out a.glb\xe3..." made the JSON
    // report throw nlohmann's type_error 316 and `export` exit 1. A file name is any bytes.
    const fs::path dir = fresh_dir();
    const std::string name = "anim\xe3.glb";
    const Outcome o =
        run_cli("export " + k_scene + " --seconds 0.01 --out '" + (dir / name).string() + "' --json");
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json r = nlohmann::json::parse(o.output); // valid JSON: the byte became U+FFFD
    EXPECT_TRUE(fs::exists(dir / name));
    EXPECT_EQ(r["glb_bytes"].get<size_t>(), fs::file_size(dir / name));
}
