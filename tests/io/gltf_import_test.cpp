// Tests for engine/src/io/mesh_import.cpp with glTF (Y-up metres by specification), node transforms,
// and the error messages for files that are missing, empty, garbage or without triangles.
#include "supermodal/mesh_io.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

std::string write_text(const char* name, const std::string& text)
{
    const fs::path dir = fs::temp_directory_path() / "supermodal_io_test";
    fs::create_directories(dir);
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
}

/// Base64 of raw bytes (RFC 4648), for the data: URI of the glTF buffer.
std::string base64(const std::string& bytes)
{
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v =
            (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8 | (unsigned char)bytes[i + 2];
        for (int s = 18; s >= 0; s -= 6)
            out += table[(v >> s) & 63];
    }
    if (i + 1 == bytes.size()) {
        const unsigned v = (unsigned char)bytes[i] << 16;
        out += std::string{table[(v >> 18) & 63], table[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const unsigned v = (unsigned char)bytes[i] << 16 | (unsigned char)bytes[i + 1] << 8;
        out += std::string{table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
    }
    return out;
}

/// A unit right tetrahedron (vertices 0, x, y, z; volume 1/6 m³) in a node translated by (1, 2, 3) m
/// and scaled by 2.
std::string tetrahedron_gltf()
{
    const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint16_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}; // outward, counter-clockwise
    std::string bytes(reinterpret_cast<const char*>(positions), sizeof positions);
    bytes.append(reinterpret_cast<const char*>(indices), sizeof indices);
    return R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [1, 2, 3], "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
           base64(bytes) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 1]},
                {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]
})";
}

} // namespace

TEST(GltfImport, IsYUpMetresWithTheNodeTransform)
{
    // glTF is Y-up metres by specification: nothing turned or scaled beyond the node's own transform.
    const auto got = sm::import_mesh(write_text("tet.gltf", tetrahedron_gltf()));
    ASSERT_TRUE(got) << got.error().message();
    EXPECT_EQ(got->format, "gltf");
    EXPECT_EQ(got->scale, 1.0);
    EXPECT_EQ(got->up_axis, sm::UpAxis::PosY);
    ASSERT_EQ(got->mesh.positions.size(), 4u);
    ASSERT_EQ(got->mesh.indices.size(), 12u);
    // Vertex y = (0, 1, 0) lands at 2·y + (1, 2, 3) = (1, 4, 3): exact in floats.
    bool found_top = false;
    for (const sm::Vec3& p : got->mesh.positions)
        found_top = found_top || (p.x == 1.0 && p.y == 4.0 && p.z == 3.0);
    EXPECT_TRUE(found_top);
    EXPECT_NEAR(sm::mesh_volume(got->mesh), 8.0 / 6.0, 1e-12); // scale 2 → 8× the volume
}

TEST(MeshImportErrors, NameThePathAndTheProblem)
{
    const std::string missing = (fs::temp_directory_path() / "supermodal_io_test" / "no_such.obj").string();
    struct Case {
        std::string path;
        const char* expect;
    };
    const Case cases[] = {
        {missing, "not found"},
        {write_text("empty.obj", ""), "empty"},
        {write_text("garbage.stl", "this is not a mesh at all \x01\x02\x03"), "cannot read mesh"},
        {write_text("garbage.glb", std::string("glTF\x02\0\0\0garbage", 15)), "cannot read mesh"},
        {write_text("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n"), "no triangles"},
        {fs::temp_directory_path().string(), "directory"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.path);
        const auto got = sm::import_mesh(c.path);
        ASSERT_FALSE(got);
        EXPECT_EQ(got.error().file, c.path);
        EXPECT_NE(got.error().message().find(c.expect), std::string::npos) << got.error().message();
    }
    sm::ImportDef bad = sm::default_import_def();
    bad.scale = -1.0;
    EXPECT_FALSE(sm::import_mesh(missing, bad));
}

TEST(MeshImport, UpAxisNamesRoundTrip)
{
    for (sm::UpAxis a : {sm::UpAxis::FromFile, sm::UpAxis::PosX, sm::UpAxis::PosY, sm::UpAxis::PosZ,
                         sm::UpAxis::NegX, sm::UpAxis::NegY, sm::UpAxis::NegZ}) {
        sm::UpAxis back = sm::UpAxis::FromFile;
        EXPECT_TRUE(sm::parse_up_axis(sm::up_axis_name(a), back));
        EXPECT_EQ(back, a);
    }
    sm::UpAxis z = sm::UpAxis::PosY;
    EXPECT_TRUE(sm::parse_up_axis("z", z));
    EXPECT_EQ(z, sm::UpAxis::PosZ);
    EXPECT_FALSE(sm::parse_up_axis("w", z));
}

TEST(MeshImportErrors, OutOfRangeIndicesAreRefused)
{
    // A face naming vertex 9 of 3: refused with assimp's message, never read past the vertex array.
    const std::string path = write_text("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    const auto got = sm::import_mesh(path);
    ASSERT_FALSE(got);
    EXPECT_EQ(got.error().file, path);
    EXPECT_NE(got.error().what.find("out of range"), std::string::npos) << got.error().message();
}
