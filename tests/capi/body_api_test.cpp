// SPDX-License-Identifier: MIT
// The C API's bodies: creation round-trips, handles, buffers, forces, refused inputs.
#include "supermodal/supermodal.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace
{

const std::string k_demo = std::string(SM_SOURCE_DIR) + "/samples/demo.json";
constexpr double k_nan = std::numeric_limits<double>::quiet_NaN();

sm_world* zero_gravity_world()
{
    sm_world_def def = sm_world_def_default();
    def.gravity = sm_vec3{0, 0, 0};
    sm_world* w = nullptr;
    EXPECT_EQ(sm_world_create(&def, &w), SM_OK) << sm_last_error();
    return w;
}

TEST(CapiBody, CreateQueryRoundTrip)
{
    sm_world* w = zero_gravity_world();
    sm_body_def def = sm_body_def_default();
    def.name = "crate";
    def.radii = sm_vec3{0.2, 0.3, 0.4};
    def.epsilon1 = def.epsilon2 = 0.3;
    def.position = sm_vec3{1, 2, 3};
    def.orientation = sm_quat{0, 0, 1, 0}; // half turn about y
    def.linear_velocity = sm_vec3{0.5, 0, 0};
    def.angular_velocity = sm_vec3{0, 0, 2};
    sm_body b{};
    ASSERT_EQ(sm_world_create_body(w, &def, &b), SM_OK) << sm_last_error();
    EXPECT_NE(b.id, 0u);
    EXPECT_EQ(sm_body_is_valid(w, b), 1);

    // An untapered superquadric's centre of mass is its origin: the pose comes back exactly.
    sm_vec3 p{};
    sm_quat q{};
    ASSERT_EQ(sm_body_get_pose(w, b, &p, &q), SM_OK);
    EXPECT_EQ(p.x, 1.0);
    EXPECT_EQ(p.y, 2.0);
    EXPECT_EQ(p.z, 3.0);
    EXPECT_EQ(q.w, 0.0);
    EXPECT_EQ(q.y, 1.0);
    sm_vec3 v{}, omega{};
    ASSERT_EQ(sm_body_get_velocity(w, b, &v, &omega), SM_OK);
    EXPECT_EQ(v.x, 0.5);
    EXPECT_EQ(omega.z, 2.0);
    sm_motion motion = SM_MOTION_STATIC;
    ASSERT_EQ(sm_body_get_motion(w, b, &motion), SM_OK);
    EXPECT_EQ(motion, SM_MOTION_DYNAMIC);
    double mass = 0.0;
    ASSERT_EQ(sm_body_get_mass(w, b, &mass), SM_OK);
    EXPECT_GT(mass, 0.0);

    char name[16];
    size_t length = 0;
    ASSERT_EQ(sm_body_get_name(w, b, name, sizeof name, &length), SM_OK);
    EXPECT_STREQ(name, "crate");
    EXPECT_EQ(length, 5u);
    EXPECT_EQ(sm_body_get_name(w, b, nullptr, 0, &length), SM_OK) << "size query";
    char tiny[3];
    EXPECT_EQ(sm_body_get_name(w, b, tiny, sizeof tiny, &length), SM_ERROR_BUFFER_TOO_SMALL);
    EXPECT_STREQ(tiny, "cr");

    sm_body found{};
    ASSERT_EQ(sm_world_find_body(w, "crate", &found), SM_OK);
    EXPECT_EQ(found.id, b.id);
    EXPECT_EQ(sm_world_find_body(w, "nothing", &found), SM_ERROR_NOT_FOUND);
    EXPECT_NE(std::string(sm_last_error()).find("nothing"), std::string::npos);
    sm_world_destroy(w);
}

TEST(CapiBody, BodiesComeInSceneOrderAndBuffersReportShortfall)
{
    sm_world* w = nullptr;
    ASSERT_EQ(sm_world_create_from_file(k_demo.c_str(), &w), SM_OK) << sm_last_error();
    size_t count = 0;
    ASSERT_EQ(sm_world_get_body_count(w, &count), SM_OK);
    ASSERT_EQ(count, 4u);
    ASSERT_EQ(sm_world_get_bodies(w, nullptr, 0, &count), SM_OK) << "size query";
    EXPECT_EQ(count, 4u);
    std::vector<sm_body> bodies(count);
    ASSERT_EQ(sm_world_get_bodies(w, bodies.data(), bodies.size(), &count), SM_OK);
    const char* names[] = {"ground", "ball", "board", "egg"};
    for (size_t i = 0; i < count; ++i) {
        char name[32];
        ASSERT_EQ(sm_body_get_name(w, bodies[i], name, sizeof name, nullptr), SM_OK);
        EXPECT_STREQ(name, names[i]);
    }
    sm_body first{};
    EXPECT_EQ(sm_world_get_bodies(w, &first, 1, &count), SM_ERROR_BUFFER_TOO_SMALL);
    EXPECT_EQ(count, 4u);
    EXPECT_EQ(first.id, bodies[0].id);
    sm_world_destroy(w);
}

TEST(CapiBody, StaleAndNullHandlesAreRefused)
{
    sm_world* w = zero_gravity_world();
    sm_body_def def = sm_body_def_default();
    sm_body b{};
    ASSERT_EQ(sm_world_create_body(w, &def, &b), SM_OK);
    ASSERT_EQ(sm_world_destroy_body(w, b), SM_OK);
    EXPECT_EQ(sm_body_is_valid(w, b), 0);
    sm_vec3 p{};
    sm_quat q{};
    EXPECT_EQ(sm_body_get_pose(w, b, &p, &q), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_world_destroy_body(w, b), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_body_apply_force_at_center(w, b, sm_vec3{1, 0, 0}), SM_ERROR_INVALID_HANDLE);
    // The slot is reused with a new generation: the old handle stays stale.
    sm_body again{};
    ASSERT_EQ(sm_world_create_body(w, &def, &again), SM_OK);
    EXPECT_NE(again.id, b.id);
    EXPECT_EQ(sm_body_is_valid(w, b), 0);
    EXPECT_EQ(sm_body_is_valid(w, again), 1);

    EXPECT_EQ(sm_body_get_pose(w, sm_body{0}, &p, &q), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_body_get_pose(w, sm_body{~uint64_t{0}}, &p, &q), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_body_get_pose(nullptr, again, &p, &q), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_body_get_pose(w, again, nullptr, &q), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_body_get_velocity(w, again, &p, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_create_body(w, nullptr, &again), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_world_find_body(w, nullptr, &again), SM_ERROR_NULL_ARGUMENT);
    size_t count = 0;
    EXPECT_EQ(sm_world_get_bodies(w, nullptr, 4, &count), SM_ERROR_NULL_ARGUMENT) << "NULL with capacity > 0";
    EXPECT_EQ(sm_world_get_bodies(w, nullptr, 0, nullptr), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_body_is_valid(nullptr, again), 0);
    sm_world_destroy(w);
}

TEST(CapiBody, InvalidDefsAreRefusedWithTheField)
{
    sm_world* w = zero_gravity_world();
    sm_body out{};
    sm_body_def def = sm_body_def_default();
    def.radii.y = -1.0;
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("radii"), std::string::npos) << sm_last_error();

    def = sm_body_def_default();
    const int seven = 7; // what a C caller may store; static_cast<sm_motion>(7) would be UB in C++
    std::memcpy(&def.motion, &seven, sizeof seven);
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("motion"), std::string::npos);

    def = sm_body_def_default();
    def.position.z = k_nan;
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);
    def = sm_body_def_default();
    def.young = k_nan; // ignored by a rigid body, refused anyway: one rule for every field
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);

    def = sm_body_def_default();
    def.shape = SM_SHAPE_PLANE; // a plane must be static
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);
    def.motion = SM_MOTION_STATIC;
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_OK) << sm_last_error();

    def = sm_body_def_default();
    def.modal_mode_count = 300;
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);
    def.modal_mode_count = 4;
    def.motion = SM_MOTION_KINEMATIC;
    EXPECT_EQ(sm_world_create_body(w, &def, &out), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("modal"), std::string::npos) << sm_last_error();
    size_t count = 0;
    ASSERT_EQ(sm_world_get_body_count(w, &count), SM_OK);
    EXPECT_EQ(count, 1u) << "only the static plane was made";
    sm_world_destroy(w);
}

TEST(CapiBody, ForcesAndImpulsesMoveTheBodyAsNewtonSays)
{
    sm_world* w = zero_gravity_world();
    sm_body_def def = sm_body_def_default();
    sm_body b{};
    ASSERT_EQ(sm_world_create_body(w, &def, &b), SM_OK);
    double m = 0.0;
    ASSERT_EQ(sm_body_get_mass(w, b, &m), SM_OK);
    // Sphere r = 0.5 m, ρ = 1000 kg/m³: m = 4/3 π r³ ρ; the closed form is exact to rounding.
    EXPECT_NEAR(m, 4.0 / 3.0 * std::numbers::pi * 0.125 * 1000.0, 1e-9 * m);

    // An impulse through the centre changes the velocity by J/m at once.
    ASSERT_EQ(sm_body_apply_impulse(w, b, sm_vec3{m * 2.0, 0, 0}, sm_vec3{0, 0, 0}), SM_OK);
    sm_vec3 v{}, omega{};
    ASSERT_EQ(sm_body_get_velocity(w, b, &v, &omega), SM_OK);
    EXPECT_NEAR(v.x, 2.0, 1e-12);
    EXPECT_EQ(omega.x, 0.0);
    // A force held over one step adds F/m · dt (semi-implicit Euler is exact for a constant force).
    ASSERT_EQ(sm_body_apply_force_at_center(w, b, sm_vec3{0, m * 3.0, 0}), SM_OK);
    ASSERT_EQ(sm_world_step(w), SM_OK);
    ASSERT_EQ(sm_body_get_velocity(w, b, &v, &omega), SM_OK);
    EXPECT_NEAR(v.y, 3.0 * 0.002, 1e-12);
    // Forces last one step only.
    ASSERT_EQ(sm_world_step(w), SM_OK);
    ASSERT_EQ(sm_body_get_velocity(w, b, &v, &omega), SM_OK);
    EXPECT_NEAR(v.y, 3.0 * 0.002, 1e-12);
    // A torque spins it about that axis; an off-centre force also turns it.
    ASSERT_EQ(sm_body_apply_torque(w, b, sm_vec3{0, 0, 1}), SM_OK);
    ASSERT_EQ(sm_body_apply_force(w, b, sm_vec3{0, 1, 0}, sm_vec3{0.5, 0, 0}), SM_OK);
    ASSERT_EQ(sm_body_apply_angular_impulse(w, b, sm_vec3{0, 0, 0.01}), SM_OK);
    ASSERT_EQ(sm_world_step(w), SM_OK);
    ASSERT_EQ(sm_body_get_velocity(w, b, &v, &omega), SM_OK);
    EXPECT_GT(omega.z, 0.0);

    ASSERT_EQ(sm_body_set_velocity(w, b, sm_vec3{0, 0, 0}, sm_vec3{0, 0, 0}), SM_OK);
    ASSERT_EQ(sm_body_set_position(w, b, sm_vec3{4, 5, 6}), SM_OK);
    ASSERT_EQ(sm_body_set_orientation(w, b, sm_quat{2, 0, 0, 0}), SM_OK); // normalised on the way in
    sm_vec3 p{};
    sm_quat q{};
    ASSERT_EQ(sm_body_get_pose(w, b, &p, &q), SM_OK);
    EXPECT_EQ(p.y, 5.0);
    EXPECT_EQ(q.w, 1.0);
    sm_world_destroy(w);
}

TEST(CapiBody, NonFiniteBodyInputsAreRefusedAndChangeNothing)
{
    sm_world* w = zero_gravity_world();
    sm_body_def def = sm_body_def_default();
    sm_body b{};
    ASSERT_EQ(sm_world_create_body(w, &def, &b), SM_OK);
    uint64_t before = 0, after = 0;
    ASSERT_EQ(sm_world_get_state_hash(w, &before), SM_OK);
    const sm_vec3 bad{0, k_nan, 0};
    const sm_vec3 good{0, 1, 0};
    EXPECT_EQ(sm_body_set_position(w, b, bad), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_body_set_orientation(w, b, sm_quat{k_nan, 0, 0, 0}), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_body_set_orientation(w, b, sm_quat{0, 0, 0, 0}), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_body_set_velocity(w, b, good, bad), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("angular"), std::string::npos);
    EXPECT_EQ(sm_body_apply_force(w, b, good, bad), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("point"), std::string::npos);
    EXPECT_EQ(sm_body_apply_force_at_center(w, b, bad), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_body_apply_torque(w, b, bad), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_body_apply_impulse(w, b, bad, good), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(sm_body_apply_angular_impulse(w, b, bad), SM_ERROR_INVALID_ARGUMENT);
    ASSERT_EQ(sm_world_get_state_hash(w, &after), SM_OK);
    EXPECT_EQ(after, before);
    // Nothing non-finite got in: a step later the body is where it was and at rest.
    ASSERT_EQ(sm_world_step(w), SM_OK);
    sm_vec3 p{};
    sm_quat q{};
    ASSERT_EQ(sm_body_get_pose(w, b, &p, &q), SM_OK);
    EXPECT_EQ(p.y, 0.0);
    sm_world_destroy(w);
}

} // namespace
