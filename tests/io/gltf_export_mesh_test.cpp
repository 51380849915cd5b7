// Render meshes (docs/pipeline.md): a scene body's "mesh" file is read with the scene
// (engine/src/scene/loader.cpp), exported instead of the tessellation, and deformed through the body's
// modal field (engine/src/io/gltf_export_record.cpp). References: import_mesh, modal_displacement and
// body_deformed_point of the public API.
#include "supermodal/body.h"
#include "supermodal/export.h"
#include "supermodal/mesh_io.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"
#include "support/obj_file.h"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

// One folder per test: ctest runs the tests of this file in parallel processes.
fs::path fresh_dir()
{
    const fs::path dir = fs::temp_directory_path() / "supermodal_export_mesh_test" /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir);
    fs::create_directories(dir / "sub");
    return dir;
}

// An artist's board: an ellipsoid-ish slab a little inside the physics board, at another resolution.
void write_board_obj(const fs::path& path)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = {0.48, 0.017, 0.04};
    s.epsilon1 = 0.3;
    s.epsilon2 = 0.5;
    const sm::TriangleMesh m = sm::tessellate(s, 20);
    sm::test::write_obj_file(m, path.string());
}

// samples/ball_on_board.json with a "mesh" on body 3 (the board).
nlohmann::json board_scene(const nlohmann::json& mesh)
{
    std::ifstream in(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json");
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json j = nlohmann::json::parse(text.str());
    EXPECT_EQ(j["bodies"][3]["name"], "board");
    j["bodies"][3]["mesh"] = mesh;
    return j;
}

std::string write_scene(const fs::path& path, const nlohmann::json& j)
{
    std::ofstream(path) << j.dump(2);
    return path.string();
}

TEST(ExportRenderMesh, TheArtistsMeshFollowsTheModalField)
{
    const fs::path dir = fresh_dir();
    write_board_obj(dir / "board.obj");
    const sm::Result<sm::Scene> scene =
        sm::load_scene(write_scene(dir / "scene.json", board_scene("board.obj")));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::SceneBody& sb = scene->bodies[3];
    EXPECT_EQ(sb.mesh, "board.obj");
    ASSERT_TRUE(sb.render_mesh);
    const sm::Result<sm::ImportedMesh> file = sm::import_mesh((dir / "board.obj").string());
    ASSERT_TRUE(file);
    ASSERT_EQ(sb.render_mesh->positions.size(), file->mesh.positions.size());

    sm::Result<sm::World> world = sm::build_world(*scene);
    ASSERT_TRUE(world);
    sm::ExportDef def = sm::default_export_def();
    def.seconds = 0.2;
    const sm::ExportBodyMesh meshes[] = {{"board", sb.render_mesh}};
    const sm::Result<sm::ExportRecording> rec = sm::record_animation(*world, def, meshes);
    ASSERT_TRUE(rec) << rec.error().message();
    const sm::ExportBody& board = rec->bodies[2]; // floor (a plane) is left out
    ASSERT_EQ(board.name, "board");
    ASSERT_EQ(board.mesh.positions.size(), file->mesh.positions.size());
    ASSERT_EQ(board.mode_displacements.size(), 8u);

    sm::Result<sm::World> ref = sm::build_world(*scene);
    ASSERT_TRUE(ref);
    while (ref->time() < rec->times.back() - 0.25 * ref->settings().dt)
        ref->step();
    const sm::Entity b = sm::find_body(*ref, "board");
    const sm::ModalBasis* basis = sm::body_modal_basis(*ref, b);
    ASSERT_NE(basis, nullptr);
    double largest = 0.0, moved = 0.0;
    for (size_t v = 0; v < board.mesh.positions.size(); v += 7) {
        const sm::Vec3 p = file->mesh.positions[v];
        EXPECT_EQ(board.mesh.positions[v].x, p.x);
        EXPECT_EQ(board.mesh.positions[v].y, p.y);
        EXPECT_EQ(board.mesh.positions[v].z, p.z);
        for (int k = 0; k < 8; ++k) {
            std::vector<double> unit(8, 0.0);
            unit[static_cast<size_t>(k)] = 1.0;
            const sm::Vec3 u = sm::modal_displacement(*basis, p, unit);
            // The same 20-term sums in another order: round-off only (1e-12 of the size).
            EXPECT_NEAR(sm::length(board.mode_displacements[static_cast<size_t>(k)][v] - u), 0.0,
                        1e-12 * (sm::length(u) + 1e-3));
            largest = std::max(largest, sm::length(u));
        }
        // The exported, posed vertex at the last sample is where the engine says the material point is.
        const sm::Vec3 e = sm::body_deformed_point(*ref, b, p);
        EXPECT_NEAR(sm::length(sm::exported_vertex(board, rec->times.size() - 1, v) - e), 0.0, 1e-12);
        moved = std::max(moved, sm::length(e - (sm::body_position(*ref, b) +
                                                sm::rotate(sm::body_orientation(*ref, b), p))));
    }
    EXPECT_GT(largest, 0.1); // mode shapes of order 1/√kg for the 1.5 kg board
    EXPECT_GT(moved, 1e-7);  // and the board has been struck: the mesh is deformed, not only posed

    // The GLB carries the artist's mesh with its 8 morph targets.
    const fs::path glb = dir / "anim.glb";
    ASSERT_TRUE(sm::write_glb(*rec, glb.string()));
    Assimp::Importer importer;
    const aiScene* s = importer.ReadFile(glb.string(), 0);
    ASSERT_NE(s, nullptr) << importer.GetErrorString();
    bool found = false;
    for (unsigned i = 0; i < s->mNumMeshes; ++i)
        if (std::string(s->mMeshes[i]->mName.C_Str()) == "board") {
            found = true;
            EXPECT_EQ(s->mMeshes[i]->mNumVertices, file->mesh.positions.size());
            EXPECT_EQ(s->mMeshes[i]->mNumAnimMeshes, 8u);
        }
    EXPECT_TRUE(found);
}

TEST(ExportRenderMesh, SavedAndIncludedScenesKeepTheMeshRelativeToTheirFile)
{
    const fs::path dir = fresh_dir();
    write_board_obj(dir / "sub" / "board.obj");
    write_scene(dir / "sub" / "part.json", board_scene("board.obj"));
    const nlohmann::json outer = {{"include", {{{"file", "sub/part.json"}, {"prefix", "a_"}}}}};
    const sm::Result<sm::Scene> scene = sm::load_scene(write_scene(dir / "outer.json", outer));
    ASSERT_TRUE(scene) << scene.error().message();
    const sm::SceneBody& board = scene->bodies[3];
    EXPECT_EQ(board.def.name, "a_board");
    EXPECT_EQ(board.mesh, "sub/board.obj"); // rebased onto outer.json's folder
    EXPECT_TRUE(board.render_mesh);
    // Saved next to outer.json, the flattened scene reads back with the same mesh.
    ASSERT_TRUE(sm::save_scene(*scene, (dir / "flat.json").string()));
    const sm::Result<sm::Scene> again = sm::load_scene((dir / "flat.json").string());
    ASSERT_TRUE(again) << again.error().message();
    EXPECT_EQ(again->bodies[3].mesh, "sub/board.obj");
    ASSERT_TRUE(again->bodies[3].render_mesh);
    EXPECT_EQ(again->bodies[3].render_mesh->positions.size(), board.render_mesh->positions.size());
    // Only the board has a mesh: the key is written once.
    EXPECT_EQ(sm::scene_to_json(*again).find("\"mesh\""), sm::scene_to_json(*again).rfind("\"mesh\""));
}

TEST(ExportRenderMesh, BadMeshesAreErrorsAtTheBodysPointer)
{
    const fs::path dir = fresh_dir();
    const auto load = [&](const nlohmann::json& j) {
        return sm::load_scene(write_scene(dir / "bad.json", j));
    };
    const sm::Result<sm::Scene> missing = load(board_scene("nope.obj"));
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().where, "/bodies/3/mesh");
    EXPECT_NE(missing.error().what.find("file not found"), std::string::npos) << missing.error().what;
    std::ofstream(dir / "garbage.obj") << "this is not a mesh\n";
    const sm::Result<sm::Scene> garbage = load(board_scene("garbage.obj"));
    ASSERT_FALSE(garbage);
    EXPECT_EQ(garbage.error().where, "/bodies/3/mesh");
    for (const nlohmann::json& value : {nlohmann::json(""), nlohmann::json(3)}) {
        const sm::Result<sm::Scene> r = load(board_scene(value));
        ASSERT_FALSE(r) << value.dump();
        EXPECT_EQ(r.error().where, "/bodies/3/mesh");
    }
    const sm::Result<sm::Scene> device = load(board_scene("/dev/null"));
    ASSERT_FALSE(device);
    EXPECT_EQ(device.error().where, "/bodies/3/mesh");
    EXPECT_NE(device.error().what.find("not a regular file"), std::string::npos) << device.error().what;
    nlohmann::json plane = board_scene("x.obj");
    plane["bodies"][3].erase("mesh");
    plane["bodies"][0]["mesh"] = "x.obj";
    const sm::Result<sm::Scene> p = load(plane);
    ASSERT_FALSE(p);
    EXPECT_EQ(p.error().where, "/bodies/0/mesh");

    // The exporter refuses meshes for unknown bodies or without triangles.
    sm::World world;
    ASSERT_FALSE(sm::create_body(world, sm::default_body_def()).is_null());
    const sm::ExportBodyMesh unknown[] = {{"nobody", std::make_shared<const sm::TriangleMesh>()}};
    EXPECT_FALSE(sm::record_animation(world, sm::default_export_def(), unknown));
}

} // namespace
