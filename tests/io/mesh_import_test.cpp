// Tests for engine/src/io/mesh_import.cpp: files written here from a tessellated superquadric come
// back with the same vertices, triangles and volume; units, up axis and node transforms; clear errors.
#include "supermodal/mesh_io.h"
#include "support/obj_file.h"
#include "support/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <vector>

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

/// A rounded box 0.3 x 0.2 x 0.1 m, off the origin so a lost translation would show.
sm::TriangleMesh source_mesh()
{
    sm::TriangleMesh m = sm::tessellate(sm::test::superquadric({0.3, 0.2, 0.1}, 0.5, 0.7), 32);
    for (sm::Vec3& p : m.positions)
        p += sm::Vec3{0.5, -0.25, 1.0};
    return m;
}

std::string write_obj(const sm::TriangleMesh& m, const char* name)
{
    const fs::path path = temp_dir() / name;
    sm::test::write_obj_file(m, path.string());
    return path.string();
}

std::string write_ply(const sm::TriangleMesh& m)
{
    const fs::path path = temp_dir() / "mesh.ply";
    std::ofstream out(path);
    out << "ply\nformat ascii 1.0\nelement vertex " << m.positions.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.indices.size() / 3
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    char line[160];
    for (const sm::Vec3& p : m.positions) {
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p.x, p.y, p.z);
        out << line;
    }
    for (size_t t = 0; t < m.indices.size(); t += 3)
        out << "3 " << m.indices[t] << ' ' << m.indices[t + 1] << ' ' << m.indices[t + 2] << '\n';
    return path.string();
}

/// Binary STL: every triangle carries its own three float vertices, so only welding reconnects them.
std::string write_stl(const sm::TriangleMesh& m)
{
    const fs::path path = temp_dir() / "mesh.stl";
    std::ofstream out(path, std::ios::binary);
    char header[80] = "supermodal test mesh";
    out.write(header, sizeof header);
    const auto count = uint32_t(m.indices.size() / 3);
    out.write(reinterpret_cast<const char*>(&count), 4);
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        float f[12] = {};
        for (int k = 0; k < 3; ++k) {
            const sm::Vec3& p = m.positions[m.indices[t + size_t(k)]];
            f[3 + 3 * k] = float(p.x);
            f[4 + 3 * k] = float(p.y);
            f[5 + 3 * k] = float(p.z);
        }
        out.write(reinterpret_cast<const char*>(f), sizeof f);
        const uint16_t attributes = 0;
        out.write(reinterpret_cast<const char*>(&attributes), 2);
    }
    return path.string();
}

void expect_same_mesh(const sm::TriangleMesh& got, const sm::TriangleMesh& want, double volume_tol)
{
    EXPECT_EQ(got.positions.size(), want.positions.size());
    EXPECT_EQ(got.indices.size(), want.indices.size());
    EXPECT_EQ(got.normals.size(), got.positions.size());
    EXPECT_NEAR(sm::mesh_volume(got) / sm::mesh_volume(want), 1.0, volume_tol);
}

} // namespace

TEST(MeshImport, ObjComesBackExactly)
{
    // %.17g round-trips doubles, but assimp stores floats: volume to float precision, ~1e-7 relative
    // per coordinate, so 1e-6 on the volume.
    const sm::TriangleMesh src = source_mesh();
    const auto got = sm::import_mesh(write_obj(src, "mesh.obj"));
    ASSERT_TRUE(got) << got.error().message();
    expect_same_mesh(got->mesh, src, 1e-6);
    EXPECT_EQ(got->format, "obj");
    EXPECT_EQ(got->scale, 1.0);
    EXPECT_EQ(got->up_axis, sm::UpAxis::PosY);
}

TEST(MeshImport, PlyAndBinaryStlComeBackWithTheSameVolume)
{
    // Both store float coordinates written from doubles: the same 1e-6 volume tolerance as OBJ.
    const sm::TriangleMesh src = source_mesh();
    for (const std::string& path : {write_ply(src), write_stl(src)}) {
        SCOPED_TRACE(path);
        const auto got = sm::import_mesh(path);
        ASSERT_TRUE(got) << got.error().message();
        expect_same_mesh(got->mesh, src, 1e-6);
    }
    // Without welding the STL keeps three vertices per triangle.
    sm::ImportDef unwelded = sm::default_import_def();
    unwelded.weld_vertices = false;
    const auto stl = sm::import_mesh(write_stl(src), unwelded);
    ASSERT_TRUE(stl) << stl.error().message();
    EXPECT_EQ(stl->mesh.positions.size(), src.indices.size());
    EXPECT_NEAR(sm::mesh_volume(stl->mesh) / sm::mesh_volume(src), 1.0, 1e-6);
}

TEST(MeshImport, ExplicitScaleAndUpAxis)
{
    // A Z-up file in millimetres: (x, y, z) mm → (x, z, −y)·0.001 m, exactly up to float storage.
    const sm::TriangleMesh src = source_mesh();
    sm::ImportDef def = sm::default_import_def();
    def.scale = 0.001;
    def.up_axis = sm::UpAxis::PosZ;
    const auto got = sm::import_mesh(write_obj(src, "zup.obj"), def);
    ASSERT_TRUE(got) << got.error().message();
    ASSERT_EQ(got->mesh.positions.size(), src.positions.size());
    for (size_t i = 0; i < src.positions.size(); i += 37) {
        const sm::Vec3 p = src.positions[i], q = got->mesh.positions[i];
        EXPECT_NEAR(q.x, 0.001 * p.x, 1e-9);
        EXPECT_NEAR(q.y, 0.001 * p.z, 1e-9);
        EXPECT_NEAR(q.z, -0.001 * p.y, 1e-9);
    }
    // A proper rotation keeps the winding: the volume stays positive and scales by 1e-9.
    EXPECT_NEAR(sm::mesh_volume(got->mesh) / (1e-9 * sm::mesh_volume(src)), 1.0, 1e-6);
}

TEST(MeshImport, MalformedPlyHeaderIsRefusedBeforeAssimpLoopsOnIt)
{
    // The mesh fuzzer's hang: a PLY whose "element" line is broken by binary bytes made Debian's assimp
    // 5.2 seek and read at the end of the file forever. The header check refuses it with its line.
    const std::string hang = std::string(SM_SOURCE_DIR) + "/tests/fuzz/mesh_regressions/hang_ply_header.ply";
    const sm::Result<sm::ImportedMesh> m = sm::import_mesh(hang);
    ASSERT_FALSE(m);
    EXPECT_NE(m.error().what.find("PLY header line 3"), std::string::npos) << m.error().message();

    const fs::path dir = temp_dir();
    auto refused = [&](const std::string& text, const char* name) {
        const fs::path path = dir / name;
        std::ofstream(path, std::ios::binary) << text;
        const sm::Result<sm::ImportedMesh> r = sm::import_mesh(path.string());
        return r ? std::string("accepted") : r.error().what;
    };
    const std::string tail = "property float x\nproperty float y\nproperty float z\nend_header\n";
    EXPECT_NE(refused("ply\nformat ascii 1.0\nelement vertex many\n" + tail, "count.ply").find("line 3"),
              std::string::npos);
    EXPECT_NE(
        refused("ply\nformat ascii 1.0\nelement vertex 3\n", "short.ply").find("ends before end_header"),
        std::string::npos);
    EXPECT_NE(refused("ply\nelement vertex 3\n" + tail, "noformat.ply").find("no format line"),
              std::string::npos);
    // Content decides, not the extension: a PLY named .obj is checked too.
    EXPECT_NE(
        refused("ply\nformat ascii 1.0\nelemen\x01t vertex 3\n" + tail, "ply_inside.obj").find("line 3"),
        std::string::npos);
    // "ply" and then junk on the magic line: assimp reads it as PLY (and looped on one); refused.
    EXPECT_NE(refused(std::string("ply\0\0asc\nformat ascii 1.0\n", 26) + tail, "magic.ply").find("line 1"),
              std::string::npos);
    // An element declared twice made assimp 5.2 free memory it does not own (mesh fuzz, ASan
    // bad-free; tests/fuzz/mesh_regressions/element_declared_twice.ply): refused at its line, as are
    // malformed property lines and properties before any element.
    EXPECT_NE(refused("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nelement vertex 4\n" + tail,
                      "twice.ply")
                  .find("line 5: element \"vertex\" declared twice"),
              std::string::npos);
    EXPECT_NE(
        refused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float y ascii 1.0\n" + tail, "prop.ply")
            .find("line 4"),
        std::string::npos);
    EXPECT_NE(refused("ply\nformat ascii 1.0\nproperty float x\nelement vertex 3\n" + tail, "early.ply")
                  .find("line 3: a property before any element"),
              std::string::npos);
    // A comment may hold any UTF-8; the well-formed PLY of the other tests still loads.
    const sm::TriangleMesh src = source_mesh();
    const std::string good = write_ply(src);
    std::string text;
    {
        std::ifstream in(good);
        std::stringstream s;
        s << in.rdbuf();
        text = s.str();
    }
    text.insert(text.find("element"), "comment made in Zürich\n");
    EXPECT_EQ(refused(text, "comment.ply"), "accepted");
}

TEST(MeshImport, KeptMeshFuzzFindingsAreRefusedOrLoadWithoutAborting)
{
    // Each file in tests/fuzz/mesh_regressions once hung or aborted the process inside assimp (an
    // assert in its triangulation on a malformed PLY: now the primitive-type flags are recomputed
    // before post-processing). Reaching the end of this test is the check; what each gives is either
    // a mesh or an error that says why.
    int files = 0;
    for (const auto& e :
         fs::directory_iterator(std::string(SM_SOURCE_DIR) + "/tests/fuzz/mesh_regressions")) {
        const sm::Result<sm::ImportedMesh> m = sm::import_mesh(e.path().string());
        if (!m) {
            EXPECT_FALSE(m.error().what.empty()) << e.path();
        }
        ++files;
    }
    EXPECT_GE(files, 2);
}

namespace
{

const std::string k_crate = std::string(SM_SOURCE_DIR) + "/samples/meshes/crate.obj";

// crate.obj's corners as (x, y, z, u, v), read with a few lines of our own: "v" and "vt" lines are
// paired by index in that file (every face corner is "i/i").
std::vector<std::array<double, 5>> crate_corners()
{
    std::ifstream in(k_crate);
    std::vector<std::array<double, 5>> v;
    std::vector<std::array<double, 2>> t;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::string tag;
        s >> tag;
        if (tag == "v") {
            std::array<double, 5> c{};
            s >> c[0] >> c[1] >> c[2];
            v.push_back(c);
        } else if (tag == "vt") {
            std::array<double, 2> c{};
            s >> c[0] >> c[1];
            t.push_back(c);
        }
    }
    for (size_t i = 0; i < v.size() && i < t.size(); ++i) {
        v[i][3] = t[i][0];
        v[i][4] = t[i][1];
    }
    return v;
}

} // namespace

TEST(MeshImport, KeepLookReadsTextureCoordinatesAndMaterials)
{
    sm::ImportDef def = sm::default_import_def();
    def.keep_look = true;
    const auto got = sm::import_mesh(k_crate, def);
    ASSERT_TRUE(got) << got.error().message();
    const sm::MeshLook& look = got->look;
    const size_t n = got->mesh.positions.size();
    ASSERT_EQ(look.texcoords.size(), 2 * n);
    ASSERT_EQ(look.triangle_materials.size() * 3, got->mesh.indices.size());
    EXPECT_EQ(got->mesh.indices.size(), 576u); // six faces of 4 × 4 quads
    // Every vertex is one of the file's (position, uv) corners: welding kept the UV seams apart.
    const std::vector<std::array<double, 5>> corners = crate_corners();
    for (size_t i = 0; i < n; ++i) {
        const sm::Vec3 p = got->mesh.positions[i];
        const bool found = std::any_of(corners.begin(), corners.end(), [&](const std::array<double, 5>& c) {
            // The file's 6-digit text goes through assimp's floats: 1e-6 m, and UVs of 0 or 1 exactly.
            return std::abs(c[0] - p.x) < 1e-6 && std::abs(c[1] - p.y) < 1e-6 &&
                   std::abs(c[2] - p.z) < 1e-6 && c[3] == look.texcoords[2 * i] &&
                   c[4] == look.texcoords[2 * i + 1];
        });
        EXPECT_TRUE(found) << "vertex " << i;
    }
    // 98 distinct positions; each face's own UVs need up to 6 × 25 vertices.
    EXPECT_GT(n, 98u);
    EXPECT_LE(n, 150u);
    ASSERT_EQ(look.materials.size(), 2u);
    size_t wood = 0, paint = 0;
    for (uint32_t m : look.triangle_materials)
        (look.materials[m].name == "crate_wood" ? wood : paint) += 1;
    EXPECT_EQ(wood, 128u); // four sides
    EXPECT_EQ(paint, 64u);
    for (const sm::MeshMaterial& m : look.materials) {
        if (m.name == "crate_wood") {
            EXPECT_EQ(fs::path(m.base_color_texture).filename(), "crate.png");
            EXPECT_TRUE(fs::is_regular_file(m.base_color_texture)) << m.base_color_texture;
        } else {
            EXPECT_EQ(m.name, "crate_paint");
            EXPECT_TRUE(m.base_color_texture.empty());
            EXPECT_NEAR(m.base_color[0], 0.7, 1e-6); // crate.mtl's Kd through floats
            EXPECT_NEAR(m.base_color[1], 0.12, 1e-6);
            EXPECT_NEAR(m.base_color[2], 0.1, 1e-6);
            EXPECT_EQ(m.base_color[3], 1.0);
        }
    }
    // Normals are summed over every triangle at a position, so the two sides of a UV seam agree.
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            if (got->mesh.positions[i] == got->mesh.positions[j]) {
                EXPECT_EQ(got->mesh.normals[i], got->mesh.normals[j]) << i << ", " << j;
            }
}

TEST(MeshImport, WithoutKeepLookTheMeshIsWeldedByPositionAlone)
{
    const auto got = sm::import_mesh(k_crate);
    ASSERT_TRUE(got) << got.error().message();
    EXPECT_EQ(got->mesh.positions.size(), 98u);
    EXPECT_TRUE(got->look.texcoords.empty());
    EXPECT_TRUE(got->look.materials.empty());
    EXPECT_TRUE(got->look.triangle_materials.empty());
}
