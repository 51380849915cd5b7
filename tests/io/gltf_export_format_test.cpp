// The GLB that engine/src/io/gltf_export.cpp writes, read with a few lines of our own rather than
// assimp: header and chunk layout, buffer views and accessors within their bounds, the min/max the
// specification requires, the signed morph weights; and the errors for bad input.
#include "supermodal/body.h"
#include "supermodal/export.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

namespace sm = supermodal;
namespace fs = std::filesystem;
using nlohmann::json;

namespace
{

uint32_t u32(const std::vector<uint8_t>& b, size_t at)
{
    return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 | uint32_t{b[at + 3]} << 24;
}

sm::ExportRecording record_board(double seconds, bool morph = true)
{
    const sm::Result<sm::Scene> scene =
        sm::load_scene(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json");
    EXPECT_TRUE(scene);
    sm::Result<sm::World> world = sm::build_world(*scene);
    EXPECT_TRUE(world);
    sm::ExportDef def = sm::default_export_def();
    def.seconds = seconds;
    def.morph_targets = morph;
    sm::Result<sm::ExportRecording> rec = sm::record_animation(*world, def);
    EXPECT_TRUE(rec) << rec.error().message();
    return std::move(*rec);
}

// The parsed GLB: its JSON and its BIN chunk.
struct Glb {
    json doc;
    std::vector<uint8_t> bin;
};
Glb parse(const std::vector<uint8_t>& b)
{
    Glb g;
    EXPECT_GE(b.size(), 28u);
    EXPECT_EQ(u32(b, 0), 0x46546C67u); // "glTF"
    EXPECT_EQ(u32(b, 4), 2u);
    EXPECT_EQ(u32(b, 8), b.size());
    const uint32_t json_len = u32(b, 12);
    EXPECT_EQ(u32(b, 16), 0x4E4F534Au); // "JSON"
    EXPECT_EQ(json_len % 4, 0u);
    const std::string text(b.begin() + 20, b.begin() + 20 + json_len);
    // Padding is spaces, which JSON parsers skip.
    EXPECT_EQ(text.find_first_not_of(' ', text.find_last_of('}') + 1), std::string::npos);
    g.doc = json::parse(text);
    const size_t bin_at = 20 + json_len;
    const uint32_t bin_len = u32(b, bin_at);
    EXPECT_EQ(u32(b, bin_at + 4), 0x004E4942u); // "BIN\0"
    EXPECT_EQ(bin_len % 4, 0u);
    EXPECT_EQ(bin_at + 8 + bin_len, b.size());
    g.bin.assign(b.begin() + static_cast<long>(bin_at) + 8, b.end());
    return g;
}

int components(const std::string& type)
{
    return type == "SCALAR" ? 1 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 0;
}

std::vector<float> floats(const Glb& g, int accessor)
{
    const json& a = g.doc["accessors"][accessor];
    const json& v = g.doc["bufferViews"][a["bufferView"].get<int>()];
    std::vector<float> out(a["count"].get<size_t>() * static_cast<size_t>(components(a["type"])));
    std::memcpy(out.data(), g.bin.data() + v["byteOffset"].get<size_t>(), out.size() * sizeof(float));
    return out;
}

TEST(GltfExportFormat, ChunksViewsAndAccessorsAreWithinBoundsWithTheRequiredMinMax)
{
    const sm::ExportRecording rec = record_board(0.2);
    const sm::Result<std::vector<uint8_t>> bytes = sm::glb_from_recording(rec);
    ASSERT_TRUE(bytes) << bytes.error().message();
    const Glb g = parse(*bytes);
    const json& doc = g.doc;
    EXPECT_EQ(doc["asset"]["version"], "2.0");
    ASSERT_EQ(doc["buffers"].size(), 1u);
    const size_t buffer_len = doc["buffers"][0]["byteLength"];
    EXPECT_LE(buffer_len, g.bin.size());
    for (const json& v : doc["bufferViews"]) {
        EXPECT_EQ(v["byteOffset"].get<size_t>() % 4, 0u);
        EXPECT_LE(v["byteOffset"].get<size_t>() + v["byteLength"].get<size_t>(), buffer_len);
        EXPECT_FALSE(v.contains("byteStride")); // tightly packed everywhere
    }
    for (const json& a : doc["accessors"]) {
        const json& v = doc["bufferViews"][a["bufferView"].get<int>()];
        const int c = components(a["type"]);
        ASSERT_GT(c, 0);
        EXPECT_TRUE(a["componentType"] == 5126 || a["componentType"] == 5125);
        EXPECT_EQ(a["count"].get<size_t>() * static_cast<size_t>(c) * 4, v["byteLength"].get<size_t>());
    }
    // Every POSITION (base and morph target) has min/max equal to its data's.
    std::vector<int> positions;
    for (const json& m : doc["meshes"])
        for (const json& p : m["primitives"]) {
            positions.push_back(p["attributes"]["POSITION"]);
            const size_t n = doc["accessors"][p["attributes"]["POSITION"].get<int>()]["count"];
            const json& idx = doc["accessors"][p["indices"].get<int>()];
            EXPECT_EQ(doc["bufferViews"][idx["bufferView"].get<int>()]["target"], 34963);
            std::vector<uint32_t> indices(idx["count"].get<size_t>());
            std::memcpy(indices.data(),
                        g.bin.data() +
                            doc["bufferViews"][idx["bufferView"].get<int>()]["byteOffset"].get<size_t>(),
                        indices.size() * 4);
            for (uint32_t i : indices)
                ASSERT_LT(i, n);
            if (p.contains("targets"))
                for (const json& t : p["targets"])
                    positions.push_back(t["POSITION"]);
        }
    EXPECT_EQ(positions.size(), 4u + 8u); // four bodies, eight modes of the board
    for (int acc : positions) {
        const json& a = doc["accessors"][acc];
        ASSERT_TRUE(a.contains("min") && a.contains("max"));
        const std::vector<float> data = floats(g, acc);
        for (int c = 0; c < 3; ++c) {
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (size_t i = static_cast<size_t>(c); i < data.size(); i += 3) {
                lo = std::min(lo, data[i]);
                hi = std::max(hi, data[i]);
            }
            EXPECT_EQ(a["min"][c].get<float>(), lo);
            EXPECT_EQ(a["max"][c].get<float>(), hi);
        }
    }
    // Animation: one shared time input from 0 to the last sample; views of animation data have no target.
    const json& anim = doc["animations"][0];
    EXPECT_EQ(anim["channels"].size(), 4u * 2u + 1u);
    for (const json& s : anim["samplers"]) {
        EXPECT_EQ(s["interpolation"], "LINEAR");
        const json& in = doc["accessors"][s["input"].get<int>()];
        EXPECT_EQ(in["min"][0].get<float>(), 0.0f);
        EXPECT_EQ(in["max"][0].get<float>(), static_cast<float>(rec.times.back()));
        EXPECT_FALSE(
            doc["bufferViews"][doc["accessors"][s["output"].get<int>()]["bufferView"].get<int>()].contains(
                "target"));
    }
}

TEST(GltfExportFormat, WeightsInTheFileAreTheSignedAmplitudes)
{
    const sm::ExportRecording rec = record_board(0.2);
    const Glb g = parse(*sm::glb_from_recording(rec));
    const sm::ExportBody* board = nullptr;
    size_t node = 0;
    for (size_t i = 0; i < rec.bodies.size(); ++i)
        if (rec.bodies[i].name == "board") {
            board = &rec.bodies[i];
            node = i;
        }
    ASSERT_NE(board, nullptr);
    int negative = 0;
    bool found = false;
    for (const json& ch : g.doc["animations"][0]["channels"]) {
        if (ch["target"]["path"] != "weights")
            continue;
        found = true;
        EXPECT_EQ(ch["target"]["node"], node);
        const int out = g.doc["animations"][0]["samplers"][ch["sampler"].get<int>()]["output"];
        const std::vector<float> w = floats(g, out);
        // frames × modes scalars, frame-major (glTF 2.0, animation sampler output for "weights").
        ASSERT_EQ(w.size(), rec.times.size() * 8);
        for (size_t i = 0; i < w.size(); ++i) {
            EXPECT_EQ(w[i], static_cast<float>(board->amplitudes[i])); // exactly one rounding to float
            negative += w[i] < 0.0f;
        }
    }
    EXPECT_TRUE(found);
    EXPECT_GT(negative, 0); // the board swings both ways: signs survive
}

TEST(GltfExportFormat, SameSceneGivesTheSameBytesAndRigidExportHasNoTargets)
{
    EXPECT_EQ(*sm::glb_from_recording(record_board(0.1)), *sm::glb_from_recording(record_board(0.1)));
    const Glb g = parse(*sm::glb_from_recording(record_board(0.1, false)));
    for (const json& m : g.doc["meshes"])
        EXPECT_FALSE(m["primitives"][0].contains("targets"));
    EXPECT_EQ(g.doc["animations"][0]["channels"].size(), 8u);
}

TEST(GltfExportFormat, BadInputIsRefusedAndNothingIsWritten)
{
    sm::ExportDef def = sm::default_export_def();
    EXPECT_TRUE(sm::validate(def));
    for (double s : {0.0, -1.0, std::nan(""), 1e9}) {
        def = sm::default_export_def();
        def.seconds = s;
        EXPECT_FALSE(sm::validate(def)) << s;
    }
    def = sm::default_export_def();
    def.fps = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(sm::validate(def));
    def = sm::default_export_def();
    def.tessellation = 4;
    EXPECT_FALSE(sm::validate(def));

    // fps above the step rate (dt = 2 ms → 500 per s) and a world of planes only.
    sm::World world;
    sm::BodyDef plane = sm::default_body_def();
    plane.motion = sm::MotionType::Static;
    plane.shape.type = sm::ShapeType::Plane;
    plane.shape.plane_normal = {0, 1, 0};
    ASSERT_FALSE(sm::create_body(world, plane).is_null());
    def = sm::default_export_def();
    const sm::Result<sm::ExportRecording> planes_only = sm::record_animation(world, def);
    ASSERT_FALSE(planes_only);
    EXPECT_NE(planes_only.error().what.find("no bodies other than planes"), std::string::npos);
    ASSERT_FALSE(sm::create_body(world, sm::default_body_def()).is_null());
    def.fps = 600.0;
    const sm::Result<sm::ExportRecording> too_fast = sm::record_animation(world, def);
    ASSERT_FALSE(too_fast);
    EXPECT_EQ(too_fast.error().where, "fps");
    def.fps = 400.0;
    def.seconds = 3600.0; // 1.44 million samples
    EXPECT_FALSE(sm::record_animation(world, def));

    // Recordings that cannot be written: a NaN pose, a value past float range, mismatched sizes.
    const sm::ExportRecording good = record_board(0.05);
    sm::ExportRecording bad = good;
    bad.bodies[0].positions[1].x = std::nan("");
    EXPECT_FALSE(sm::glb_from_recording(bad));
    bad = good;
    bad.bodies[2].amplitudes[0] = 1e39;
    EXPECT_FALSE(sm::glb_from_recording(bad));
    bad = good;
    bad.bodies[1].orientations.pop_back();
    EXPECT_FALSE(sm::glb_from_recording(bad));
    bad = good;
    bad.bodies[1].mesh.indices[0] = 1u << 30;
    EXPECT_FALSE(sm::glb_from_recording(bad));

    const fs::path dir =
        fs::temp_directory_path() / ("supermodal_export_format_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const sm::Status s = sm::write_glb(bad, (dir / "bad.glb").string());
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().file, (dir / "bad.glb").string());
    EXPECT_FALSE(sm::write_glb(good, (dir / "missing" / "a.glb").string()));
    std::ofstream(dir / "file") << "x";
    EXPECT_FALSE(sm::write_obj_sequence(good, (dir / "file").string()));
    // Only the file made above: no GLB, no temporary files.
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        (void)e;
        ++entries;
    }
    EXPECT_EQ(entries, 1u);
    fs::remove_all(dir);
}

} // namespace
