// Tests for engine/src/world/body.cpp (the principal frame) and its use in engine/src/dynamics: bodies
// whose principal axes of inertia are not the shape axes (taper + bend, oblique hyperquadrics) spin as
// the full inertia tensor says, while their pose stays the shape frame.
#include "geometry/mass_deformed.h"
#include "supermodal/body.h"
#include "supermodal/world.h"
#include "support/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

sm::World free_world(double dt)
{
    sm::WorldDef def = sm::default_world_def();
    def.dt = dt;
    def.gravity = {};
    return sm::World(def);
}

/// Angle of a rotation [rad].
double angle_of(const sm::Quat& q)
{
    return 2.0 * std::atan2(std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z), std::abs(q.w));
}

/// World inertia tensor R·I_shape·Rᵀ from the shape-frame tensor of the quadrature (not from the
/// body's principal frame, which is what is under test).
sm::Mat3 world_inertia(const sm::Mat3& shape_tensor, const sm::Quat& orientation)
{
    const sm::Mat3 r = sm::to_mat3(orientation);
    return r * shape_tensor * sm::transpose(r);
}

sm::ShapeDef hyperquadric(const sm::Quat& turn)
{
    // Three γ = 4 slabs: a rounded box with half-widths 0.2, 0.35, 0.6 m, turned by `turn` in its frame.
    sm::ShapeDef s = sm::default_shape_def();
    s.type = sm::ShapeType::Hyperquadric;
    for (const sm::Vec3& n : {sm::Vec3{5.0, 0, 0}, sm::Vec3{0, 1 / 0.35, 0}, sm::Vec3{0, 0, 1 / 0.6}})
        s.terms.push_back({sm::rotate(turn, n), 0.0, 4.0});
    return s;
}

} // namespace

TEST(BodyFrame, AlignedShapesKeepTheShapeAxes)
{
    // Untapered, unbent superquadrics are principal in their own axes: exactly identity, so their
    // steps are bit-identical to the shape-frame integration (Hamilton product with 1 is exact).
    const sm::MassProperties mp =
        sm::compute_mass_properties(sm::test::superquadric({0.2, 0.3, 0.5}, 0.4, 2.5), 1000.0);
    EXPECT_EQ(mp.principal_axes, sm::Quat::identity());
}

TEST(BodyFrame, BentTaperedBodySpinsWithItsFullInertiaTensor)
{
    // Energy ½ωᵀIω and momentum Iω with I from the quadrature's shape-frame tensor turned by the pose.
    // The implicit midpoint rotation conserves them to its Newton tolerance (1e-14 per step): over
    // 3000 steps a few 1e-12 (measured below). Integrating the principal moments about the shape axes
    // instead (the old behaviour) drifts by the ~0.1 rad principal tilt, many orders above 1e-9.
    constexpr double k_rel = 1e-9;
    sm::BodyDef def = sm::default_body_def();
    def.shape = sm::test::superquadric({0.2, 0.3, 0.8}, 0.5, 1.0);
    def.shape.taper = {0.6, -0.3};
    def.shape.bend = {0.9, 0.6};
    def.density = 800.0;
    def.position = {1.0, 2.0, 3.0};
    def.orientation = sm::quat_from_rotation_vector({0.3, -0.2, 0.5});
    def.angular_velocity = {1.0, 0.7, 3.0};
    def.linear_velocity = {0.5, 0, 0};
    sm::World world = free_world(0.001);
    const sm::Entity e = sm::create_body(world, def);
    const sm::QuadratureMass q = sm::quadrature_mass(def.shape, def.density, sm::k_default_mass_order);
    const double tilt = angle_of(sm::body_mass_properties(world, e).principal_axes);
    ASSERT_GT(tilt, 0.05); // the premise
    RecordProperty("principal_tilt_rad", testing::PrintToString(tilt));

    auto invariants = [&](double& energy, sm::Vec3& momentum) {
        const sm::Vec3 w = sm::body_angular_velocity(world, e);
        momentum = world_inertia(q.inertia_tensor, sm::body_orientation(world, e)) * w;
        energy = 0.5 * sm::dot(w, momentum);
    };
    double e0 = 0.0;
    sm::Vec3 l0;
    invariants(e0, l0);
    const double v2 = sm::dot(def.linear_velocity, def.linear_velocity);
    EXPECT_NEAR(sm::body_kinetic_energy(world, e), e0 + 0.5 * q.properties.mass * v2, 1e-12 * e0);
    double worst_e = 0.0, worst_l = 0.0;
    for (int i = 0; i < 3000; ++i) {
        world.step();
        double en = 0.0;
        sm::Vec3 l;
        invariants(en, l);
        worst_e = std::max(worst_e, std::abs(en - e0) / e0);
        worst_l = std::max(worst_l, sm::length(l - l0) / sm::length(l0));
    }
    EXPECT_LT(worst_e, k_rel);
    EXPECT_LT(worst_l, k_rel);
    // The body's own bookkeeping agrees with the tensor, and the shape origin moves with the COM.
    EXPECT_LT(sm::length(sm::body_angular_momentum(world, e) - l0), k_rel * sm::length(l0));
    const sm::Vec3 com = sm::body_center_of_mass(world, e);
    EXPECT_LT(sm::length(com - (def.position + sm::rotate(def.orientation, q.properties.center_of_mass) +
                                3.0 * def.linear_velocity)),
              1e-9);
    RecordProperty("max_rel_energy_error", testing::PrintToString(worst_e));
    RecordProperty("max_rel_momentum_error", testing::PrintToString(worst_l));
}

TEST(BodyFrame, ObliqueShapeMovesLikeTheAlignedOne)
{
    // The same solid described twice: aligned with its shape axes, and turned by T inside its shape frame
    // with the body turned back by T⁻¹. The world sees one body; the two must move alike. The two
    // descriptions' quadratures use different ray grids (≤ 1e-10 relative, docs/geometry.md), and the
    // spin is about the stable major axis, so the gap stays near that level; 1e-7 leaves margin.
    constexpr double k_same = 1e-7;
    const sm::Quat turn = sm::quat_from_rotation_vector({0.4, -0.7, 0.3});
    sm::BodyDef aligned = sm::default_body_def();
    aligned.shape = hyperquadric(sm::Quat::identity());
    aligned.orientation = sm::quat_from_rotation_vector({-0.2, 0.1, 0.4});
    aligned.angular_velocity = sm::rotate(aligned.orientation, sm::Vec3{4.0, 0.3, -0.2});
    sm::BodyDef oblique = aligned;
    oblique.shape = hyperquadric(turn);
    oblique.orientation = aligned.orientation * sm::conjugate(turn);

    sm::World wa = free_world(0.001), wb = free_world(0.001);
    const sm::Entity a = sm::create_body(wa, aligned), b = sm::create_body(wb, oblique);
    const sm::MassProperties& ma = sm::body_mass_properties(wa, a);
    const sm::MassProperties& mb = sm::body_mass_properties(wb, b);
    EXPECT_LT(angle_of(ma.principal_axes), 1e-9);
    ASSERT_GT(angle_of(mb.principal_axes), 0.3); // the premise: principal axes far off the shape axes
    RecordProperty("principal_tilt_rad", testing::PrintToString(angle_of(mb.principal_axes)));
    // Same moments; which slot each lands in depends on which shape axis its principal axis is nearest.
    std::array<double, 3> ia{ma.inertia_diagonal.x, ma.inertia_diagonal.y, ma.inertia_diagonal.z};
    std::array<double, 3> ib{mb.inertia_diagonal.x, mb.inertia_diagonal.y, mb.inertia_diagonal.z};
    std::sort(ia.begin(), ia.end());
    std::sort(ib.begin(), ib.end());
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(ib[i], ia[i], k_same * ia[i]);

    double worst_turn = 0.0, worst_spin = 0.0;
    for (int i = 0; i < 3000; ++i) {
        wa.step();
        wb.step();
        // Shape frame of b times T is the shape frame of a.
        const sm::Quat gap = sm::conjugate(sm::body_orientation(wa, a)) * sm::body_orientation(wb, b) * turn;
        worst_turn = std::max(worst_turn, angle_of(gap));
        worst_spin =
            std::max(worst_spin,
                     sm::length(sm::body_angular_velocity(wb, b) - sm::body_angular_velocity(wa, a)) / 4.0);
    }
    EXPECT_LT(worst_turn, k_same);
    EXPECT_LT(worst_spin, k_same);
    RecordProperty("max_orientation_gap_rad", testing::PrintToString(worst_turn));
    RecordProperty("max_rel_spin_gap", testing::PrintToString(worst_spin));
}
