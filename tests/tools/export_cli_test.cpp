// Tests for tools/cmd_export.cpp: `supermodal export` run as a separate process on the ball on the
// board, then the GLB read back by the engine's own import (assimp) and the report checked.
#include "supermodal/geometry.h"
#include "supermodal/mesh_io.h"
#include "supermodal/scene.h"
#include "support/run_command.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
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

namespace
{

uint32_t u32(const std::vector<uint8_t>& b, size_t at)
{
    return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 | uint32_t{b[at + 3]} << 24;
}

std::vector<uint8_t> file_bytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A GLB's JSON chunk and BIN chunk (the layout itself is checked in tests/io/gltf_export_format_test.cpp).
struct Glb {
    nlohmann::json doc;
    std::vector<uint8_t> bin;
};
Glb read_glb(const fs::path& path)
{
    const std::vector<uint8_t> b = file_bytes(path);
    Glb g;
    if (b.size() < 28)
        return g;
    const uint32_t json_len = u32(b, 12);
    g.doc = nlohmann::json::parse(std::string(b.begin() + 20, b.begin() + 20 + json_len));
    g.bin.assign(b.begin() + 28 + json_len, b.end());
    return g;
}

// The bytes of bufferView v.
std::vector<uint8_t> view_bytes(const Glb& g, int v)
{
    const nlohmann::json& view = g.doc["bufferViews"][v];
    const size_t at = view.value("byteOffset", size_t{0}), n = view["byteLength"].get<size_t>();
    return {g.bin.begin() + static_cast<long>(at), g.bin.begin() + static_cast<long>(at + n)};
}

// Accessor a as floats (tightly packed, as the exporter writes them).
std::vector<float> accessor_floats(const Glb& g, int a)
{
    const std::vector<uint8_t> bytes = view_bytes(g, g.doc["accessors"][a]["bufferView"].get<int>());
    std::vector<float> out(bytes.size() / 4);
    std::memcpy(out.data(), bytes.data(), out.size() * 4);
    return out;
}

const std::string k_crate = std::string(SM_SOURCE_DIR) + "/samples/meshes/crate.obj";

} // namespace

TEST(ExportCli, EveryBodyHasAMaterialOfItsSceneColour)
{
    const fs::path dir = fresh_dir();
    ASSERT_EQ(run_cli("export " + k_scene + " --seconds 0.05 --out " + (dir / "a.glb").string()).status, 0);
    const Glb g = read_glb(dir / "a.glb");
    const sm::Result<sm::Scene> scene = sm::load_scene(k_scene);
    ASSERT_TRUE(scene);
    const std::vector<sm::Vec3> colors = sm::scene_body_colors(*scene);
    // Scene bodies in order, the plane (body 0) left out, as the nodes are.
    ASSERT_EQ(scene->bodies[0].def.shape.type, sm::ShapeType::Plane);
    ASSERT_EQ(g.doc["meshes"].size(), scene->bodies.size() - 1);
    for (size_t i = 0; i < g.doc["meshes"].size(); ++i) {
        const nlohmann::json& prims = g.doc["meshes"][i]["primitives"];
        ASSERT_EQ(prims.size(), 1u);
        const nlohmann::json& factor =
            g.doc["materials"][prims[0]["material"].get<int>()]["pbrMetallicRoughness"]["baseColorFactor"];
        const sm::Vec3 c = colors[i + 1];
        EXPECT_NEAR(factor[0].get<double>(), c.x, 1e-12) << i;
        EXPECT_NEAR(factor[1].get<double>(), c.y, 1e-12) << i;
        EXPECT_NEAR(factor[2].get<double>(), c.z, 1e-12) << i;
        EXPECT_EQ(factor[3].get<double>(), 1.0);
    }
}

// crate.obj (sides textured with crate.png, top and bottom painted) through `fit --attach` and
// `export`: the GLB has the two materials, the image byte for byte, and every corner's (u, v).
TEST(ExportCli, AnAttachedMeshKeepsItsTextureCoordinatesAndMaterials)
{
    const fs::path dir = fresh_dir();
    const fs::path scene = dir / "crate.json", glb = dir / "crate.glb";
    const Outcome fit = run_cli("fit " + k_crate + " --scene " + scene.string() + " --attach");
    ASSERT_EQ(fit.status, 0) << fit.output;
    ASSERT_TRUE(fs::exists(dir / "crate_crate.obj"));
    ASSERT_TRUE(fs::exists(dir / "crate_crate.mtl"));
    const Outcome out = run_cli("export " + scene.string() + " --seconds 0.05 --out " + glb.string());
    ASSERT_EQ(out.status, 0) << out.output;
    const Glb g = read_glb(glb);
    ASSERT_EQ(g.doc["meshes"].size(), 1u);
    const nlohmann::json& prims = g.doc["meshes"][0]["primitives"];
    ASSERT_EQ(prims.size(), 2u); // one per material
    std::map<std::string, nlohmann::json> by_name;
    size_t triangles = 0;
    for (const nlohmann::json& p : prims) {
        const nlohmann::json& m = g.doc["materials"][p["material"].get<int>()];
        by_name[m["name"]] = m;
        triangles += g.doc["accessors"][p["indices"].get<int>()]["count"].get<size_t>() / 3;
        ASSERT_TRUE(p["attributes"].contains("TEXCOORD_0"));
    }
    EXPECT_EQ(triangles, 192u); // six faces of 4 × 4 quads
    ASSERT_EQ(by_name.count("crate_wood"), 1u);
    ASSERT_EQ(by_name.count("crate_paint"), 1u);
    const nlohmann::json& paint = by_name["crate_paint"]["pbrMetallicRoughness"];
    EXPECT_FALSE(paint.contains("baseColorTexture"));
    EXPECT_NEAR(paint["baseColorFactor"][0].get<double>(), 0.7, 1e-6); // crate.mtl's Kd, as floats
    EXPECT_NEAR(paint["baseColorFactor"][1].get<double>(), 0.12, 1e-6);
    EXPECT_NEAR(paint["baseColorFactor"][2].get<double>(), 0.1, 1e-6);
    const nlohmann::json& wood = by_name["crate_wood"]["pbrMetallicRoughness"];
    ASSERT_TRUE(wood.contains("baseColorTexture"));
    const int image = g.doc["textures"][wood["baseColorTexture"]["index"].get<int>()]["source"].get<int>();
    EXPECT_EQ(g.doc["images"][image]["mimeType"], "image/png");
    EXPECT_EQ(view_bytes(g, g.doc["images"][image]["bufferView"].get<int>()),
              file_bytes(std::string(SM_SOURCE_DIR) + "/samples/meshes/crate.png"));
    // The (u, v) of the vertices, turned back to OBJ's v-up, are crate.obj's "vt" values, all of them.
    const std::vector<float> uv = accessor_floats(g, prims[0]["attributes"]["TEXCOORD_0"].get<int>());
    const std::vector<float> pos = accessor_floats(g, prims[0]["attributes"]["POSITION"].get<int>());
    ASSERT_EQ(uv.size() / 2, pos.size() / 3);
    std::set<std::pair<float, float>> seen;
    for (size_t i = 0; i + 1 < uv.size(); i += 2)
        seen.insert({uv[i], 1.0f - uv[i + 1]});
    std::set<std::pair<float, float>> file;
    std::ifstream obj(k_crate);
    for (std::string line; std::getline(obj, line);)
        if (line.rfind("vt ", 0) == 0) {
            float u = 0, v = 0;
            std::sscanf(line.c_str(), "vt %f %f", &u, &v);
            file.insert({u, v});
        }
    EXPECT_EQ(file.size(), 25u); // a 4 × 4 grid's corners
    EXPECT_EQ(seen, file);
}
