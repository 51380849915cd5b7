// Tests for engine/src/geometry/mass_deformed.cpp.
#include "geometry/mass_deformed.h"
#include "supermodal/geometry.h"
#include "supermodal/shape.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace sm = supermodal;

namespace
{

// The superquadric quadrature measures ≤ 1e-10 relative at the default order over ε ∈ [0.01, 4]
// (docs/geometry.md); the closed forms it is checked against are exact to round-off.
constexpr double k_quadrature = 1e-9;
// Summing ~10^5 positive terms in double: ~1e-12 relative.
constexpr double k_summation = 1e-11;

sm::ShapeDef superquadric(double e1, double e2, sm::Vec3 radii = {0.5, 0.7, 1.1})
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = radii;
    s.epsilon1 = e1;
    s.epsilon2 = e2;
    return s;
}

double trace(const sm::Mat3& m)
{
    return m.m[0][0] + m.m[1][1] + m.m[2][2];
}

double max_off_diagonal(const sm::Mat3& m)
{
    return std::max({std::abs(m.m[0][1]), std::abs(m.m[0][2]), std::abs(m.m[1][2])});
}

/// ∫z² dV over the undeformed shape from the closed-form inertia: I_xx + I_yy − I_zz = 2∫z² (ρ = 1).
double second_moment_z(const sm::ShapeDef& s)
{
    const sm::Vec3 i = sm::compute_mass_properties(s, 1.0).inertia_diagonal;
    return 0.5 * (i.x + i.y - i.z);
}

} // namespace

TEST(MassDeformed, UndeformedQuadratureMatchesTheClosedForm)
{
    for (double e1 : {0.01, 0.1, 1.0, 2.0, 4.0})
        for (double e2 : {0.01, 0.1, 1.0, 2.0, 4.0}) {
            const sm::ShapeDef s = superquadric(e1, e2);
            const sm::MassProperties exact = sm::compute_mass_properties(s, 1.0);
            const sm::QuadratureMass q = sm::quadrature_mass(s, 1.0, sm::k_default_mass_order);
            EXPECT_NEAR(q.properties.volume / exact.volume, 1.0, k_quadrature) << e1 << " " << e2;
            for (int i = 0; i < 3; ++i)
                EXPECT_NEAR(q.properties.inertia_diagonal[i] / exact.inertia_diagonal[i], 1.0, k_quadrature);
            EXPECT_LT(sm::length(q.properties.center_of_mass), k_summation);
            EXPECT_LT(max_off_diagonal(q.inertia_tensor), k_summation * trace(q.inertia_tensor));
        }
    // Aspect ratio 1:100.
    const sm::ShapeDef board = superquadric(0.1, 0.1, {1.0, 0.01, 0.1});
    EXPECT_NEAR(sm::quadrature_mass(board, 1.0, sm::k_default_mass_order).properties.volume /
                    sm::superquadric_volume(board),
                1.0, k_quadrature);
}

TEST(MassDeformed, TaperedVolumeAndCentreMatchTheClosedForm)
{
    // det J = (1 + kx z/a3)(1 + ky z/a3); its odd powers of z integrate to zero over the symmetric body:
    //   V_t = V + kx·ky/a3²·∫z² dV,   z_c = (kx + ky)/a3·∫z² dV / V_t,   x_c = y_c = 0.
    for (double e1 : {0.1, 1.0, 3.0})
        for (const sm::Taper& t : {sm::Taper{0.5, -0.3}, sm::Taper{1, 1}, sm::Taper{-1, 0.4}}) {
            sm::ShapeDef s = superquadric(e1, 0.6);
            const double v = sm::superquadric_volume(s), z2 = second_moment_z(s), a3 = s.radii.z;
            s.taper = t;
            const double v_t = v + t.kx * t.ky / (a3 * a3) * z2;
            const sm::MassProperties mp = sm::compute_mass_properties(s, 1.0);
            EXPECT_NEAR(mp.volume / v_t, 1.0, k_quadrature);
            EXPECT_NEAR(mp.center_of_mass.z, (t.kx + t.ky) / a3 * z2 / v_t, k_quadrature * a3);
            EXPECT_NEAR(mp.center_of_mass.x, 0.0, k_summation);
            EXPECT_NEAR(mp.center_of_mass.y, 0.0, k_summation);
        }
}

TEST(MassDeformed, BendingKeepsTheVolume)
{
    // det J gains the factor 1 − k·u, u linear in x and y: odd, so it integrates to nothing.
    for (double angle : {0.0, 0.7, 2.0}) {
        sm::ShapeDef s = superquadric(0.5, 1.5);
        s.taper = {0.4, -0.2};
        const double tapered = sm::compute_mass_properties(s, 1.0).volume;
        s.bend = {0.8, angle};
        EXPECT_NEAR(sm::compute_mass_properties(s, 1.0).volume / tapered, 1.0, k_quadrature);
    }
}

TEST(MassDeformed, BendInAnAxisPlaneKeepsTheShapeAxesPrincipal)
{
    // Bending in the x-z plane keeps the mirror symmetries y → −y and z → −z of the body, so the shape
    // axes stay principal; the centre of mass moves toward the centre of curvature.
    sm::ShapeDef s = superquadric(0.4, 1.2);
    s.bend = {0.9, 0.0};
    const sm::QuadratureMass q = sm::quadrature_mass(s, 1.0, sm::k_default_mass_order);
    EXPECT_GT(q.properties.center_of_mass.x, 0.01);
    EXPECT_NEAR(q.properties.center_of_mass.y, 0.0, k_summation);
    EXPECT_NEAR(q.properties.center_of_mass.z, 0.0, k_summation);
    EXPECT_LT(max_off_diagonal(q.inertia_tensor), k_summation * trace(q.inertia_tensor));
}

TEST(MassDeformed, PrincipalMomentsDiagonaliseTheTensor)
{
    sm::ShapeDef s = superquadric(0.4, 1.2);
    s.taper = {0.5, -0.2};
    s.bend = {0.9, 0.7};
    const sm::QuadratureMass q = sm::quadrature_mass(s, 1.0, sm::k_default_mass_order);
    const sm::Mat3& tensor = q.inertia_tensor;
    EXPECT_GT(max_off_diagonal(tensor), 1e-3 * trace(tensor)) << "this shape's axes should rotate";
    const sm::Vec3 moments = q.properties.inertia_diagonal;
    EXPECT_NEAR(moments.x + moments.y + moments.z, trace(tensor), k_summation * trace(tensor));
    for (int i = 0; i < 3; ++i) {
        const sm::Vec3 axis = q.principal_axes.col(i);
        EXPECT_NEAR(sm::length(axis), 1.0, k_summation);
        EXPECT_LT(sm::length(tensor * axis - moments[i] * axis), k_summation * trace(tensor));
        // Slot i holds the principal axis nearest shape axis i.
        EXPECT_GT(std::abs(axis[i]), std::sqrt(1.0 / 3.0));
    }
}

TEST(MassDeformed, SuperquadricAndHyperquadricPathsAgree)
{
    // With ε1 = ε2 = ε a superquadric is the hyperquadric Σ|x_i/a_i|^(2/ε) ≤ 1. The two quadratures share
    // nothing but the deformation, so their agreement checks both, deformed, to the precision of the
    // cruder (the hyperquadric's rays).
    constexpr double k_paths = 1e-8;
    for (double e : {1.0, 0.5}) {
        sm::ShapeDef sq = superquadric(e, e);
        sq.taper = {0.6, -0.4};
        sq.bend = {0.7, 0.5};
        sm::ShapeDef hq = sq;
        hq.type = sm::ShapeType::Hyperquadric;
        for (int i = 0; i < 3; ++i) {
            sm::Vec3 n{};
            n[i] = 1.0 / sq.radii[i];
            hq.terms.push_back({n, 0.0, 2.0 / e});
        }
        const sm::QuadratureMass a = sm::quadrature_mass(sq, 1.0, sm::k_default_mass_order);
        const sm::QuadratureMass b = sm::quadrature_mass(hq, 1.0, sm::k_default_mass_order);
        EXPECT_NEAR(a.properties.volume / b.properties.volume, 1.0, k_paths);
        EXPECT_LT(sm::length(a.properties.center_of_mass - b.properties.center_of_mass), k_paths);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a.inertia_tensor.m[r][c], b.inertia_tensor.m[r][c],
                            k_paths * trace(a.inertia_tensor));
    }
}

TEST(MassDeformed, QuadratureConvergesWithOrder)
{
    sm::ShapeDef s = superquadric(0.3, 2.5);
    s.taper = {-0.7, 0.3};
    s.bend = {1.2, 2.2};
    const double reference = sm::quadrature_mass(s, 1.0, 16).properties.volume;
    double previous = 1.0;
    for (int order : {1, 2, 4, 8}) {
        const double error = std::abs(sm::quadrature_mass(s, 1.0, order).properties.volume / reference - 1);
        EXPECT_LT(error, previous);
        previous = std::max(error, k_summation);
    }
    EXPECT_LT(previous, k_quadrature);
}

TEST(MassDeformed, ComputeMassPropertiesDispatches)
{
    sm::ShapeDef s = superquadric(0.7, 1.3);
    EXPECT_EQ(sm::compute_mass_properties(s, 3.0).volume, sm::superquadric_volume(s)) << "closed form kept";
    s.taper = {0.3, 0.3};
    const sm::MassProperties mp = sm::compute_mass_properties(s, 3.0);
    EXPECT_EQ(mp.volume, sm::quadrature_mass(s, 3.0, sm::k_default_mass_order).properties.volume);
    EXPECT_EQ(mp.mass, 3.0 * mp.volume);
    EXPECT_GT(mp.center_of_mass.z, 0.0) << "a taper that widens upward moves the mass up";
    // A tiny deformation keeps each moment in its axis's slot.
    s.taper = {1e-3, 0};
    const sm::Vec3 small = sm::compute_mass_properties(s, 1.0).inertia_diagonal;
    s.taper = {0, 0};
    const sm::Vec3 none = sm::compute_mass_properties(s, 1.0).inertia_diagonal;
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(small[i] / none[i], 1.0, 1e-2);
}
