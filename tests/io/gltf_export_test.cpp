// Round trip of engine/src/io/gltf_export*.cpp through assimp's glTF 2.0 reader: export 0.2 s of the
// ball on the board (a modal board, a rigid ball, two static supports, a floor plane), read the GLB
// back and compare what assimp sees with a second, identical run of the same scene (same scene, same
// build → bit-identical states, so the reference is exact).
#include "supermodal/body.h"
#include "supermodal/export.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"

#include <assimp/Importer.hpp>
#include <assimp/anim.h>
#include <assimp/scene.h>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>

namespace sm = supermodal;
namespace fs = std::filesystem;

namespace
{

// One float rounding of x: |x − float(x)| ≤ 2^−24·|x| (round to nearest, normal range).
constexpr double k_float_eps = 1.0 / (1 << 24);

sm::World load_world()
{
    const sm::Result<sm::Scene> scene =
        sm::load_scene(std::string(SM_SOURCE_DIR) + "/samples/ball_on_board.json");
    EXPECT_TRUE(scene) << scene.error().message();
    sm::Result<sm::World> world = sm::build_world(*scene);
    EXPECT_TRUE(world) << world.error().message();
    return std::move(*world);
}

// The reference run, stepped to the step whose time is nearest t (the exporter's rule).
void step_to(sm::World& w, double t)
{
    while (w.time() < t - 0.5 * w.settings().dt)
        w.step();
    ASSERT_NEAR(w.time(), t, 0.5 * w.settings().dt);
}

const aiNodeAnim* node_channel(const aiAnimation& a, const char* name)
{
    for (unsigned i = 0; i < a.mNumChannels; ++i)
        if (std::string(a.mChannels[i]->mNodeName.C_Str()) == name)
            return a.mChannels[i];
    return nullptr;
}

const aiMesh* mesh_named(const aiScene& s, const char* name)
{
    for (unsigned i = 0; i < s.mNumMeshes; ++i)
        if (std::string(s.mMeshes[i]->mName.C_Str()) == name)
            return s.mMeshes[i];
    return nullptr;
}

class GltfExport : public ::testing::Test
{
  protected:
    static void SetUpTestSuite()
    {
        sm::World world = load_world();
        sm::ExportDef def = sm::default_export_def();
        def.seconds = 0.2;
        def.fps = 30.0;
        sm::Result<sm::ExportRecording> rec = sm::record_animation(world, def);
        ASSERT_TRUE(rec) << rec.error().message();
        s_recording = new sm::ExportRecording(std::move(*rec));
        // One folder per process: ctest runs the tests of this suite in parallel processes.
        const fs::path dir =
            fs::temp_directory_path() / ("supermodal_export_test_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        s_path = new std::string((dir / "ball_on_board.glb").string());
        const sm::Status s = sm::write_glb(*s_recording, *s_path);
        ASSERT_TRUE(s) << s.error().message();
    }
    static void TearDownTestSuite()
    {
        if (s_path != nullptr)
            fs::remove_all(fs::path(*s_path).parent_path());
        delete s_recording;
        delete s_path;
    }
    static sm::ExportRecording* s_recording;
    static std::string* s_path;
};
sm::ExportRecording* GltfExport::s_recording = nullptr;
std::string* GltfExport::s_path = nullptr;

TEST_F(GltfExport, AssimpReadsNodesMeshesAnimationAndMorphTargets)
{
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(*s_path, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    // Floor (a plane) is left out: supports ×2, board, ball.
    EXPECT_EQ(scene->mNumMeshes, 4u);
    for (const char* name : {"support_left", "support_right", "board", "ball"}) {
        const aiNode* node = scene->mRootNode->FindNode(name);
        ASSERT_NE(node, nullptr) << name;
        EXPECT_EQ(node->mNumMeshes, 1u) << name;
    }
    EXPECT_EQ(scene->mRootNode->FindNode("floor"), nullptr);
    ASSERT_EQ(scene->mNumAnimations, 1u);
    const aiAnimation& anim = *scene->mAnimations[0];
    EXPECT_EQ(anim.mNumChannels, 4u);
    ASSERT_EQ(anim.mNumMorphMeshChannels, 1u); // only the board is modal
    const aiMesh* board = mesh_named(*scene, "board");
    const aiMesh* ball = mesh_named(*scene, "ball");
    ASSERT_NE(board, nullptr);
    ASSERT_NE(ball, nullptr);
    EXPECT_EQ(board->mNumAnimMeshes, 8u); // "modes": 8 in the scene
    EXPECT_EQ(ball->mNumAnimMeshes, 0u);
    // 0.2 s at 30 per second: samples at 0, 1/30, ..., 6/30.
    const aiNodeAnim* ch = node_channel(anim, "ball");
    ASSERT_NE(ch, nullptr);
    EXPECT_EQ(ch->mNumPositionKeys, 7u);
    EXPECT_EQ(ch->mNumRotationKeys, 7u);
    EXPECT_EQ(anim.mMorphMeshChannels[0]->mNumKeys, 7u);
}

TEST_F(GltfExport, KeysEqualTheEnginesPosesAndAmplitudesToFloatPrecision)
{
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(*s_path, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    const aiAnimation& anim = *scene->mAnimations[0];
    const double ticks = anim.mTicksPerSecond > 0.0 ? anim.mTicksPerSecond : 1.0;
    const aiMeshMorphAnim& morph = *anim.mMorphMeshChannels[0];
    sm::World ref = load_world();
    const sm::Entity ball = sm::find_body(ref, "ball"), board = sm::find_body(ref, "board");
    double max_q = 0.0;
    for (const char* name : {"ball", "board"}) {
        const aiNodeAnim* ch = node_channel(anim, name);
        ASSERT_NE(ch, nullptr) << name;
    }
    const aiNodeAnim& ball_ch = *node_channel(anim, "ball");
    const aiNodeAnim& board_ch = *node_channel(anim, "board");
    for (unsigned k = 0; k < ball_ch.mNumPositionKeys; ++k) {
        const double t = ball_ch.mPositionKeys[k].mTime / ticks;
        step_to(ref, t);
        // Positions: one float rounding each (the key time itself is a float, whose rounding is far
        // below the half-step slack of step_to).
        const sm::Vec3 p = sm::body_position(ref, ball);
        const aiVector3D& v = ball_ch.mPositionKeys[k].mValue;
        EXPECT_NEAR(v.x, p.x, k_float_eps * std::fabs(p.x) + 1e-30) << "key " << k;
        EXPECT_NEAR(v.y, p.y, k_float_eps * std::fabs(p.y) + 1e-30) << "key " << k;
        EXPECT_NEAR(v.z, p.z, k_float_eps * std::fabs(p.z) + 1e-30) << "key " << k;
        // Rotation, up to the sign the exporter chooses for continuity; components ≤ 1, so one rounding
        // is ≤ 2^−24.
        const sm::Quat q = sm::body_orientation(ref, board);
        const aiQuaternion& r = board_ch.mRotationKeys[k].mValue;
        const double sign = (r.w * q.w + r.x * q.x + r.y * q.y + r.z * q.z) < 0.0 ? -1.0 : 1.0;
        EXPECT_NEAR(r.w, sign * q.w, k_float_eps) << "key " << k;
        EXPECT_NEAR(r.x, sign * q.x, k_float_eps) << "key " << k;
        EXPECT_NEAR(r.y, sign * q.y, k_float_eps) << "key " << k;
        EXPECT_NEAR(r.z, sign * q.z, k_float_eps) << "key " << k;
        // Morph weights are the modal amplitudes q(t).
        ASSERT_LT(k, morph.mNumKeys);
        EXPECT_NEAR(morph.mKeys[k].mTime, ball_ch.mPositionKeys[k].mTime, 1e-9 * ticks);
        const std::vector<double> amps = sm::body_modal_state(ref, board).amplitudes;
        ASSERT_EQ(morph.mKeys[k].mNumValuesAndWeights, amps.size());
        for (unsigned j = 0; j < morph.mKeys[k].mNumValuesAndWeights; ++j) {
            const unsigned mode = morph.mKeys[k].mValues[j];
            ASSERT_LT(mode, amps.size());
            // assimp 5.2's glTF reader clamps negative weights to 0 (CreateMeshMorphAnim), though glTF
            // allows them; the file holds the signed q, checked in gltf_export_format_test.cpp.
            const double expected = std::max(amps[mode], 0.0);
            EXPECT_NEAR(morph.mKeys[k].mWeights[j], expected, k_float_eps * expected + 1e-30)
                << "key " << k << " mode " << mode;
            max_q = std::max(max_q, expected);
        }
    }
    // The ball strikes the board at about 0.08 s: some weights checked above are positive.
    EXPECT_GT(max_q, 1e-6);
}

TEST_F(GltfExport, MorphTargetsAreTheModeShapesAtTheVertices)
{
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(*s_path, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    const aiMesh& board = *mesh_named(*scene, "board");
    sm::World ref = load_world();
    const sm::Entity b = sm::find_body(ref, "board");
    const sm::ModalBasis* basis = sm::body_modal_basis(ref, b);
    ASSERT_NE(basis, nullptr);
    const sm::TriangleMesh rest =
        sm::tessellate(sm::body_shape(ref, b), sm::default_export_def().tessellation);
    ASSERT_EQ(board.mNumVertices, rest.positions.size());
    ASSERT_EQ(board.mNumAnimMeshes, static_cast<unsigned>(basis->mode_count));
    double checked = 0.0;
    for (size_t v = 0; v < rest.positions.size(); v += 37) { // a spread of vertices, corners to middle
        const sm::Vec3& p = rest.positions[v];
        EXPECT_NEAR(board.mVertices[v].x, p.x, k_float_eps * std::fabs(p.x) + 1e-30);
        for (int k = 0; k < basis->mode_count; ++k) {
            std::vector<double> unit(static_cast<size_t>(basis->mode_count), 0.0);
            unit[static_cast<size_t>(k)] = 1.0;
            const sm::Vec3 u =
                sm::modal_displacement(*basis, p, unit); // the public API, not the exporter's sum
            // assimp stores target positions as rest + displacement (floats): the difference carries
            // the roundings of the rest position, the displacement and the sum: ≤ 2·2^−24·(|p| + |u|).
            const aiVector3D& t = board.mAnimMeshes[k]->mVertices[v];
            const aiVector3D& r = board.mVertices[v];
            const double tol = 2.0 * k_float_eps * (sm::length(p) + sm::length(u)) + 1e-30;
            EXPECT_NEAR(t.x - r.x, u.x, tol) << "vertex " << v << " mode " << k;
            EXPECT_NEAR(t.y - r.y, u.y, tol) << "vertex " << v << " mode " << k;
            EXPECT_NEAR(t.z - r.z, u.z, tol) << "vertex " << v << " mode " << k;
            checked = std::max(checked, sm::length(u));
        }
    }
    EXPECT_GT(checked, 0.1); // mass-normalised shapes of a 1.5 kg board are of order 1/√kg
}

TEST_F(GltfExport, ObjSequenceHoldsTheDeformedPosedSurface)
{
    const fs::path dir = fs::path(*s_path).parent_path() / "objs";
    fs::remove_all(dir);
    const sm::Status s = sm::write_obj_sequence(*s_recording, dir.string());
    ASSERT_TRUE(s) << s.error().message();
    const size_t frames = s_recording->times.size();
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        (void)e;
        ++files;
    }
    EXPECT_EQ(files, frames); // and no temporary files left behind
    // The last frame's board vertices against body_deformed_point of the reference run.
    sm::World ref = load_world();
    step_to(ref, s_recording->times.back());
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06zu.obj", frames - 1);
    std::FILE* f = std::fopen((dir / name).c_str(), "r");
    ASSERT_NE(f, nullptr);
    const sm::Entity board = sm::find_body(ref, "board");
    const sm::TriangleMesh rest =
        sm::tessellate(sm::body_shape(ref, board), sm::default_export_def().tessellation);
    char line[256];
    bool in_board = false;
    size_t v = 0, compared = 0;
    while (std::fgets(line, sizeof line, f) != nullptr) {
        if (line[0] == 'o') {
            in_board = std::string(line) == "o board\n";
            v = 0;
        } else if (line[0] == 'v' && line[1] == ' ') {
            double x, y, z;
            ASSERT_EQ(std::sscanf(line, "v %lf %lf %lf", &x, &y, &z), 3);
            if (in_board && v % 31 == 0) {
                const sm::Vec3 e = sm::body_deformed_point(ref, board, rest.positions[v]);
                // %.9g text rounds to 9 significant digits (≤ 5e-9 relative); the exporter sums the
                // modes in another order than modal_displacement (≈ 1e-16 m, under the 1e-12 m floor).
                EXPECT_NEAR(x, e.x, 5e-9 * std::fabs(e.x) + 1e-12);
                EXPECT_NEAR(y, e.y, 5e-9 * std::fabs(e.y) + 1e-12);
                EXPECT_NEAR(z, e.z, 5e-9 * std::fabs(e.z) + 1e-12);
                ++compared;
            }
            ++v;
        }
    }
    std::fclose(f);
    EXPECT_GT(compared, 10u);
}

} // namespace
