// Tests for ContactDef::deformed_inside_test (contact/narrowphase.cpp with world/modal_system.cpp): sampled
// points tested against a modal body meet its deformed shape, so both bodies' dents count.
#include "contact/narrowphase.h"
#include "modal/full_model.h"
#include "modal/inverse_map.h"
#include "supermodal/body.h"
#include "supermodal/contact.h"
#include "supermodal/modal.h"
#include "supermodal/scene.h"
#include "supermodal/world.h"
#include "support/world_fixture.h"
#include "world/modal_system.h"
#include "world/world_impl.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace sm = supermodal;

namespace
{

// Two identical soft balls (radius 0.1 m, E 1 MPa, ν 0.3, 1000 kg/m³) side by side along x in zero
// gravity, pushed together by `load` [N] through their centres (a body force: it does not deform them,
// so each is held by inertia relief, a uniform body force, against the contact load alone).
constexpr double k_ball_radius = 0.1, k_ball_young = 1e6, k_ball_poisson = 0.3;

struct Press {
    double dent_a = 0.0;    ///< How far A's pole facing B moved towards A's centre [m].
    double dent_b = 0.0;    ///< Same for B [m].
    double gap = 0.0;       ///< Distance between the two deformed poles along x [m]; < 0: overlap.
    double force = 0.0;     ///< Contact force along x at the end [N].
    double max_speed = 0.0; ///< Largest body speed over the last 50 steps [m/s].
};

sm::BodyDef ball_def(double x, int modes, int cells, bool correction = false)
{
    sm::BodyDef def = sm::default_body_def();
    def.shape.radii = {k_ball_radius, k_ball_radius, k_ball_radius};
    def.position = {x, 0.0, 0.0};
    def.young = k_ball_young;
    def.poisson = k_ball_poisson;
    def.modal.enabled = true;
    def.modal.mode_count = modes;
    def.modal.lattice = {cells, cells, cells};
    def.modal.damping_ratio = 0.5; // settles the dents within a few periods
    def.modal.static_correction = correction;
    return def;
}

Press press_balls(double load, bool deformed_test, int modes, int cells, int steps, bool correction = false)
{
    sm::WorldDef wdef = sm::default_world_def();
    wdef.gravity = {};
    wdef.dt = 1e-3;
    wdef.contact.deformed_inside_test = deformed_test;
    wdef.contact.sample_spacing = 2.5e-3;   // a few samples across the ≈1 cm contact radius
    wdef.contact.soft.frequency_hz = 300.0; // a stiff spring: its give stays small against the dents
    wdef.contact.max_samples_per_body = 40000;
    sm::World world(wdef);
    const sm::Entity a = sm::create_body(world, ball_def(-k_ball_radius, modes, cells, correction));
    const sm::Entity b = sm::create_body(world, ball_def(k_ball_radius, modes, cells, correction));
    Press out;
    for (int i = 0; i < steps; ++i) {
        sm::apply_force_at_center(world, a, {load, 0.0, 0.0});
        sm::apply_force_at_center(world, b, {-load, 0.0, 0.0});
        world.step();
        if (i >= steps - 50)
            out.max_speed = std::max({out.max_speed, sm::length(sm::body_linear_velocity(world, a)),
                                      sm::length(sm::body_linear_velocity(world, b))});
    }
    const sm::Vec3 pole_a = sm::body_deformed_point(world, a, {k_ball_radius, 0.0, 0.0});
    const sm::Vec3 pole_b = sm::body_deformed_point(world, b, {-k_ball_radius, 0.0, 0.0});
    const sm::Vec3 centre_a = sm::body_position(world, a), centre_b = sm::body_position(world, b);
    out.dent_a = k_ball_radius - (pole_a.x - centre_a.x);
    out.dent_b = k_ball_radius - (centre_b.x - pole_b.x);
    out.gap = pole_b.x - pole_a.x;
    for (const sm::ContactInfo& c : sm::world_contacts(world))
        out.force += std::abs(c.force_on_a.x);
    return out;
}

// Hertz: two balls of radius R and modulus E*: F = (4/3)·E*·√(R*)·d^1.5, R* = R/2, E* = E/(2(1 − ν²)).
double hertz_force(double approach)
{
    const double e_star = k_ball_young / (2.0 * (1.0 - k_ball_poisson * k_ball_poisson));
    return 4.0 / 3.0 * e_star * std::sqrt(k_ball_radius / 2.0) * std::pow(approach, 1.5);
}

} // namespace

TEST(DeformedContact, TwoSoftBallsPressedTogetherDentAlikeAndMeet)
{
    // Each direction of the sampled pair now meets the other ball's dented surface, so the deformed
    // shapes touch (they overlap by the contact spring's give) and the two dents match. Over loads of
    // 5–40 N, after 0.4 s (ζ = 0.5 settles every mode):
    for (const double load : {5.0, 10.0, 20.0, 40.0}) {
        SCOPED_TRACE(load);
        const Press p = press_balls(load, true, 60, 4, 400);
        const double approach = p.dent_a + p.dent_b;
        std::printf("load %4.1f N: dents %.4f / %.4f mm, poles' gap %+.4f mm, contact force %.3f N, Hertz "
                    "force at that approach %.3f N\n",
                    load, 1e3 * p.dent_a, 1e3 * p.dent_b, 1e3 * p.gap, p.force, hertz_force(approach));
        // At rest, so the contact carries the load (measured within 1.5%: the stiff spring keeps the
        // surface modes humming at ≈1e-5 of the load's work).
        EXPECT_LT(p.max_speed, 1e-3);
        EXPECT_NEAR(p.force, load, 0.03 * load);
        // Symmetric dents: the soft solver takes the pair's rows one after another, and the two balls'
        // samples mirror each other only to round-off (measured: equal to 0.03%). Tolerance 2%.
        EXPECT_GT(p.dent_a, 0.0);
        EXPECT_NEAR(p.dent_a, p.dent_b, 0.02 * approach / 2.0);
        // The deformed poles overlap by the soft spring's give (k = m_eff·(2π·300 Hz)² ≈ 7e6 N/m: 6 µm at
        // 40 N) and the samples' gap (the poles fall between samples spaced 2.5 mm); measured 0.04–0.05
        // mm. Bound 0.1 mm. They never stand apart.
        EXPECT_LT(p.gap, 0.0);
        EXPECT_GT(p.gap, -1e-4);
        // Hertz (F = (4/3)·E*·√R*·d^1.5) asks a far larger dent: the 4³ lattice of 20-node cells (5 cm)
        // and 60 modes cannot form the ≈1 cm contact patch, so the model is much stiffer (the approach is
        // linear in the load, 0.017 mm/N; measured Hertz force at that approach: 2.5–7% of the load).
        // A Ritz model can only err stiff: asserted below the load.
        EXPECT_LT(hertz_force(approach), load);
    }
    // Without the deformed test each ball's samples meet the other's rest shape: the contact stops the
    // balls a dent early and the deformed poles stand apart by about one dent (measured 0.30 mm, dent
    // 0.34 mm).
    const Press off = press_balls(40.0, false, 60, 4, 400);
    std::printf("rest test, 40 N: dents %.4f / %.4f mm, poles' gap %+.4f mm\n", 1e3 * off.dent_a,
                1e3 * off.dent_b, 1e3 * off.gap);
    EXPECT_GT(off.gap, 0.5 * off.dent_b);
}

// With the static correction on both balls (docs/modal.md "Static correction in the world"), the
// deformed test inverts it too, so each ball's samples meet the other's dent as the full lattice
// would make it under the rows' forces. 20 N, after 0.4 s.
TEST(DeformedContact, StaticCorrectionDentsBothBallsAlikeAndNearerHertz)
{
    const Press plain = press_balls(20.0, true, 60, 4, 400);
    const Press p = press_balls(20.0, true, 60, 4, 400, true);
    const double approach = p.dent_a + p.dent_b - p.gap; // of the centres
    std::printf("20 N with the correction: dents %.4f / %.4f mm, poles' gap %+.4f mm, Hertz force at the "
                "centres' approach %.3f N (modes alone %.3f N)\n",
                1e3 * p.dent_a, 1e3 * p.dent_b, 1e3 * p.gap, hertz_force(approach),
                hertz_force(plain.dent_a + plain.dent_b - plain.gap));
    EXPECT_LT(p.max_speed, 1e-3);
    EXPECT_NEAR(p.force, 20.0, 0.03 * 20.0);
    EXPECT_NEAR(p.dent_a, p.dent_b, 0.02 * approach / 2.0); // symmetric bodies, symmetric dents
    // The lattice's point compliance: several times the modes' dent (measured 0.775 against 0.169 mm),
    // still stiffer than Hertz (a Ritz model errs stiff; measured Hertz force 44% of the load).
    EXPECT_GT(p.dent_a, 3.0 * plain.dent_a);
    EXPECT_LT(hertz_force(approach), 20.0);
}

namespace
{

// The 2x4 board's shape (1.0 × 0.038 × 0.089 m), softened to E 1 GPa so it bends visibly, free in zero
// gravity; a 2.5 cm steel ball pressed onto the centre of its top face by `load` [N], the board held by
// the opposite body force.
constexpr double k_board_half_thickness = 0.019, k_small_ball = 0.025;

struct BoardPress {
    double deflection = 0.0;  ///< How far the top face's centre moved down in the board frame [m].
    double bottom = 0.0;      ///< How far the bottom face's centre moved down in the board frame [m].
    double gap = 0.0;         ///< Ball's lowest point above the deformed top centre [m]; < 0: inside.
    double contact_y = 0.0;   ///< Contact point height above the deformed top centre [m].
    double point_depth = 0.0; ///< Depth of the ball's lowest point in the deformed board [m], 0 outside.
    double max_speed = 0.0;   ///< Largest body speed over the last 50 steps [m/s].
};

// The board of press_board as a modal body with `modes` modes (and the static correction or not).
sm::BodyDef soft_board_def(int modes, bool correction)
{
    sm::BodyDef bdef = sm::default_body_def();
    bdef.shape.radii = {0.5, k_board_half_thickness, 0.0445};
    bdef.shape.epsilon1 = bdef.shape.epsilon2 = 0.05;
    bdef.density = 450.0;
    bdef.young = 1e9;
    bdef.modal.enabled = true;
    bdef.modal.mode_count = modes;
    bdef.modal.lattice = {8, 1, 1};
    bdef.modal.damping_ratio = 0.5;
    bdef.modal.static_correction = correction;
    return bdef;
}

BoardPress press_board(double load, bool deformed_test, int steps, bool correction = false)
{
    sm::WorldDef wdef = sm::default_world_def();
    wdef.gravity = {};
    wdef.dt = 1e-4;
    wdef.contact.solver = sm::ContactSolver::Penalty;
    wdef.contact.deformed_inside_test = deformed_test;
    wdef.contact.sample_spacing = 2.5e-3;
    wdef.contact.max_samples_per_body = 50000;
    sm::World world(wdef);
    const sm::Entity board = sm::create_body(world, soft_board_def(12, correction));
    sm::BodyDef ball = sm::default_body_def();
    ball.shape.radii = {k_small_ball, k_small_ball, k_small_ball};
    ball.density = 7800.0;
    ball.position = {0.0, k_board_half_thickness + k_small_ball, 0.0};
    const sm::Entity b = sm::create_body(world, ball);
    BoardPress out;
    for (int i = 0; i < steps; ++i) {
        sm::apply_force_at_center(world, b, {0.0, -load, 0.0});
        sm::apply_force_at_center(world, board, {0.0, load, 0.0});
        world.step();
        if (i >= steps - 50)
            out.max_speed = std::max({out.max_speed, sm::length(sm::body_linear_velocity(world, b)),
                                      sm::length(sm::body_linear_velocity(world, board))});
    }
    const sm::Vec3 top{0.0, k_board_half_thickness, 0.0};
    const sm::Vec3 rigid_top =
        sm::body_position(world, board) + sm::rotate(sm::body_orientation(world, board), top);
    const sm::Vec3 deformed_top = sm::body_deformed_point(world, board, top);
    const sm::Vec3 lowest = sm::body_position(world, b) - sm::Vec3{0.0, k_small_ball, 0.0};
    out.deflection = rigid_top.y - deformed_top.y;
    out.bottom = -sm::test::body_frame_displacement(world, board, {0.0, -k_board_half_thickness, 0.0}).y;
    out.gap = lowest.y - deformed_top.y;
    if (!sm::world_contacts(world).empty())
        out.contact_y = sm::world_contacts(world)[0].point.y - deformed_top.y;
    const sm::BodyPointTest t = sm::body_point_test(world, board, lowest);
    out.point_depth = t.inside ? t.depth : 0.0;
    return out;
}

} // namespace

TEST(DeformedContact, BallPressedOnAModalBoardSitsInItsDeflection)
{
    // The ball's samples meet the board's bent top face: the ball follows the deflection, its lowest
    // point within the samples' gap of the deformed surface (spacing 2.5 mm on a 2.5 cm ball: the pole
    // falls between samples, ≈spacing²/(8r) = 0.03 mm; measured 0.04 mm at 100 N, 0.07 mm at 400 N;
    // bound 0.1 mm), and the contact point on it. The board's top centre sinks 0.75 mm at 100 N and
    // 3.0 mm at 400 N (inertia relief); with the rest test the ball stays on the rest face, that far up.
    for (const double load : {100.0, 400.0}) {
        SCOPED_TRACE(load);
        const BoardPress on = press_board(load, true, 1500);
        const BoardPress off = press_board(load, false, 1500);
        std::printf("load %5.1f N: deflection %.4f mm; deformed test: gap %+.4f mm, contact point %+.4f mm, "
                    "depth %.4f mm; rest test: gap %+.4f mm, contact point %+.4f mm\n",
                    load, 1e3 * on.deflection, 1e3 * on.gap, 1e3 * on.contact_y, 1e3 * on.point_depth,
                    1e3 * off.gap, 1e3 * off.contact_y);
        EXPECT_LT(on.max_speed, 1e-3);
        EXPECT_GT(on.deflection, 5e-4);
        EXPECT_LT(std::abs(on.gap), 1e-4);
        EXPECT_LT(on.point_depth, 1e-4);
        EXPECT_LT(std::abs(on.contact_y), 1e-4);
        // The rest test fails for the right reason: the ball hovers about one deflection above the dent.
        EXPECT_GT(off.gap, 0.8 * off.deflection);
        EXPECT_GT(off.contact_y, 0.8 * off.deflection);
    }
}

TEST(DeformedContact, RigidScenesStepBitIdenticallyWithIt)
{
    // Only points tested against a modal body change: the chair sample (rigid, sampled concave parts)
    // steps to the same state hash with the setting on as off.
    const std::string path = std::string(SM_SOURCE_DIR) + "/samples/chair_with_dummy.json";
    sm::Result<sm::Scene> scene = sm::load_scene(path);
    ASSERT_TRUE(scene) << scene.error().message();
    sm::Scene on_scene = *scene;
    on_scene.world.contact.deformed_inside_test = true;
    sm::Result<sm::World> off = sm::build_world(*scene);
    sm::Result<sm::World> on = sm::build_world(on_scene);
    ASSERT_TRUE(off && on);
    for (int i = 0; i < 200; ++i) {
        off->step();
        on->step();
    }
    EXPECT_EQ(on->state_hash(), off->state_hash());
}

TEST(DeformedContact, TheNarrowphaseHookIsBodyPointTestAndFallsBackToTheRestShape)
{
    // The hook the narrowphase calls (world/modal_system.cpp) gives what body_point_test gives, to the
    // bit, on a bent board; where Newton fails (a folded field) it gives the rest shape's test; a rigid
    // body has none (the narrowphase keeps test_point).
    sm::WorldDef wdef = sm::default_world_def();
    wdef.gravity = {};
    sm::World world(wdef);
    sm::BodyDef bdef = sm::default_body_def();
    bdef.shape.radii = {0.5, k_board_half_thickness, 0.0445};
    bdef.shape.epsilon1 = bdef.shape.epsilon2 = 0.05;
    bdef.young = 1e9;
    bdef.modal.enabled = true;
    bdef.modal.mode_count = 12;
    bdef.modal.lattice = {8, 1, 1};
    const sm::Entity board = sm::create_body(world, bdef);
    sm::BodyDef ball = sm::default_body_def();
    ball.position = {0.0, 2.0, 0.0};
    const sm::Entity rigid = sm::create_body(world, ball);
    const sm::World::Impl& w = sm::impl_of(world);
    EXPECT_EQ(sm::modal_deformed_test(w.reg, rigid).test, nullptr);
    const sm::Collider& collider = *w.reg.get<sm::BodyModel>(board).collider;
    const sm::ModalBasis& basis = *sm::body_modal_basis(world, board);
    const sm::Vec3 com = w.reg.get<sm::BodyModel>(board).mass.center_of_mass;

    // Every mode at 2e-3 √kg·m (about a millimetre each on the 3.4 kg board): points across the top face.
    std::vector<double> q(static_cast<size_t>(basis.mode_count), 2e-3), v(q.size(), 0.0);
    ASSERT_TRUE(sm::set_body_modal_state(world, board, q, v).ok());
    sm::DeformedTest hook = sm::modal_deformed_test(w.reg, board);
    ASSERT_NE(hook.test, nullptr);
    int inside = 0;
    for (double x = -0.45; x <= 0.45; x += 0.05)
        for (const double y : {0.015, 0.018, 0.021}) {
            const sm::Vec3 p{x, y, 0.01}; // the board sits at the origin, unrotated: world = shape frame
            const sm::InsideTest t = hook.test(hook.ctx, collider, p + com);
            const sm::BodyPointTest ref = sm::body_point_test(world, board, p);
            ASSERT_EQ(t.inside, ref.inside) << x << " " << y;
            if (!t.inside)
                continue;
            ++inside;
            EXPECT_EQ(t.depth, ref.depth);
            EXPECT_EQ(t.normal.x, ref.normal.x);
            EXPECT_EQ(t.normal.y, ref.normal.y);
            EXPECT_EQ(t.normal.z, ref.normal.z);
        }
    EXPECT_GT(inside, 10);

    // Folded: amplitudes a thousand times larger turn F singular or send Newton away somewhere on the
    // face; there the hook answers as the rest shape does.
    for (double& qk : q)
        qk *= 1000.0;
    ASSERT_TRUE(sm::set_body_modal_state(world, board, q, v).ok());
    hook = sm::modal_deformed_test(w.reg, board);
    int folded = 0;
    for (double x = -0.45; x <= 0.45; x += 0.01)
        for (const double y : {-0.015, 0.0, 0.015}) {
            const sm::Vec3 p = sm::Vec3{x, y, 0.0} + com;
            if (sm::modal::invert_deformation(basis, q, p).converged)
                continue;
            ++folded;
            const sm::InsideTest t = hook.test(hook.ctx, collider, p);
            const sm::InsideTest rest = sm::test_point(collider, p);
            EXPECT_EQ(t.inside, rest.inside);
            EXPECT_EQ(t.depth, rest.depth);
        }
    EXPECT_GT(folded, 0);
}

// The board's deflection under the ball against the full lattice's static answer to the same total load
// at the top centre (sparse solve of the 8×1×1 lattice, inertia relief: the board is held by a body
// force). Measured at the bottom face's centre, one cell (38 mm) below the contact. 400 N, penalty. With
// the correction the surface shows the full lattice's answer to the contact's own loads; they differ from
// the point load only in spreading over the ball's few millimetres of contact (measured 0.013%; bound
// 0.1%). The 12 modes alone miss the local part (measured 0.32% short), more than the bound.
TEST(DeformedContact, StaticCorrectionBoardDeflectionMatchesTheFullLattice)
{
    const double load = 400.0;
    const sm::BodyDef def = soft_board_def(12, true);
    auto full =
        sm::modal::FullModel::build(sm::modal_basis_def(def), sm::modal::fit_rayleigh(0.02, 100.0, 200.0));
    ASSERT_TRUE(full.has_value());
    const sm::modal::PointLoad at_top{{0.0, k_board_half_thickness, 0.0}, {0.0, -load, 0.0}};
    const std::vector<double> nodal = (*full)->static_solution({&at_top, 1});
    auto basis = sm::build_modal_basis(sm::modal_basis_def(def));
    ASSERT_TRUE(basis.has_value());
    const sm::LatticeWeights w = sm::modal_weights(*basis, {0.0, -k_board_half_thickness, 0.0});
    double reference = 0.0;
    for (int j = 0; j < w.count; ++j)
        reference -= w.weights[j] * nodal[static_cast<size_t>(w.nodes[j]) * 3 + 1];
    const BoardPress on = press_board(load, true, 1500, true);
    const BoardPress plain = press_board(load, true, 1500, false);
    std::printf("400 N: bottom centre sinks %.4f mm with the correction, %.4f mm with 12 modes alone; full "
                "lattice %.4f mm\n",
                1e3 * on.bottom, 1e3 * plain.bottom, 1e3 * reference);
    EXPECT_NEAR(on.bottom, reference, 1e-3 * reference);
    EXPECT_GT(std::abs(plain.bottom - reference), 2e-3 * reference);
}
