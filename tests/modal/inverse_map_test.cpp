// Tests for the inside-outside test of a deformed modal body (engine/src/modal/inverse_map.cpp through
// body_point_test): points are mapped back to the rest shape by Newton's method on the deformation field.
#include "modal_scenes.h"
#include "supermodal/body.h"
#include "supermodal/geometry.h"
#include "supermodal/modal.h"
#include "supermodal/world.h"

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace sm = supermodal;
using sm::test::k_board_thickness;

namespace
{

// The board (8×1×1, 12 modes) at the origin, bent in its first flatwise mode so the centre of its top
// face rises by 5 mm. Returns that mode's index.
sm::Entity bent_board(sm::World& world)
{
    sm::BodyDef def = sm::default_body_def();
    def.shape = sm::test::board_def({0, 0, 0}).shape;
    def.density = 450.0;
    def.modal.enabled = true;
    def.modal.mode_count = 12;
    def.modal.lattice = {8, 1, 1}; // the lattice the figures here were measured on
    def.young = 11e9;
    const sm::Entity board = sm::create_body(world, def);
    const sm::ModalBasis& basis = *sm::body_modal_basis(world, board);
    const sm::Vec3 top{0, k_board_thickness / 2, 0};
    for (int k = 0; k < basis.mode_count; ++k) {
        std::vector<double> unit(basis.mode_count, 0.0);
        unit[k] = 1.0;
        const sm::Vec3 u = sm::modal_displacement(basis, top, unit);
        if (std::abs(u.y) > 10.0 * std::max(std::abs(u.x), std::abs(u.z))) { // flatwise bending
            unit[k] = 5e-3 / u.y;
            EXPECT_TRUE(
                sm::set_body_modal_state(world, board, unit, std::vector<double>(unit.size(), 0.0)).ok());
            return board;
        }
    }
    ADD_FAILURE() << "no flatwise mode";
    return board;
}

} // namespace

TEST(ModalInverseMap, PointInsideTheDeformedButOutsideTheRestShapeIsInside)
{
    sm::World world(sm::default_world_def());
    const sm::Entity board = bent_board(world);
    const double c = k_board_thickness / 2;
    const sm::ShapeDef& shape = sm::test::board_def({0, 0, 0}).shape;
    // 2.5 mm above the rest top face: outside the rest shape, 2.5 mm below the lifted face.
    const sm::Vec3 above{0.0, c + 2.5e-3, 0.0};
    EXPECT_GT(sm::contact_measure(shape, above), 0.0);
    const sm::BodyPointTest t = sm::body_point_test(world, board, above);
    ASSERT_TRUE(t.inside);
    // It came from 2.5 mm below the rest top face (the field is smooth: ∇u ~ 1e-2 over mm).
    EXPECT_NEAR(t.rest_point.y, c - 2.5e-3, 1e-4);
    // Depth: the lifted face is 2.5 mm away along y; the measure/gradient depth of this near-box
    // superquadric (ε = 0.05) is the distance to a few %: 10%.
    EXPECT_NEAR(t.depth, 2.5e-3, 0.1 * 2.5e-3);
    EXPECT_GT(t.normal.y, 0.99);
    // And it is where the deformed body says the material point is.
    const sm::Vec3 back = sm::body_deformed_point(world, board, t.rest_point);
    EXPECT_LT(length(back - above), 1e-9);
    // 2.5 mm above the rest bottom face: inside the rest shape, but the bottom face rose by ~5 mm.
    const sm::Vec3 low{0.0, -c + 2.5e-3, 0.0};
    EXPECT_LT(sm::contact_measure(shape, low), 0.0);
    EXPECT_FALSE(sm::body_point_test(world, board, low).inside);
}

TEST(ModalInverseMap, AtRestAndRigidTheShapeDecides)
{
    sm::World world(sm::default_world_def());
    const sm::Entity board = bent_board(world);
    std::vector<double> zero(12, 0.0);
    ASSERT_TRUE(sm::set_body_modal_state(world, board, zero, zero).ok());
    const double c = k_board_thickness / 2;
    EXPECT_FALSE(sm::body_point_test(world, board, {0.0, c + 2.5e-3, 0.0}).inside);
    const sm::BodyPointTest t = sm::body_point_test(world, board, {0.0, c - 1e-3, 0.0});
    ASSERT_TRUE(t.inside);
    EXPECT_NEAR(t.depth, 1e-3, 1e-4);
    EXPECT_GT(t.normal.y, 0.99);
}
