// Tests for engine/src/io/mesh_import.cpp with FBX: the file's UnitScaleFactor (centimetres per unit)
// and UpAxis are honoured. The FBX is written by assimp's own ASCII exporter from an OBJ written here,
// then its global settings are edited as text, so the test needs no binary fixture.
#include "supermodal/mesh_io.h"
#include "support/obj_file.h"
#include "support/shapes.h"

#include <algorithm>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

fs::path temp_dir()
{
    const fs::path dir = fs::temp_directory_path() / "supermodal_io_test";
    fs::create_directories(dir);
    return dir;
}

sm::TriangleMesh source_mesh()
{
    sm::TriangleMesh m = sm::tessellate(sm::test::superquadric({0.3, 0.2, 0.1}, 0.5, 0.7), 24);
    for (sm::Vec3& p : m.positions)
        p += sm::Vec3{0.5, -0.25, 1.0};
    return m;
}

/// The FBX text assimp writes for the source mesh (UnitScaleFactor 1, UpAxis 1: centimetres, Y-up).
std::string fbx_text(const sm::TriangleMesh& m)
{
    const fs::path obj = temp_dir() / "fbx_source.obj";
    sm::test::write_obj_file(m, obj.string());
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(obj.string(), 0);
    if (scene == nullptr)
        return {};
    const fs::path fbx = temp_dir() / "exported.fbx";
    Assimp::Exporter exporter;
    if (exporter.Export(scene, "fbxa", fbx.string()) != AI_SUCCESS)
        return {};
    std::ifstream in(fbx);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string replace_setting(std::string text, const std::string& prefix, const std::string& value)
{
    const size_t at = text.find(prefix);
    if (at == std::string::npos)
        return {};
    const size_t end = text.find('\n', at);
    return text.replace(at, end - at, prefix + value);
}

std::string write(const char* name, const std::string& text)
{
    std::ofstream(temp_dir() / name, std::ios::binary) << text;
    return (temp_dir() / name).string();
}

} // namespace

TEST(FbxImport, HonoursUnitScaleFactorAndUpAxis)
{
    const sm::TriangleMesh src = source_mesh();
    const std::string text = fbx_text(src);
    ASSERT_FALSE(text.empty());
    const double volume = sm::mesh_volume(src);

    // As exported: centimetres (UnitScaleFactor 1), so lengths shrink 100× and volumes 10^6×. The
    // coordinates pass through float storage twice (OBJ → assimp → FBX text → assimp), ~1e-7 relative
    // of |p| ≈ 1 m each, on a body 0.2 m thin: up to ~1e-6 on the volume each pass (measured 1.5e-6).
    constexpr double volume_tol = 1e-5;
    const auto cm = sm::import_mesh(write("cm.fbx", text));
    ASSERT_TRUE(cm) << cm.error().message();
    EXPECT_EQ(cm->format, "fbx");
    EXPECT_NEAR(cm->scale, 0.01, 1e-12);
    EXPECT_EQ(cm->up_axis, sm::UpAxis::PosY);
    EXPECT_EQ(cm->mesh.indices.size(), src.indices.size());
    EXPECT_NEAR(sm::mesh_volume(cm->mesh) / (1e-6 * volume), 1.0, volume_tol);

    // Metres (UnitScaleFactor 100) and Z up: (x, y, z) → (x, z, −y).
    std::string edited =
        replace_setting(text, "P: \"UnitScaleFactor\", \"double\", \"Number\", \"\", ", "100");
    edited = replace_setting(edited, "P: \"UpAxis\", \"int\", \"Integer\", \"\", ", "2");
    ASSERT_FALSE(edited.empty());
    const auto zup = sm::import_mesh(write("zup.fbx", edited));
    ASSERT_TRUE(zup) << zup.error().message();
    EXPECT_NEAR(zup->scale, 1.0, 1e-12);
    EXPECT_EQ(zup->up_axis, sm::UpAxis::PosZ);
    EXPECT_NEAR(sm::mesh_volume(zup->mesh) / volume, 1.0, volume_tol);
    sm::Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
    for (const sm::Vec3& p : zup->mesh.positions)
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], p[i]);
            hi[i] = std::max(hi[i], p[i]);
        }
    // Source box: x ∈ 0.5 ± 0.3, y ∈ −0.25 ± 0.2, z ∈ 1 ± 0.1 → world y ∈ 1 ± 0.1, z ∈ 0.25 ± 0.2.
    EXPECT_NEAR(0.5 * (hi.x + lo.x), 0.5, 1e-6);
    EXPECT_NEAR(0.5 * (hi.y + lo.y), 1.0, 1e-6);
    EXPECT_NEAR(0.5 * (hi.z + lo.z), 0.25, 1e-6);
    EXPECT_NEAR(hi.y - lo.y, 0.2, 1e-6);
    EXPECT_NEAR(hi.z - lo.z, 0.4, 1e-6);

    // An explicit scale and up axis win over the file.
    sm::ImportDef def = sm::default_import_def();
    def.scale = 1.0;
    def.up_axis = sm::UpAxis::PosY;
    const auto forced = sm::import_mesh(write("forced.fbx", edited), def);
    ASSERT_TRUE(forced) << forced.error().message();
    EXPECT_NEAR(sm::mesh_volume(forced->mesh) / volume, 1.0, volume_tol);
    EXPECT_EQ(forced->up_axis, sm::UpAxis::PosY);
}
