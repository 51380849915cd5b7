// Tests for tools/cmd_fit.cpp: `supermodal fit` on an OBJ written here, run as a separate process.
#include "fit/fit_cases.h"
#include "supermodal/geometry.h"
#include "supermodal/scene.h"
#include "support/obj_file.h"
#include "support/run_command.h"
#include "support/shapes.h"

#include <algorithm>
#include <cmath>
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

fs::path temp_dir()
{
    const fs::path dir = fs::temp_directory_path() / "supermodal_fit_cli";
    fs::create_directories(dir);
    return dir;
}

std::string write_obj(const sm::TriangleMesh& m, const char* name)
{
    const fs::path path = temp_dir() / name;
    sm::test::write_obj_file(m, path.string());
    return path.string();
}

} // namespace

TEST(FitCli, FitsAnObjAndPrintsALoadableScene)
{
    // Radii to 1 % and ε to 0.02 as docs/pipeline.md states; OBJ goes through float storage (1e-7 relative).
    const sm::test::PosedShape truth =
        sm::test::random_pose(sm::test::superquadric({0.15, 0.3, 0.6}, 0.4, 0.9), 3);
    const std::string obj = write_obj(sm::test::posed_mesh(truth, 48), "body.obj");
    const std::string scene_path = (temp_dir() / "fitted.json").string();
    const Outcome o = run_cli("fit " + obj + " --json --scene " + scene_path);
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json j = nlohmann::json::parse(o.output);
    const auto& fit = j["fit"];
    EXPECT_LT(fit["rms_m"].get<double>(), 1e-3 * 0.3);
    EXPECT_LT(fit["rms_relative"].get<double>(), 5e-3);
    EXPECT_TRUE(fit["acceptable"].get<bool>());
    EXPECT_GT(fit["iterations"].get<int>(), 0);
    EXPECT_EQ(fit["import"]["triangles"].get<size_t>(), sm::tessellate(truth.shape, 48).indices.size() / 3);
    ASSERT_EQ(j["scene"]["bodies"].size(), 1u);
    const auto& body = j["scene"]["bodies"][0];
    EXPECT_EQ(body["name"], "body");
    EXPECT_EQ(body["shape"]["type"], "superquadric");
    std::vector<double> radii = body["shape"]["radii"].get<std::vector<double>>();
    // a1 and a2 may swap (a quarter turn about z); the polar radius stays third.
    std::sort(radii.begin(), radii.begin() + 2);
    EXPECT_NEAR(radii[0] / 0.15, 1.0, 0.01);
    EXPECT_NEAR(radii[1] / 0.3, 1.0, 0.01);
    EXPECT_NEAR(radii[2] / 0.6, 1.0, 0.01);
    EXPECT_NEAR(body["shape"]["exponents"][0].get<double>(), 0.4, 0.02);
    EXPECT_NEAR(body["shape"]["exponents"][1].get<double>(), 0.9, 0.02);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(body["position"][i].get<double>(), truth.position[i], 0.01 * 0.6);
    // The written scene loads as it is.
    const Outcome inspect = run_cli("inspect " + scene_path + " --json");
    ASSERT_EQ(inspect.status, 0) << inspect.output;
    EXPECT_EQ(nlohmann::json::parse(inspect.output)["bodies"].size(), 1u);
}

TEST(FitCli, PartsGiveOneBodyEach)
{
    sm::test::PosedShape a{sm::test::superquadric({0.2, 0.15, 0.1}, 0.1, 0.1), {-0.6, 0, 0}, {}};
    sm::test::PosedShape b{sm::test::superquadric({0.2, 0.15, 0.1}, 0.1, 0.1), {0.6, 0, 0}, {}};
    sm::TriangleMesh pair = sm::test::posed_mesh(a, 32);
    sm::test::append_mesh(pair, sm::test::posed_mesh(b, 32));
    const Outcome o = run_cli("fit " + write_obj(pair, "pair.obj") + " --parts 2 --json");
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json j = nlohmann::json::parse(o.output);
    ASSERT_EQ(j["scene"]["bodies"].size(), 2u);
    EXPECT_EQ(j["scene"]["bodies"][1]["name"], "pair_1");
    EXPECT_LT(j["fit"]["rms_relative"].get<double>(), 0.005); // the worse of two exact boxes
}

TEST(FitCli, BadInputExitsWithStatusTwo)
{
    const std::string missing = (temp_dir() / "missing.obj").string();
    EXPECT_EQ(run_cli("fit " + missing + " --json 2>/dev/null").status, 2);
    const std::string obj = write_obj(sm::tessellate(sm::test::superquadric({1, 1, 1}, 1, 1), 8), "ok.obj");
    EXPECT_EQ(run_cli("fit " + obj + " --up sideways 2>/dev/null").status, 2);
    EXPECT_EQ(run_cli("fit " + obj + " --parts 0 2>/dev/null").status, 2);
}

TEST(FitCli, AttachWritesTheMeshInTheBodyFrameAsItsRenderMesh)
{
    // The posed mesh, brought into the fitted body's frame, must lie on the fitted superquadric: every
    // vertex's radial distance to it within a few fit rms (the fit's own residual), and the scene
    // loads with that mesh as the body's render mesh (the same vertex count).
    const sm::test::PosedShape truth =
        sm::test::random_pose(sm::test::superquadric({0.2, 0.1, 0.15}, 0.5, 0.7), 5);
    const std::string obj = write_obj(sm::test::posed_mesh(truth, 40), "attach.obj");
    const fs::path dir = temp_dir() / "attach";
    fs::create_directories(dir);
    const std::string scene_path = (dir / "scene.json").string();
    const Outcome o = run_cli("fit " + obj + " --json --attach --scene " + scene_path);
    ASSERT_EQ(o.status, 0) << o.output;
    const nlohmann::json j = nlohmann::json::parse(o.output);
    const auto& body = j["scene"]["bodies"][0];
    ASSERT_EQ(body["mesh"], "scene_attach.obj");
    ASSERT_TRUE(fs::exists(dir / "scene_attach.obj"));
    const sm::Result<sm::Scene> scene = sm::load_scene(scene_path);
    ASSERT_TRUE(scene) << scene.error().message();
    ASSERT_TRUE(scene->bodies[0].render_mesh);
    const sm::TriangleMesh& mesh = *scene->bodies[0].render_mesh;
    EXPECT_EQ(mesh.positions.size(), sm::test::posed_mesh(truth, 40).positions.size());
    const double rms = j["fit"]["rms_m"].get<double>();
    double worst = 0.0;
    for (const sm::Vec3& p : mesh.positions) {
        // Radial distance from the surface along the ray from the centre: |p|·(1 − F^(−ε1/2)).
        const double f = sm::inside_outside(scene->bodies[0].def.shape, p);
        worst = std::max(worst,
                         std::abs(sm::length(p) *
                                  (1.0 - std::pow(f, -0.5 * body["shape"]["exponents"][0].get<double>()))));
    }
    EXPECT_LT(worst, std::max(10.0 * rms, 1e-6));
    // --attach needs a scene and one part.
    EXPECT_EQ(run_cli("fit " + obj + " --attach 2>/dev/null").status, 2);
    EXPECT_EQ(run_cli("fit " + obj + " --attach --parts 2 --scene " + scene_path + " 2>/dev/null").status, 2);
}
