// SPDX-License-Identifier: MIT
// The C API's deformation queries: meshes, deformed points and modal amplitudes, against the C++ API.
#include "supermodal/supermodal.h"
#include "supermodal/supermodal.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <string>
#include <vector>

namespace
{

const std::string k_board = std::string(SM_SOURCE_DIR) + "/tests/tools/scenes/modal_board.json";

double distance(const sm_vec3& a, const sm_vec3& b)
{
    return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

TEST(CapiDeform, RigidSphereMeshLiesOnTheSphereAtItsPose)
{
    sm_world_def wd = sm_world_def_default();
    sm_world* w = nullptr;
    ASSERT_EQ(sm_world_create(&wd, &w), SM_OK);
    sm_body_def def = sm_body_def_default();
    def.radii = sm_vec3{0.3, 0.3, 0.3};
    def.position = sm_vec3{1, 2, 3};
    sm_body b{};
    ASSERT_EQ(sm_world_create_body(w, &def, &b), SM_OK);
    size_t nv = 0, ni = 0;
    ASSERT_EQ(sm_body_get_mesh(w, b, 16, nullptr, 0, nullptr, 0, &nv, &ni), SM_OK) << "size query";
    ASSERT_GT(nv, 16u);
    ASSERT_EQ(ni % 3, 0u);
    std::vector<sm_vec3> positions(nv);
    std::vector<uint32_t> indices(ni);
    EXPECT_EQ(sm_body_get_mesh(w, b, 16, positions.data(), nv - 1, indices.data(), ni, &nv, &ni),
              SM_ERROR_BUFFER_TOO_SMALL);
    ASSERT_EQ(sm_body_get_mesh(w, b, 16, positions.data(), nv, indices.data(), ni, &nv, &ni), SM_OK);
    // Tessellation vertices sit on the analytic surface: |v − centre| = r to rounding (1e-12 m at
    // 0.3 m, a few ulps through the trigonometric parametrisation).
    for (const sm_vec3& v : positions)
        ASSERT_NEAR(distance(v, def.position), 0.3, 1e-12);
    for (uint32_t i : indices)
        ASSERT_LT(i, nv);
    sm_world_destroy(w);
}

TEST(CapiDeform, ModalBoardDeformsAsTheCppWorldSays)
{
    sm_world* c = nullptr;
    ASSERT_EQ(sm_world_create_from_file(k_board.c_str(), &c), SM_OK) << sm_last_error();
    supermodal::Result<supermodal::Scene> scene = supermodal::load_scene(k_board);
    ASSERT_TRUE(scene);
    supermodal::Result<supermodal::World> cpp = supermodal::build_world(*scene);
    ASSERT_TRUE(cpp);
    sm_body board{}, ball{};
    ASSERT_EQ(sm_world_find_body(c, "board", &board), SM_OK);
    ASSERT_EQ(sm_world_find_body(c, "ball", &ball), SM_OK);
    const supermodal::Entity cpp_board = supermodal::find_body(*cpp, "board");

    // Strike the board's tip upwards: it bends. The same impulse in both worlds.
    const sm_vec3 impulse{0, 2.0, 0}, tip{0.45, 0, 0};
    ASSERT_EQ(sm_body_apply_impulse(c, board, impulse, tip), SM_OK);
    supermodal::apply_linear_impulse(*cpp, cpp_board, {0, 2.0, 0}, {0.45, 0, 0});
    for (int i = 0; i < 20; ++i) { // 10 ms at dt = 0.5 ms: about a quarter period of the first bend mode
        ASSERT_EQ(sm_world_step(c), SM_OK);
        cpp->step();
    }
    uint64_t h = 0;
    ASSERT_EQ(sm_world_get_state_hash(c, &h), SM_OK);
    EXPECT_EQ(h, cpp->state_hash());

    size_t r = 0;
    ASSERT_EQ(sm_body_get_modal_amplitudes(c, board, nullptr, 0, &r), SM_OK);
    ASSERT_EQ(r, 6u); // the scene asks for 6 modes
    std::vector<double> q(r);
    ASSERT_EQ(sm_body_get_modal_amplitudes(c, board, q.data(), q.size(), &r), SM_OK);
    const supermodal::BodyModalState state = supermodal::body_modal_state(*cpp, cpp_board);
    for (size_t k = 0; k < r; ++k)
        EXPECT_EQ(q[k], state.amplitudes[k]) << k;
    ASSERT_EQ(sm_body_get_modal_amplitudes(c, ball, nullptr, 0, &r), SM_OK);
    EXPECT_EQ(r, 0u) << "a rigid body has no modes";

    // Deformed points: bit-identical to the C++ API's, and away from the rigid placement by the
    // bending (the rigid placement is body_deformed_point with the modal part taken out).
    const sm_vec3 rest[] = {{0.5, 0, 0}, {-0.5, 0, 0}, {0, 0.019, 0}};
    sm_vec3 out[3];
    ASSERT_EQ(sm_body_get_deformed_points(c, board, rest, 3, out), SM_OK);
    sm_vec3 pos{};
    sm_quat rot{};
    ASSERT_EQ(sm_body_get_pose(c, board, &pos, &rot), SM_OK);
    const supermodal::Quat qr{rot.w, rot.x, rot.y, rot.z};
    double max_bend = 0.0;
    for (int i = 0; i < 3; ++i) {
        const supermodal::Vec3 want =
            supermodal::body_deformed_point(*cpp, cpp_board, {rest[i].x, rest[i].y, rest[i].z});
        EXPECT_EQ(out[i].x, want.x);
        EXPECT_EQ(out[i].y, want.y);
        EXPECT_EQ(out[i].z, want.z);
        const supermodal::Vec3 rigid =
            supermodal::Vec3{pos.x, pos.y, pos.z} + supermodal::rotate(qr, {rest[i].x, rest[i].y, rest[i].z});
        max_bend = std::max(max_bend, distance(out[i], {rigid.x, rigid.y, rigid.z}));
    }
    // A 2 N·s strike on the 1.5 kg board bends it by 1.5 mm here (measured); 1e-5 m is far above rounding
    // and far below that, so only a missing modal part fails it.
    EXPECT_GT(max_bend, 1e-5);

    // The mesh follows the same field: its vertices are the deformed rest mesh.
    size_t nv = 0, ni = 0;
    ASSERT_EQ(sm_body_get_mesh(c, board, 12, nullptr, 0, nullptr, 0, &nv, &ni), SM_OK);
    std::vector<sm_vec3> positions(nv);
    std::vector<uint32_t> indices(ni);
    ASSERT_EQ(sm_body_get_mesh(c, board, 12, positions.data(), nv, indices.data(), ni, &nv, &ni), SM_OK);
    const supermodal::TriangleMesh rest_mesh =
        supermodal::tessellate(supermodal::body_shape(*cpp, cpp_board), 12);
    ASSERT_EQ(rest_mesh.positions.size(), nv);
    ASSERT_EQ(rest_mesh.indices.size(), ni);
    // The rest mesh and its lattice weights are cached after the first call: a later frame must still
    // follow the body (moved, bent differently), bit-identically to body_deformed_point.
    for (int frame = 0; frame < 2; ++frame) {
        for (size_t i = 0; i < nv; ++i) {
            const supermodal::Vec3 want =
                supermodal::body_deformed_point(*cpp, cpp_board, rest_mesh.positions[i]);
            ASSERT_EQ(positions[i].x, want.x) << i;
            ASSERT_EQ(positions[i].y, want.y) << i;
            ASSERT_EQ(positions[i].z, want.z) << i;
        }
        for (size_t i = 0; i < ni; ++i)
            ASSERT_EQ(indices[i], rest_mesh.indices[i]);
        const sm_vec3 before = positions[0];
        for (int i = 0; i < 7; ++i) {
            ASSERT_EQ(sm_world_step(c), SM_OK);
            cpp->step();
        }
        ASSERT_EQ(sm_body_get_mesh(c, board, 12, positions.data(), nv, indices.data(), ni, &nv, &ni), SM_OK);
        EXPECT_NE(distance(before, positions[0]), 0.0) << "the vertex moved with the body";
    }
    sm_world_destroy(c);
}

TEST(CapiDeform, BadArgumentsAreRefused)
{
    sm_world* c = nullptr;
    ASSERT_EQ(sm_world_create_from_file(k_board.c_str(), &c), SM_OK) << sm_last_error();
    sm_body board{};
    ASSERT_EQ(sm_world_find_body(c, "board", &board), SM_OK);
    sm_vec3 out[1] = {{7, 7, 7}};
    const sm_vec3 bad[1] = {{0, std::numeric_limits<double>::infinity(), 0}};
    EXPECT_EQ(sm_body_get_deformed_points(c, board, bad, 1, out), SM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(sm_last_error()).find("rest_points[0]"), std::string::npos) << sm_last_error();
    EXPECT_EQ(out[0].x, 7.0) << "nothing written on failure";
    EXPECT_EQ(sm_body_get_deformed_points(c, board, nullptr, 1, out), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_body_get_deformed_points(c, board, nullptr, 0, nullptr), SM_OK) << "nothing asked";
    size_t nv = 0, ni = 0;
    EXPECT_EQ(sm_body_get_mesh(c, board, 12, nullptr, 0, nullptr, 0, nullptr, &ni), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_body_get_mesh(c, board, 12, nullptr, 5, nullptr, 0, &nv, &ni), SM_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(sm_body_get_mesh(c, sm_body{0}, 12, nullptr, 0, nullptr, 0, &nv, &ni), SM_ERROR_INVALID_HANDLE);
    EXPECT_EQ(sm_body_get_modal_amplitudes(c, board, nullptr, 0, nullptr), SM_ERROR_NULL_ARGUMENT);
    sm_world_destroy(c);
}

} // namespace
