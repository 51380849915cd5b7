// SPDX-License-Identifier: MIT
// The C API's worlds: loading, errors, stepping, determinism against the C++ world, snapshots.
#include "supermodal/supermodal.h"
#include "supermodal/supermodal.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <string>

namespace
{

const std::string k_demo = std::string(SM_SOURCE_DIR) + "/samples/demo.json";
constexpr double k_nan = std::numeric_limits<double>::quiet_NaN();
constexpr double k_inf = std::numeric_limits<double>::infinity();

sm_world* load(const std::string& path)
{
    sm_world* w = nullptr;
    EXPECT_EQ(sm_world_create_from_file(path.c_str(), &w), SM_OK) << sm_last_error();
    return w;
}

uint64_t hash(const sm_world* w)
{
    uint64_t h = 0;
    EXPECT_EQ(sm_world_get_state_hash(w, &h), SM_OK);
    return h;
}

TEST(CapiWorld, SameHashAsTheCppWorldStepByStep)
{
    sm_world* c = load(k_demo);
    ASSERT_NE(c, nullptr);
    supermodal::Result<supermodal::Scene> scene = supermodal::load_scene(k_demo);
    ASSERT_TRUE(scene);
    supermodal::Result<supermodal::World> cpp = supermodal::build_world(*scene);
    ASSERT_TRUE(cpp);
    // 750 steps of 2 ms: the board lands at about 0.6 s, the ball first bounces near 1 s: contact is in it;
    // bit-identical hashes are the determinism contract, so no tolerance.
    for (int i = 0; i < 750; ++i) {
        ASSERT_EQ(sm_world_step(c), SM_OK);
        cpp->step();
        if (i % 50 == 49) {
            ASSERT_EQ(hash(c), cpp->state_hash()) << "step " << i;
        }
    }
    uint64_t steps = 0;
    double time = 0.0;
    ASSERT_EQ(sm_world_get_step_count(c, &steps), SM_OK);
    ASSERT_EQ(sm_world_get_time(c, &time), SM_OK);
    EXPECT_EQ(steps, 750u);
    EXPECT_EQ(time, cpp->time());
    sm_world_destroy(c);
}

TEST(CapiWorld, BadJsonNamesTheJsonPointer)
{
    const char* json = R"({ "bodies": [ { "name": "a", "shape": { "type": "superquadric",
                          "radii": [-1, 0.5, 0.5] } } ] })";
    sm_world* w = nullptr;
    EXPECT_EQ(sm_world_create_from_json(json, &w), SM_ERROR_SCENE);
    EXPECT_EQ(w, nullptr) << "a failed create leaves the out-param alone";
    const std::string message = sm_last_error();
    EXPECT_NE(message.find("/bodies/0/shape/radii/0"), std::string::npos) << message;
    EXPECT_NE(message.find("<string>"), std::string::npos) << message;

    EXPECT_EQ(sm_world_create_from_json("{ not json", &w), SM_ERROR_SCENE);
    EXPECT_STRNE(sm_last_error(), "");
    EXPECT_EQ(w, nullptr);
}

TEST(CapiWorld, MissingFileNamesTheFile)
{
    sm_world* w = nullptr;
    EXPECT_EQ(sm_world_create_from_file("/nonexistent/scene.json", &w), SM_ERROR_SCENE);
    EXPECT_NE(std::string(sm_last_error()).find("/nonexistent/scene.json"), std::string::npos)
        << sm_last_error();
    EXPECT_EQ(w, nullptr);
}

TEST(CapiWorld, SuccessClearsTheLastError)
{
    sm_world* w = nullptr;
    ASSERT_EQ(sm_world_create_from_file(nullptr, &w), SM_ERROR_NULL_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("path"), std::string::npos);
    w = load(k_demo);
    EXPECT_STREQ(sm_last_error(), "");
    sm_world_destroy(w);
}

TEST(CapiWorld, NullWorldsAndOutParamsAreRefused)
{
    sm_world_def def = sm_world_def_default();
    uint64_t u = 0;
    double d = 0.0;
    int steps = 0;
    sm_snapshot* snap = nullptr;
    EXPECT_EQ(sm_world_step(nullptr), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_advance(nullptr, 0.1, &steps), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_get_state_hash(nullptr, &u), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_get_time(nullptr, &d), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_get_step_count(nullptr, &u), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_get_interpolation_alpha(nullptr, &d), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_get_def(nullptr, &def), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_set_def(nullptr, &def), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_set_gravity(nullptr, sm_vec3{0, 0, 0}), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_snapshot(nullptr, &snap), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_restore(nullptr, snap), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_create(nullptr, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_create_from_json(nullptr, nullptr), SM_ERROR_NULL_ARGUMENT);
    sm_world_destroy(nullptr); // like free(NULL)
    sm_snapshot_destroy(nullptr);

    sm_world* w = load(k_demo);
    EXPECT_EQ(sm_world_get_state_hash(w, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_get_time(w, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_get_def(w, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_set_def(w, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_snapshot(w, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_restore(w, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_advance(w, 0.004, nullptr), SM_OK) << "out_steps is optional";
    // A pointer that is not a world (here: a zeroed block of the right size) is caught by the tag.
    alignas(64) unsigned char junk[4096] = {};
    EXPECT_EQ(sm_world_step(reinterpret_cast<sm_world*>(junk)), SM_ERROR_INVALID_HANDLE);
    sm_world_destroy(w);
}

TEST(CapiWorld, NonFiniteInputsAreRefusedAndChangeNothing)
{
    sm_world* w = load(k_demo);
    ASSERT_EQ(sm_world_step(w), SM_OK);
    const uint64_t before = hash(w);
    int steps = -1;
    EXPECT_EQ(sm_world_advance(w, k_nan, &steps), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_world_advance(w, k_inf, &steps), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_world_advance(w, -1.0, &steps), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(steps, -1);
    EXPECT_EQ(sm_world_set_gravity(w, sm_vec3{0, k_nan, 0}), SM_ERROR_INVALID_ARGUMENT);
    sm_world_def def = sm_world_def_default();
    def.gravity.x = k_inf;
    EXPECT_EQ(sm_world_set_def(w, &def), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("gravity"), std::string::npos) << sm_last_error();
    EXPECT_EQ(hash(w), before);
    sm_world_def now{};
    ASSERT_EQ(sm_world_get_def(w, &now), SM_OK);
    EXPECT_EQ(now.gravity.y, -9.81);
    sm_world_destroy(w);
}

TEST(CapiWorld, AdvanceRunsWholeStepsAndLeavesAlpha)
{
    sm_world* w = load(k_demo); // dt = 2 ms
    int steps = 0;
    ASSERT_EQ(sm_world_advance(w, 0.005, &steps), SM_OK);
    EXPECT_EQ(steps, 2);
    double alpha = -1.0;
    ASSERT_EQ(sm_world_get_interpolation_alpha(w, &alpha), SM_OK);
    // 1 ms of 2 ms left over; the accumulator's subtractions round at 1e-16 s.
    EXPECT_NEAR(alpha, 0.5, 1e-12);
    sm_world_destroy(w);
}

TEST(CapiWorld, SettingsChangeBetweenStepsWithinTheirRules)
{
    sm_world_def def = sm_world_def_default();
    def.gravity = sm_vec3{0, 0, 0};
    sm_world* w = nullptr;
    ASSERT_EQ(sm_world_create(&def, &w), SM_OK);
    def.dt = 0.001; // before the first step: allowed
    ASSERT_EQ(sm_world_set_def(w, &def), SM_OK) << sm_last_error();
    ASSERT_EQ(sm_world_step(w), SM_OK);
    double t = 0.0;
    ASSERT_EQ(sm_world_get_time(w, &t), SM_OK);
    EXPECT_EQ(t, 0.001);
    def.dt = 0.002;
    EXPECT_EQ(sm_world_set_def(w, &def), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("dt"), std::string::npos);
    def.dt = 0.001;
    def.thread_count = 2;
    EXPECT_EQ(sm_world_set_def(w, &def), SM_ERROR_INVALID_ARGUMENT);
    def.thread_count = 1;
    def.substep_count = 4;
    def.gravity = sm_vec3{1, 2, 3};
    EXPECT_EQ(def.split_islands, 0);
    def.split_islands = 1;
    ASSERT_EQ(sm_world_set_def(w, &def), SM_OK);
    sm_world_def now{};
    ASSERT_EQ(sm_world_get_def(w, &now), SM_OK);
    EXPECT_EQ(now.substep_count, 4);
    EXPECT_EQ(now.split_islands, 1);
    EXPECT_EQ(now.gravity.z, 3.0);
    def.substep_count = 0;
    EXPECT_EQ(sm_world_create(&def, &w), SM_ERROR_INVALID_ARGUMENT) << "checked like WorldDef";
    sm_world_destroy(w);
}

TEST(CapiWorld, SnapshotRestoreIsBitIdentical)
{
    sm_world* w = load(k_demo);
    for (int i = 0; i < 600; ++i)
        ASSERT_EQ(sm_world_step(w), SM_OK);
    // The board (1.9 cm half-thickness) lies on the ground by 1.2 s: contact anchors are in the snapshot.
    sm_body board{};
    ASSERT_EQ(sm_world_find_body(w, "board", &board), SM_OK);
    sm_vec3 p{};
    sm_quat q{};
    ASSERT_EQ(sm_body_get_pose(w, board, &p, &q), SM_OK);
    ASSERT_LT(p.y, 0.025);
    sm_snapshot* snap = nullptr;
    ASSERT_EQ(sm_world_snapshot(w, &snap), SM_OK);
    const uint64_t at_snapshot = hash(w);
    for (int i = 0; i < 300; ++i)
        ASSERT_EQ(sm_world_step(w), SM_OK);
    const uint64_t first = hash(w);
    ASSERT_EQ(sm_world_restore(w, snap), SM_OK) << sm_last_error();
    EXPECT_EQ(hash(w), at_snapshot);
    for (int i = 0; i < 300; ++i)
        ASSERT_EQ(sm_world_step(w), SM_OK);
    EXPECT_EQ(hash(w), first);

    // A snapshot of other bodies does not fit.
    sm_body_def def = sm_body_def_default();
    def.position = sm_vec3{5, 5, 5};
    sm_body extra{};
    ASSERT_EQ(sm_world_create_body(w, &def, &extra), SM_OK);
    const uint64_t with_extra = hash(w);
    EXPECT_EQ(sm_world_restore(w, snap), SM_ERROR_SNAPSHOT_MISMATCH);
    EXPECT_NE(std::string(sm_last_error()).find("created or destroyed"), std::string::npos)
        << sm_last_error();
    EXPECT_EQ(hash(w), with_extra);
    sm_snapshot_destroy(snap);
    sm_world_destroy(w);
}

TEST(CapiWorld, StatusStringsNameEveryCode)
{
    EXPECT_STREQ(sm_status_string(SM_OK), "SM_OK");
    EXPECT_STREQ(sm_status_string(SM_ERROR_SCENE), "SM_ERROR_SCENE");
    EXPECT_STREQ(sm_status_string(SM_ERROR_INTERNAL), "SM_ERROR_INTERNAL");
    // SM_STATUS_MAX_ENUM makes every int a valid sm_status, so a stray code from C is defined here too.
    EXPECT_STREQ(sm_status_string(static_cast<sm_status>(99)), "SM_UNKNOWN_STATUS");
    EXPECT_STREQ(sm_status_string(SM_STATUS_MAX_ENUM), "SM_UNKNOWN_STATUS");
}

} // namespace
